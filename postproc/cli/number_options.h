// Validators for numeric options. CLI11's PositiveNumber lets NaN and
// infinity through (NaN compares false with both bounds) and words its
// refusal with DBL_MAX in full; these refuse every non-finite number and
// say what was expected in a few words. A refusal is a usage error: exit 2.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace vcpost::cli {

// A finite number > 0 (and <= `at_most`, when given; then also >= `at_least`).
CLI::Validator positive_number(double at_least = 0, double at_most = 0);

// A finite number >= 0.
CLI::Validator non_negative_number();

// The number in a message: shortest form that reads back ("1e+300", "0.5").
std::string shown(double value);

}  // namespace vcpost::cli
