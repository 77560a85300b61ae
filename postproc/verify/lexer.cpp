#include "postproc/verify/lexer.h"

#include <algorithm>

#include "postproc/gcode/block.h"
#include "postproc/gcode/lexer.h"

namespace vcpost::verify {

// The reader's character classes: the proof reads the text as it does.
using gcode::syntax::is_alpha;
using gcode::syntax::is_blank;
using gcode::syntax::is_digit;
using gcode::syntax::upper;

char Token::letter() const { return kind == TokenKind::word ? upper(text[0]) : '\0'; }

std::string_view Token::value() const {
  if (kind != TokenKind::word) return {};
  std::size_t k = 1;
  while (k < text.size() && is_blank(text[k])) ++k;
  return text.substr(k);
}

std::size_t line_at(std::string_view text, std::size_t offset, std::uint32_t number, Line& line) {
  line.number = number;
  const std::size_t nl = text.find('\n', offset);
  if (nl == std::string_view::npos) {
    line.text = text.substr(offset);
    line.eol = {};
    return text.size();
  }
  std::size_t end = nl;
  if (end > offset && text[end - 1] == '\r') --end;
  line.text = text.substr(offset, end - offset);
  line.eol = text.substr(end, nl + 1 - end);
  return nl + 1;
}

std::size_t line_before(std::string_view text, std::size_t end, std::uint32_t number, Line& line) {
  line.number = number;
  const std::size_t nl_end = text[end - 1] == '\n' ? end - 1 : end;
  std::size_t start = 0;
  if (nl_end > 0) {
    const std::size_t previous = text.rfind('\n', nl_end - 1);
    start = previous == std::string_view::npos ? 0 : previous + 1;
  }
  std::size_t content_end = nl_end;
  if (nl_end < end && content_end > start && text[content_end - 1] == '\r') --content_end;
  line.text = text.substr(start, content_end - start);
  line.eol = text.substr(content_end, end - content_end);
  return start;
}

std::uint32_t count_lines(std::string_view text) {
  std::uint32_t n = 0;
  for (std::size_t at = 0; (at = text.find('\n', at)) != std::string_view::npos; ++at) ++n;
  if (!text.empty() && text.back() != '\n') ++n;
  return n;
}

std::uint32_t first_line_longer_than(std::string_view text, std::size_t limit) {
  std::uint32_t number = 0;
  for (std::size_t at = 0; at < text.size();) {
    ++number;
    const std::size_t scan = std::min(text.size() - at, limit + 2);
    const std::size_t nl = text.substr(at, scan).find('\n');
    std::size_t length = nl == std::string_view::npos ? scan : nl;
    if (length > 0 && text[at + length - 1] == '\r') --length;
    if (length > limit) return number;
    if (nl == std::string_view::npos) break;  // the last line, within the limit
    at += nl + 1;
  }
  return 0;
}

std::vector<Line> split_lines(std::string_view text) {
  std::vector<Line> lines;
  std::size_t at = 0;
  std::uint32_t number = 0;
  while (at < text.size()) {
    Line line;
    at = line_at(text, at, ++number, line);
    lines.push_back(line);
  }
  return lines;
}

void tokenize(std::string_view s, std::vector<Token>& out) {
  out.clear();
  std::size_t i = 0;
  int depth = 0;
  auto push = [&](TokenKind kind, std::size_t begin, std::size_t end) {
    out.push_back(Token{kind, s.substr(begin, end - begin), static_cast<std::uint32_t>(begin + 1)});
  };
  while (i < s.size()) {
    const char c = s[i];
    const std::size_t begin = i;
    if (is_blank(c)) {
      while (i < s.size() && is_blank(s[i])) ++i;
      push(TokenKind::blank, begin, i);
    } else if (c == '(') {
      const std::size_t close = s.find(')', i);
      i = close == std::string_view::npos ? s.size() : close + 1;
      push(TokenKind::comment, begin, i);
    } else if (c == ';') {
      i = s.size();
      push(TokenKind::comment, begin, i);
    } else if (c == '#' && i + 1 < s.size() && s[i + 1] == '<') {
      // A named parameter: its letters are no words (#<f1> holds no F word).
      const std::size_t close = s.find('>', i);
      i = close == std::string_view::npos ? s.size() : close + 1;
      push(TokenKind::other, begin, i);
    } else if (is_alpha(c)) {
      if (depth == 0 && !(i + 1 < s.size() && is_alpha(s[i + 1]))) {
        std::size_t k = i + 1;
        while (k < s.size() && is_blank(s[k])) ++k;
        const std::size_t end = gcode::word_value_end(s, k);
        if (end > k) {
          i = end;
          push(TokenKind::word, begin, i);
          continue;
        }
      }
      while (i < s.size() && is_alpha(s[i])) ++i;
      push(TokenKind::name, begin, i);
    } else {
      if (c == '[') ++depth;
      if (c == ']' && depth > 0) --depth;
      ++i;
      push(TokenKind::other, begin, i);
    }
  }
}

bool is_plain_positive(std::string_view v) {
  bool digit = false, nonzero = false, point = false;
  for (char c : v) {
    if (c == '.') {
      if (point) return false;
      point = true;
    } else if (is_digit(c)) {
      digit = true;
      nonzero = nonzero || c != '0';
    } else {
      return false;
    }
  }
  return digit && nonzero;
}

}  // namespace vcpost::verify
