#include "postproc/gcode/diagnostics.h"

#include <cstdio>

namespace vcpost::gcode {

namespace {

std::string id(char letter, Code code) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%c%04u", letter, static_cast<unsigned>(code));
  return buffer;
}

}  // namespace

CodeInfo info(Code code) {
  // The error row when the code has one, else its warning row.
  const vcpost::CodeInfo* row = vcpost::find_code(id('E', code));
  if (row == nullptr) row = &vcpost::code_info(id('W', code));
  return CodeInfo{code, row->severity, row->summary};
}

std::string code_id(Code code, Severity severity) {
  return id(severity == Severity::error ? 'E' : 'W', code);
}

std::string format(const Diagnostic& d, std::string_view file_name) {
  return vcpost::format_diagnostic(code_id(d.code, d.severity),
                                   {std::string(file_name), d.line, d.column}, d.message);
}

GcodeError::GcodeError(Diagnostic diagnostic)
    : vcpost::Error(code_id(diagnostic.code, diagnostic.severity), format(diagnostic, ""),
                    {"", diagnostic.line, diagnostic.column}),
      diagnostic_(std::move(diagnostic)) {}

}  // namespace vcpost::gcode
