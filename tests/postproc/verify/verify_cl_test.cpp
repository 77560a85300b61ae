// verify_cl on a small hand-written CL program and the G-code written
// from it (as the G-code writer writes it for a Fanuc control with G68.2,
// checked line by line by hand): it holds; a changed tool, spindle
// direction, missing spindle start or a working plane turned about its
// own tool axis is named with its code at its output line.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "postproc/cldata/cl_reader.h"
#include "postproc/verify/verify.h"

namespace vcpost::verify {
namespace {

// Lines 5-7: a tool change, the spindle, the move to the start; CSYS on
// line 5 tilts the frame by 90 degrees about X (tool axis -Y): the moves
// after it run along that axis through the frame's origin.
const std::string kCl =
    "LOADTL/1\n"
    "SPINDL/5000,RPM,CLW\n"
    "RAPID\n"
    "GOTO/0,0,100\n"
    "CSYS/1,0,0,0,0,0,-1,0,0,1,0,0\n"
    "RAPID\n"
    "GOTO/0,-50,0,0,-1,0\n"
    "FEDRAT/800,MMPM\n"
    "GOTO/0,-2,0,0,-1,0\n"
    "RAPID\n"
    "GOTO/0,-50,0,0,-1,0\n"
    "FINI\n";

// Output lines: 5 T1 M6, 6 S5000 M3, 7 the rapid, 8 the frame (Euler ZXZ
// 0, 90, 0), 10-12 the three moves in it.
const std::string kGcode =
    "%\n"
    "O1000\n"
    "G21 G17 G40 G49 G80 G90 G94\n"
    "G54\n"
    "T1 M6\n"
    "S5000 M3\n"
    "G43 H1 G0 X0. Y0. Z100.\n"
    "G68.2 X0. Y0. Z0. I0. J90. K0.\n"
    "G53.1\n"
    "G0 X0. Y0. Z50.\n"
    "G1 Z2. F800.\n"
    "G0 Z50.\n"
    "G69\n"
    "M30\n"
    "%\n";

Options fanuc() {
  Options options;
  options.dialect = gcode::fanuc_dialect();
  return options;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

// The one violation of `output`, formatted.
std::string only_violation(const std::string& output) {
  const Result r = verify_cl(kCl, output, fanuc(), "t.cl");
  if (r.violation_count != 1)
    return std::to_string(r.violation_count) + " violations" +
           (r.violations.empty() ? "" : ", first " + format(r.violations[0], "out"));
  return format(r.violations[0], "out");
}

TEST(VerifyCl, TheWrittenProgramHolds) {
  const Result r = verify_cl(kCl, kGcode, fanuc(), "t.cl");
  EXPECT_TRUE(r.ok()) << format(r.violations.front(), "out");
  EXPECT_EQ(r.motions, 4u);
}

TEST(VerifyCl, AnotherToolOrSpindleIsNamedAtItsLine) {
  // The tool change's column is its M6's; the spindle start's its M3's.
  EXPECT_EQ(only_violation(replaced(kGcode, "T1 M6", "T2 M6")),
            "out:5:4: error[E7135]: the output means CHANGE_TOOL(2) where the CL data mean "
            "CHANGE_TOOL(1) (input line 1)");
  EXPECT_EQ(only_violation(replaced(kGcode, "S5000 M3", "S5000 M4")),
            "out:6:7: error[E7135]: the output means START_SPINDLE_COUNTERCLOCKWISE(0) where the "
            "CL data mean START_SPINDLE_CLOCKWISE(0) (input line 2)");
  // No M3: where the CL data start the spindle the output moves (line 7,
  // its G0 at column 8); the comparison stops there.
  EXPECT_EQ(only_violation(replaced(kGcode, "S5000 M3", "S5000")),
            "out:7:8: error[E7135]: the output has a rapid where the CL data have a spindle start: "
            "STRAIGHT_TRAVERSE(0.0000, 0.0000, 100.0000, 0.0000, 0.0000, 0.0000) vs "
            "START_SPINDLE_CLOCKWISE(0) (input line 2)");
}

// K1. turns the output's frame by 1 degree about its own z, the tool axis:
// its x column becomes (cos 1deg, 0, sin 1deg) = (0.9998, 0, 0.0175). The
// moves run along that axis through the origin, so their points stay where
// the CL's are: only the frame is named, once, at the first move in it.
TEST(VerifyCl, AFrameTurnedAboutTheToolAxisIsNamed) {
  EXPECT_EQ(only_violation(replaced(kGcode, "K0.", "K1.")),
            "out:10:1: error[E7143]: the output's working plane has the tool axis (0, -1, 0) and "
            "x (0.9998, 0, 0.0175) where the CL's has (0, -1, 0) and (1, 0, 0) (input line 7)");
}

// A CL record that does not read is the CL reader's error as `vcpost post`
// gets it from the reader: its code, its file:line:col (the number on line
// 9 starts at column 11, after "GOTO/0,-2,") and its hint.
TEST(VerifyCl, AnInputThatDoesNotReadKeepsTheReadersPlaceAndHint) {
  const std::string bad = replaced(kCl, "GOTO/0,-2,0,", "GOTO/0,-2,0.1.2,");
  try {
    verify_cl(bad, kGcode, fanuc(), "bad.cl");
    ADD_FAILURE() << "read";
  } catch (const vcpost::Error& e) {
    EXPECT_STREQ(e.what(), "bad.cl:9:11: error[E3103]: malformed number '0.1.2'");
    EXPECT_EQ(e.where().file, "bad.cl");
    EXPECT_EQ(e.where().line, 9u);
    EXPECT_EQ(e.where().column, 11u);
    EXPECT_EQ(e.hint(), "Fix the number the column points at.");  // E3103's row
  }
  // The reader's own, as the post reads the file.
  std::istringstream in(bad);
  cldata::ClReader reader(in, "bad.cl");
  try {
    while (reader.next()) {
    }
    ADD_FAILURE() << "read";
  } catch (const vcpost::Error& e) {
    EXPECT_STREQ(e.what(), "bad.cl:9:11: error[E3103]: malformed number '0.1.2'");
    EXPECT_EQ(e.where().line, 9u);
    EXPECT_EQ(e.where().column, 11u);
  }
}

}  // namespace
}  // namespace vcpost::verify
