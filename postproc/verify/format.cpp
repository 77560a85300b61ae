#include "postproc/verify/verify.h"

namespace vcpost::verify {

std::string format(const Violation& v, std::string_view output_name) {
  std::string out =
      format_diagnostic(v.code, {std::string(output_name), v.line, v.column}, v.message);
  if (v.input_line > 0) out += " (input line " + std::to_string(v.input_line) + ")";
  return out;
}

std::string describe(const Change& c) {
  if (c.added) return "+ " + c.new_text;
  return c.old_text + " -> " + c.new_text;
}

}  // namespace vcpost::verify
