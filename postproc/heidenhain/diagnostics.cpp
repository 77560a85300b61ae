#include "postproc/heidenhain/diagnostics.h"

#include <cstdio>

namespace vcpost::heidenhain {

namespace {

std::string id(char letter, Code code) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%c%04u", letter, static_cast<unsigned>(code));
  return buffer;
}

}  // namespace

Severity severity_of(Code code) {
  return vcpost::find_code(id('E', code)) != nullptr ? Severity::error : Severity::warning;
}

std::string code_id(Code code) {
  return id(severity_of(code) == Severity::error ? 'E' : 'W', code);
}

// The table's code of the reader's enumerator (its row exists: tested).
vcpost::Code table_code(Code code) { return vcpost::find_code(code_id(code))->code; }

std::string format(const Diagnostic& d, std::string_view file_name) {
  return vcpost::format_diagnostic(
      table_code(d.code), {d.file.empty() ? std::string(file_name) : d.file, d.line, d.column},
      d.message);
}

KlartextError::KlartextError(Diagnostic diagnostic)
    : vcpost::Error(table_code(diagnostic.code), format(diagnostic, ""),
                    {diagnostic.file, diagnostic.line, diagnostic.column}),
      diagnostic_(std::move(diagnostic)) {}

}  // namespace vcpost::heidenhain
