// CL CUTCOM/LEFT|RIGHT|OFF written as G41/G42 D and G40 (wear mode: the CL
// path is the tool centre, the D register holds only the wear): the
// blocks, what rs274 and vcpost verify read of them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "machines/builtin.h"
#include "machines/profile.h"
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

// A contour cut on the left (its register the tool's), an exit, a second
// stretch on the right with register 12, a rapid out.
const char* const contour =
    "LOADTL/3\nSPINDL/1000,RPM,CLW\nRAPID\nGOTO/0,0,5\nFEDRAT/100,MMPM\nGOTO/0,0,-2\n"
    "CUTCOM/LEFT\nGOTO/10,0,-2\nCIRCLE/10,10,-2,0,0,1,10\nGOTO/20,10,-2\nGOTO/20,20,-2\n"
    "CUTCOM/OFF\nGOTO/30,20,-2\nCUTCOM/RIGHT,XYPLAN,12\nGOTO/30,30,-2\nCUTCOM/OFF\nRAPID\n"
    "GOTO/30,30,5\nFINI\n";

Format rs274ngc_format() {
  Format f;
  f.program_number.reset();
  f.dwell = DwellWord::p_seconds;
  f.g83_pecks_out_to_r = false;
  return f;
}

// Checked by hand: G41/G42 with the first straight move after CUTCOM (the
// entry move rs274 and Fanuc want), D the register or else the tool; G40
// with the first straight move after CUTCOM/OFF (the exit move).
TEST(CutterCompensation, WrittenAsG41G42WithDAndG40) {
  const std::string expected =
      "%\n"
      "G21 G17 G40 G49 G80 G90 G94\n"
      "G54\n"
      "T3 M6\n"
      "S1000 M3\n"
      "G43 H3 G0 X0. Y0. Z5.\n"
      "G1 Z-2. F100.\n"
      "G41 D3 X10.\n"
      "G3 X20. Y10. I0. J10.\n"
      "G1 Y20.\n"
      "G40 X30.\n"
      "G42 D12 Y30.\n"
      "G40 G0 Z5.\n"
      "M30\n"
      "%\n";
  EXPECT_EQ(write_gcode(contour, rs274ngc_format()), expected);
}

// Compensation on one side, then the other with no OFF between: G40 first
// (rs274 refuses G42 while G41 is on); a second CUTCOM/LEFT changes nothing;
// an arc right after CUTCOM/OFF keeps the compensation until the next
// straight move (rs274 wants a straight move after G40); the tool change
// and the end turn it off.
TEST(CutterCompensation, SideChangesArcsAndToolChanges) {
  const std::string cl =
      "LOADTL/1\nSPINDL/1000\nFEDRAT/100,MMPM\nGOTO/0,0,0\nCUTCOM/LEFT\nGOTO/10,0,0\nCUTCOM/"
      "LEFT\nGOTO/20,0,0\n"
      "CUTCOM/RIGHT\nGOTO/30,0,0\nCUTCOM/OFF\nCIRCLE/30,10,0,0,0,1,10\nGOTO/40,10,0\n"
      "GOTO/40,20,0\nCUTCOM/LEFT,XYPLAN\nGOTO/50,20,0\nLOADTL/2\nGOTO/60,20,0\nFINI\n";
  const std::string program = write_gcode(cl, rs274ngc_format());
  const std::string expected =
      "%\n"
      "G21 G17 G40 G49 G80 G90 G94\n"
      "G54\n"
      "T1 M6\n"
      "S1000 M3\n"
      "G43 H1\n"
      "G1 X0. Y0. Z0. F100.\n"
      "G41 D1 X10.\n"
      "X20.\n"
      "G40\n"
      "G42 D1 X30.\n"
      "G3 X40. Y10. I0. J10.\n"
      "G40 G1 Y20.\n"
      "G41 D1 X50.\n"
      "G40\n"
      "T2 M6\n"
      "G43 H2\n"
      "G1 X60.\n"
      "M30\n"
      "%\n";
  EXPECT_EQ(program, expected);
}

// grbl has no G41/G42: its profile keeps CUTCOM as comments (the path is
// the tool centre already), as does the Klartext writer (R0, never RL/RR);
// every other shipped profile writes G41/G42.
TEST(CutterCompensation, GrblKeepsComments) {
  for (const auto& builtin : machines::builtin_profiles()) {
    const std::string name(builtin.name);
    SCOPED_TRACE(name);
    const Format format = format_for(machines::builtin_profile(name));
    EXPECT_EQ(format.cutter_compensation,
              name != "grbl" && name.rfind("heidenhain-tnc640", 0) != 0);
  }
  Format format = rs274ngc_format();
  format.cutter_compensation = false;
  const std::string program = write_gcode(contour, format);
  EXPECT_EQ(program.find("G41"), std::string::npos) << program;
  EXPECT_NE(program.find("(CUTCOM LEFT - CL PATH IS THE TOOL CENTRE)\nX10.\n"), std::string::npos)
      << program;
  EXPECT_NE(program.find("(CUTCOM OFF)\nX30.\n"), std::string::npos) << program;
}

// rs274 reads the program with the motion of the CL data when the registers
// hold no wear, and reads it whole (its rules on the entry move, the move
// after G40) with a wear of 0.002 in; vcpost verify holds, and tells a
// compensation on the wrong side.
TEST(CutterCompensation, Rs274AndVerifyReadTheClMotion) {
  const std::string program = write_gcode(contour, rs274ngc_format());
  for (const bool fanuc : {false, true}) {
    SCOPED_TRACE(fanuc ? "fanuc" : "rs274ngc");
    Format format = rs274ngc_format();
    if (fanuc) {
      format.program_number = 1000;
      format.dwell = DwellWord::x_seconds;
    }
    const std::string text = write_gcode(contour, format);
    const verify::Result v = verify_written(contour, text, fanuc);
    EXPECT_TRUE(v.ok()) << first_violation(v) << "\n" << text;
    EXPECT_EQ(v.motions, 8u);
  }

  // verify compares the sides: G42 where the CL says LEFT is a difference.
  std::string wrong = program;
  const auto at = wrong.find("G41 D3");
  ASSERT_NE(at, std::string::npos) << program;
  wrong.replace(at, 3, "G42");
  const verify::Result v = verify::verify_cl(contour, wrong, {}, "contour.cl");
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(verify::format(v.violations[0], "out"),
            "out:8:1: error[E7135]: the output means COMMENT(\"interpreter: cutter radius "
            "compensation on right\") where the CL data mean COMMENT(\"interpreter: cutter radius "
            "compensation on left\") (input line 7)");

  if (!cldata::testing::have_rs274()) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const fs::path dir = fs::temp_directory_path() / ("vcpost_cutcom_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path nc = dir / "contour.ngc";
  std::ofstream(nc, std::ios::binary) << program;
  const auto rs274 = cldata::testing::run_rs274(nc.string());
  const auto worn = cldata::testing::run_rs274(nc.string(), 0.002);
  fs::remove_all(dir);
  ASSERT_TRUE(rs274 && worn);
  EXPECT_NE(worn->find("PROGRAM_END()"), std::string::npos) << *worn;
  EXPECT_NE(worn->find("cutter radius compensation on right"), std::string::npos) << *worn;
  const auto want = cl_moves(contour);
  const auto got = moves_only(*rs274);
  ASSERT_EQ(want.size(), got.size()) << *rs274;
  EXPECT_EQ(want.size(), 8u);
  expect_same_moves(want, got);
}

}  // namespace
}  // namespace vcpost::output
