#include <algorithm>
#include <cstdio>

#include "postproc/verify/verify.h"

namespace vcpost::verify {

const std::vector<CodeInfo>& code_table() {
  static const std::vector<CodeInfo> table = {
      {Code::line_count, "lines added or removed"},
      {Code::line_ending, "line terminator changed"},
      {Code::word_changed, "a word other than S/F changed"},
      {Code::token_added, "a token only in the output"},
      {Code::token_removed, "a token missing from the output"},
      {Code::whitespace_changed, "blanks changed"},
      {Code::comment_changed, "a comment changed"},
      {Code::word_in_comment, "an S/F word inside a comment changed"},
      {Code::sf_removed, "an S or F word removed"},
      {Code::sf_repeated, "a second S or F word in one block"},
      {Code::bad_sf_value, "S/F value not a plain positive number"},
      {Code::event_differs, "an interpreted event differs"},
      {Code::event_count, "interpreted event counts differ"},
      {Code::output_unreadable, "the output does not interpret"},
      {Code::motion_count, "a motion only on one side"},
      {Code::end_point, "end point beyond the tolerance"},
      {Code::motion_kind, "rapid, feed or arc differs"},
      {Code::arc_differs, "arc centre, plane or direction differs"},
      {Code::spindle_or_tool, "spindle or tool change differs"},
  };
  return table;
}

const CodeInfo& info(Code code) {
  const auto& table = code_table();
  const auto it = std::find_if(table.begin(), table.end(),
                               [code](const CodeInfo& i) { return i.code == code; });
  return *it;  // every enumerator is in the table (tested)
}

std::string code_id(Code code) { return "E" + std::to_string(static_cast<unsigned>(code)); }

std::string format(const Violation& v, std::string_view output_name) {
  std::string out(output_name);
  out += ':' + std::to_string(v.line) + ':' + std::to_string(v.column) + ": error[" +
         code_id(v.code) + "]: " + v.message;
  if (v.input_line > 0) out += " (input line " + std::to_string(v.input_line) + ")";
  return out;
}

std::string describe(const Change& c) {
  if (c.added) return "+ " + c.new_text;
  return c.old_text + " -> " + c.new_text;
}

}  // namespace vcpost::verify
