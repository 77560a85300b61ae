// Small string helpers every module shares: trimming, ASCII case and a
// strict number. Header-only, no locale (std::isspace and friends in the
// "C" locale, which vcpost never changes).
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

namespace vcpost {

inline constexpr std::string_view kBlanks = " \t";              // spaces and tabs
inline constexpr std::string_view kWhitespace = " \t\n\v\f\r";  // std::isspace

// `text` without the leading and trailing characters of `chars`. A plain
// loop over the few characters of the set: the CL reader trims every
// record and parameter, and find_first_not_of cost it 5 % of its speed.
constexpr std::string_view trim(std::string_view text, std::string_view chars = kWhitespace) {
  const auto in_set = [chars](char c) {
    for (const char x : chars)
      if (x == c) return true;
    return false;
  };
  std::size_t begin = 0, end = text.size();
  while (begin < end && in_set(text[begin])) ++begin;
  while (end > begin && in_set(text[end - 1])) --end;
  return text.substr(begin, end - begin);
}

constexpr char ascii_lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c + 32) : c; }
constexpr char ascii_upper(char c) { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 32) : c; }

// ASCII case only; other bytes are kept.
inline std::string to_lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), ascii_lower);
  return out;
}
inline std::string to_upper(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), ascii_upper);
  return out;
}

// The whole of `text` as a finite decimal number (std::from_chars: no
// blanks, no leading '+'), or nothing.
inline std::optional<double> finite_number(std::string_view text) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc{} || end != text.data() + text.size() ||
      !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

}  // namespace vcpost
