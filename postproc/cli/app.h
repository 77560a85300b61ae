// The whole `vcpost` command line: its description, subcommands, version
// and footer. main() parses with it; the build's help-page generator
// (packaging/help_pages.cpp) writes the man pages and the bash completion
// from it, so they say what `--help` says.
#pragma once

#include <CLI/CLI.hpp>

namespace vcpost::cli {

void configure_app(CLI::App& app);

}  // namespace vcpost::cli
