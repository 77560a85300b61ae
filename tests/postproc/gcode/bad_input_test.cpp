// Bad input: every file in tests/postproc/bad/gcode holds its expected
// diagnostic in a comment "(expect <CODE> <line>:<col> <message part>)",
// optionally "(dialect <name>)" and "(speed output E<n>)" (Dialect::
// speed_output), as LinuxCNC's tests/interp/bad do. Plus
// inputs too large or random to keep as files: never a crash, always a
// diagnostic with a position.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <set>
#include <string_view>
#include <utility>

#include "postproc/gcode/interpreter.h"
#include "tests/postproc/codes_in_sources_support.h"

namespace vcpost::gcode {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs the program to its end; the first error, or else the last warning.
std::optional<Diagnostic> run(std::string_view text, const Dialect& dialect) {
  Interpreter interpreter(text, dialect);
  std::vector<program::Event> events;
  try {
    while (interpreter.next(events)) events.clear();
  } catch (const GcodeError& e) {
    return e.diagnostic();
  }
  if (interpreter.warnings().empty()) return std::nullopt;
  return interpreter.warnings().back();
}

TEST(BadInput, EveryFileGivesItsExpectedDiagnostic) {
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "tests/postproc/bad/gcode";
  static const std::regex expect_re(R"(\(expect ([EW]\d{4}) (\d+):(\d+) ([^)]*)\))");
  static const std::regex dialect_re(R"(\(dialect (\w+)\))");
  static const std::regex speed_output_re(R"(\(speed output E(\d+)\))");
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    SCOPED_TRACE(entry.path().string());
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    std::smatch expect, dialect_name;
    ASSERT_TRUE(std::regex_search(text, expect, expect_re)) << "no (expect ...) comment";
    Dialect dialect = rs274ngc_dialect();
    if (std::regex_search(text, dialect_name, dialect_re))
      dialect = dialect_from_name(dialect_name[1].str()).value();
    if (std::smatch output; std::regex_search(text, output, speed_output_re))
      dialect.speed_output = std::stoi(output[1].str());
    const auto d = run(text, dialect);
    ASSERT_TRUE(d.has_value()) << "no diagnostic";
    EXPECT_EQ(to_string(d->code), expect[1].str());
    EXPECT_EQ(d->line, std::stoul(expect[2].str()));
    EXPECT_EQ(d->column, std::stoul(expect[3].str()));
    EXPECT_NE(d->message.find(expect[4].str()), std::string::npos) << d->message;
    ++count;
  }
  EXPECT_GE(count, 40);
}

TEST(BadInput, TenMegabyteLineIsRefused) {
  std::string text = "G0 X1\nG1 X";
  text.append(10u << 20, '1');
  text += " F100\nM2\n";
  const auto d = run(text, rs274ngc_dialect());
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->code, Code::E1006);
  EXPECT_EQ(d->line, 2u);
}

TEST(BadInput, RandomBytesNeverCrash) {
  // Random mixtures of G-code characters and arbitrary bytes: each run must
  // end with events, a warning or a positioned error, never a crash.
  std::mt19937 rng(12345);
  const std::string alphabet = "GXYZIJKRFSMTNPO#[]<>()=;./-+ 0123456789\n\r\t\0\xff";
  for (int run_index = 0; run_index < 2000; ++run_index) {
    std::string text;
    const int length = static_cast<int>(rng() % 200);
    for (int k = 0; k < length; ++k) text += alphabet[rng() % alphabet.size()];
    for (const Dialect& dialect : {rs274ngc_dialect(), mazak_dialect()}) {
      const auto d = run(text, dialect);
      if (d) {
        EXPECT_GE(d->line, 1u);
        EXPECT_GE(d->column, 1u);
      }
    }
  }
}

// Every code the G-code reader and interpreter raise (each Code:: in
// postproc/gcode) has a file in tests/postproc/bad/gcode that expects it,
// but for a line past the reader's limit (the test above) and the loop limit
// (ten million passes: hostile_reading_test lowers the limit instead).
TEST(BadInput, EveryCodeTheReaderRaisesHasAFile) {
  const std::regex expect_re(R"(\(expect ([EW]\d{4}) )");
  std::set<std::string> used = testing::codes_in_sources("postproc/gcode"), expected;
  for (const auto& entry :
       fs::directory_iterator(fs::path(VCPOST_SOURCE_DIR) / "tests/postproc/bad/gcode")) {
    const std::string text = read_file(entry.path());
    for (std::sregex_iterator it(text.begin(), text.end(), expect_re), end; it != end; ++it)
      expected.insert((*it)[1].str());
  }
  EXPECT_GT(used.size(), 40u);
  used.erase("E1006");
  used.erase("E1307");
  for (const std::string& code : used)
    EXPECT_TRUE(expected.contains(code)) << code << " has no file in tests/postproc/bad/gcode";
  const Diagnostic d{Code::E1502, 12, 3, "radius differs"};
  EXPECT_EQ(format(d, "a.nc"), "a.nc:12:3: error[E1502]: radius differs");
}

}  // namespace
}  // namespace vcpost::gcode
