// CL hole cycles written as canned cycles (Format::canned_cycles): the
// blocks, and the moves rs274 and vcpost's own reader make of them compared
// with the CL reader's moves of the same holes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "postproc/gcode/dialect.h"
#include "postproc/output/gcode_writer.h"
#include "postproc/program/transcript.h"
#include "postproc/verify/verify.h"
#include "tests/postproc/cldata/cl_support.h"

namespace vcpost::output {
namespace {

namespace fs = std::filesystem;
using cldata::testing::Call;
using cldata::testing::cl_moves;
using cldata::testing::expect_same_moves;
using cldata::testing::first_violation;
using cldata::testing::motion_calls;
using cldata::testing::moves_only;
using cldata::testing::read_events;
using cldata::testing::verify_written;
using cldata::testing::write_gcode;

// One hole of every cycle kind; the tool starts at the return level Z20.
const char* const every_kind =
    "LOADTL/1\nSPINDL/1000,RPM,CLW\nRAPID\nGOTO/0,0,20\n"
    "CYCLE/DRILL,FEDTO,5,MMPM,100,RAPTO,2,RTRCTO,20\nGOTO/10,10,0\nGOTO/20,10,0\n"
    "CYCLE/DRILL,FEDTO,5,MMPM,100,RAPTO,2,RTRCTO,20,DWELL,1.5\nGOTO/30,10,0\n"
    "CYCLE/DEEP,FEDTO,10,STEP,3,MMPM,100,RAPTO,2,RTRCTO,20\nGOTO/40,10,0\n"
    "CYCLE/BRKCHP,FEDTO,10,STEP,3,MMPM,100,RAPTO,2,RTRCTO,20\nGOTO/50,10,0\n"
    "CYCLE/TAP,FEDTO,8,MMPR,1.5,RAPTO,3,RTRCTO,20\nGOTO/60,10,0\n"
    "CYCLE/BORE,FEDTO,10,MMPM,80,RAPTO,2,RTRCTO,20\nGOTO/70,10,0\n"
    "CYCLE/BORE6,FEDTO,10,MMPM,80,RAPTO,2,RTRCTO,20,DWELL,0.5\nGOTO/80,10,0\n"
    "CYCLE/BORE9,FEDTO,10,MMPM,80,RAPTO,2,DWELL,0.5,RTRCTO,20\nGOTO/90,10,0\n"
    "CYCLE/DRILL,FEDTO,5,MMPM,100,RAPTO,15\nGOTO/100,10,5\n"
    "CYCLE/OFF\nRAPID\nGOTO/0,0,50\nFINI\n";

Format rs274ngc_format() {
  Format f;
  f.program_number.reset();
  f.dwell = DwellWord::p_seconds;
  f.g83_pecks_out_to_r = false;
  f.canned_cycles = true;
  return f;
}

// Checked by hand against the CL: G98 where the cycle's last move out ends
// at the return level (G81 G82 G73 G85 G86), G99 and a G0 up where it
// ends at R (G84 G89; G83 in rs274, which pecks out to the G98 level),
// G99 alone where R is the return level.
TEST(CannedCycles, EveryKindAsItsCycleBlock) {
  const std::string expected =
      "%\n"
      "G21 G17 G40 G49 G80 G90 G94\n"
      "G54\n"
      "T1 M6\n"
      "S1000 M3\n"
      "G43 H1 G0 X0. Y0. Z20.\n"
      "G98 G81 X10. Y10. Z-5. R2. F100.\n"
      "X20. Y10.\n"
      "G80\n"
      "G98 G82 X30. Y10. Z-5. R2. P1.5\n"
      "G80\n"
      "G0 X40.\n"  // G83 here: its moves (rs274 would peck out to Z20)
      "Z2.\n"
      "G1 Z-1.\n"
      "G0 Z2.\n"
      "Z-0.746\n"
      "G1 Z-4.\n"
      "G0 Z2.\n"
      "Z-3.746\n"
      "G1 Z-7.\n"
      "G0 Z2.\n"
      "Z-6.746\n"
      "G1 Z-10.\n"
      "G0 Z20.\n"
      "G98 G73 X50. Y10. Z-10. R2. Q3.\n"
      "G80\n"
      "G95\n"
      "G99 G84 X60. Y10. Z-8. R3. P0. F1.5\n"
      "G80\n"
      "G0 Z20.\n"
      "G94\n"
      "G98 G85 X70. Y10. Z-10. R2. F80.\n"
      "G80\n"
      "G98 G86 X80. Y10. Z-10. R2. P0.5\n"
      "G80\n"
      "G99 G89 X90. Y10. Z-10. R2. P0.5\n"
      "G80\n"
      "G0 Z20.\n"
      "G99 G81 X100. Y10. Z0. R20. F100.\n"
      "G80\n"
      "G0 X0. Y0. Z50.\n"
      "M30\n"
      "%\n";
  EXPECT_EQ(write_gcode(every_kind, rs274ngc_format()), expected);
}

// The Fanuc/Mazak form: P in milliseconds, as an integer; G98 G83.
TEST(CannedCycles, FanucDwellInMilliseconds) {
  Format f;
  f.canned_cycles = true;
  const std::string program = write_gcode(every_kind, f);
  EXPECT_NE(program.find("G98 G82 X30. Y10. Z-5. R2. P1500\n"), std::string::npos) << program;
  EXPECT_NE(program.find("G98 G86 X80. Y10. Z-10. R2. P500\n"), std::string::npos) << program;
  // Fanuc's G98 G83 pecks out to R, as the CL cycle does.
  EXPECT_NE(program.find("G98 G83 X40. Y10. Z-10. R2. Q3.\n"), std::string::npos) << program;
}

// What no canned cycle makes exactly stays as moves: two peck depths, a
// tool above the hole's return level (the moves go down diagonally), a
// profile without cycles.
TEST(CannedCycles, HolesNoCycleMakesStayMoves) {
  const Format f = rs274ngc_format();
  const std::string two_pecks = write_gcode(
      "SPINDL/1000\nGOTO/0,0,20\nCYCLE/DEEP2,FEDTO,10,1STPECK,5,SUBPECK,2,MMPM,100,RAPTO,2,"
      "RTRCTO,20\nGOTO/10,0,0\nFINI\n",
      f);
  EXPECT_EQ(two_pecks.find("G8"), two_pecks.find("G80"));  // only the header's G80
  EXPECT_NE(two_pecks.find("G1 Z-3. F100.\n"), std::string::npos) << two_pecks;
  const std::string above = write_gcode(
      "SPINDL/1000\nGOTO/0,0,50\nCYCLE/DRILL,FEDTO,5,MMPM,100,RAPTO,2,RTRCTO,20\n"
      "GOTO/10,0,0\nFINI\n",
      f);
  EXPECT_EQ(above.find("G81"), std::string::npos) << above;
  EXPECT_NE(above.find("G0 X10. Z20.\n"), std::string::npos) << above;
  Format off = f;
  off.canned_cycles = false;
  const std::string moves = write_gcode(every_kind, off);
  for (const char* code : {"G73", "G81", "G82", "G83", "G84", "G85", "G86", "G89", "G98", "G99"})
    EXPECT_EQ(moves.find(code), std::string::npos) << code;
}

// A per-revolution feed before a hole whose cycle feeds per minute: the
// cycle's block reads its F per minute (G94 on a block of its own when G95
// was written), and the per-revolution feed comes back after it. Before, the
// unwritten G95 stayed in the cycle's block beside its G94 ("G98 G85 X60.
// Y30. Z-10. R2. G94 F150. G95": two codes of one modal group, refused by
// rs274 and by vcpost verify, E7123).
const char* const per_rev_then_cycle =
    "LOADTL/1\nSPINDL/1000,RPM,CLW\nRAPID\nGOTO/0,0,20\nFEDRAT/0.1,MMPR\n"
    "CYCLE/BORE,FEDTO,10,MMPM,150,RAPTO,2,RTRCTO,20\nGOTO/60,30,0\nCYCLE/OFF\n"
    "GOTO/0,0,15\nCYCLE/BORE,FEDTO,10,MMPM,150,RAPTO,2,RTRCTO,20\nGOTO/60,30,0\nCYCLE/OFF\n"
    "GOTO/0,0,20\nFINI\n";

TEST(CannedCycles, PerRevolutionFeedAroundAPerMinuteCycle) {
  const std::string expected =
      "%\n"
      "G21 G17 G40 G49 G80 G90 G94\n"
      "G54\n"
      "T1 M6\n"
      "S1000 M3\n"
      "G43 H1 G0 X0. Y0. Z20.\n"
      "G98 G85 X60. Y30. Z-10. R2. F150.\n"
      "G80\n"
      "G1 X0. Y0. Z15. G95 F0.1\n"
      "G0 Z20.\n"
      "G94\n"
      "G98 G85 X60. Y30. Z-10. R2. F150.\n"
      "G80\n"
      "G1 X0. Y0. G95 F0.1\n"
      "M30\n"
      "%\n";
  const std::string program = write_gcode(per_rev_then_cycle, rs274ngc_format());
  EXPECT_EQ(program, expected);
  for (const bool fanuc : {false, true}) {
    SCOPED_TRACE(fanuc ? "fanuc" : "rs274ngc");
    Format format = rs274ngc_format();
    if (fanuc) {
      format.program_number = 1000;
      format.dwell = DwellWord::x_seconds;
      format.g83_pecks_out_to_r = true;
    }
    const std::string text = write_gcode(per_rev_then_cycle, format);
    const verify::Result v = verify_written(per_rev_then_cycle, text, fanuc);
    EXPECT_TRUE(v.ok()) << first_violation(v) << "\n" << text;
  }
  if (!cldata::testing::have_rs274()) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const fs::path dir = fs::temp_directory_path() / ("vcpost_per_rev_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path nc = dir / "per_rev.ngc";
  std::ofstream(nc, std::ios::binary) << program;
  const auto rs274 = cldata::testing::run_rs274(nc.string());
  fs::remove_all(dir);
  ASSERT_TRUE(rs274);
  // rs274 reads it whole (it stops at the first error) with the feeds
  // the CL says: 0.1 mm/rev, 150 mm/min in the holes, 0.1 mm/rev again.
  EXPECT_NE(rs274->find("PROGRAM_END()"), std::string::npos) << *rs274;
  std::vector<std::string> modes;
  std::istringstream lines(*rs274);
  for (std::string line; std::getline(lines, line);) {
    if (const auto at = line.find("SET_FEED_MODE("); at != std::string::npos)
      modes.push_back(line.substr(at, line.find(')', at) + 1 - at));
  }
  EXPECT_EQ(modes, (std::vector<std::string>{"SET_FEED_MODE(0, 0)", "SET_FEED_MODE(0, 1)",
                                             "SET_FEED_MODE(0, 0)", "SET_FEED_MODE(0, 1)",
                                             "SET_FEED_MODE(0, 0)"}))
      << *rs274;
}

// rs274 makes of the cycles the moves the CL reader made of the holes, and
// vcpost's reader does too in both dialects (verify: same motion, spindle
// changes, S and F).
TEST(CannedCycles, Rs274AndVcpostReadTheClMoves) {
  for (const bool fanuc : {false, true}) {
    SCOPED_TRACE(fanuc ? "fanuc" : "rs274ngc");
    Format format = rs274ngc_format();
    if (fanuc) {
      format.program_number = 1000;
      format.dwell = DwellWord::x_seconds;
    }
    const std::string program = write_gcode(every_kind, format);
    verify::Options options;
    options.dialect = fanuc ? gcode::fanuc_dialect() : gcode::rs274ngc_dialect();
    const verify::Result v = verify::verify_cl(every_kind, program, options, "every_kind.cl");
    EXPECT_TRUE(v.ok()) << (v.violations.empty() ? "" : verify::format(v.violations[0], "output"))
                        << "\n"
                        << program;
    EXPECT_TRUE(v.changes.empty())
        << (v.changes.empty() ? "" : verify::describe(v.changes[0])) << " output line "
        << (v.changes.empty() ? 0 : v.changes[0].line);
  }
  if (!cldata::testing::have_rs274()) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const fs::path dir =
      fs::temp_directory_path() / ("vcpost_canned_cycles_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path nc = dir / "cycles.ngc";
  std::ofstream(nc, std::ios::binary) << write_gcode(every_kind, rs274ngc_format());
  const auto rs274 = cldata::testing::run_rs274(nc.string());
  fs::remove_all(dir);
  ASSERT_TRUE(rs274);
  const auto want = cl_moves(every_kind);
  const auto got = moves_only(*rs274);
  ASSERT_EQ(want.size(), got.size()) << *rs274;
  EXPECT_GT(want.size(), 50u);
  expect_same_moves(want, got);
}

}  // namespace
}  // namespace vcpost::output
