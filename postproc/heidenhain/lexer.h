// The first stage of the Klartext reader: characters of one block -> its
// lexical pieces (blanks, letter runs, numbers, signed values and Q
// parameter references, quoted names, comments). It knows nothing of block
// kinds; every error is a KlartextError at the line and column of the byte.
// The hot path (blanks, letters, plain numbers) is inline: the block parser
// calls it for every word.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "postproc/heidenhain/block.h"
#include "postproc/heidenhain/diagnostics.h"

namespace vcpost::heidenhain::syntax {

// Inside a block, the line break of a '~' continuation and the '~' itself
// separate words as blanks do.
constexpr bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '~';
}
constexpr bool is_digit(char c) { return c >= '0' && c <= '9'; }
constexpr bool is_upper(char c) { return c >= 'A' && c <= 'Z'; }

inline constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                    1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                    1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// Largest magnitude of a literal (Code::E3303 beyond), as the G-code
// reader's: far past any machine, keeps every sum and square finite.
inline constexpr double kMaxMagnitude = 1e12;

class Lexer {
 public:
  explicit Lexer(const Block& block) : block_(block), s_(block.text) {}

  [[noreturn]] void fail(Code code, std::size_t at, std::string message) const;

  std::size_t pos() const { return i_; }
  void seek(std::size_t at) { i_ = at; }
  bool at_end() const { return i_ >= s_.size(); }
  char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
  std::string_view text() const { return s_; }

  void skip_blanks() {
    while (i_ < s_.size() && is_blank(s_[i_])) ++i_;
  }

  // Upper-case letters from the cursor (empty when none).
  std::string_view read_letters() {
    const std::size_t first = i_;
    while (i_ < s_.size() && is_upper(s_[i_])) ++i_;
    return s_.substr(first, i_ - first);
  }

  // An unsigned decimal literal ("12", "0.5", ".5", "5."); false (cursor
  // unchanged) when no digit starts here.
  bool read_unsigned(double& out) {
    const std::size_t n = s_.size();
    std::size_t k = i_;
    std::uint64_t mantissa = 0;
    std::size_t digits = 0, fraction = 0;
    for (; k < n && is_digit(s_[k]); ++k, ++digits) {
      if (digits < 19) mantissa = mantissa * 10 + static_cast<unsigned>(s_[k] - '0');
    }
    if (k < n && s_[k] == '.') {
      ++k;
      for (; k < n && is_digit(s_[k]); ++k, ++fraction) {
        if (digits + fraction < 19) mantissa = mantissa * 10 + static_cast<unsigned>(s_[k] - '0');
      }
    }
    if (digits + fraction == 0) return false;
    if (digits + fraction > 19 || fraction > 22) return read_long_number(k, out);
    i_ = k;
    out = static_cast<double>(mantissa) / kPow10[fraction];
    if (out > kMaxMagnitude) fail(Code::E3303, i_ - 1, "number too large");
    return true;
  }

  // A value at the cursor: an optional sign, then a literal or a Q, QL or
  // QR parameter. False (cursor after the sign) when neither follows.
  bool read_value(Value& out, char& sign);

  // A "name" with the cursor on its opening quote: the text between the
  // quotes, the cursor after the closing one.
  std::string_view read_quoted();

  // From the cursor to the end of its line (a comment's text); the cursor
  // at the line break.
  std::string_view rest_of_line() {
    const std::size_t first = i_;
    while (i_ < s_.size() && s_[i_] != '\n' && s_[i_] != '\r') ++i_;
    return s_.substr(first, i_ - first);
  }

  // NUL and control bytes fail anywhere; bytes above 127 outside comments
  // and names (the parser checks the bytes it reads as words).
  void check_word_byte(std::size_t at) const;

 private:
  bool read_long_number(std::size_t end, double& out);

  const Block& block_;
  std::string_view s_;
  std::size_t i_ = 0;
};

}  // namespace vcpost::heidenhain::syntax
