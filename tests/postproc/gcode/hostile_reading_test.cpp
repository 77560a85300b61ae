// The reader on hostile input (issue 42): values nested thousands deep,
// programs that would run for ever, and readings of Fanuc and Sinumerik
// constructs that differed from the control's. The cases rs274 decides are
// in rs274_hostile_test.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "postproc/gcode/interpreter.h"
#include "tests/postproc/cli_run_support.h"

namespace vcpost::gcode {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  std::vector<program::StraightTraverse> traverses;
  std::vector<program::StraightFeed> feeds;
  std::optional<Diagnostic> error;
  std::vector<Diagnostic> warnings;
  std::uint64_t lines_read = 0;
};

Outcome run(const std::string& text, const Dialect& dialect, InterpreterLimits limits = {}) {
  Interpreter interpreter(text, dialect, limits);
  Outcome out;
  std::vector<program::Event> events;
  try {
    while (interpreter.next(events)) {
      for (const auto& e : events) {
        if (const auto* t = std::get_if<program::StraightTraverse>(&e)) out.traverses.push_back(*t);
        if (const auto* f = std::get_if<program::StraightFeed>(&e)) out.feeds.push_back(*f);
      }
      events.clear();
    }
  } catch (const GcodeError& e) {
    out.error = e.diagnostic();
  }
  out.warnings = interpreter.warnings();
  out.lines_read = interpreter.lines_read();
  return out;
}

std::string code_of(const Outcome& o) {
  return o.error ? std::string(to_string(o.error->code)) : std::string("none");
}

// ---- values nested deep ----------------------------------------------------

// Each chain in the dialect that writes it: 50,000 signs or '#' recursed
// once a character, past any stack.
struct Chain {
  const char* name;
  Dialect dialect;
  std::string program;
};

std::vector<Chain> chains() {
  const std::string minus(50'000, '-'), plus(50'000, '+'), hashes(50'000, '#');
  return {
      {"rs274ngc X---1", rs274ngc_dialect(), "G0 X" + minus + "1\nM2\n"},
      {"rs274ngc X+++1", rs274ngc_dialect(), "G0 X" + plus + "1\nM2\n"},
      {"rs274ngc X###1", rs274ngc_dialect(), "G0 X" + hashes + "1\nM2\n"},
      {"fanuc #1=---1", fanuc_dialect(), "#1=" + minus + "1\nM30\n"},
      {"fanuc X###1", fanuc_dialect(), "G0 X" + hashes + "1\nM30\n"},
      {"sinumerik X=---1", sinumerik_dialect(), "G0 X=" + minus + "1\nM30\n"},
      {"sinumerik R1=---1", sinumerik_dialect(), "R1=" + minus + "1\nM30\n"},
  };
}

TEST(HostileReading, SignAndParameterChainsAreRefusedAsNestedTooDeep) {
  for (const Chain& c : chains()) {
    SCOPED_TRACE(c.name);
    const Outcome o = run(c.program, c.dialect);
    EXPECT_EQ(code_of(o), "E1201");
    ASSERT_TRUE(o.error);
    EXPECT_NE(o.error->message.find("nested more than 100 deep"), std::string::npos);
  }
  // A hundred levels still read: 100 signs ("X--...-1" with an even count is 1).
  const Outcome o = run("G0 X" + std::string(98, '-') + "1\nM2\n", rs274ngc_dialect());
  EXPECT_EQ(code_of(o), "none");
  ASSERT_EQ(o.traverses.size(), 1u);
  EXPECT_DOUBLE_EQ(o.traverses[0].end.x(), 1.0);
}

// The binary as a user runs it, with a 1 MB stack (a thread's, or a
// shell's `ulimit -s 1024`): moves, verify and post refuse each chain with
// E1201 (a crash was SIGSEGV, exit 139 from the shell).
class HostileCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vcpost_hostile_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  testing::CliOutcome run_small_stack(const std::string& arguments) const {
    return testing::run_vcpost(arguments, dir_, "ulimit -s 1024 && ");
  }
  fs::path dir_;
};

const char* dialect_name(const Dialect& d) {
  switch (d.kind) {
    case machines::Dialect::fanuc:
      return "fanuc";
    case machines::Dialect::sinumerik:
      return "sinumerik";
    default:
      return "rs274ngc";
  }
}

TEST_F(HostileCli, ChainsGiveE1201UnderAOneMegabyteStack) {
  const std::string samples = std::string(VCPOST_SOURCE_DIR) + "/samples";
  bool posted = false;
  for (const Chain& c : chains()) {
    SCOPED_TRACE(c.name);
    std::ofstream(dir_ / "chain.nc", std::ios::binary) << c.program;
    const std::string dialect = std::string(" --dialect ") + dialect_name(c.dialect);
    const auto moves = run_small_stack("moves chain.nc" + dialect);
    EXPECT_EQ(moves.exit_code, 2) << moves.err;
    EXPECT_NE(moves.err.find("chain.nc:1:"), std::string::npos) << moves.err;
    EXPECT_NE(moves.err.find("E1201"), std::string::npos) << moves.err;
    const auto verify = run_small_stack("verify chain.nc chain.nc" + dialect);
    EXPECT_EQ(verify.exit_code, 2) << verify.err;
    EXPECT_NE(verify.err.find("E1201"), std::string::npos) << verify.err;
    if (posted) continue;  // post reads as moves does: one chain is enough
    posted = true;
    const auto post =
        run_small_stack("post chain.nc" + dialect + " --model '" + samples +
                        "/wavy.step' --tool ball:10 --vc 120 --ap 0.3 --ae 2 -o out.nc");
    EXPECT_EQ(post.exit_code, 2) << post.err;
    EXPECT_NE(post.err.find("E1201"), std::string::npos) << post.err;
    EXPECT_FALSE(fs::exists(dir_ / "out.nc"));
  }
}

// ---- programs that would run for ever ----------------------------------------

TEST(HostileReading, TheBlocksAProgramRunsAreBoundedByDefault) {
  // Far above the longest real programs (tens of millions of blocks).
  EXPECT_EQ(InterpreterLimits{}.max_blocks, 100'000'000u);
  // 40 Fanuc programs each calling the next twice (2^39 calls, no loop, 40
  // levels): the bound ends it (here lowered to keep the test fast).
  std::string text = "O1\nM98 P2\nM30\n";
  for (int i = 2; i <= 41; ++i)
    text += "O" + std::to_string(i) + "\n" +
            (i < 41 ? "M98 P" + std::to_string(i + 1) + "\nM98 P" + std::to_string(i + 1) + "\n"
                    : std::string("G91 G0 X1\nG90\n")) +
            "M99\n";
  InterpreterLimits limits;
  limits.max_blocks = 200'000;
  const Outcome o = run(text, fanuc_dialect(), limits);
  EXPECT_EQ(code_of(o), "E1309");
  EXPECT_EQ(o.lines_read, 200'001u);
}

TEST(HostileReading, ARepeatThatWouldPassTheBoundIsRefusedAfterItsFirstPass) {
  std::string text = "F100\no100 repeat [9000000]\n";
  for (int i = 0; i < 50; ++i) text += "G1 X" + std::to_string(i % 7) + "\n";
  text += "o100 endrepeat\nM2\n";
  const Outcome o = run(text, rs274ngc_dialect());
  EXPECT_EQ(code_of(o), "E1309");
  ASSERT_TRUE(o.error);
  EXPECT_EQ(o.error->line, 53u);   // the endrepeat
  EXPECT_EQ(o.feeds.size(), 50u);  // one pass ran
  EXPECT_NE(o.error->message.find("8999999 more passes of 51 lines"), std::string::npos)
      << o.error->message;
  // 2000 passes (102,000 blocks) run.
  std::string small = text;
  small.replace(small.find("9000000"), 7, "2000");
  EXPECT_EQ(code_of(run(small, rs274ngc_dialect())), "none");
}

TEST(HostileReading, NestedM98RepeatsAreCountedByTheLoopAndBlockLimits) {
  // L9999 three deep: 1e12 passes. The middle level's first pass (about
  // 20,000 lines) shows 9,998 more would pass the bound.
  const std::string nested =
      "O1\nM98 P2 L9999\nM30\nO2\nM98 P3 L9999\nM99\nO3\nM98 P4 L9999\nM99\nO4\nG91 G0 X1\nG90\n"
      "M99\n";
  const Outcome o = run(nested, fanuc_dialect());
  EXPECT_EQ(code_of(o), "E1309");
  EXPECT_LT(o.lines_read, 100'000u);
  // Each M98 pass counts against the iteration limit, as a while's does.
  InterpreterLimits limits;
  limits.max_loop_iterations = 100;
  const std::string repeated = "O1\nM98 P99992000\nM30\nO2000\nG91 G0 X1\nG90\nM99\n";
  const Outcome counted = run(repeated, fanuc_dialect(), limits);
  EXPECT_EQ(code_of(counted), "E1307");
  EXPECT_EQ(counted.traverses.size(), 101u);
}

// ---- Fanuc M98 L and G65 -----------------------------------------------------

TEST(HostileReading, FanucM98LCountsPasses) {
  const std::string body = "M30\nO2000\nG91 G0 X1.\nG90\nM99\n";
  const Outcome none = run("O1\nM98 P2000 L0\n" + body, fanuc_dialect());
  EXPECT_EQ(code_of(none), "none");
  EXPECT_EQ(none.traverses.size(), 0u);
  const Outcome three = run("O1\nM98 P2000 L3\n" + body, fanuc_dialect());
  ASSERT_EQ(three.traverses.size(), 3u);
  EXPECT_DOUBLE_EQ(three.traverses[2].end.x(), 3.0);
  for (const char* bad : {"L-5", "L2.7"}) {
    SCOPED_TRACE(bad);
    const Outcome o = run(std::string("O1\nM98 P2000 ") + bad + "\n" + body, fanuc_dialect());
    EXPECT_EQ(code_of(o), "E1511");
  }
}

TEST(HostileReading, G65RunsAProgramOfTheFileWithItsArgumentsAsLocals) {
  const Outcome o =
      run("O1\nG0 X0. Y0.\nG65 P2000 X5. Y7.\nG0 X1.\nM30\nO2000\nG1 X#24 Y#25 F100.\nM99\n",
          fanuc_dialect());
  EXPECT_EQ(code_of(o), "none");
  ASSERT_EQ(o.feeds.size(), 1u);
  EXPECT_DOUBLE_EQ(o.feeds[0].end.x(), 5.0);
  EXPECT_DOUBLE_EQ(o.feeds[0].end.y(), 7.0);
  ASSERT_EQ(o.traverses.size(), 2u);
  EXPECT_DOUBLE_EQ(o.traverses[1].end.x(), 1.0);
  EXPECT_DOUBLE_EQ(o.traverses[1].end.y(), 7.0);
  // A, B and C are arguments #1, #2, #3; L passes; the caller's locals return.
  const Outcome abc =
      run("O1\n#1=9.\nG65 P2000 A1. B2. C0.5 L2\nG0 X#1\nM30\nO2000\nG91 G1 X#1 Y#2 Z#3 F100.\n"
          "G90\nM99\n",
          fanuc_dialect());
  EXPECT_EQ(code_of(abc), "none");
  ASSERT_EQ(abc.feeds.size(), 2u);
  EXPECT_DOUBLE_EQ(abc.feeds[1].end.x(), 2.0);
  EXPECT_DOUBLE_EQ(abc.feeds[1].end.y(), 4.0);
  EXPECT_DOUBLE_EQ(abc.feeds[1].end.z(), 1.0);
  ASSERT_EQ(abc.traverses.size(), 1u);
  EXPECT_DOUBLE_EQ(abc.traverses[0].end.x(), 9.0);
}

TEST(HostileReading, G65OfAMacroElsewhereTakesABCAsArguments) {
  const Outcome o = run("O1\nG65 P9010 A1. B2.\nG0 X1.\nM30\n", fanuc_dialect());
  EXPECT_EQ(code_of(o), "none");
  ASSERT_EQ(o.warnings.size(), 1u);
  EXPECT_EQ(o.warnings[0].code, Code::W1306);
  // Elsewhere A is still an axis.
  EXPECT_EQ(code_of(run("O1\nG0 A1.\nM30\n", fanuc_dialect())), "E1506");
}

// ---- Sinumerik R parameters --------------------------------------------------

TEST(HostileReading, SinumerikAssignsInTheOrderWritten) {
  const Outcome o =
      run("R1=5 R2=R1*2 G0 X=R2\nR1=7 G0 X=R1 Y=R2\nG0 X=R1+R2\nM30\n", sinumerik_dialect());
  EXPECT_EQ(code_of(o), "none");
  ASSERT_EQ(o.traverses.size(), 3u);
  EXPECT_DOUBLE_EQ(o.traverses[0].end.x(), 10.0);
  EXPECT_DOUBLE_EQ(o.traverses[1].end.x(), 7.0);
  EXPECT_DOUBLE_EQ(o.traverses[1].end.y(), 10.0);
  EXPECT_DOUBLE_EQ(o.traverses[2].end.x(), 17.0);
}

TEST(HostileReading, AnRParameterBeyondTheLastIsNamed) {
  for (const char* text : {"R1234567=5\nM30\n", "G0 X=R1234567\nM30\n"}) {
    SCOPED_TRACE(text);
    const Outcome o = run(text, sinumerik_dialect());
    EXPECT_EQ(code_of(o), "E1203");
    ASSERT_TRUE(o.error);
    EXPECT_NE(o.error->message.find("R1234567 is beyond R99999"), std::string::npos)
        << o.error->message;
  }
}

// ---- the closing '%' ---------------------------------------------------------

TEST_F(HostileCli, LinesAfterTheClosingPercentAreNamedAndFailStrict) {
  // The sample raster (it opens with '%'), closed by a '%' after line 100.
  const std::string samples = std::string(VCPOST_SOURCE_DIR) + "/samples";
  std::istringstream raster(testing::slurp(samples + "/wavy_raster_a0_ae2.nc"));
  std::string program, line;
  for (int n = 1; n <= 200 && std::getline(raster, line); ++n)
    program += line + "\n" + (n == 100 ? "%\n" : "");
  std::ofstream(dir_ / "in.nc", std::ios::binary) << program;
  const std::string warning =
      "in.nc:101:1: warning[W1311]: 100 lines after the closing '%' (from line 102) are not read";
  const auto moves = testing::run_vcpost("moves in.nc", dir_);
  EXPECT_EQ(moves.exit_code, 0) << moves.err;
  EXPECT_NE(moves.err.find(warning), std::string::npos) << moves.err;
  const std::string post = "post in.nc --model '" + samples +
                           "/wavy.step' --tool ball:10 --vc 120 --ap 0.3 --ae 2 -o out.nc";
  const auto posted = testing::run_vcpost(post, dir_);
  EXPECT_EQ(posted.exit_code, 0) << posted.err;
  EXPECT_NE(posted.err.find(warning), std::string::npos) << posted.err;
  fs::remove(dir_ / "out.nc");
  const auto strict = testing::run_vcpost(post + " --strict", dir_);
  EXPECT_EQ(strict.exit_code, 1) << strict.err;
  EXPECT_NE(strict.err.find(warning), std::string::npos) << strict.err;
  EXPECT_FALSE(fs::exists(dir_ / "out.nc"));
}

// A cut with the spindle stopped (M5 or S0 before it) is named with the
// line of its first point and fails --strict; the same program with the
// spindle turning has no such warning.
TEST_F(HostileCli, CutsWithTheSpindleStoppedAreNamedAndFailStrict) {
  const std::string samples = std::string(VCPOST_SOURCE_DIR) + "/samples";
  const std::string post =
      "--model '" + samples + "/wavy.step' --tool ball:10 --vc 120 --ap 0.3 --ae 2 -o out.nc";
  for (const std::string stop : {"M5", "S0"}) {
    std::istringstream raster(testing::slurp(samples + "/wavy_raster_a0_ae2.nc"));
    std::string program, line;
    // Line 101 stops the spindle; line 102 is the next cutting move.
    for (int n = 1; std::getline(raster, line); ++n)
      program += line + "\n" + (n == 100 ? stop + "\n" : "");
    std::ofstream(dir_ / "in.nc", std::ios::binary) << program;
    const auto posted = testing::run_vcpost("post in.nc " + post, dir_);
    EXPECT_EQ(posted.exit_code, 0) << posted.err;
    EXPECT_NE(posted.err.find("in.nc:102: W2030: "), std::string::npos) << stop << posted.err;
    fs::remove(dir_ / "out.nc");
    const auto strict = testing::run_vcpost("post in.nc --strict " + post, dir_);
    EXPECT_EQ(strict.exit_code, 1) << strict.err;
    EXPECT_FALSE(fs::exists(dir_ / "out.nc"));
  }
  std::ofstream(dir_ / "in.nc", std::ios::binary)
      << testing::slurp(samples + "/wavy_raster_a0_ae2.nc");
  const auto turning = testing::run_vcpost("post in.nc --strict " + post, dir_);
  EXPECT_EQ(turning.exit_code, 0) << turning.err;
  EXPECT_EQ(turning.err.find("W2030"), std::string::npos) << turning.err;
}

// A --vc or --fz beyond the machine clamps every point: said (W2031 with
// the spindle's highest or lowest speed, W2032 for F), and --strict fails;
// the nominal vc clamps a part of the time only and says nothing.
TEST_F(HostileCli, AProgramClampedWholeByTheMachineIsNamed) {
  const std::string samples = std::string(VCPOST_SOURCE_DIR) + "/samples";
  const std::string post = "post '" + samples + "/wavy_raster_a0_ae2.nc' --model '" + samples +
                           "/wavy.step' --tool ball:10 --ap 0.3 --ae 2 -o out.nc ";
  const auto fast = testing::run_vcpost(post + "--vc 1e9", dir_);
  EXPECT_EQ(fast.exit_code, 0) << fast.err;
  EXPECT_NE(fast.err.find("W2031: the spindle's highest speed decides S on 100 % of the cutting "
                          "time: vc 1e+09 m/min"),
            std::string::npos)
      << fast.err;
  const auto slow = testing::run_vcpost(post + "--vc 1e-3 --strict", dir_);
  EXPECT_EQ(slow.exit_code, 1) << slow.err;
  EXPECT_NE(slow.err.find("W2031: the spindle's lowest speed"), std::string::npos) << slow.err;
  const auto feed = testing::run_vcpost(post + "--vc 120 --adjust-feed --fz 1e-9", dir_);
  EXPECT_EQ(feed.exit_code, 0) << feed.err;
  EXPECT_NE(feed.err.find("W2032: the machine's feed limit (f_min or f_max) decides F on 100 %"),
            std::string::npos)
      << feed.err;
  const auto nominal = testing::run_vcpost(post + "--vc 120 --adjust-feed", dir_);
  EXPECT_EQ(nominal.exit_code, 0) << nominal.err;
  EXPECT_EQ(nominal.err.find("W203"), std::string::npos) << nominal.err;
}

// Old Mac line ends (CR alone) are named at the first one, in every
// command that reads a program; CRLF reads as before.
TEST_F(HostileCli, LoneCarriageReturnLineEndsAreRefused) {
  std::ofstream(dir_ / "cr.nc", std::ios::binary) << "G21 G90\rG0 X1\rG1 X2 F100\rM2\r";
  for (const std::string command : {"moves cr.nc", "verify cr.nc cr.nc"}) {
    const auto run = testing::run_vcpost(command, dir_);
    EXPECT_EQ(run.exit_code, 2) << command << run.err;
    EXPECT_NE(run.err.find("cr.nc:1:8: error[E2033]: the lines end with a lone CR"),
              std::string::npos)
        << run.err;
  }
  std::ofstream(dir_ / "crlf.nc", std::ios::binary) << "G21 G90\r\nG0 X1\r\nM2\r\n";
  const auto crlf = testing::run_vcpost("moves crlf.nc", dir_);
  EXPECT_EQ(crlf.exit_code, 0) << crlf.err;
}

// A model with no extent (a STEP whose length unit is LENGTH_MEASURE(0.),
// a mesh of one triangle shrunk to a point) is named as such, not as a
// path that never touches it.
TEST_F(HostileCli, AModelWithoutExtentIsRefused) {
  const std::string samples = std::string(VCPOST_SOURCE_DIR) + "/samples";
  std::string step = testing::slurp(samples + "/dome.step");
  const std::string unit = "#68 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );";
  ASSERT_NE(step.find(unit), std::string::npos);
  step.replace(step.find(unit), unit.size(),
               "#68 = ( CONVERSION_BASED_UNIT('ZERO',#300) LENGTH_UNIT() NAMED_UNIT(#302) );\n"
               "#300 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(0.),#301);\n"
               "#301 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\n"
               "#302 = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);");
  std::ofstream(dir_ / "zero.step", std::ios::binary) << step;
  std::ofstream(dir_ / "point.stl", std::ios::binary)
      << "solid p\nfacet normal 0 0 1\nouter loop\nvertex 1 1 1\nvertex 1.0001 1 1\n"
         "vertex 1 1.0001 1\nendloop\nendfacet\nendsolid p\n";
  for (const std::string model : {"zero.step", "point.stl"}) {
    const auto run = testing::run_vcpost("post '" + samples + "/dome_raster_a0_ae3.nc' --model " +
                                             model + " --tool ball:10 --vc 120 --ap 0.3 -o out.nc",
                                         dir_);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_NE(run.err.find("'" + model + "': the model has no extent"), std::string::npos)
        << run.err;
  }
}

}  // namespace
}  // namespace vcpost::gcode
