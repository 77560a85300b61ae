// verify_gcode on a small hand-written program: a legitimate rewrite (made
// with the writer, as `vcpost post` makes it) passes with exactly the
// changes it made, at the columns counted by hand; each hand-made mutation
// of it is caught with its code at its line, and only there.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "postproc/gcode/writer.h"
#include "postproc/verify/lexer.h"
#include "postproc/verify/verify.h"

namespace vcpost::verify {
namespace {

// Line numbers: 1 %, 2 comment, 5 S word, 7 F word, 8 S word, 9 comment.
const std::string kInput =
    "%\n"
    "(finish pass)\n"
    "G21 G90 G17 G94\n"
    "T1 M6\n"
    "S12000 M3\n"
    "G0 X0 Y0 Z5\n"
    "G1 Z-1 F800\n"
    "G1 X10.5 Y2 S11000\n"
    "X20 Y4 (edge)\n"
    "G0 Z5\n"
    "M5\n"
    "M30\n"
    "%\n";

// Byte offset of the first byte of 1-based line `n`.
std::uint64_t line_offset(const std::string& text, int n) {
  std::uint64_t at = 0;
  for (int k = 1; k < n; ++k) at = text.find('\n', at) + 1;
  return at;
}

std::string posted(const std::string& input) {
  const std::vector<gcode::WordPatch> patches = {
      {line_offset(input, 5), 'S', "9870"},
      {line_offset(input, 7), 'F', "750"},
      {line_offset(input, 7), 'S', "9500"},
      {line_offset(input, 8), 'S', "11000"},  // the same value: no change
      {line_offset(input, 9), 'S', "9000"},
  };
  return gcode::patched(input, patches);
}

Result run(const std::string& input, const std::string& output) {
  return verify_gcode(input, output, Options{});
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The output with exactly one violation: its code, output line and column.
void expect_one(const std::string& output, Code code, std::uint32_t line,
                std::uint32_t column = 0) {
  const Result r = run(kInput, output);
  ASSERT_EQ(r.violation_count, 1u)
      << output << (r.violations.empty() ? "" : format(r.violations[0], "out"));
  EXPECT_EQ(r.violations[0].code, code) << format(r.violations[0], "out");
  EXPECT_EQ(r.violations[0].line, line) << format(r.violations[0], "out");
  if (column) {
    EXPECT_EQ(r.violations[0].column, column) << format(r.violations[0], "out");
  }
  EXPECT_FALSE(r.ok());
}

TEST(VerifyGcode, TheWritersRewritePassesWithEachChangeAtItsPlace) {
  const std::string out = posted(kInput);
  ASSERT_EQ(out.substr(line_offset(out, 7), 18), "G1 Z-1 F750 S9500\n");
  const Result r = run(kInput, out);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.violation_count, 0u);
  ASSERT_EQ(r.changes.size(), 4u);
  EXPECT_EQ(r.s_changes, 3u);
  EXPECT_EQ(r.f_changes, 1u);
  // line 5 "S9870 M3"
  EXPECT_EQ(r.changes[0].line, 5u);
  EXPECT_EQ(r.changes[0].column, 1u);
  EXPECT_EQ(r.changes[0].old_text, "S12000");
  EXPECT_EQ(r.changes[0].new_text, "S9870");
  EXPECT_FALSE(r.changes[0].added);
  EXPECT_EQ(describe(r.changes[0]), "S12000 -> S9870");
  // line 7 "G1 Z-1 F750 S9500": F in place, S added after the last word
  EXPECT_EQ(r.changes[1].line, 7u);
  EXPECT_EQ(r.changes[1].letter, 'F');
  EXPECT_EQ(r.changes[1].column, 8u);
  EXPECT_EQ(describe(r.changes[1]), "F800 -> F750");
  EXPECT_EQ(r.changes[2].line, 7u);
  EXPECT_EQ(r.changes[2].letter, 'S');
  EXPECT_EQ(r.changes[2].column, 13u);
  EXPECT_TRUE(r.changes[2].added);
  EXPECT_EQ(describe(r.changes[2]), "+ S9500");
  // line 9 "X20 Y4 S9000 (edge)": added before the trailing comment
  EXPECT_EQ(r.changes[3].line, 9u);
  EXPECT_EQ(r.changes[3].column, 8u);
  EXPECT_TRUE(r.changes[3].added);
  // Motions compared by the interpreted proof, counted by hand: lines 6 to 10.
  EXPECT_EQ(r.motions, 5u);
}

TEST(VerifyGcode, IdenticalProgramsPassWithNoChange) {
  const Result r = run(kInput, kInput);
  EXPECT_TRUE(r.ok());
  EXPECT_TRUE(r.changes.empty());
}

TEST(VerifyGcode, ExpressionReplacedByANumberIsAChange) {
  const std::string input = "#1=6000\nS[#1*2] M3\nG1 X1 F100\nM30\n";
  const std::string output = gcode::patched(input, std::vector<gcode::WordPatch>{{8, 'S', "9870"}});
  ASSERT_EQ(output, "#1=6000\nS9870 M3\nG1 X1 F100\nM30\n");
  const Result r = run(input, output);
  EXPECT_TRUE(r.ok());
  ASSERT_EQ(r.changes.size(), 1u);
  EXPECT_EQ(describe(r.changes[0]), "S[#1*2] -> S9870");
}

TEST(VerifyGcode, CrlfProgramRewrittenKeepsItsLineEndsAndPasses) {
  std::string input;
  for (char c : kInput) input += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const Result r = run(input, posted(input));
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.changes.size(), 4u);
}

TEST(VerifyGcode, CoordinateDigitChanged) {
  expect_one(replace(posted(kInput), "X10.5", "X10.6"), Code::E7103, 8, 4);
}

TEST(VerifyGcode, XWordRemoved) {
  expect_one(replace(posted(kInput), "G1 X10.5 Y2", "G1 Y2"), Code::E7105, 8);
}

TEST(VerifyGcode, G1BecameG0) {
  expect_one(replace(posted(kInput), "G1 X10.5", "G0 X10.5"), Code::E7103, 8, 1);
}

TEST(VerifyGcode, CommentEdited) {
  expect_one(replace(posted(kInput), "(finish pass)", "(finish  pass)"), Code::E7107, 2, 1);
}

TEST(VerifyGcode, FInsertedIntoAComment) {
  expect_one(replace(posted(kInput), "(edge)", "(edge F500)"), Code::E7108, 9);
}

TEST(VerifyGcode, SWordInsideACommentChanged) {
  const std::string input = "(S1000 rough)\nG1 X1 F100\nM30\n";
  const Result r = run(input, "(S900 rough)\nG1 X1 F100\nM30\n");
  ASSERT_EQ(r.violation_count, 1u);
  EXPECT_EQ(r.violations[0].code, Code::E7108);
  EXPECT_EQ(r.violations[0].line, 1u);
}

TEST(VerifyGcode, LineAdded) {
  const std::string out = posted(kInput);
  const std::string added =
      out.substr(0, line_offset(out, 7)) + "G4 P1\n" + out.substr(line_offset(out, 7));
  const Result r = run(kInput, added);
  ASSERT_GE(r.violation_count, 1u);
  EXPECT_EQ(r.violations[0].code, Code::E7101);
  EXPECT_EQ(r.violations[0].line, 7u);
  EXPECT_EQ(r.violation_count, 1u) << format(r.violations.back(), "out");
  // The lines after it still pair up: their changes are found.
  EXPECT_EQ(r.changes.size(), 4u);
  EXPECT_EQ(r.changes.back().line, 10u);
}

TEST(VerifyGcode, LineRemoved) {
  expect_one(replace(posted(kInput), "G0 Z5\nM5\n", "M5\n"), Code::E7101, 10, 1);
}

TEST(VerifyGcode, WhitespaceChanged) {
  expect_one(replace(posted(kInput), "G1 X10.5 Y2", "G1 X10.5  Y2"), Code::E7106, 8, 9);
  expect_one(replace(posted(kInput), "G21 G90", "G21\tG90"), Code::E7106, 3, 4);
  expect_one(replace(posted(kInput), "M5\n", "M5 \n"), Code::E7106, 11, 3);
}

TEST(VerifyGcode, SWordRemoved) {
  expect_one(replace(posted(kInput), "S9870 M3", "M3"), Code::E7109, 5, 1);
}

TEST(VerifyGcode, SWithANegativeValue) {
  expect_one(replace(posted(kInput), "S9870 M3", "S-9870 M3"), Code::E7111, 5, 1);
}

TEST(VerifyGcode, SWithANonNumericValue) {
  expect_one(replace(posted(kInput), "S9870 M3", "S#1 M3"), Code::E7111, 5, 1);
  expect_one(replace(posted(kInput), "S9870 M3", "S0 M3"), Code::E7111, 5, 1);
}

TEST(VerifyGcode, SecondSWordInABlock) {
  expect_one(replace(posted(kInput), "S9870 M3", "S9870 S9000 M3"), Code::E7110, 5, 7);
}

// Issue 42: an S or F that sets no speed or feed is no speed word: a
// changed G65 macro argument or Sinumerik spindle limit is a changed word
// of the program, found at its column.
TEST(VerifyGcode, MacroArgumentsAndSpindleLimitsAreNoSpeedWords) {
  Options fanuc;
  fanuc.dialect = gcode::fanuc_dialect();
  const std::string macro = "O1000\nG65 P2000 S5000 F300\nG0 X0 Y0 S6000\nM30\nO2000\nM99\n";
  Result r = verify_gcode(macro, replace(macro, "S5000", "S9999"), fanuc);
  ASSERT_EQ(r.violation_count, 1u);
  EXPECT_EQ(r.violations[0].code, Code::E7103) << format(r.violations[0], "out");
  EXPECT_EQ(r.violations[0].line, 2u);
  EXPECT_EQ(r.violations[0].column, 11u);
  r = verify_gcode(macro, replace(macro, "F300", "F250"), fanuc);
  ASSERT_EQ(r.violation_count, 1u);
  EXPECT_EQ(r.violations[0].code, Code::E7103);
  EXPECT_EQ(r.violations[0].column, 17u);
  // The S of an ordinary block of the same program stays a speed word.
  r = verify_gcode(macro, replace(macro, "S6000", "S5900"), fanuc);
  EXPECT_TRUE(r.ok()) << (r.violations.empty() ? "" : format(r.violations[0], "out"));

  Options siemens;
  siemens.dialect = gcode::sinumerik_dialect();
  const std::string limit = "G26 S8000\nS6000 M3\nG1 X10 F500\nM30\n";
  r = verify_gcode(limit, replace(limit, "S8000", "S20000"), siemens);
  ASSERT_EQ(r.violation_count, 1u);
  EXPECT_EQ(r.violations[0].code, Code::E7103);
  EXPECT_EQ(r.violations[0].line, 1u);
  EXPECT_EQ(r.violations[0].column, 5u);
  r = verify_gcode(limit, replace(limit, "S6000", "S5500"), siemens);
  EXPECT_TRUE(r.ok()) << (r.violations.empty() ? "" : format(r.violations[0], "out"));
}

// Sinumerik's G4 takes its time as F (seconds) or S (spindle turns): no
// feed or speed, so a change of theirs is a changed word at its column, as
// a macro argument's, not a speed change the events then contradict
// (E7121 at column 1); one added to the dwell is text the input lacks.
// Other dialects' F in a G4 block is a feed.
TEST(VerifyGcode, SinumerikDwellTimesAreNoSpeedWords) {
  Options siemens;
  siemens.dialect = gcode::sinumerik_dialect();
  const std::string dwell = "S1000 M3\nG4 F2\nG4 S10\nG1 X10 F500\nM30\n";
  const auto one = [&](const std::string& output, Code code, std::uint32_t line,
                       std::uint32_t column) {
    const Result r = verify_gcode(dwell, output, siemens);
    ASSERT_EQ(r.violation_count, 1u)
        << (r.violations.empty() ? "" : format(r.violations[0], "out"));
    EXPECT_EQ(r.violations[0].code, code) << format(r.violations[0], "out");
    EXPECT_EQ(r.violations[0].line, line);
    EXPECT_EQ(r.violations[0].column, column);
    EXPECT_TRUE(r.changes.empty());
  };
  one(replace(dwell, "G4 F2", "G4 F3"), Code::E7103, 2, 4);
  one(replace(dwell, "G4 S10", "G4 S20"), Code::E7103, 3, 4);
  one(replace(dwell, "G4 F2", "G4 F2 S20"), Code::E7106, 2, 6);
  // The speeds and feeds of the other blocks stay free.
  const Result r = verify_gcode(dwell, replace(dwell, "F500", "F450"), siemens);
  EXPECT_TRUE(r.ok()) << (r.violations.empty() ? "" : format(r.violations[0], "out"));
  EXPECT_EQ(r.f_changes, 1u);
  const std::string ngc = "G4 P1 F100\nG1 X10\nM30\n";
  const Result feed = run(ngc, replace(ngc, "F100", "F90"));
  EXPECT_TRUE(feed.ok()) << (feed.violations.empty() ? "" : format(feed.violations[0], "out"));
  EXPECT_EQ(feed.f_changes, 1u);
}

// Issue 41: the input posted for a speed on analog output 0 (as
// linuxcnc-3axis-m67 writes it): the start keeps its S word with M68 beside
// it, the S word of line 8 becomes M67, lines 7 and 9 get one added.
std::string posted_m67(const std::string& input) {
  const auto speed = [&](int line, std::string value, gcode::SpeedForm form) {
    gcode::WordPatch patch{line_offset(input, line), 'S', std::move(value)};
    patch.form = form;
    return patch;
  };
  const std::vector<gcode::WordPatch> patches = {
      speed(5, "9870", gcode::SpeedForm::start),  {line_offset(input, 7), 'F', "750"},
      speed(7, "9500", gcode::SpeedForm::synced), speed(8, "11000", gcode::SpeedForm::synced),
      speed(9, "9000", gcode::SpeedForm::synced),
  };
  return gcode::patched(input, patches);
}

Options m67_options() {
  Options options;
  options.speed_output = 0;
  options.dialect.speed_output = 0;
  return options;
}

TEST(VerifyGcode, SpeedsOnTheAnalogOutputAreSpeedWords) {
  const std::string out = posted_m67(kInput);
  ASSERT_EQ(out.substr(line_offset(out, 5)),
            "S9870 M3 M68 E0 Q9870\nG0 X0 Y0 Z5\nG1 Z-1 F750 M67 E0 Q9500\n"
            "G1 X10.5 Y2 M67 E0 Q11000\nX20 Y4 M67 E0 Q9000 (edge)\nG0 Z5\nM5\nM30\n%\n");
  const Result r = verify_gcode(kInput, out, m67_options());
  EXPECT_TRUE(r.ok()) << (r.violations.empty() ? "" : format(r.violations[0], "out"));
  ASSERT_EQ(r.changes.size(), 6u);
  EXPECT_EQ(r.s_changes, 5u);
  const std::vector<std::string> described = {
      "S12000 -> S9870", "+ M68 E0 Q9870",          "F800 -> F750",
      "+ M67 E0 Q9500",  "S11000 -> M67 E0 Q11000", "+ M67 E0 Q9000"};
  const std::vector<std::uint32_t> lines = {5, 5, 7, 7, 8, 8 + 1};
  const std::vector<std::uint32_t> columns = {1, 10, 8, 13, 13, 8};
  for (std::size_t k = 0; k < described.size(); ++k) {
    EXPECT_EQ(describe(r.changes[k]), described[k]);
    EXPECT_EQ(r.changes[k].line, lines[k]) << described[k];
    EXPECT_EQ(r.changes[k].column, columns[k]) << described[k];
  }
  EXPECT_EQ(r.motions, 5u);
  // Posted again: the M67 words of the input are its speed words, their Q may change.
  const std::string again = replace(out, "Q11000", "Q10500");
  const Result r2 = verify_gcode(out, again, m67_options());
  EXPECT_TRUE(r2.ok());
  ASSERT_EQ(r2.changes.size(), 1u);
  EXPECT_EQ(describe(r2.changes[0]), "M67 E0 Q11000 -> M67 E0 Q10500");
}

TEST(VerifyGcode, SpeedOutputMutationsAreCaught) {
  const std::string out = posted_m67(kInput);
  const auto one = [&](const std::string& output, Code code, std::uint32_t line,
                       std::uint32_t column, const Options& options = m67_options()) {
    const Result r = verify_gcode(kInput, output, options);
    ASSERT_EQ(r.violation_count, 1u)
        << output << (r.violations.empty() ? "" : format(r.violations[0], "out"));
    EXPECT_EQ(r.violations[0].code, code) << format(r.violations[0], "out");
    EXPECT_EQ(r.violations[0].line, line) << format(r.violations[0], "out");
    EXPECT_EQ(r.violations[0].column, column) << format(r.violations[0], "out");
  };
  one(replace(out, "Q9500", "Q-9500"), Code::E7150, 7, 20);
  one(replace(out, "Q9500", "Q#1"), Code::E7150, 7, 20);
  // The motion changed along with the speed word.
  one(replace(out, "G1 X10.5 Y2 M67", "G1 X10.6 Y2 M67"), Code::E7103, 8, 4);
  // Another output is no speed word: an added M67 E1 is text the input lacks
  // (found at its blank).
  one(replace(out, "Z-1 F750 M67 E0 Q9500", "Z-1 F750 M67 E1 Q9500"), Code::E7106, 7, 12);
  // Verified without the profile's speed output: the M67/M68 words are named.
  Options plain;
  const Result r = verify_gcode(kInput, out, plain);
  EXPECT_EQ(r.violations.at(0).code, Code::E7151);
  EXPECT_EQ(r.violations.at(0).line, 5u);
  EXPECT_EQ(r.violations.at(0).column, 10u);
}

// A token the input's line lacks, where the rest lines up around it, is
// named at its column; a run of them at the line's end as one text.
TEST(VerifyGcode, TokenAdded) {
  // Line 6 "G0 X0 Y0 Z5": M8 at column 10, before Z5. (Its coolant event is
  // news on a line the lexical proof flagged already: not named again.)
  expect_one(replace(posted(kInput), "G0 X0 Y0 Z5", "G0 X0 Y0 M8 Z5"), Code::E7104, 6, 10);
  // Line 11 "M5": a comment right after it (column 3), then two.
  Result r = run(kInput, replace(posted(kInput), "M5\n", "M5(stop)\n"));
  ASSERT_EQ(r.violation_count, 1u);
  EXPECT_EQ(format(r.violations[0], "out"),
            "out:11:3: error[E7104]: comment '(stop)' added (input line 11)");
  r = run(kInput, replace(posted(kInput), "M5\n", "M5(stop)(now)\n"));
  ASSERT_EQ(r.violation_count, 1u);
  EXPECT_EQ(format(r.violations[0], "out"),
            "out:11:3: error[E7104]: '(stop)(now)' added (input line 11)");
}

// The interpreted proof alone: a Sinumerik dwell in spindle turns (G4 S)
// lasts 60 * turns / rpm seconds, so a legitimate new speed before it
// makes another dwell (10 turns: 0.6 s at 1000 rpm, 0.3 s at 2000), found
// at the dwell's line though its bytes are the input's.
TEST(VerifyGcode, EventDiffersWhereTheTextIsTheInputsButItsSpeeds) {
  Options siemens;
  siemens.dialect = gcode::sinumerik_dialect();
  const std::string input = "S1000 M3\nG4 S10\nG1 X10 F500\nM30\n";
  const Result r = verify_gcode(input, replace(input, "S1000", "S2000"), siemens);
  ASSERT_EQ(r.violation_count, 1u) << format(r.violations[0], "out");
  EXPECT_EQ(r.violations[0].code, Code::E7121);
  EXPECT_EQ(r.violations[0].line, 2u);
  EXPECT_EQ(r.violations[0].column, 1u);
  EXPECT_EQ(r.violations[0].input_line, 2u);
  ASSERT_EQ(r.changes.size(), 1u);  // the S word itself is a change
  EXPECT_EQ(describe(r.changes[0]), "S1000 -> S2000");
}

// Lines added or removed: the events are compared in order, and one side
// running out of them is named where the other goes on (the output's
// line), or at no line when the output ends first.
TEST(VerifyGcode, EventCountDiffers) {
  // The output ends first: "1 line removed" at line 2, and the input's
  // second move has no counterpart (no output line: the end of the file).
  Result r = run("G0 X1\nG0 X2\n", "G0 X1\n");
  ASSERT_EQ(r.violation_count, 2u);
  EXPECT_EQ(r.violations[0].code, Code::E7122);
  EXPECT_EQ(r.violations[0].line, 0u);
  EXPECT_EQ(r.violations[0].input_line, 2u);
  EXPECT_EQ(r.violations[1].code, Code::E7101);
  EXPECT_EQ(r.violations[1].line, 2u);
  // The output goes on: its comment line 2 became lines 2..3, and the move
  // of line 4 is one the input lacks (a line the first proof did not name).
  r = run("G0 X1\n(a)\n", "G0 X1\n(b)\n(c)\nG0 X2\n");
  ASSERT_EQ(r.violation_count, 2u);
  EXPECT_EQ(r.violations[0].code, Code::E7101);
  EXPECT_EQ(r.violations[0].line, 2u);
  EXPECT_EQ(r.violations[1].code, Code::E7122);
  EXPECT_EQ(r.violations[1].line, 4u);
  EXPECT_EQ(r.violations[1].column, 1u);
  EXPECT_EQ(r.violations[1].input_line, 0u);
}

TEST(VerifyGcode, CrlfInsteadOfLf) {
  const std::string out = posted(kInput);
  std::string crlf;
  for (char c : out) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const Result r = run(kInput, crlf);
  ASSERT_EQ(r.violation_count, 13u);  // every line of 13
  for (std::uint32_t k = 0; k < 13; ++k) {
    EXPECT_EQ(r.violations[k].code, Code::E7102);
    EXPECT_EQ(r.violations[k].line, k + 1);
  }
  EXPECT_EQ(r.violations[1].column, 14u);  // after "(finish pass)"
}

TEST(VerifyGcode, MissingFinalNewline) {
  const std::string out = posted(kInput);
  expect_one(out.substr(0, out.size() - 1), Code::E7102, 13, 2);
}

TEST(VerifyGcode, OutputThatDoesNotInterpretButLooksEqualCannotExist) {
  // The interpreted proof catches what the lexical one would: a word
  // changed where the second reading agrees (both find line 8 only).
  const Result r = run(kInput, replace(posted(kInput), "Y2 S11000", "Y3 S11000"));
  ASSERT_EQ(r.violation_count, 1u);
  EXPECT_EQ(r.violations[0].line, 8u);
}

TEST(VerifyGcode, InputThatDoesNotReadIsAnInputError) {
  EXPECT_THROW(run("G1 X1 F100\nG2 X2\nM30\n", "G1 X1 F100\nG2 X2\nM30\n"), vcpost::Error);
}

TEST(VerifyGcode, FormatsAViolationWithItsCodeAndPlaces) {
  EXPECT_EQ(format(Violation{Code::E7109, 8, 12, 0, "S12000 removed"}, "out.nc"),
            "out.nc:8:12: error[E7109]: S12000 removed");
  EXPECT_EQ(format(Violation{Code::E7132, 4, 0, 17, "end point 0.2 mm off"}, "out.nc"),
            "out.nc:4: error[E7132]: end point 0.2 mm off (input line 17)");
}

TEST(VerifyGcode, ChangesStreamToTheCallbackInTheSameOrder) {
  const Result kept = run(kInput, posted(kInput));
  Options options;
  std::vector<Change> streamed;
  options.on_change = [&](const Change& c) { streamed.push_back(c); };
  const Result r = verify_gcode(kInput, posted(kInput), options);
  EXPECT_TRUE(r.changes.empty());
  EXPECT_EQ(r.s_changes, 3u);
  EXPECT_EQ(r.f_changes, 1u);
  ASSERT_EQ(streamed.size(), kept.changes.size());
  for (std::size_t k = 0; k < streamed.size(); ++k) {
    EXPECT_EQ(streamed[k].line, kept.changes[k].line);
    EXPECT_EQ(streamed[k].column, kept.changes[k].column);
    EXPECT_EQ(describe(streamed[k]), describe(kept.changes[k]));
  }
}

TEST(VerifyGcode, LineRemovedFromACrlfProgramKeepsTheTailPaired) {
  std::string input, out;
  for (char c : kInput) input += c == '\n' ? std::string("\r\n") : std::string(1, c);
  for (char c : posted(kInput)) out += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const Result r = run(input, replace(out, "T1 M6\r\n", ""));
  ASSERT_EQ(r.violation_count, 1u) << format(r.violations.back(), "out");
  EXPECT_EQ(r.violations[0].code, Code::E7101);
  EXPECT_EQ(r.violations[0].line, 4u);
  EXPECT_EQ(r.changes.size(), 4u);
  EXPECT_EQ(r.changes.front().line, 4u);  // the S12000 line moved up
}

TEST(VerifyLexer, LinesForwardAndBackwardAgree) {
  const std::string text = "a\r\n\nb\rc\nlast";
  const auto lines = split_lines(text);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(count_lines(text), 4u);
  EXPECT_EQ(count_lines(text + "\n"), 4u);
  EXPECT_EQ(count_lines(""), 0u);
  EXPECT_EQ(lines[2].text, "b\rc");  // a lone CR is no line end
  std::size_t end = text.size();
  for (std::uint32_t k = 4; k >= 1; --k) {
    Line line;
    end = line_before(text, end, k, line);
    EXPECT_EQ(line.text, lines[k - 1].text) << k;
    EXPECT_EQ(line.eol, lines[k - 1].eol) << k;
  }
  EXPECT_EQ(end, 0u);
}

TEST(VerifyLexer, FirstLineLongerThanTheLimitAsTheReaderCountsIt) {
  // Limit 4: the terminator and a CR before it do not count; a lone CR does.
  EXPECT_EQ(first_line_longer_than("abcd\r\nabcd\nabcd", 4), 0u);
  EXPECT_EQ(first_line_longer_than("abcd\nabcde\nx\n", 4), 2u);
  EXPECT_EQ(first_line_longer_than("ab\rcd\n", 4), 1u);
  EXPECT_EQ(first_line_longer_than("a\n\nabcdefgh", 4), 3u);  // the last line, no terminator
  EXPECT_EQ(first_line_longer_than("", 4), 0u);
  // A line too long in the input is refused as the reader refuses it; in
  // the output it is the one violation.
  const std::string long_line = "G1 X1" + std::string(70000, ' ') + "\n";
  try {
    run("G21\n" + long_line, "G21\nM30\n");
    ADD_FAILURE() << "accepted";
  } catch (const vcpost::Error& e) {
    EXPECT_EQ(e.code(), Code::E1006);
    EXPECT_STREQ(e.what(),
                 "input:2:1: error[E1006]: line longer than 65536 bytes, the reader's limit");
  }
  const Result r = run(kInput, "%\n" + long_line);
  ASSERT_EQ(r.violation_count, 1u);
  EXPECT_EQ(r.violations[0].code, Code::E7123);
  EXPECT_EQ(r.violations[0].line, 2u);
}

TEST(VerifyLexer, TokensCoverTheLineAndFindWords) {
  std::vector<Token> tokens;
  const std::string_view line = "N80G0X53.Y-56.128 S #<rpm> F[#1*2] (S100) #<f1>=2";
  tokenize(line, tokens);
  std::string joined;
  std::vector<std::string> words;
  for (const auto& t : tokens) {
    joined += t.text;
    if (t.kind == TokenKind::word) words.emplace_back(t.text);
  }
  EXPECT_EQ(joined, line);
  EXPECT_EQ(words,
            (std::vector<std::string>{"N80", "G0", "X53.", "Y-56.128", "S #<rpm>", "F[#1*2]"}));
  EXPECT_TRUE(is_plain_positive("9870"));
  EXPECT_TRUE(is_plain_positive("850.5"));
  EXPECT_TRUE(is_plain_positive(".5"));
  EXPECT_FALSE(is_plain_positive("0"));
  EXPECT_FALSE(is_plain_positive("0.0"));
  EXPECT_FALSE(is_plain_positive("-5"));
  EXPECT_FALSE(is_plain_positive("+5"));
  EXPECT_FALSE(is_plain_positive("5.5.5"));
  EXPECT_FALSE(is_plain_positive("."));
  EXPECT_FALSE(is_plain_positive("9 870"));
}

}  // namespace
}  // namespace vcpost::verify
