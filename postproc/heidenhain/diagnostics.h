// Diagnostics of the Klartext reader: the error it throws and the warnings
// it collects. Their codes (E33xx errors, W334x warnings) are rows of the
// one code table, core/error_codes.csv (vcpost::Code).
// Format: "<file>:<line>:<col>: error[E3310]: <message>".
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/error.h"

namespace vcpost::heidenhain {

using vcpost::Severity;

using vcpost::Code;  // E33xx errors, W334x warnings

struct Diagnostic {
  Code code = Code::E3304;
  std::uint32_t line = 0;    // 1-based
  std::uint32_t column = 0;  // 1-based, bytes
  std::string message;
  std::string file;  // a called program's name; "" for the program being posted
  Severity severity() const { return code_info(code).severity; }
};

// "<file>:<line>:<col>: error[E3310]: <message>" (the diagnostic's own file,
// a called program, when it has one)
std::string format(const Diagnostic& diagnostic, std::string_view file_name);

// Thrown for input the reader cannot follow soundly: the block is not
// executed and the interpreter stops.
class KlartextError : public vcpost::Error {
 public:
  explicit KlartextError(Diagnostic diagnostic);
  const Diagnostic& diagnostic() const { return diagnostic_; }

 private:
  Diagnostic diagnostic_;
};

}  // namespace vcpost::heidenhain
