#include "postproc/cli/number_options.h"

#include <charconv>
#include <cmath>

namespace vcpost::cli {
namespace {

// The option's text as a finite number, or the reason it is none.
std::string parse(const std::string& text, double& value) {
  const std::string::size_type start = !text.empty() && text.front() == '+' ? 1 : 0;
  const char* begin = text.data() + start;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(begin, end, value);
  if (text.empty() || begin == end || error == std::errc::invalid_argument || stop != end) {
    return "'" + text + "' is not a number";
  }
  if (error == std::errc::result_out_of_range || !std::isfinite(value)) {
    return "'" + text + "' is not a finite number";
  }
  return {};
}

}  // namespace

std::string shown(double value) {
  if (value == std::floor(value) && std::abs(value) < 1e15) {
    return std::to_string(static_cast<long long>(value));  // 1000000, not 1e+06
  }
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

CLI::Validator positive_number(double at_least, double at_most) {
  const std::string description =
      at_most > 0 ? "NUMBER in [" + shown(at_least) + ", " + shown(at_most) + "]" : "POSITIVE";
  return CLI::Validator(
      [at_least, at_most](std::string& text) -> std::string {
        double value = 0;
        if (std::string reason = parse(text, value); !reason.empty()) return reason;
        if (!(value > 0)) return "must be positive, got " + text;
        if (at_most > 0 && (value < at_least || value > at_most)) {
          return "must be between " + shown(at_least) + " and " + shown(at_most) + ", got " + text;
        }
        return {};
      },
      description);
}

CLI::Validator non_negative_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0;
        if (std::string reason = parse(text, value); !reason.empty()) return reason;
        if (value < 0) return "must not be negative, got " + text;
        return {};
      },
      "NON-NEGATIVE");
}

}  // namespace vcpost::cli
