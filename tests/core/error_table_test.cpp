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

// Every code the product's sources name is a row: each E1234/W1234 token
// (a quoted literal or the comment beside an enumerator), and each number
// of an enumeration of codes (`count_mismatch = 4609,`: its id is built
// from the number, "E" + 4609, and no literal names it; such a code was
// thrown with no row, so it reported as an internal error, exit 3).
TEST(CodeTable, EveryCodeInTheSourcesIsInTheTable) {
  const fs::path root(VCPOST_SOURCE_DIR);
  const std::regex token(R"(\b([EW][0-9]{4})\b)");
  const std::regex enumeration(R"(enum\s+class\s+\w+[^{;]*\{([^}]*)\})");
  const std::regex numbered(R"(\b[a-z_0-9]+\s*=\s*([0-9]{4})\s*[,/\n])");
  int files = 0, numbers = 0;
  for (const char* folder : {"core", "geometry", "machines", "postproc", "api"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
      const auto ext = entry.path().extension();
      if (ext != ".cpp" && ext != ".h") continue;
      ++files;
      const std::string text = read(entry.path());
      for (std::sregex_iterator it(text.begin(), text.end(), token), end; it != end; ++it) {
        EXPECT_NE(find_code((*it)[1].str()), nullptr)
            << (*it)[1].str() << " in " << entry.path() << " is not in core/error_codes.csv";
      }
      for (std::sregex_iterator e(text.begin(), text.end(), enumeration), end; e != end; ++e) {
        const std::string body = (*e)[1].str();
        for (std::sregex_iterator it(body.begin(), body.end(), numbered); it != end; ++it) {
          const std::string number = (*it)[1].str();
          ++numbers;
          EXPECT_TRUE(find_code("E" + number) != nullptr || find_code("W" + number) != nullptr)
              << "code " << number << " (" << (*it)[0].str() << ") in " << entry.path()
              << " is not in core/error_codes.csv as E" << number << " or W" << number;
        }
      }
    }
  }
  EXPECT_GT(files, 50);
  // The enumerations of G-code, STL and verify codes.
  EXPECT_GT(numbers, 60);
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
