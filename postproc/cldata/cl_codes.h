// Diagnostics of the APT CL reader: the error type it throws and the
// warnings it collects. Their codes (E31xx errors, W31xx warnings) are rows
// of the one code table, core/error_codes.csv (vcpost::Code).
// Format of a diagnostic: "file:line:col: error[E3103]: message".
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/error.h"

namespace vcpost::cldata {

using vcpost::Severity;

using vcpost::Code;  // E31xx errors, W31xx warnings

// A problem at a place in a CL file. line and column are 1-based (0 = unknown).
struct ClDiagnostic {
  Code code = Code::E3117;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  std::string message;
};

// "file:line:col: error[E3103]: message" (file may be empty).
std::string format(const ClDiagnostic& diagnostic, std::string_view file_name);

// Thrown for input the reader cannot convert soundly; what() is the formatted
// diagnostic with the file name.
class ClError : public vcpost::Error {
 public:
  ClError(ClDiagnostic diagnostic, std::string_view file_name)
      : vcpost::Error(diagnostic.code, format(diagnostic, file_name),
                      {std::string(file_name), diagnostic.line, diagnostic.column}),
        diagnostic_(std::move(diagnostic)) {}
  const ClDiagnostic& diagnostic() const { return diagnostic_; }

 private:
  ClDiagnostic diagnostic_;
};

}  // namespace vcpost::cldata
