// Diagnostics of G-code reading: messages that name file:line:col, and the
// exception thrown for a fatal problem. The codes, their summaries,
// severities and hints are the one code table's (core/error_codes.csv,
// vcpost::Code, docs/errors.md): a new code is a row there.
//
// Format: "<file>:<line>:<col>: error[E1203]: <message>" (warning[W....]).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/error.h"

namespace vcpost::gcode {

using vcpost::Severity;

using vcpost::Code;  // E1xxx, W1xxx; E1620, E1621 (the analog speed output)

struct Diagnostic {
  Code code = Code::E1001;
  std::uint32_t line = 0;    // 1-based
  std::uint32_t column = 0;  // 1-based, bytes
  std::string message;
  Severity severity() const { return code_info(code).severity; }
};

// "<file>:<line>:<col>: error[E1502]: <message>"
std::string format(const Diagnostic& diagnostic, std::string_view file_name);

// Thrown by the reader/interpreter for an error: the block is not executed
// and the interpreter stops (what follows would depend on it).
class GcodeError : public vcpost::Error {
 public:
  explicit GcodeError(Diagnostic diagnostic);
  const Diagnostic& diagnostic() const { return diagnostic_; }

 private:
  Diagnostic diagnostic_;
};

}  // namespace vcpost::gcode
