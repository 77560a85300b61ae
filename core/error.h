// One error type and one table of diagnostic codes for all of vcpost.
//
// The table is data: core/error_codes.csv (code, name, exit status, summary,
// what to do), compiled at build time into the enum vcpost::Code
// (core/code.h: Code::E1403, Code::W1402 ...), the lookup below and
// docs/errors.md. Modules name a code by its enumerator only, so a code not
// in the table does not compile. Every error vcpost reports is a vcpost::Error (or a subclass
// of it that adds the module's own typed fields) carrying a code from that
// table; the command line turns it into one line on stderr and the table's
// exit status. Anything else that escapes is an internal error (exit 3).
//
// Codes are stable: "E1403" (error) and "W1402" (warning); never renumber
// or reuse one, only append.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/code.h"  // generated from core/error_codes.csv
#include "vcpost/severity.h"

namespace vcpost {

std::string_view to_string(Severity severity);  // "error", "warning"

// One row of the code table.
struct CodeInfo {
  Code code;                 // Code::E1403
  std::string_view id;       // "E1403"
  std::string_view name;     // "modal_group_conflict"
  Severity severity;         // E... error, W... warning
  int exit_code;             // vcpost's exit status when this code ends the run
  std::string_view summary;  // what the code means, one line
  std::string_view hint;     // what to do about it
};

// The whole table, in code order.
std::span<const CodeInfo> code_table();

// The row of `id` ("E1403"; case-insensitive), or nullptr when no such code
// (for codes the user types, as `vcpost explain`'s).
const CodeInfo* find_code(std::string_view id);

// The row of `code`.
const CodeInfo& code_info(Code code);

// "E1403": the code as users see it. Tests print it too.
std::string_view to_string(Code code);
std::ostream& operator<<(std::ostream& out, Code code);

// Where a diagnostic points. line and column are 1-based; 0 = not known.
struct SourceLocation {
  std::string file;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
};

// "file:line:col: error[E1403]: message"; ":line:col" is left out when line
// is 0 (":col" when column is 0), "file:" when file is empty.
std::string format_diagnostic(Code code, const SourceLocation& where, std::string_view message);

// The error every module throws (directly or through a subclass). what() is
// the whole text the user sees after "vcpost: error: ".
class Error : public std::runtime_error {
 public:
  // `text` is the complete message (modules that format their own
  // "file:line:col: error[...]" prefix pass it whole); `where` tells tools
  // the position; `hint` overrides the table's "what to do".
  Error(Code code, const std::string& text, SourceLocation where = {}, std::string hint = {});

  Code code() const { return info_->code; }
  std::string_view id() const { return info_->id; }  // "E1403"
  const CodeInfo& info() const { return *info_; }
  Severity severity() const { return info_->severity; }
  int exit_code() const { return info_->exit_code; }
  const SourceLocation& where() const { return where_; }
  std::string_view hint() const { return hint_.empty() ? info_->hint : std::string_view(hint_); }

 private:
  const CodeInfo* info_;
  SourceLocation where_;
  std::string hint_;
};

}  // namespace vcpost
