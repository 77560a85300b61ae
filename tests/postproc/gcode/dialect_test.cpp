// Dialect features against hand-worked expectations: Fanuc/ISO numbers
// without a decimal point under both settings, M98/M99 subprograms in one
// file, Mazak EIA codes and macros, and word columns and spans with blanks
// inside words.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "postproc/gcode/block.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/program/transcript.h"

namespace vcpost::gcode {
namespace {

// The transcript of the motion events of a program (rs274 vocabulary).
std::string moves(std::string_view text, const Dialect& dialect) {
  Interpreter interpreter(text, dialect);
  std::vector<program::Event> events;
  std::string out;
  while (interpreter.next(events)) {
    for (const auto& e : events)
      if (program::is_motion(e)) program::append_transcript(out, e);
    events.clear();
  }
  return out;
}

std::vector<program::Event> all_events(std::string_view text, const Dialect& dialect) {
  Interpreter interpreter(text, dialect);
  std::vector<program::Event> events;
  while (interpreter.next(events)) {
  }
  return events;
}

Diagnostic error_of(std::string_view text, const Dialect& dialect) {
  try {
    moves(text, dialect);
  } catch (const GcodeError& e) {
    return e.diagnostic();
  }
  ADD_FAILURE() << "no error";
  return {};
}

// ---- Fanuc/ISO numbers without a decimal point ----------------------------

// Issue 41: with a speed output (a profile's output.speed_word "M67 E0"),
// M67/M68 E0 Q is the spindle speed, as an S word; other outputs, and every
// output without it, set nothing vcpost follows. E is a word of LinuxCNC's.
TEST(SpeedOutput, M67AndM68OnTheSpeedOutputSetTheSpindleSpeed) {
  const std::string text =
      "S4000 M3 M68 E0 Q4000\nG1 X1 F100 M67 E0 Q5000\nM67 E1 Q7\nG1 X2 M67 E0 Q0\nM2\n";
  const auto speeds = [&](const Dialect& dialect) {
    std::vector<std::pair<double, std::uint32_t>> out;  // rpm, line
    for (const auto& e : all_events(text, dialect))
      if (const auto* s = std::get_if<program::SetSpindleSpeed>(&e))
        out.emplace_back(s->rpm, s->source.line);
    return out;
  };
  Dialect dialect = rs274ngc_dialect();
  using Speeds = std::vector<std::pair<double, std::uint32_t>>;
  EXPECT_EQ(speeds(dialect), (Speeds{{4000, 1}}));  // S only
  dialect.speed_output = 0;
  EXPECT_EQ(speeds(dialect), (Speeds{{4000, 1}, {4000, 1}, {5000, 2}, {0, 4}}));
  dialect.speed_output = 1;
  EXPECT_EQ(speeds(dialect), (Speeds{{4000, 1}, {7, 3}}));
  // The moves are the same whichever output carries the speed.
  EXPECT_EQ(moves(text, rs274ngc_dialect()), moves(text, dialect));
  // An E word no M66-M68 uses is refused, as rs274 does.
  EXPECT_EQ(error_of("G1 X1 E5 F100\nM2\n", rs274ngc_dialect()).code, Code::E1009);
}

TEST(FanucNumbers, IntegersAreLeastIncrementsByDefault) {
  // Increment 0.001 mm: X1000 = 1 mm, Y-2500 = -2.5 mm; Z1. has a point: 1 mm.
  EXPECT_EQ(moves("G21 G90\nG0 X1000 Y-2500 Z1.\nM30\n", fanuc_dialect()),
            "STRAIGHT_TRAVERSE(1.0000, -2.5000, 1.0000, 0.0000, 0.0000, 0.0000)\n");
}

TEST(FanucNumbers, IntegersAreMillimetresWithTheUnitsSetting) {
  Dialect d = fanuc_dialect();
  d.integer_lengths = IntegerLengths::units;
  EXPECT_EQ(moves("G21 G90\nG0 X1000 Y-2500 Z1.\nM30\n", d),
            "STRAIGHT_TRAVERSE(1000.0000, -2500.0000, 1.0000, 0.0000, 0.0000, 0.0000)\n");
  // RS274NGC never scales.
  EXPECT_EQ(moves("G21 G90\nG0 X1000\nM2\n", rs274ngc_dialect()),
            "STRAIGHT_TRAVERSE(1000.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n");
}

TEST(FanucNumbers, InchIncrementsArcWordsAndUnscaledWords) {
  // G20: increment 0.0001 inch, X10000 = 1 inch = 25.4 mm.
  EXPECT_EQ(moves("G20 G90\nG0 X10000 Y5000\nM30\n", fanuc_dialect()),
            "STRAIGHT_TRAVERSE(25.4000, 12.7000, 0.0000, 0.0000, 0.0000, 0.0000)\n");
  // I/J and R are lengths too: from X0, G2 X2000 I1000 = half circle of
  // radius 1 mm about (1, 0); R1000 = R 1 mm, same arc back (G2 clockwise).
  // F1000 and S5000 are no lengths: 1000 mm/min, 5000 rpm.
  const std::string text =
      "G21 G90 G17\nS5000 M3\nG0 X0 Y0\nG2 X2000 Y0 I1000 J0 F1000\n"
      "G2 X0 Y0 R1000\nM30\n";
  EXPECT_EQ(moves(text, fanuc_dialect()),
            "STRAIGHT_TRAVERSE(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "ARC_FEED(2.0000, 0.0000, 1.0000, 0.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "ARC_FEED(0.0000, 0.0000, 1.0000, 0.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)\n");
  const auto events = all_events(text, fanuc_dialect());
  bool feed = false, speed = false;
  for (const auto& e : events) {
    if (const auto* f = std::get_if<program::SetFeedRate>(&e); f && f->rate > 0) {
      EXPECT_DOUBLE_EQ(f->rate, 1000.0);
      feed = true;
    }
    if (const auto* sp = std::get_if<program::SetSpindleSpeed>(&e)) {
      EXPECT_DOUBLE_EQ(sp->rpm, 5000.0);
      speed = true;
    }
  }
  EXPECT_TRUE(feed && speed);
}

TEST(FanucNumbers, MacroValuesAndDwell) {
  // A value computed by a macro is a number of mm, not of increments.
  EXPECT_EQ(moves("G21 G90\n#1 = 1000\nG0 X#1 Y[#1 / 4]\nM30\n", fanuc_dialect()),
            "STRAIGHT_TRAVERSE(1000.0000, 250.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n");
  // G04 P1500 = 1500 ms; G04 X2.5 = 2.5 s.
  const auto events = all_events("G04 P1500\nG04 X2.5\nM30\n", fanuc_dialect());
  std::vector<double> dwells;
  for (const auto& e : events)
    if (const auto* d = std::get_if<program::Dwell>(&e)) dwells.push_back(d->seconds);
  ASSERT_EQ(dwells.size(), 2u);
  EXPECT_DOUBLE_EQ(dwells[0], 1.5);
  EXPECT_DOUBLE_EQ(dwells[1], 2.5);
}

// ---- M98/M99 subprograms: Fanuc O-number programs in one file -------------

constexpr const char* kFanucSubs =
    "%\n"
    "O1000 (MAIN)\n"
    "G21 G90 G17\n"
    "G0 X0. Y0. Z5.\n"
    "G1 Z0. F500.\n"
    "M98 P2000 L2\n"
    "M98 P3000\n"
    "G0 Z5.\n"
    "M30\n"
    "O2000 (10 MM STEP IN X)\n"
    "G91 G1 X10.\n"
    "G90\n"
    "M99\n"
    "O3000 (NESTED: ONE STEP IN Y, THEN O2000 ONCE)\n"
    "G91 G1 Y5.\n"
    "G90\n"
    "M98 P2000\n"
    "M99\n"
    "%\n";

TEST(FanucSubprograms, M98CallsWithRepetitionsAndNesting) {
  EXPECT_EQ(moves(kFanucSubs, fanuc_dialect()),
            "STRAIGHT_TRAVERSE(0.0000, 0.0000, 5.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(20.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(20.0000, 5.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(30.0000, 5.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(30.0000, 5.0000, 5.0000, 0.0000, 0.0000, 0.0000)\n");
  // Mazak reads the same file alike.
  EXPECT_EQ(moves(kFanucSubs, mazak_dialect()), moves(kFanucSubs, fanuc_dialect()));
}

TEST(FanucSubprograms, EventsKeepTheSubprogramsSourceLines) {
  const auto events = all_events(kFanucSubs, fanuc_dialect());
  std::vector<std::uint32_t> feed_lines;
  for (const auto& e : events)
    if (std::holds_alternative<program::StraightFeed>(e))
      feed_lines.push_back(program::source_of(e).line);
  // Z0 on line 5, then O2000's G1 (line 11) twice, O3000's G1 (line 15), O2000's again.
  EXPECT_EQ(feed_lines, (std::vector<std::uint32_t>{5, 11, 11, 15, 11}));
}

TEST(FanucSubprograms, ShortFormRepetitionsInP) {
  // Fanuc M98 P32000: O2000 three times (repetitions above the last four digits).
  const std::string text = "G21 G90\nG1 X0. F100.\nM98 P32000\nM30\nO2000\nG91 G1 X1.\nG90\nM99\n";
  EXPECT_EQ(moves(text, fanuc_dialect()),
            "STRAIGHT_FEED(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(2.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(3.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n");
}

TEST(FanucSubprograms, RefusedForms) {
  // A program not in this file.
  Diagnostic d = error_of("G21\nM98 P4711\nM30\n", fanuc_dialect());
  EXPECT_EQ(d.code, Code::E1302);
  EXPECT_EQ(d.line, 2u);
  // M99 P: return to a sequence number.
  d = error_of("G21\nM98 P2000\nM30\nO2000\nM99 P20\n", fanuc_dialect());
  EXPECT_EQ(d.code, Code::E1301);
  EXPECT_EQ(d.line, 5u);
  EXPECT_EQ(d.column, 5u);
}

// ---- Mazak EIA -------------------------------------------------------------

TEST(MazakEia, HighSpeedAndPathCodesAreAccepted) {
  const std::string text =
      "G21 G90 G17\n"
      "G05 P2 (high-speed machining mode on)\n"
      "G61.1 (geometry compensation)\n"
      "G0 X0 Y0 Z5.\n"
      "G1 Z0 F800.\n"
      "G1 X10.\n"
      "G05 P0\n"
      "G64\n"
      "M30\n";
  EXPECT_EQ(moves(text, mazak_dialect()),
            "STRAIGHT_TRAVERSE(0.0000, 0.0000, 5.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n");
}

TEST(MazakEia, G117AxisWordsAreAPositionNotAMove) {
  const std::string text = "G21 G90\nG1 X0 Y0 F500.\nG117 X5. Y0 M8\nG1 X10.\nM30\n";
  EXPECT_EQ(moves(text, mazak_dialect()),
            "STRAIGHT_FEED(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n");
  // S inside G117 would change the speed within the next move: refused.
  const Diagnostic d = error_of("G21\nG117 X5. S9000\nM30\n", mazak_dialect());
  EXPECT_EQ(d.code, Code::E1404);
  EXPECT_EQ(d.line, 2u);
  EXPECT_EQ(d.column, 10u);
}

TEST(MazakEia, MacrosAndIfThen) {
  const std::string text =
      "G21 G90\n"
      "#100 = 2.5\n"
      "#101 = #100 * 2 + 1 (Fanuc-style expression without brackets: 6)\n"
      "IF [#101 GT 4] THEN #102 = 1.\n"
      "IF [#101 LT 4] THEN #102 = 2.\n"
      "IF [#102 EQ 1] THEN\n"
      "G0 X#101 Y#102\n"
      "ELSE\n"
      "G0 X-1. Y-1.\n"
      "ENDIF\n"
      "IF [#1 EQ #0] THEN G0 Z[#101 / 3] (local #1 is vacant)\n"
      "M30\n";
  EXPECT_EQ(moves(text, mazak_dialect()),
            "STRAIGHT_TRAVERSE(6.0000, 1.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(6.0000, 1.0000, 2.0000, 0.0000, 0.0000, 0.0000)\n");
}

TEST(MazakEia, SharedMazakMacroIsRefusedWhereItReadsMachineState) {
  // ENSURE_TOOL_LENGTH.EIA (keycult/mazak-hcn) called without H: #11 is
  // vacant, the first IF is taken and writes alarm #3006 -> machine state.
  const std::string text =
      "IF [#11 EQ #0] THEN\n#3006 = 31 (MISSING*ARG*H)\nGOTO 9999\nENDIF\nM99\n";
  const Diagnostic d = error_of(text, mazak_dialect());
  EXPECT_EQ(d.code, Code::E1204);
  EXPECT_EQ(d.line, 2u);
}

// ---- Tokenizer: blanks inside words ----------------------------------------

TEST(Tokenizer, BlanksInsideWordsKeepColumnsAndSpans) {
  const std::string line = "N 10 G 1 X 10.5 Y1 0 . 2 5 Z - 3 F 2 00";
  Block b;
  read_block(line, 7, 0, fanuc_dialect(), Parameters(fanuc_dialect()), b);
  ASSERT_TRUE(b.n.has_value());
  EXPECT_EQ(*b.n, 10);
  ASSERT_EQ(b.words.size(), 5u);
  struct Expect {
    char letter;
    double value;
    std::uint32_t column;
    std::string_view text;
  };
  const Expect expect[] = {{'G', 1, 6, "G 1"},
                           {'X', 10.5, 10, "X 10.5"},
                           {'Y', 10.25, 17, "Y1 0 . 2 5"},
                           {'Z', -3, 28, "Z - 3"},
                           {'F', 200, 34, "F 2 00"}};
  for (std::size_t i = 0; i < 5; ++i) {
    SCOPED_TRACE(i);
    const Word& w = b.words[i];
    EXPECT_EQ(w.letter, expect[i].letter);
    EXPECT_DOUBLE_EQ(w.value, expect[i].value);
    EXPECT_EQ(w.column, expect[i].column);
    EXPECT_EQ(line.substr(w.begin, w.end - w.begin), expect[i].text);
  }
  // "Y1 0 . 2 5" has a point, "G 1" and "F 2 00" have none.
  EXPECT_TRUE(b.words[2].decimal_point);
  EXPECT_FALSE(b.words[4].decimal_point);
}

TEST(Tokenizer, CompactWordsLowerCaseAndCrLf) {
  const std::string text = "g21g90\r\nx10.4y10.444z-.5\r\nm30\r\n";
  EXPECT_EQ(moves("g0" + text.substr(8), rs274ngc_dialect()),
            "STRAIGHT_TRAVERSE(10.4000, 10.4440, -0.5000, 0.0000, 0.0000, 0.0000)\n");
  Block b;
  read_block("x10.4y10.444", 1, 0, rs274ngc_dialect(), Parameters(rs274ngc_dialect()), b);
  ASSERT_EQ(b.words.size(), 2u);
  EXPECT_EQ(b.words[1].letter, 'Y');
  EXPECT_EQ(b.words[1].column, 6u);
  EXPECT_EQ(b.words[1].begin, 5u);
  EXPECT_EQ(b.words[1].end, 12u);
}

TEST(Tokenizer, ErrorColumnsInsideBlankedWords) {
  // The second point of "X 1 . 2 . 3" is at column 9.
  const Diagnostic d = error_of("G1 X 1 . 2 . 3 F100\nM2\n", rs274ngc_dialect());
  EXPECT_EQ(d.code, Code::E1003);
  EXPECT_EQ(d.line, 1u);
  EXPECT_EQ(d.column, 12u);
}

}  // namespace
}  // namespace vcpost::gcode

// ---- Fanuc-like posts: safety lines, cycles beside G0/G1, machine codes -----

namespace vcpost::gcode {
namespace {

TEST(FanucPosts, SafetyLineAndProgramNumberAreRead) {
  const std::string text =
      "%\nO0001 (PART)\nN0008 G00 G40 G80 G90 G17 G21\nN1 G00 G17 G21 G40 G49 G80 G90\n"
      "G0 X1. Y2.\nM30\n%\n";
  for (const auto& d : {fanuc_dialect(), mazak_dialect(), rs274ngc_dialect()})
    EXPECT_EQ(moves(text, d),
              "STRAIGHT_TRAVERSE(1.0000, 2.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n");
}

TEST(FanucPosts, CycleLeavesTheG01ModeAndG80ReturnsToIt) {
  // Fanuc: G81 is group 09 beside G01 (group 01); after G80, X10. feeds at
  // the initial level (G98 retract, Fanuc's default).
  const std::string text = "G21 G90 G17\nG1 X0 Y0 Z5. F100.\nG81 X5. Y5. Z-1. R1.\nG80 X10.\nM30\n";
  EXPECT_EQ(moves(text, fanuc_dialect()),
            "STRAIGHT_FEED(0.0000, 0.0000, 5.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(5.0000, 5.0000, 5.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(5.0000, 5.0000, 1.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(5.0000, 5.0000, -1.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(5.0000, 5.0000, 5.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(10.0000, 5.0000, 5.0000, 0.0000, 0.0000, 0.0000)\n");
  // RS274NGC: G80 leaves no motion mode; axis words after it are an error.
  EXPECT_EQ(error_of(text, rs274ngc_dialect()).code, Code::E1508);
}

TEST(FanucPosts, MachineCodesWarnOnceAndMistWithFlood) {
  const std::string text =
      "G21 G90\nM9026\nG05.1 Q1\nG0 X1.\nM9026\nG05.1 Q0\nM08 M07\nG91 G28 Z0.\nG90\nM30\n";
  Interpreter interpreter(text, fanuc_dialect());
  std::vector<program::Event> events;
  while (interpreter.next(events)) {
  }
  // M9026 once, G5.1 once, G28's reference point once.
  ASSERT_EQ(interpreter.warning_count(), 3u);
  EXPECT_EQ(interpreter.warnings()[0].code, Code::W1402);
  EXPECT_EQ(interpreter.warnings()[1].code, Code::W1406);
  EXPECT_EQ(interpreter.warnings()[2].code, Code::W1509);
  int coolant = 0;
  for (const auto& e : events) coolant += std::holds_alternative<program::Coolant>(e);
  EXPECT_EQ(coolant, 2);
  // G91 G28 Z0.: through the current point (incremental 0) to Z = 0.
  EXPECT_EQ(moves(text, fanuc_dialect()),
            "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n");
}

TEST(FanucPosts, CodesThatMoveTheToolUnknowablyAreRefused) {
  for (const char* code : {"G68 X0 Y0 R30.", "G51 X0 Y0 P2000", "G51.1 X0", "G16"}) {
    SCOPED_TRACE(code);
    const Diagnostic d = error_of(std::string("G21\n") + code + "\nG0 X1.\nM30\n", fanuc_dialect());
    EXPECT_EQ(d.code, Code::E1404);
    EXPECT_EQ(d.line, 2u);
  }
}

TEST(FanucPosts, PeckCycleWithRepeatsInK) {
  // G91 G83 with K2: two holes 5 mm apart, pecks of 2 mm back to R, 0.254 mm
  // back-off (rs274's clearance), retract to the initial level (G98).
  const std::string text =
      "G21 G90\nG0 X0 Y0 Z3.\nG91 G83 X5. Z-4. R-2. Q2. K2 F100.\nG90 G80\nM30\n";
  const std::string m = moves(text, fanuc_dialect());
  EXPECT_NE(m.find("STRAIGHT_FEED(5.0000, 0.0000, -1.0000"), std::string::npos) << m;
  EXPECT_NE(m.find("STRAIGHT_TRAVERSE(5.0000, 0.0000, -0.7460"), std::string::npos) << m;
  EXPECT_NE(m.find("STRAIGHT_FEED(10.0000, 0.0000, -3.0000"), std::string::npos) << m;
  EXPECT_TRUE(m.ends_with("STRAIGHT_TRAVERSE(10.0000, 0.0000, 3.0000, 0.0000, 0.0000, 0.0000)\n"))
      << m;
}

}  // namespace
}  // namespace vcpost::gcode

// ---- Sinumerik 840D --------------------------------------------------------

namespace vcpost::gcode {
namespace {

TEST(Sinumerik, MessagesCrArcsRParametersAndToolWords) {
  const std::string text =
      "MSG(\"FINISHING\") ; operator message\n"
      "N10 G54 G40 G90 G17 G71\n"
      "N20 T1 D1\nN30 M6\n"
      "R1=2.5\nR2 = R1*2\n"
      "N40 G0 X=R2 Y0 S900 M3\n"
      "N50 G1 G642 Z=-R1+0.5 F150\n"
      "N60 G2 X15 Y0 CR=5 TURN=0\n"
      "N70 SOFT FFWON\n"
      "N80 G4 F0.5\n"
      "N90 M30\n";
  EXPECT_EQ(moves(text, sinumerik_dialect()),
            "STRAIGHT_TRAVERSE(5.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(5.0000, 0.0000, -2.0000, 0.0000, 0.0000, 0.0000)\n"
            "ARC_FEED(15.0000, 0.0000, 10.0000, 0.0000, -1, -2.0000, 0.0000, 0.0000, 0.0000)\n");
  int tools = 0, dwells = 0, messages = 0;
  for (const auto& e : all_events(text, sinumerik_dialect())) {
    tools += std::holds_alternative<program::SelectTool>(e) +
             std::holds_alternative<program::ChangeTool>(e);
    dwells += std::holds_alternative<program::Dwell>(e);
    messages += std::holds_alternative<program::Message>(e);
  }
  EXPECT_EQ(tools, 2);
  EXPECT_EQ(dwells, 1);
  EXPECT_EQ(messages, 1);
}

TEST(Sinumerik, ModalDrillingCycleRunsAtEveryPositionUntilMcall) {
  // CYCLE81(RTP 10, RFP 0, SDIS 2, DP -5): rapid to 2, feed to -5, rapid to 10.
  const std::string text =
      "G0 G90 G17 X0 Y0 Z20 S1000 M3\n"
      "MCALL CYCLE81(10,0,2,-5)\n"
      "X5 F100\n"
      "X10\n"
      "MCALL\n"
      "X20\n"
      "M30\n";
  EXPECT_EQ(moves(text, sinumerik_dialect()),
            "STRAIGHT_TRAVERSE(0.0000, 0.0000, 20.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(5.0000, 0.0000, 20.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(5.0000, 0.0000, 20.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(5.0000, 0.0000, 2.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(5.0000, 0.0000, -5.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(5.0000, 0.0000, 10.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(10.0000, 0.0000, 10.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(10.0000, 0.0000, 10.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(10.0000, 0.0000, 2.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(10.0000, 0.0000, -5.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(10.0000, 0.0000, 10.0000, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(20.0000, 0.0000, 10.0000, 0.0000, 0.0000, 0.0000)\n");
}

TEST(Sinumerik, FramesAndFlowAreRefusedAndOtherDialectsNameIt) {
  for (const char* line :
       {"ROT Z30", "TRANS X10", "MIRROR X0", "GOTOF LABEL1", "CYCLE800(1,\"TC\",0,192)"}) {
    SCOPED_TRACE(line);
    const Diagnostic d = error_of(std::string("G0 X0\n") + line + "\nM30\n", sinumerik_dialect());
    EXPECT_EQ(d.line, 2u);
    EXPECT_EQ(d.column, 1u);
  }
  // The same program read as RS274NGC or Fanuc: the error names the dialect.
  for (const auto& d : {rs274ngc_dialect(), fanuc_dialect()}) {
    const Diagnostic e = error_of("MSG(\"X\")\nG0 X1\nM30\n", d);
    EXPECT_EQ(e.code, Code::E1010);
    EXPECT_NE(e.message.find("--dialect sinumerik"), std::string::npos);
  }
}

}  // namespace
}  // namespace vcpost::gcode
