// The one code table: lookups, the Error type, and the rules that keep the
// table whole: every code literal in the sources is in it, and the
// committed docs/errors.md is the page generated from it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "core/error.h"

namespace vcpost {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(CodeTable, LooksUpCodesCaseInsensitively) {
  const CodeInfo* row = find_code("E1403");
  ASSERT_NE(row, nullptr);
  EXPECT_EQ(row->name, "modal_group_conflict");
  EXPECT_EQ(row->severity, Severity::error);
  EXPECT_EQ(row->exit_code, 2);
  EXPECT_EQ(find_code("e1403"), row);
  EXPECT_EQ(find_code("E1403 "), nullptr);
  EXPECT_EQ(find_code("E0000"), nullptr);
  EXPECT_EQ(find_code(""), nullptr);
  // An unknown code in a throw still reports, as an internal error.
  EXPECT_EQ(code_info("E0000").id, "E9999");
  EXPECT_EQ(code_info("E0000").exit_code, 3);
}

TEST(CodeTable, WarningsExitZeroAndErrorsDoNot) {
  std::set<std::string_view> ids;
  for (const CodeInfo& row : code_table()) {
    EXPECT_TRUE(ids.insert(row.id).second) << row.id;
    EXPECT_EQ(row.severity == Severity::warning, row.id[0] == 'W') << row.id;
    EXPECT_EQ(row.exit_code == 0, row.severity == Severity::warning) << row.id;
    EXPECT_FALSE(row.summary.empty()) << row.id;
    EXPECT_FALSE(row.hint.empty()) << row.id;
  }
  // The codes fixed by issue 19: the loop limit and the missing dwell/M98
  // word have codes of their own.
  EXPECT_EQ(code_info("E1307").name, "loop_limit");
  EXPECT_EQ(code_info("E1514").name, "missing_word");
}

TEST(Error, CarriesCodeLocationAndHint) {
  const Error e("E1502", "a.nc:3:4: error[E1502]: radius differs", {"a.nc", 3, 4});
  EXPECT_STREQ(e.what(), "a.nc:3:4: error[E1502]: radius differs");
  EXPECT_EQ(e.code(), "E1502");
  EXPECT_EQ(e.severity(), Severity::error);
  EXPECT_EQ(e.exit_code(), 2);
  EXPECT_EQ(e.where().file, "a.nc");
  EXPECT_EQ(e.where().line, 3u);
  EXPECT_EQ(e.hint(), code_info("E1502").hint);
  const Error custom("E2001", "--ap: bad", {}, "give a number");
  EXPECT_EQ(custom.hint(), "give a number");
  EXPECT_EQ(Error("E2010", "warnings with --strict").exit_code(), 1);
  EXPECT_EQ(Error("E9001", "planning").exit_code(), 3);
}

TEST(Error, FormatsDiagnostics) {
  EXPECT_EQ(format_diagnostic("E1403", {"p.nc", 7, 2}, "two motions"),
            "p.nc:7:2: error[E1403]: two motions");
  EXPECT_EQ(format_diagnostic("W3150", {"p.cls", 4, 0}, "ignored"),
            "p.cls:4: warning[W3150]: ignored");
  EXPECT_EQ(format_diagnostic("E4101", {"m.step", 0, 0}, "missing"),
            "m.step: error[E4101]: missing");
  EXPECT_EQ(format_diagnostic("E2001", {}, "bad"), "error[E2001]: bad");
}

// Every "E1234"/"W1234" literal in the product's sources names a row.
TEST(CodeTable, EveryCodeInTheSourcesIsInTheTable) {
  const fs::path root(VCPOST_SOURCE_DIR);
  const std::regex literal("\"([EW][0-9]{4})\"");
  int files = 0;
  for (const char* folder : {"core", "geometry", "machines", "postproc"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
      const auto ext = entry.path().extension();
      if (ext != ".cpp" && ext != ".h") continue;
      ++files;
      const std::string text = read(entry.path());
      for (std::sregex_iterator it(text.begin(), text.end(), literal), end; it != end; ++it) {
        EXPECT_NE(find_code((*it)[1].str()), nullptr)
            << (*it)[1].str() << " in " << entry.path() << " is not in core/error_codes.csv";
      }
    }
  }
  EXPECT_GT(files, 50);
}

// docs/errors.md is generated at build time; the committed copy must match.
TEST(CodeTable, CommittedDocsPageIsTheGeneratedOne) {
  const fs::path committed = fs::path(VCPOST_SOURCE_DIR) / "docs" / "errors.md";
  const fs::path generated = fs::path(VCPOST_BINARY_DIR) / "docs" / "errors.md";
  ASSERT_TRUE(fs::exists(generated)) << generated;
  EXPECT_EQ(read(committed), read(generated))
      << "docs/errors.md is stale: cp " << generated << " " << committed;
}

}  // namespace
}  // namespace vcpost
