#include <algorithm>
#include <cstdio>

#include "postproc/verify/verify.h"

namespace vcpost::verify {

const std::vector<CodeInfo>& code_table() {
  // The findings' codes; their summaries come from the one code table.
  static const std::vector<CodeInfo> table = [] {
    std::vector<CodeInfo> rows;
    for (Code code : {Code::line_count,
                      Code::line_ending,
                      Code::word_changed,
                      Code::token_added,
                      Code::token_removed,
                      Code::whitespace_changed,
                      Code::comment_changed,
                      Code::word_in_comment,
                      Code::sf_removed,
                      Code::sf_repeated,
                      Code::bad_sf_value,
                      Code::event_differs,
                      Code::event_count,
                      Code::output_unreadable,
                      Code::motion_count,
                      Code::end_point,
                      Code::motion_kind,
                      Code::arc_differs,
                      Code::spindle_or_tool,
                      Code::klartext_block_changed,
                      Code::klartext_numbering,
                      Code::klartext_misplaced_speed,
                      Code::klartext_block_added,
                      Code::klartext_bad_value,
                      Code::klartext_event_differs,
                      Code::klartext_output_unreadable,
                      Code::frame_differs,
                      Code::bad_speed_output_value,
                      Code::speed_output_unexpected}) {
      rows.push_back({code, vcpost::code_info(code_id(code)).summary});
    }
    return rows;
  }();
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
  std::string out =
      format_diagnostic(code_id(v.code), {std::string(output_name), v.line, v.column}, v.message);
  if (v.input_line > 0) out += " (input line " + std::to_string(v.input_line) + ")";
  return out;
}

std::string describe(const Change& c) {
  if (c.added) return "+ " + c.new_text;
  return c.old_text + " -> " + c.new_text;
}

}  // namespace vcpost::verify
