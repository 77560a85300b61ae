#include "core/error.h"

#include <algorithm>
#include <cctype>

namespace vcpost {

namespace {

constexpr CodeInfo kTable[] = {
#include "core/error_table.inc"
};

}  // namespace

std::string_view to_string(Severity severity) {
  return severity == Severity::error ? "error" : "warning";
}

std::span<const CodeInfo> code_table() { return kTable; }

const CodeInfo* find_code(std::string_view id) {
  if (id.size() != 5) return nullptr;
  std::string key(id);
  key[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(key[0])));
  const auto it = std::find_if(std::begin(kTable), std::end(kTable),
                               [&](const CodeInfo& row) { return row.id == key; });
  return it == std::end(kTable) ? nullptr : &*it;
}

const CodeInfo& code_info(std::string_view id) {
  if (const CodeInfo* row = find_code(id)) return *row;
  return *find_code("E9999");
}

std::string format_diagnostic(std::string_view code, const SourceLocation& where,
                              std::string_view message) {
  std::string out = where.file;
  if (where.line > 0) {
    if (!out.empty()) out += ':';
    out += std::to_string(where.line);
    if (where.column > 0) out += ':' + std::to_string(where.column);
  }
  if (!out.empty()) out += ": ";
  out += to_string(code_info(code).severity);
  out += '[';
  out += code;
  out += "]: ";
  out += message;
  return out;
}

Error::Error(std::string_view code, const std::string& text, SourceLocation where, std::string hint)
    : std::runtime_error(text),
      info_(&code_info(code)),
      where_(std::move(where)),
      hint_(std::move(hint)) {}

}  // namespace vcpost
