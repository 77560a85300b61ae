// Bad input: every file in tests/postproc/bad/heidenhain holds its expected
// diagnostic in its first line, "; expect <CODE> <line>:<col> <message part>"
// (a Klartext comment), as the G-code and CL bad files do. Plus inputs too
// large or random to keep as files: never a crash, always a position.
#include <gtest/gtest.h>

#include <deque>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <set>

#include "postproc/heidenhain/interpreter.h"
#include "tests/postproc/codes_in_sources_support.h"

namespace vcpost::heidenhain {
namespace {

namespace fs = std::filesystem;

// Runs the program to its end; the first error, or else the last warning.
// The bad files' called programs: beside them, read as vcpost post reads
// them (a TOOL CALL in one refused).
std::optional<CalledProgram> called(std::string_view path, std::string_view /*caller*/) {
  static std::deque<std::string> texts;
  std::ifstream in(fs::path(VCPOST_SOURCE_DIR) / "tests/postproc/bad/heidenhain" / path,
                   std::ios::binary);
  if (!in) return std::nullopt;
  texts.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return CalledProgram{texts.back(), std::string(path)};
}

std::optional<Diagnostic> run(std::string_view text) {
  InterpreterLimits limits;
  limits.max_loop_iterations = 10000;  // the endless loops end fast
  limits.max_blocks = 1'000'000;
  Interpreter interpreter(text, limits);
  interpreter.set_program_loader(called);
  interpreter.refuse_tool_calls_in_called_programs();
  std::vector<program::Event> events;
  try {
    while (interpreter.next(events)) events.clear();
  } catch (const KlartextError& e) {
    return e.diagnostic();
  }
  if (interpreter.warnings().empty()) return std::nullopt;
  return interpreter.warnings().back();
}

TEST(KlartextBadInput, EveryFileGivesItsExpectedDiagnostic) {
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "tests/postproc/bad/heidenhain";
  static const std::regex expect_re(R"(^; expect ([EW]\d{4}) (\d+):(\d+) ([^\n]*))");
  std::set<std::string> codes;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;  // called/: the programs the bad files call
    SCOPED_TRACE(entry.path().string());
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    std::smatch expect;
    ASSERT_TRUE(std::regex_search(text, expect, expect_re)) << "no '; expect ...' line";
    const auto d = run(text);
    ASSERT_TRUE(d.has_value()) << "no diagnostic";
    EXPECT_EQ(to_string(d->code), expect[1].str());
    EXPECT_EQ(d->line, std::stoul(expect[2].str()));
    EXPECT_EQ(d->column, std::stoul(expect[3].str()));
    EXPECT_NE(d->message.find(expect[4].str()), std::string::npos) << d->message;
    codes.insert(expect[1].str());
  }
  // Every code the reader raises but the block-length limit (below) has its
  // file.
  std::set<std::string> raised = testing::codes_in_sources("postproc/heidenhain");
  EXPECT_GT(raised.size(), 30u);
  raised.erase("E3301");
  for (const std::string& code : raised)
    EXPECT_TRUE(codes.contains(code)) << code << " has no file in tests/postproc/bad/heidenhain";
}

TEST(KlartextBadInput, OverlongBlockIsRefused) {
  std::string text = "BEGIN PGM T MM\nL X+1";
  text.append(70000, '1');
  text += " FMAX\nEND PGM T MM\n";
  const auto d = run(text);
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->code, Code::E3301);
  EXPECT_EQ(d->line, 2u);
}

TEST(KlartextBadInput, RandomBytesNeverCrash) {
  // Random mixtures of Klartext pieces and arbitrary bytes after a valid
  // header: each run ends with events, a warning or a positioned error.
  std::mt19937 rng(4711);
  const std::vector<std::string> pieces = {
      "L ",        "C ",         "CC ",   "CR ",         "CT ",       "LP ",
      "CP ",       "RND ",       "CHF ",  "X+",          "Y-",        "Z",
      "IX",        "PA+",        "IPA",   "PR",          "DR+ ",      "DR- ",
      "R",         "F",          "FMAX ", "FQ",          "M",         "Q",
      "FN ",       ": ",         "=",     "LBL ",        "CALL LBL ", "REP",
      "CYCL DEF ", "CYCL CALL",  "~\n",   "\n",          ";",         "\"",
      "1",         "2.5",        "0",     "9",           " ",         "-",
      "+",         "TOOL CALL ", "S",     "PLANE RESET", "\xff",      std::string(1, '\0')};
  for (int round = 0; round < 2000; ++round) {
    std::string text = "BEGIN PGM T MM\n";
    const int length = static_cast<int>(rng() % 40);
    for (int k = 0; k < length; ++k) text += pieces[rng() % pieces.size()];
    const auto d = run(text);
    if (d) {
      EXPECT_GE(d->line, 1u) << text;
      EXPECT_GE(d->column, 1u) << text;
    }
  }
}

}  // namespace
}  // namespace vcpost::heidenhain
