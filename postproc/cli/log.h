// The command line's messages on standard error, through spdlog: warnings,
// the end-of-run lines, progress and, at the debug level (-v), each stage's
// time and counts. Every line reads "vcpost: <message>", a warning's
// "vcpost: warning: <message>" and a debug line's "vcpost: debug: <message>",
// as they read before spdlog. Diagnostics with a position
// ("file:line:col: error[E....]: message") and the final error line stay
// the commands' own (main.cpp): their format is part of the interface.
#pragma once

#include <spdlog/logger.h>

#include <optional>
#include <string_view>

namespace vcpost::cli {

// The one logger of the command line (not in spdlog's registry); info by
// default.
spdlog::logger& log();

// "error", "warning", "info" or "debug"; empty for anything else.
std::optional<spdlog::level::level_enum> parse_log_level(std::string_view name);

// The level below which nothing is printed.
void set_log_level(spdlog::level::level_enum level);

}  // namespace vcpost::cli
