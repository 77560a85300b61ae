// The command reference of docs/commands/ against the command line's own
// definition, the one `--help` and the man pages are generated from
// (packaging/help_pages.cpp): every subcommand has its page, and the page
// names every long option the subcommand takes. An option added without
// its documentation fails here, naming the page and the option.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <cctype>
#include <filesystem>
#include <string>

#include "postproc/cli/app.h"
#include "tests/postproc/cli_run_support.h"

namespace {

// Whether `text` holds "--name" not followed by more of an option's name
// ("--ae" is not found in "--ae-override").
bool names_option(const std::string& text, const std::string& option) {
  const std::string written = "--" + option;
  for (std::size_t at = text.find(written); at != std::string::npos;
       at = text.find(written, at + 1)) {
    const std::size_t end = at + written.size();
    if (end == text.size()) return true;
    const auto next = static_cast<unsigned char>(text[end]);
    if (std::isalnum(next) == 0 && next != '-' && next != '_') return true;
  }
  return false;
}

TEST(CommandDocs, NamesOptionOnlyWhole) {
  EXPECT_TRUE(names_option("`--ae MM`", "ae"));
  EXPECT_FALSE(names_option("`--ae-override`", "ae"));
  EXPECT_TRUE(names_option("ends with --ae", "ae"));
}

TEST(CommandDocs, EverySubcommandHasAPageNamingEachOfItsOptions) {
  CLI::App app;
  vcpost::cli::configure_app(app);
  const auto subcommands = app.get_subcommands([](const CLI::App*) { return true; });
  ASSERT_GE(subcommands.size(), 7U);
  for (const CLI::App* sub : subcommands) {
    const std::filesystem::path page =
        std::filesystem::path(VCPOST_SOURCE_DIR) / "docs/commands" / (sub->get_name() + ".md");
    ASSERT_TRUE(std::filesystem::exists(page)) << page << " is missing";
    const std::string text = vcpost::testing::slurp(page);
    for (const CLI::Option* option : sub->get_options()) {
      for (const std::string& name : option->get_lnames()) {
        if (name == "help") continue;
        EXPECT_TRUE(names_option(text, name)) << page << " does not name --" << name;
      }
    }
  }
}

}  // namespace
