#include "postproc/output/comment_text.h"

namespace vcpost::output {

std::string clean_comment(std::string_view text, CommentEnd end) {
  const bool in_parentheses = end == CommentEnd::parenthesis;
  std::string s;
  s.reserve(text.size());
  for (const char c : text) {
    if (in_parentheses && c == '(') {
      s += '[';
    } else if (in_parentheses && c == ')') {
      s += ']';
    } else if (static_cast<unsigned char>(c) >= 0x20 && static_cast<unsigned char>(c) < 0x7F) {
      s += c;
    }
  }
  return s;
}

}  // namespace vcpost::output
