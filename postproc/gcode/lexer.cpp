#include "postproc/gcode/lexer.h"

#include <algorithm>
#include <charconv>

#include "postproc/gcode/block.h"

namespace vcpost::gcode::syntax {

void Lexer::fail(Code code, std::size_t at, std::string message) const {
  throw GcodeError(Diagnostic{code, line_, static_cast<std::uint32_t>(at + 1), std::move(message)});
}

void Lexer::fail_control_byte(unsigned char c, std::size_t at) const {
  const char* digits = "0123456789ABCDEF";
  const std::string hex{digits[(c >> 4) & 15], digits[c & 15]};
  fail(Code::E1002, at, "control byte 0x" + hex + " in the program text");
}

double Lexer::read_general_number(bool& decimal_point, std::size_t word_start, char letter) {
  std::uint64_t mantissa = 0;
  int digits = 0;
  int fraction = 0;
  bool point = false;
  bool any = false;
  char compact[80];
  std::size_t compact_length = 0;
  while (!at_end()) {
    const char c = s_[i_];
    if (is_digit(c)) {
      any = true;
      if (mantissa != 0 || c != '0') ++digits;
      mantissa = mantissa * 10 + static_cast<std::uint64_t>(c - '0');
      if (point) ++fraction;
    } else if (c == '.') {
      if (point) fail(Code::E1003, i_, "second decimal point in a number");
      point = true;
    } else if (is_blank(c) && literal_follows(i_)) {
      ++i_;
      continue;
    } else {
      break;
    }
    if (compact_length < sizeof compact) compact[compact_length++] = c;
    ++i_;
  }
  if (!any) fail(Code::E1003, word_start, std::string(1, letter) + " word without a number");
  decimal_point = point;
  if (digits <= 15 && fraction <= 22) return static_cast<double>(mantissa) / kPow10[fraction];
  if (compact_length >= sizeof compact) fail(Code::E1003, word_start, "number too long");
  double v = 0.0;
  const auto r = std::from_chars(compact, compact + compact_length, v);
  if (r.ec != std::errc()) fail(Code::E1003, word_start, "number out of range");
  return v;
}

std::string_view Lexer::read_comment_text() {
  const std::size_t open = i_;
  ++i_;
  const std::size_t begin = i_;
  while (!at_end() && s_[i_] != ')') {
    if (s_[i_] == '(') fail(Code::E1005, i_, "'(' inside a comment");
    check_byte(i_);
    ++i_;
  }
  if (at_end()) fail(Code::E1004, open, "comment opened here is not closed");
  const std::string_view text = s_.substr(begin, i_ - begin);
  ++i_;
  return text;
}

std::size_t find_keyword_outside_comments(std::string_view rest, std::string_view key) {
  bool in_comment = false;
  for (std::size_t k = 0; k < rest.size(); ++k) {
    const char c = rest[k];
    if (in_comment) {
      in_comment = c != ')';
      continue;
    }
    if (c == '(') {
      in_comment = true;
      continue;
    }
    if (c == ';') return std::string_view::npos;
    if (k + key.size() <= rest.size()) {
      bool match = true;
      for (std::size_t m = 0; m < key.size() && match; ++m) match = upper(rest[k + m]) == key[m];
      if (match) return k;
    }
  }
  return std::string_view::npos;
}

bool only_comments(std::string_view rest) {
  bool in_comment = false;
  for (char c : rest) {
    if (in_comment) {
      in_comment = c != ')';
    } else if (c == '(') {
      in_comment = true;
    } else if (c == ';') {
      return true;
    } else if (!is_blank(c)) {
      return false;
    }
  }
  return true;
}

}  // namespace vcpost::gcode::syntax

// The lexical scans of block.h: spans of words without reading the block.
namespace vcpost::gcode {

using syntax::is_alpha;
using syntax::is_blank;
using syntax::is_digit;
using syntax::upper;

std::size_t word_value_end(std::string_view s, std::size_t k) {
  const std::size_t start = k;
  // A loop, not a recursion: a chain of 65,536 '#' must not exhaust the stack.
  while (true) {
    while (k < s.size() && (s[k] == '-' || s[k] == '+')) {  // unary signs, as unary() reads them
      ++k;
      while (k < s.size() && is_blank(s[k])) ++k;
    }
    if (k < s.size() && s[k] == '[') {
      int depth = 0;
      for (; k < s.size(); ++k) {
        if (s[k] == '[') ++depth;
        if (s[k] == ']' && --depth == 0) return k + 1;
      }
      return s.size();
    }
    if (k >= s.size() || s[k] != '#') break;
    ++k;
    if (k < s.size() && s[k] == '<') {
      while (k < s.size() && s[k] != '>') ++k;
      return k < s.size() ? k + 1 : k;
    }
    // The parameter's number is a value itself (#5, ##1, #[1+2], #++1).
    while (k < s.size() && is_blank(s[k])) ++k;
  }
  const std::size_t digits = k;
  while (k < s.size() && (is_digit(s[k]) || s[k] == '.' ||
                          (is_blank(s[k]) && k > digits && k + 1 < s.size() &&
                           (is_digit(s[k + 1]) || s[k + 1] == '.'))))
    ++k;
  return k > digits ? k : start;
}

std::optional<Span> find_word_span(std::string_view line, char letter) {
  letter = upper(letter);
  std::size_t i = 0;
  int depth = 0;
  while (i < line.size()) {
    const char c = line[i];
    if (c == '(') {
      while (i < line.size() && line[i] != ')') ++i;
      ++i;
      continue;
    }
    if (c == ';') return std::nullopt;
    if (c == '[') ++depth;
    if (c == ']') --depth;
    if (c == '#' && i + 1 < line.size() && line[i + 1] == '<') {
      while (i < line.size() && line[i] != '>') ++i;
      continue;
    }
    const bool word_start = depth == 0 && upper(c) == letter &&
                            (i == 0 || !is_alpha(line[i - 1])) &&
                            !(i + 1 < line.size() && is_alpha(line[i + 1]));
    if (word_start) {
      std::size_t k = i + 1;
      while (k < line.size() && is_blank(line[k])) ++k;
      k = word_value_end(line, k);
      return Span{static_cast<std::uint32_t>(i),
                  static_cast<std::uint32_t>(std::min(k, line.size()))};
    }
    ++i;
  }
  return std::nullopt;
}

}  // namespace vcpost::gcode
