// The one code table: lookups, the Error type, and the rules that keep the
// table whole: every row is a code the sources raise (or says it is no
// longer raised), and the committed docs/errors.md is the page generated
// from it.
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
  EXPECT_EQ(row->code, Code::E1403);
  EXPECT_EQ(&code_info(Code::E1403), row);
  // E1402 and W1402 share a name and a number but are two codes.
  EXPECT_EQ(code_info(Code::W1402).id, "W1402");
  EXPECT_EQ(code_info(Code::W1402).severity, Severity::warning);
  EXPECT_EQ(code_info(Code::E1402).severity, Severity::error);
  std::ostringstream printed;
  printed << Code::W1509;
  EXPECT_EQ(printed.str(), "W1509");
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
  EXPECT_EQ(code_info(Code::E1307).name, "loop_limit");
  EXPECT_EQ(code_info(Code::E1514).name, "missing_word");
}

TEST(Error, CarriesCodeLocationAndHint) {
  const Error e(Code::E1502, "a.nc:3:4: error[E1502]: radius differs", {"a.nc", 3, 4});
  EXPECT_STREQ(e.what(), "a.nc:3:4: error[E1502]: radius differs");
  EXPECT_EQ(e.code(), Code::E1502);
  EXPECT_EQ(e.id(), "E1502");
  EXPECT_EQ(e.severity(), Severity::error);
  EXPECT_EQ(e.exit_code(), 2);
  EXPECT_EQ(e.where().file, "a.nc");
  EXPECT_EQ(e.where().line, 3u);
  EXPECT_EQ(e.hint(), code_info(Code::E1502).hint);
  const Error custom(Code::E2001, "--ap: bad", {}, "give a number");
  EXPECT_EQ(custom.hint(), "give a number");
  EXPECT_EQ(Error(Code::E2010, "warnings with --strict").exit_code(), 1);
  EXPECT_EQ(Error(Code::E9001, "planning").exit_code(), 3);
}

TEST(Error, FormatsDiagnostics) {
  EXPECT_EQ(format_diagnostic(Code::E1403, {"p.nc", 7, 2}, "two motions"),
            "p.nc:7:2: error[E1403]: two motions");
  EXPECT_EQ(format_diagnostic(Code::W3150, {"p.cls", 4, 0}, "ignored"),
            "p.cls:4: warning[W3150]: ignored");
  EXPECT_EQ(format_diagnostic(Code::E4101, {"m.step", 0, 0}, "missing"),
            "m.step: error[E4101]: missing");
  EXPECT_EQ(format_diagnostic(Code::E2001, {}, "bad"), "error[E2001]: bad");
}

// Every row of the table is a code the product raises: named as Code::E1234
// in the sources of core, geometry, machines, postproc or api (a code that
// is not a row does not compile), or a row kept for a code no longer
// raised, which its summary says. A row nothing raises documents a
// diagnostic users never see.
TEST(CodeTable, EveryRowIsRaisedOrSaysItIsNoLonger) {
  const fs::path root(VCPOST_SOURCE_DIR);
  const std::regex token(R"(\bCode::([EW][0-9]{4})\b)");
  std::set<std::string> raised;
  int files = 0;
  for (const char* folder : {"core", "geometry", "machines", "postproc", "api"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
      const auto ext = entry.path().extension();
      if (ext != ".cpp" && ext != ".h") continue;
      ++files;
      const std::string text = read(entry.path());
      for (std::sregex_iterator it(text.begin(), text.end(), token), end; it != end; ++it)
        raised.insert((*it)[1].str());
    }
  }
  EXPECT_GT(files, 50);
  // Rows with no code that raises them yet: the internal error (main's
  // fallback for anything that is no vcpost::Error), a work offset changed
  // after motion (the interpreter takes G54..G59 changes as frame changes,
  // W1512) and a cutter that is no modelled tool (refused as E6002/E6003).
  const std::set<std::string> not_raised = {"E9999", "E1510", "E6001"};
  for (const CodeInfo& row : code_table()) {
    const bool retired = row.summary.find("no longer") != std::string_view::npos;
    const bool is_raised = raised.contains(std::string(row.id));
    if (not_raised.contains(std::string(row.id))) {
      EXPECT_FALSE(is_raised) << row.id << " is raised now: take it off the list";
      continue;
    }
    EXPECT_TRUE(is_raised || retired)
        << row.id << " (" << row.name << ") is raised nowhere in the sources";
    EXPECT_FALSE(is_raised && retired) << row.id << " says it is no longer raised, but it is";
  }
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
