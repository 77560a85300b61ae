// The first stage of the G-code reader: characters -> lexical pieces. A
// Lexer walks one line (no terminator) with a cursor and hands the stages
// above it (expression.h, block_parser.h) what the characters spell:
// blanks, letters, digits, number literals, comments, stray bytes. It knows
// nothing of words, parameters or dialects; every error it finds is a
// GcodeError at the line and 1-based column of the problem.
//
// The hot path of a plain program (blanks, letters, plain numbers) is
// inline here: the block parser calls it for every word.
#pragma once

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "postproc/gcode/diagnostics.h"

namespace vcpost::gcode::syntax {

constexpr bool is_blank(char c) { return c == ' ' || c == '\t'; }
constexpr bool is_digit(char c) { return c >= '0' && c <= '9'; }
constexpr bool is_alpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
constexpr char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c; }

// Exact powers of ten (10^22 is the largest exact double).
inline constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                    1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                    1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// Where a keyword (upper case) starts in `rest` outside ( ) comments and
// before a ';' comment; npos if it does not.
std::size_t find_keyword_outside_comments(std::string_view rest, std::string_view key);
// Whether `rest` holds only blanks and comments.
bool only_comments(std::string_view rest);

class Lexer {
 public:
  Lexer(std::string_view s, std::uint32_t line) : s_(s), line_(line) {}

  [[noreturn]] void fail(Code code, std::size_t at, std::string message) const;

 protected:
  std::string_view s_;  // the line
  std::size_t i_ = 0;   // the cursor: index of the next character
  std::uint32_t line_;

  bool at_end() const { return i_ >= s_.size(); }

  void skip_blanks() {
    while (i_ < s_.size() && is_blank(s_[i_])) ++i_;
  }

  // A #<name> or O<name> with the cursor on its '<': the name as LinuxCNC
  // keys it (blanks dropped, lower case) into `name`, the cursor after the
  // '>'. False when the name is not closed: the line ends, or '(' or ';'
  // starts a comment, as it does even there on LinuxCNC (rs274: "Unclosed
  // comment found", "Equal sign missing in parameter setting").
  bool read_angle_name(std::string& name) {
    ++i_;
    while (!at_end() && s_[i_] != '>' && s_[i_] != '(' && s_[i_] != ';') {
      if (!is_blank(s_[i_]))
        name += static_cast<char>(std::tolower(static_cast<unsigned char>(s_[i_])));
      ++i_;
    }
    if (at_end() || s_[i_] != '>') return false;
    ++i_;
    return true;
  }

  // Letters from the cursor, upper-cased ("if" -> "IF").
  std::string read_letters() {
    std::string key;
    while (!at_end() && is_alpha(s_[i_])) key += upper(s_[i_++]);
    return key;
  }

  // Digits from the cursor, as written.
  std::string read_digits_text() {
    std::string text;
    while (!at_end() && is_digit(s_[i_])) text += s_[i_++];
    return text;
  }

  // Whether a digit or a point follows index k (blanks skipped).
  bool literal_follows(std::size_t k) const {
    while (k < s_.size() && is_blank(s_[k])) ++k;
    return k < s_.size() && (is_digit(s_[k]) || s_[k] == '.');
  }

  // A decimal literal without sign; blanks between digits are skipped
  // (Fanuc and LinuxCNC ignore them). `word_start` and `letter` word the
  // error of a missing or bad number.
  double read_number(bool& decimal_point, std::size_t word_start, char letter) {
    if (const auto v = read_plain_number(decimal_point)) return *v;
    return read_general_number(decimal_point, word_start, letter);
  }

  // The common case, on the hot path: digits, an optional point, digits,
  // no blanks, at most 19 digits, exactly representable (mantissa below
  // 2^53, so mantissa / 10^k is correctly rounded). nullopt (and i_
  // unchanged) for anything else.
  std::optional<double> read_plain_number(bool& decimal_point) {
    const std::size_t n = s_.size();
    std::size_t k = i_;
    std::uint64_t mantissa = 0;
    auto digits = [&] {
      const std::size_t first = k;
      for (unsigned d; k < n && (d = static_cast<unsigned char>(s_[k]) - unsigned{'0'}) < 10; ++k)
        mantissa = mantissa * 10 + d;
      return k - first;
    };
    const std::size_t whole = digits();
    std::size_t fraction = 0;
    const bool point = k < n && s_[k] == '.';
    if (point) {
      ++k;
      fraction = digits();
    }
    constexpr std::uint64_t kExact = std::uint64_t{1} << 53;
    if (whole + fraction == 0 || whole + fraction > 19 || fraction > 22 || mantissa > kExact ||
        (k < n && (s_[k] == '.' || (is_blank(s_[k]) && literal_follows(k)))))
      return std::nullopt;  // no digits, long, or a blank or second point: the general path
    i_ = k;
    decimal_point = point;
    return static_cast<double>(mantissa) / kPow10[fraction];
  }

  // Any other literal: blanks between digits, many digits (from_chars).
  double read_general_number(bool& decimal_point, std::size_t word_start, char letter);

  // A NUL or control byte at `at` fails (tab, CR and form feed pass).
  void check_byte(std::size_t at) const {
    const auto c = static_cast<unsigned char>(s_[at]);
    if (c == 0) fail(Code::E1002, at, "NUL byte in the program text");
    if (c < 0x20 && c != '\t' && c != '\r' && c != '\f') fail_control_byte(c, at);
  }

  // A ( ) comment at the cursor: its text without the parentheses; the
  // cursor after the ')'. Fails on a '(' inside, a bad byte or no ')'.
  std::string_view read_comment_text();

 private:
  [[noreturn]] void fail_control_byte(unsigned char c, std::size_t at) const;
};

}  // namespace vcpost::gcode::syntax
