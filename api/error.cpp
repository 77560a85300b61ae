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

Error error_from(const vcpost::Error& error, const std::string& program_file) {
  const std::string what = error.what();
  const std::string code(error.id());
  const Severity severity =
      error.severity() == vcpost::Severity::error ? Severity::error : Severity::warning;
  SourceLocation where = error.where();
  // No place: the text is the message as the command line prints it.
  if (where.file.empty() && where.line == 0)
    return Error(what, code, what, {}, 0, 0, std::string(error.hint()), severity);
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
