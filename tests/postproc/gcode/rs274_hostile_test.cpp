// Programs a careless or hostile user writes, read by vcpost and by
// LinuxCNC's rs274 (rs274_compare_support.h): rs274 decides what a correct
// reading is. Each case says whether rs274 reads it (then vcpost reads it
// with the same motion) or refuses it (then vcpost refuses it too, with the
// code given). vcpost read each of them differently before (issue 42).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/postproc/gcode/rs274_compare_support.h"

namespace vcpost::gcode {
namespace {

namespace fs = std::filesystem;
using namespace rs274cmp;  // NOLINT(google-build-using-namespace): this suite's helpers

struct HostileCase {
  const char* name;
  const char* program;
  const char* refused_with;  // vcpost's code when rs274 refuses it; nullptr: both read it
};

constexpr HostileCase kCases[] = {
    // Predefined parameters exist (their values are the control's).
    {"EXISTS of a predefined parameter", "o1 if [EXISTS[#<_x>]]\nG0 X1\no1 endif\nM2\n", nullptr},
    // Predefined parameters are read-only (found by the random comparison).
    {"assignment to a predefined parameter", "#<_v> = 1\nG0 X1\nM2\n", "E1204"},
    {"EXISTS of an unset parameter", "o1 if [EXISTS[#<_nothing>]]\nG0 X1\no1 endif\nG0 Y1\nM2\n",
     nullptr},
    // G53 positions are machine coordinates: rs274 prints them in the
    // program's frame, the offsets G10 L2 set taken off (Z 0 -> Z 50).
    {"G53 after G10 L2", "G10 L2 P1 X3 Z-50\nG0 X1 Z1\nG53 G0 Z0\nG53 G0 X0\nG0 X2\nM2\n", nullptr},
    {"G53 after G92", "G0 X5 Z5\nG92 X0 Z0\nG53 G0 Z1\nG0 X1\nM2\n", nullptr},
    // Arc radii: 0.0283 mm absolute (0.002828 inch), or 100 times that
    // within 0.1 % of the radius.
    {"arc radii 0.02 mm apart", "F100 G2 X10.02 Y0 I5 J0\nM2\n", nullptr},
    {"arc radii 0.028 mm apart", "F100 G2 X10.028 Y0 I5 J0\nM2\n", nullptr},
    {"arc radii 0.029 mm apart", "F100 G2 X10.029 Y0 I5 J0\nM2\n", "E1502"},
    {"arc radii 1 mm apart on R1000", "F100 G2 X2001 Y0 I1000 J0\nM2\n", nullptr},
    {"arc radii 2 mm apart on R1000", "F100 G2 X2002 Y0 I1000 J0\nM2\n", "E1502"},
    {"arc radii 3 mm apart on R5000", "F100 G2 X10003 Y0 I5000 J0\nM2\n", "E1502"},
    {"inch arc radii 0.0028 inch apart", "G20 F10 G2 X1.0028 Y0 I0.5 J0\nM2\n", nullptr},
    {"inch arc radii 0.0029 inch apart", "G20 F10 G2 X1.0029 Y0 I0.5 J0\nM2\n", "E1502"},
    {"R arc 0.0012 mm short", "F100 G2 X10 Y0 R4.9988\nM2\n", nullptr},
    {"R arc 0.002 mm short", "F100 G2 X10 Y0 R4.998\nM2\n", "E1503"},
    // Subroutines: one definition each, met before the calls that run it;
    // nine calls deep at most.
    {"sub defined twice",
     "o100 sub\nG0 X1\no100 endsub\no100 sub\nG0 X2\no100 endsub\no100 call\nM2\n", "E1310"},
    {"call before the definition", "o100 call\no100 sub\nG0 X1\no100 endsub\nM2\n", "E1310"},
    {"call of a sub defined after M2", "o100 call\nG0 Y1\nM2\no100 sub\nG0 X1\no100 endsub\n",
     nullptr},
    {"call ahead past another definition",
     "o300 call\no400 sub\nG0 X4\no400 endsub\no400 call\nM2\no300 sub\nG0 X3\no300 endsub\n",
     nullptr},
    {"subs nested 9 deep",
     "o9 sub\nG0 X9\no9 endsub\no8 sub\no9 call\no8 endsub\no7 sub\no8 call\no7 endsub\n"
     "o6 sub\no7 call\no6 endsub\no5 sub\no6 call\no5 endsub\no4 sub\no5 call\no4 endsub\n"
     "o3 sub\no4 call\no3 endsub\no2 sub\no3 call\no2 endsub\no1 sub\no2 call\no1 endsub\n"
     "o1 call\nM2\n",
     nullptr},
    {"subs nested 10 deep",
     "o10 sub\nG0 X9\no10 endsub\no9 sub\no10 call\no9 endsub\no8 sub\no9 call\no8 endsub\n"
     "o7 sub\no8 call\no7 endsub\no6 sub\no7 call\no6 endsub\no5 sub\no6 call\no5 endsub\n"
     "o4 sub\no5 call\no4 endsub\no3 sub\no4 call\no3 endsub\no2 sub\no3 call\no2 endsub\n"
     "o1 sub\no2 call\no1 endsub\no1 call\nM2\n",
     "E1304"},
    // M98 with an O-numbered program in the same file; L counts the passes.
    {"M98 P2000 L2", "M98 P2000 L2\nG0 Y1\nM2\nO2000\nG91 G0 X1\nG90\nM99\n", nullptr},
    {"M98 L0 runs none", "M98 P2000 L0\nG0 Y1\nM2\nO2000\nG91 G0 X1\nG90\nM99\n", nullptr},
    {"M98 negative L", "M98 P2000 L-5\nM2\nO2000\nG91 G0 X1\nG90\nM99\n", "E1511"},
    {"M98 fractional L", "M98 P2000 L2.7\nM2\nO2000\nG91 G0 X1\nG90\nM99\n", "E1511"},
    // '%' stands alone, on the first line and the closing one.
    {"'%' and a comment", "G0 X1\n% (note)\nG0 X2\nM2\n", "E1001"},
    {"'%' and a move", "G0 X1\n% G1 X5\nG0 X2\nM2\n", "E1001"},
    {"lone '%' in a program not opened with it", "G0 X1\n%\nG0 X2\nM2\n", "E1001"},
    {"closing '%' ends the program", "%\nG0 X1\n%\nG0 X2\nM2\n", nullptr},
    // Splines as rs274 reads them: XY plane, no Z, their words complete.
    {"G5 with Z", "F100 G5 I0 J3 P0 Q-3 X1 Y1 Z2\nM2\n", "E1404"},
    {"G5 in the XZ plane", "G18\nF100 G5 I0 J3 P0 Q-3 X1 Y1\nM2\n", "E1404"},
    {"G5 without Q", "F100 G5 I1 J1 P1 X3 Y3\nM2\n", "E1514"},
    {"G5.1 without J", "F100 G5.1 X2 I1\nM2\n", "E1514"},
    {"G5 P on a block without G5", "F100 G5 I1 J1 P1 Q-1 X4 Y2\nX6 Y0 P1 Q1\nM2\n", "E1009"},
};

TEST(Rs274Hostile, EachCaseReadAsRs274ReadsIt) {
  if (!rs274_available()) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const fs::path dir = fs::temp_directory_path() / ("vcpost-hostile-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const HostileCase& c : kCases) {
    SCOPED_TRACE(c.name);
    const fs::path file = dir / "case.ngc";
    std::ofstream(file, std::ios::binary) << c.program;
    const std::string rs274 = rs274_error(run_rs274(file));
    if (c.refused_with == nullptr) {
      EXPECT_EQ(rs274, "") << "the case says rs274 reads it";
      compare(file);
    } else {
      EXPECT_NE(rs274, "") << "the case says rs274 refuses it";
      std::string error;
      run_vcpost(file, error);
      EXPECT_NE(error.find(c.refused_with), std::string::npos)
          << "rs274: " << rs274 << "; vcpost: " << (error.empty() ? "reads it" : error);
    }
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vcpost::gcode
