// The whole `vcpost` command line: its description, subcommands, version
// and footer. main() parses with it; the build's help-page generator
// (packaging/help_pages.cpp) writes the man pages and the bash completion
// from it, so they say what `--help` says.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace vcpost::cli {

void configure_app(CLI::App& app);

// The refusal of a long option given with '=' and nothing after it
// (`--ap= -o out.nc`), before CLI11 parses: it would take the next argument
// as the value ("--ap: '-o' is not a number") or lose it ("--output is
// required"). Arguments after a lone "--" are not options. Empty: none.
std::optional<std::string> empty_option_value(const std::vector<std::string>& args);

}  // namespace vcpost::cli
