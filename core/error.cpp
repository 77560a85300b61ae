#include "core/error.h"

#include <algorithm>
#include <cctype>
#include <ostream>

namespace vcpost {

namespace {

constexpr CodeInfo kTable[] = {
#include "core/error_table.inc"
};

// code_info indexes the table by the enumerator: row i is Code(i).
static_assert(std::size(kTable) == kCodeCount);
static_assert(std::ranges::all_of(kTable, [](const CodeInfo& row) {
  return &row - std::begin(kTable) == static_cast<std::ptrdiff_t>(row.code);
}));

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

const CodeInfo& code_info(Code code) { return kTable[static_cast<std::size_t>(code)]; }

std::string_view to_string(Code code) { return code_info(code).id; }

std::ostream& operator<<(std::ostream& out, Code code) { return out << to_string(code); }

std::string format_diagnostic(Code code, const SourceLocation& where, std::string_view message) {
  std::string out = where.file;
  if (where.line > 0) {
    if (!out.empty()) out += ':';
    out += std::to_string(where.line);
    if (where.column > 0) out += ':' + std::to_string(where.column);
  }
  if (!out.empty()) out += ": ";
  const CodeInfo& row = code_info(code);
  out += to_string(row.severity);
  out += '[';
  out += row.id;
  out += "]: ";
  out += message;
  return out;
}

Error::Error(Code code, const std::string& text, SourceLocation where, std::string hint)
    : std::runtime_error(text),
      info_(&code_info(code)),
      where_(std::move(where)),
      hint_(std::move(hint)) {}

}  // namespace vcpost
