#include "postproc/heidenhain/lexer.h"

#include <charconv>
#include <cstdio>
#include <string>

namespace vcpost::heidenhain::syntax {

void Lexer::fail(Code code, std::size_t at, std::string message) const {
  const auto [line, column] = block_.position(static_cast<std::uint32_t>(at));
  throw KlartextError(Diagnostic{code, line, column, std::move(message), {}});
}

bool Lexer::read_long_number(std::size_t end, double& out) {
  std::string digits(s_.substr(i_, end - i_));
  double value = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec != std::errc() || ptr != digits.data() + digits.size() || !(value <= kMaxMagnitude))
    fail(Code::E3303, i_, "number '" + digits + "' too large or malformed");
  i_ = end;
  out = value;
  return true;
}

bool Lexer::read_value(Value& out, char& sign) {
  out = Value{};
  sign = 0;
  if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-')) sign = s_[i_++];
  if (i_ < s_.size() && s_[i_] == 'Q') {
    const std::size_t at = i_++;
    out.bank = Value::Bank::q;
    if (i_ < s_.size() && (s_[i_] == 'L' || s_[i_] == 'R')) {
      out.bank = s_[i_] == 'L' ? Value::Bank::ql : Value::Bank::qr;
      ++i_;
    }
    double number = 0;
    if (!read_unsigned(number) || number != static_cast<double>(static_cast<long>(number)))
      fail(Code::E3303, at, "a Q parameter needs its number (Q1, QL2, QR3)");
    out.number = number;
    out.negate = sign == '-';
    return true;
  }
  double number = 0;
  if (!read_unsigned(number)) return false;
  out.number = sign == '-' ? -number : number;
  return true;
}

std::string_view Lexer::read_quoted() {
  const std::size_t open = i_++;
  const std::size_t first = i_;
  while (i_ < s_.size() && s_[i_] != '"' && s_[i_] != '\n' && s_[i_] != '\r') {
    if (s_[i_] == '\0') fail(Code::E3302, i_, "NUL byte in a name");
    ++i_;
  }
  if (i_ >= s_.size() || s_[i_] != '"') fail(Code::E3326, open, "name without its closing '\"'");
  return s_.substr(first, i_++ - first);
}

void Lexer::check_word_byte(std::size_t at) const {
  const auto c = static_cast<unsigned char>(s_[at]);
  if (c == 0) fail(Code::E3302, at, "NUL byte in the program text");
  if (c < 0x20 || c == 0x7f || c > 0x7f) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%02X", c);
    fail(Code::E3302, at,
         std::string("byte ") + hex + " outside a comment or name (Klartext words are ASCII)");
  }
}

}  // namespace vcpost::heidenhain::syntax
