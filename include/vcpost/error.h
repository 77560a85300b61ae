// The one exception the vcpost library throws: every failure of the
// internals (bad program, model or profile, impossible set-up) leaves
// <vcpost/...> as a vcpost::api::Error carrying the same stable code and
// position that `vcpost` prints on the command line.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include "vcpost/export.h"
#include "vcpost/severity.h"

namespace vcpost::api {

using vcpost::Severity;  // the one enum (vcpost/severity.h)

class VCPOST_API Error : public std::runtime_error {
 public:
  // `what()` is the whole one-line message as the command line prints it,
  // e.g. "part.nc:12:5: error[E1201]: unknown G code G7.3".
  Error(const std::string& what, std::string code, std::string message, std::string file = {},
        unsigned line = 0, unsigned column = 0, std::string hint = {},
        Severity severity = Severity::error);

  const std::string& code() const;     // "E1201"; empty when the failure has no code
  const std::string& message() const;  // the message alone, without position or code
  const std::string& file() const;     // input file at fault; empty when none applies
  unsigned line() const;               // 1-based; 0 when no position applies
  unsigned column() const;             // 1-based, bytes; 0 when none applies
  const std::string& hint() const;     // what to do about it; may be empty
  Severity severity() const;

 private:
  struct Detail;
  std::shared_ptr<const Detail> detail_;  // shared: exceptions must copy without throwing
};

}  // namespace vcpost::api
