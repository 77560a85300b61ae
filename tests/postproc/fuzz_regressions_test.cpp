// Inputs the fuzzers found (fuzz/regressions/gcode_fuzz/, cldata_fuzz/),
// replayed through the ordinary build with the same drivers as the fuzz
// targets (fuzz/*_driver.h): each must give its documented outcome, a stable
// error code or "ok", and never a crash, a sanitizer report or another
// exception type. The expected outcomes are worked out from the input by
// hand (the comment of each case says how).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>

#include "fuzz/cldata_driver.h"
#include "fuzz/gcode_driver.h"
#include "fuzz/verify_driver.h"

namespace vcpost::fuzz {
namespace {

namespace fs = std::filesystem;

const fs::path kRegressions = fs::path(VCPOST_SOURCE_DIR) / "fuzz" / "regressions";

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::set<std::string> files_in(const fs::path& folder) {
  std::set<std::string> names;
  if (fs::is_directory(folder))
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.is_regular_file()) names.insert(entry.path().filename().string());
  return names;
}

// Outcome per dialect: "rs274ngc:<code> fanuc:<code> mazak:<code>".
// Since a word's value is bounded at the reader (kMaxWordMagnitude, 1e12),
// the first five inputs stop there, E1003, before the later guards they
// once reached (those guards, E1401 and E1511, still take values up to 1e12).
const std::map<std::string, std::string> kGcodeCases = {
    // A Fanuc G83 with L320 repeats and Q2 (0.002 mm pecks: no decimal
    // point): 3.5 M moves in one block, 6 s under the sanitizers. Past the
    // product's limit of moves per cycle block (1,000,000) and the fuzz
    // driver's (200,000): refused before expanding (E1308).
    {"fanuc_micro_pecks_repeated.ngc", "rs274ngc:E1001 fanuc:E1308 mazak:E1308"},
    // G with a 70-digit number (8.9e66): its conversion to a code number
    // overflowed a long (UBSan).
    {"huge_g_code.ngc", "rs274ngc:E1003 fanuc:E1003 mazak:E1003"},
    // T1e20 overflowed the int tool number.
    {"huge_tool_number.ngc", "rs274ngc:E1003 fanuc:E1003 mazak:E1003"},
    // G43 H1e20 overflowed the int register.
    {"huge_h_register.ngc", "rs274ngc:E1003 fanuc:E1003 mazak:E1003"},
    // G43 H-3.5 was silently truncated to register -3: E1511 as for T.
    {"fractional_negative_h.ngc", "rs274ngc:E1511 fanuc:E1511 mazak:E1511"},
    // G2 X1 I0.5 P1e20: P (turns, RS274NGC only) overflowed an int.
    {"huge_arc_turns.ngc", "rs274ngc:E1003 fanuc:E1003 mazak:E1003"},
    // X[EXP[1000]]: e^1000 overflows to infinity, which reached the motion
    // events (CI's fuzz run). The expression fails: E1205.
    {"overflowing_expression.ngc", "rs274ngc:E1205 fanuc:E1205 mazak:E1205"},
    // X with 60 nines (1e60): finite, but its squares and sums in arcs and
    // offsets are not. Beyond 1e12: E1003.
    {"sixty_digit_coordinate.ngc", "rs274ngc:E1003 fanuc:E1003 mazak:E1003"},
    // "o200 while [#4 LT 3]" with #4 never set: an endless loop whose body
    // calls a subroutine with an arc; 100,000 iterations took over 5 s.
    // The fuzz limit of 50,000 blocks ends it: E1309. Fanuc and Mazak stop
    // at line 2's named parameter: E1206.
    {"endless_while_calling_arcs.ngc", "rs274ngc:E1309 fanuc:E1206 mazak:E1206"},
};

// Outcome of the CL reader.
const std::map<std::string, std::string> kClCases = {
    // A NURBS with a CNTRL point at Y = 14,843,522 mm (line 74): 321,000
    // lines at 1 um, over the 5 s limit under the sanitizers. Now refused
    // before flattening: E3111, the point lies beyond 100 m (the reader
    // test ClReader.NurbsPointBeyondTheMachineReachIsRefused keeps that case).
    // Since parameters beyond 1e12 are no numbers, the same curve's
    // CNTRL/-254.9e88 (line 77) is refused first, while the curve is read:
    // E3103.
    {"nurbs_control_point_15_km.cls", "E3103"},
    // UNITS/INCHES, then FROM/0,1e308,3.775 (line 8): 1e308 in times 25.4
    // is infinite, which reached the motion events. A parameter beyond 1e12
    // is no number (kMaxClNumber): E3103.
    {"inch_coordinate_1e308.cls", "E3103"},
};

TEST(FuzzRegressions, GcodeInputsGiveTheirDocumentedOutcome) {
  for (const auto& [name, expected] : kGcodeCases) {
    const fs::path path = kRegressions / "gcode_fuzz" / name;
    ASSERT_TRUE(fs::is_regular_file(path)) << path;
    EXPECT_EQ(run_gcode_all_dialects(read_file(path)), expected) << name;
  }
}

TEST(FuzzRegressions, ClInputsGiveTheirDocumentedOutcome) {
  for (const auto& [name, expected] : kClCases) {
    const fs::path path = kRegressions / "cldata_fuzz" / name;
    ASSERT_TRUE(fs::is_regular_file(path)) << path;
    EXPECT_EQ(run_cldata(read_file(path)), expected) << name;
  }
}

// Outcome of the verify driver.
const std::map<std::string, std::string> kVerifyCases = {
    // A while loop whose counter is set to #1 + 1 = 3 < 4 on every turn:
    // endless. Its 10,000 turns ran past the 5 s limit under the sanitizers
    // on a loaded machine; the driver now gives up past its budget of
    // 10,000 loop turns (a legal program, too slow to fuzz): "budget".
    {"endless_while_loop.ngc", "budget"},
    // "S+++++++++++1": the reader takes a run of unary signs (as rs274
    // does: S++1 is 1), the writer's word span and verify's lexer took one
    // sign only, so the S patched into it did not replace the whole value
    // and verify saw the S word removed. All three now share
    // gcode::word_value_end.
    {"repeated_unary_signs.ngc", "ok"},
    // "#<_dep...(Ith> = -1.42": the reader took '(' into the parameter's
    // name, where LinuxCNC starts a comment (rs274: "Unclosed comment
    // found"); the writer put the S word before that '(', inside the name
    // as the reader saw it. The reader now refuses the name unclosed.
    {"paren_in_parameter_name.ngc", "input"},
    // ';' inside a #<name>: also a comment's start on LinuxCNC (rs274:
    // "Equal sign missing in parameter setting"); the reader took it into
    // the name, the verify lexer ended the line there. Refused unclosed.
    {"semicolon_in_parameter_name.ngc", "input"},
    // "S++++++#++++1": a parameter whose number is itself a signed value;
    // the word's span ended after the '#'.
    {"signs_in_parameter_number.ngc", "ok"},
};

TEST(FuzzRegressions, VerifyInputsGiveTheirDocumentedOutcome) {
  for (const auto& [name, expected] : kVerifyCases) {
    const fs::path path = kRegressions / "verify_fuzz" / name;
    ASSERT_TRUE(fs::is_regular_file(path)) << path;
    EXPECT_EQ(run_verify(read_file(path)), expected) << name;
  }
}

// A saved input without an expected outcome would never be checked.
TEST(FuzzRegressions, EverySavedInputHasACase) {
  for (const auto& name : files_in(kRegressions / "gcode_fuzz"))
    EXPECT_TRUE(kGcodeCases.contains(name)) << "gcode_fuzz/" << name << " has no case";
  for (const auto& name : files_in(kRegressions / "cldata_fuzz"))
    EXPECT_TRUE(kClCases.contains(name)) << "cldata_fuzz/" << name << " has no case";
  for (const auto& name : files_in(kRegressions / "verify_fuzz"))
    EXPECT_TRUE(kVerifyCases.contains(name)) << "verify_fuzz/" << name << " has no case";
}

}  // namespace
}  // namespace vcpost::fuzz
