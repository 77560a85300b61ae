#include <charconv>
#include <string_view>

#include "api/translate.h"

namespace vcpost::api {

struct Error::Detail {
  std::string code, message, file, hint;
  unsigned line = 0, column = 0;
  Severity severity = Severity::error;
};

Error::Error(const std::string& what, std::string code, std::string message, std::string file,
             unsigned line, unsigned column, std::string hint, Severity severity)
    : std::runtime_error(what),
      detail_(std::make_shared<const Detail>(Detail{std::move(code), std::move(message),
                                                    std::move(file), std::move(hint), line, column,
                                                    severity})) {}

const std::string& Error::code() const { return detail_->code; }
const std::string& Error::message() const { return detail_->message; }
const std::string& Error::file() const { return detail_->file; }
unsigned Error::line() const { return detail_->line; }
unsigned Error::column() const { return detail_->column; }
const std::string& Error::hint() const { return detail_->hint; }
Severity Error::severity() const { return detail_->severity; }

namespace {

// A trailing ":<digits>" of `text`, removed from it when found.
unsigned take_number(std::string_view& text) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string_view::npos || colon + 1 == text.size()) return 0;
  unsigned value = 0;
  const char* first = text.data() + colon + 1;
  const char* last = text.data() + text.size();
  const auto [end, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || end != last) return 0;
  text.remove_suffix(text.size() - colon);
  return value;
}

}  // namespace

Error error_from_message(const std::string& what) {
  // "<where>: <error|warning>[<code>]: <message>"; <where> is "file",
  // "file:line" or "file:line:col".
  for (const std::string_view kind : {": error[", ": warning["}) {
    const std::size_t at = what.find(kind);
    if (at == std::string::npos) continue;
    const std::size_t code_begin = at + kind.size();
    const std::size_t code_end = what.find("]: ", code_begin);
    if (code_end == std::string::npos) continue;
    std::string_view where(what.data(), at);
    unsigned line = take_number(where);
    unsigned column = 0;
    if (line != 0) {
      column = line;
      line = take_number(where);
      if (line == 0) std::swap(line, column);  // "file:line" only
    }
    return Error(what, what.substr(code_begin, code_end - code_begin), what.substr(code_end + 3),
                 std::string(where), line, column, {},
                 kind == ": error[" ? Severity::error : Severity::warning);
  }
  return Error(what, {}, what);
}

Error error_from(const vcpost::Error& error, const std::string& program_file) {
  const std::string what = error.what();
  const std::string code(error.id());
  const Severity severity =
      error.severity() == vcpost::Severity::error ? Severity::error : Severity::warning;
  SourceLocation where = error.where();
  if (where.file.empty() && where.line == 0) {  // the place only in the text, if anywhere
    const Error read = error_from_message(what);
    return Error(what, code, read.message(), read.file(), read.line(), read.column(),
                 std::string(error.hint()), severity);
  }
  // The message: what() after its "error[E....]: ", or all of it (a
  // message worded without the prefix).
  const std::string marker = "[" + code + "]: ";
  const std::size_t at = what.find(marker);
  const std::string message = at == std::string::npos ? what : what.substr(at + marker.size());
  if (where.file.empty()) where.file = program_file;
  return Error(format_diagnostic(error.code(), where, message), code, message, where.file,
               where.line, where.column, std::string(error.hint()), severity);
}

}  // namespace vcpost::api
