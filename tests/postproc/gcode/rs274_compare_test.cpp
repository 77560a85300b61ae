// vcpost's interpreted moves against LinuxCNC's interpreter
// (rs274_compare_support.h says how and what is compared): the test
// programs, every real program of ../shared in its dialect (read where
// rs274 reads it, refused where it refuses it), and a coverage run through
// LinuxCNC's G and M code list. The tests skip when rs274 or the shared
// data are absent.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "tests/postproc/gcode/rs274_compare_support.h"

namespace vcpost::gcode {
namespace {

namespace fs = std::filesystem;

using namespace rs274cmp;  // NOLINT(google-build-using-namespace): this suite's helpers

TEST(Rs274Compare, OwnTestPrograms) {
  if (!rs274_available()) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "tests/postproc/gcode/programs";
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".ngc") {
      compare(entry.path());
      ++count;
    }
  EXPECT_GE(count, 7);
}

TEST(Rs274Compare, SharedRealPrograms) {
  if (!rs274_available()) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const fs::path dir = fs::path(VCPOST_SHARED_DATA_DIR) / "gcode";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "shared data not found at " << dir;
  // The RS274NGC-compatible programs of PROVENANCE.md (ENSURE_TOOL_LENGTH.EIA
  // is a Mazak macro, not RS274NGC).
  for (const char* name : {"3D_Chips.ngc", "3D_Chips_2006.ngc", "Waterline_OCL.gcode", "bear.nc"}) {
    if (!fs::exists(dir / name)) continue;
    compare(dir / name);
  }
}

// The dialect a real program of ../shared is written in, by its CAM post.
Dialect dialect_of_program(const fs::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".ptp") return fanuc_dialect();
  if (ext == ".EIA") return mazak_dialect();
  if (ext == ".MPF") return sinumerik_dialect();
  return rs274ngc_dialect();
}

// Every real program: rs274 reads it -> vcpost reads it (RS274NGC) with
// the same motion; rs274 refuses it -> vcpost refuses it too. Then in its
// own dialect it must read, but for the ones a control of that dialect
// refuses as well (listed with the reason).
TEST(Rs274Compare, EveryRealProgramOfShared) {
  if (!rs274_available()) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const fs::path shared(VCPOST_SHARED_DATA_DIR);
  if (!fs::is_directory(shared / "corpus/gcode"))
    GTEST_SKIP() << "shared data not found at " << shared;
  // Refused in their own dialect, for a reason the control gives too.
  const std::map<std::string, std::string> refused = {
      // #3006 (stop with message) acts on the running control; #0 is vacant.
      {"ENSURE_TOOL_LENGTH.EIA", "E1204"},
      // G1 before any F: rs274 ("Cannot do g1 with zero feed rate") and grbl refuse it.
      {"F360_grbl_SheepTile-v2.nc", "E1505"},
      // G2 with K in the XY plane: rs274 refuses it ("K word given for arc in xy plane").
      {"FreeCAD_grbl_casting_mold_top.nc", "E1009"},
      // GE 1050 implied-decimal program (X0019685), its own G87/G86: not Fanuc.
      {"NX_Monarch_VMC150_GE_sample.ptp", "E1513"},
      // Read to line 222, "TURN=.5": TURN counts whole extra circles; a
      // fractional count is refused (not checked on a real 840D).
      {"NX_Huron_KX20_840D.MPF", "E1511"},
      // G73 with Q0.0: a peck of zero never reaches the bottom; Fanuc alarms.
      {"NX_Makino_3ax_mill.ptp", "E1513"},
  };
  int count = 0;
  for (const fs::path& dir : {shared / "gcode", shared / "corpus/gcode"}) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      const fs::path file = entry.path();
      if (file.extension() == ".md" || file.extension() == ".json") continue;
      SCOPED_TRACE(file.string());
      ++count;
      const std::string transcript = run_rs274(file);
      std::string error;
      if (rs274_error(transcript).empty()) {
        compare(file);
      } else {
        run_vcpost(file, error);
        EXPECT_NE(error, "") << "rs274 refuses it (" << rs274_error(transcript)
                             << "), vcpost reads it";
      }
      error.clear();
      run_vcpost(file, error, dialect_of_program(file));
      const auto known = refused.find(file.filename().string());
      if (known == refused.end()) {
        EXPECT_EQ(error, "") << "refused in its own dialect";
      } else {
        EXPECT_NE(error.find(known->second), std::string::npos) << error;
      }
    }
  }
  EXPECT_GE(count, 15);
}

// One code of LinuxCNC's G and M code list, in a small program.
struct CoverageCase {
  const char* code;
  const char* body;
};

constexpr CoverageCase kCoverageCases[] = {
    {"G0", "G0 X3 Y4 Z6\n"},
    {"G1", "G1 X3 Y4 Z2\n"},
    {"G2", "G2 X3 Y2 I1 J0\n"},
    {"G3", "G3 X3 Y2 R1\n"},
    {"G4", "G4 P0.5\n"},
    {"G5", "G5 I0 J3 P0 Q-3 X1 Y1\n"},
    {"G5.1", "G5.1 X2 I1 J1\n"},
    {"G5.2", "G5.2 X2 Y3 P1 L3\nX4 Y5 P1\nG5.3\n"},
    {"G7", "G7\nG0 X1\n"},
    {"G8", "G8\nG0 X1\n"},
    {"G10 L1", "G10 L1 P1 Z1\n"},
    {"G10 L10", "G10 L10 P1 Z1\n"},
    {"G10 L11", "G10 L11 P1 Z1\n"},
    {"G10 L2", "G10 L2 P1 X5 Y5\nG0 X0 Y0\nG28\n"},
    {"G10 L20", "G10 L20 P1 X0 Y0\nG0 X2\nG28\n"},
    {"G17", "G17 G2 X3 Y2 I1 J0\n"},
    {"G18", "G18 G2 X3 Z5 I1 K0\n"},
    {"G19", "G19 G2 Y4 Z5 J1 K0\n"},
    {"G17.1", "G17.1\n"},
    {"G20", "G20 G0 X1 Y1\n"},
    {"G21", "G21 G0 X1 Y1\n"},
    {"G28", "G28 Z8\n"},
    {"G28.1", "G0 X4 Y4 Z4\nG28.1\nG0 X0\nG28\n"},
    {"G30", "G91 G30 Z1\nG90\n"},
    {"G30.1", "G0 X4 Y4 Z4\nG30.1\nG0 X0\nG30\n"},
    {"G33", "G33 X2 K0.1\n"},
    {"G33.1", "G33.1 Z-1 K0.1\n"},
    {"G38.2", "G38.2 Z-1 F10\n"},
    {"G40", "G40\nG0 X2\n"},
    {"G41", "G41\nG0 X9\nG40\n"},
    {"G43", "G43 H0\nG0 Z3\nG49\n"},
    {"G43.1", "G43.1 Z0.5\nG0 Z3\nG49\n"},
    {"G52", "G52 X5\nG0 X0\nG52 X0\nG0 X1\n"},
    {"G53", "G53 G0 Z0\n"},
    {"G54", "G55\nG0 X1\nG54\nG0 X2\n"},
    {"G59.3", "G59.3 G0 X1\n"},
    {"G61", "G61\nG1 X4\nG61.1\nG64 P0.01\nG1 X5\n"},
    {"G73", "G73 X2 Y2 Z-2 R1 Q0.7\nG80\n"},
    {"G74", "M4\nG74 X2 Y2 Z-2 R1\nG80\n"},
    {"G76", "G76 P1 Z-1 I-0.1 J0.1 K0.5\n"},
    {"G81", "G81 X2 Y2 Z-2 R1\nX4\nG91 X1 L2\nG90 G80\n"},
    {"G82", "G98 G82 X2 Y2 Z-2 R1 P0.5\nG80\n"},
    {"G83", "G83 X2 Y2 Z-2 R1 Q0.6\nG80\n"},
    {"G84", "G84 X2 Y2 Z-2 R1\nG80\n"},
    {"G85", "G85 X2 Y2 Z-2 R1\nG80\n"},
    {"G86", "G86 X2 Y2 Z-2 R1 P1\nG80\n"},
    {"G87", "G87 X2 Y2 Z-2 R1 I0.5 J0 K-1\nG80\n"},
    {"G88", "G88 X2 Y2 Z-2 R1 P1\nG80\n"},
    {"G89", "G89 X2 Y2 Z-2 R1 P1\nG80\n"},
    {"G90", "G90 G0 X1\n"},
    {"G90.1", "G90.1 G2 X3 Y2 I2 J2\n"},
    {"G91", "G91 G0 X1\nG90\n"},
    {"G91.1", "G91.1 G2 X3 Y2 I1 J0\n"},
    {"G92", "G92 X0 Y0\nG0 X1\nG92.2\nG0 X1\nG92.3\nG0 X1\nG92.1\nG0 X1\n"},
    {"G93", "G93 G1 X5 F2\nG94\n"},
    {"G95", "G95 G1 X5 F0.1\nG94\n"},
    {"G96", "G96 D2000 S100\n"},
    {"G97", "G97 S500\n"},
    {"G98", "G98 G81 X2 Y2 Z-2 R1\nG99 X3\nG80\n"},
    {"G80 beside G0", "G0 G80 X3\n"},
    {"M0", "M0\n"},
    {"M1", "M1\n"},
    {"M3", "M3 S200\n"},
    {"M4", "M4\n"},
    {"M5", "M5\n"},
    {"M6", "T2 M6\n"},
    {"M7", "M7\nM8\nM9\n"},
    {"M7 M8", "M7 M8\n"},
    {"M19", "M19\n"},
    {"M48", "M48\nM49\nM50 P1\nM51 P1\nM52 P1\nM53 P1\n"},
    {"M60", "M60\n"},
    {"M61", "M61 Q1\n"},
    {"M62", "M62 P0\n"},
    {"M66", "M66 P0 L0\n"},
    {"M70", "M70\nM71\n"},
    {"M72", "M70\nG20\nM72\n"},
    {"M100", "M100\n"},
    {"M9026", "M9026\n"},
    {"Q unused", "G1 Q7 X1\n"},
};

// Codes vcpost refuses by design where rs274 reads them: they move the
// tool in ways the post does not follow (lathe diameter mode,
// spindle-synchronised and probing moves, constant surface speed,
// the UV planes, restored modal state).
bool refused_by_design(const std::string& code) {
  static const std::set<std::string> by_design = {"G7",    "G17.1", "G33", "G33.1",
                                                  "G38.2", "G76",   "G96", "M72"};
  return by_design.contains(code);
}

// The case read by rs274 and vcpost: the same motion, or both refuse it.
void check_coverage_case(const fs::path& dir, const CoverageCase& c) {
  SCOPED_TRACE(c.code);
  const std::string start = "G21 G90 G17 G94 F500 S1000 M3\nG0 X1 Y2 Z5\n";
  const fs::path file = dir / "case.ngc";
  std::ofstream(file, std::ios::binary) << start << c.body << "M2\n";
  const std::string transcript = run_rs274(file);
  const bool rs274_reads = rs274_error(transcript).empty();
  std::string error;
  run_vcpost(file, error);
  if (!rs274_reads) {
    EXPECT_NE(error, "") << "rs274 refuses it (" << rs274_error(transcript) << "), vcpost reads it";
  } else if (refused_by_design(c.code)) {
    EXPECT_NE(error.find("E1404"), std::string::npos) << "refused by design, but: " << error;
  } else {
    compare(file);
  }
}

// LinuxCNC's G and M code list: each code in a small program, read by rs274
// and vcpost; both read it with the same motion, or both refuse it.
TEST(Rs274Compare, CoverageOfLinuxCncCodeList) {
  if (!rs274_available()) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const fs::path dir =
      fs::temp_directory_path() / ("vcpost-coverage-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  int agreed = 0;
  for (const CoverageCase& c : kCoverageCases) {
    check_coverage_case(dir, c);
    ++agreed;
  }
  fs::remove_all(dir);
  EXPECT_EQ(agreed, static_cast<int>(std::size(kCoverageCases)));
}

}  // namespace
}  // namespace vcpost::gcode
