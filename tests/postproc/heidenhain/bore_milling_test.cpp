// Cycle 208 (bore milling) as the TNC runs it: a helix of radius (Q335 -
// tool diameter) / 2 at Q334 per turn, entered by a semicircle from the
// hole's centre, a full circle at the depth, back to the centre. Worked by
// hand; tolerance 1e-9 mm.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "postproc/program/arc.h"
#include "tests/postproc/heidenhain/klartext_support.h"

namespace vcpost::heidenhain {
namespace {

using program::Event;
using testing::end_of;
using testing::error_of;
using testing::expect_point;
using testing::motions;
using testing::run;

std::string hole(const std::string& pitch, const std::string& tool, const std::string& spindle) {
  return "BEGIN PGM T MM\n" + tool + "L X+10 Y+20 Z+50 R0 FMAX " + spindle +
         "\n"
         "CYCL DEF 208 BORE MILLING ~\n"
         "  Q200=2 ;SET-UP CLEARANCE ~\n"
         "  Q201=-5 ;DEPTH ~\n"
         "  Q206=150 ;FEED RATE FOR PLUNGING ~\n"
         "  Q334=" +
         pitch +
         " ;PLUNGING DEPTH ~\n"
         "  Q203=+0 ;SURFACE COORDINATE ~\n"
         "  Q204=50 ;2ND SET-UP CLEARANCE ~\n"
         "  Q335=16 ;NOMINAL DIAMETER ~\n"
         "  Q342=0 ;ROUGHING DIAMETER ~\n"
         "  Q351=+1 ;CLIMB OR UP-CUT\n"
         "CYCL CALL\n"
         "END PGM T MM\n";
}

const std::string kToolR3 = "TOOL DEF 1 L+0 R+3\nTOOL CALL 1 Z S1000\n";

// Tool R3 in a 16 mm hole: helix radius 8 - 3 = 5 about (10, 20). From the
// clearance Z2 a semicircle about (12.5, 20) to (15, 20, 1) (half a pitch
// down), full turns to Z-1, -3, -5, a full circle at -5, back to (10, 20,
// -5), up to Z2 and Z50. M3 and climb (Q351 +1): counterclockwise.
TEST(KlartextBoreMilling, HelixOfWholeTurns) {
  const auto m = motions(run(hole("2", kToolR3, "M3")));
  ASSERT_EQ(m.size(), 10u);
  expect_point(end_of(m[1]), 10, 20, 2);
  const auto& entry = std::get<program::ArcFeed>(m[2]);
  expect_point(entry.centre, 12.5, 20, 2);
  expect_point(entry.end, 15, 20, 1);
  EXPECT_EQ(entry.rotation, 1);
  EXPECT_NEAR(program::arc_sweep(entry), std::numbers::pi, 1e-12);
  for (int turn = 0; turn < 3; ++turn) {
    const auto& a = std::get<program::ArcFeed>(m[3 + turn]);
    expect_point(a.centre, 10, 20, 1 - 2 * turn);
    expect_point(a.end, 15, 20, -1 - 2 * turn);
    EXPECT_NEAR(program::arc_sweep(a), 2 * std::numbers::pi, 1e-12);
  }
  const auto& bottom = std::get<program::ArcFeed>(m[6]);
  expect_point(bottom.start, 15, 20, -5);
  expect_point(bottom.end, 15, 20, -5);
  expect_point(end_of(m[7]), 10, 20, -5);
  expect_point(end_of(m[8]), 10, 20, 2);
  expect_point(end_of(m[9]), 10, 20, 50);
}

// Q334=3: Z 2 -> 0.5 on the semicircle, a turn to -2.5, then 2.5 of the
// next 3 mm: 300 deg, clockwise (M4 reverses the climb direction):
// (10 + 5 cos -300, 20 + 5 sin -300) = (12.5, 24.33013).
TEST(KlartextBoreMilling, PartTurnAndSpindleReversed) {
  const auto m = motions(run(hole("3", kToolR3, "M4")));
  ASSERT_EQ(m.size(), 9u);
  EXPECT_EQ(std::get<program::ArcFeed>(m[2]).rotation, -1);
  expect_point(end_of(m[2]), 15, 20, 0.5);
  expect_point(end_of(m[3]), 15, 20, -2.5);
  const auto& part = std::get<program::ArcFeed>(m[4]);
  expect_point(part.end, 12.5, 20 + 5 * std::sin(std::numbers::pi / 3), -5);
  EXPECT_NEAR(program::arc_sweep(part), -300 * std::numbers::pi / 180, 1e-12);
}

// Without the tool's radius the hole is taken along its axis, warned once.
TEST(KlartextBoreMilling, UnknownToolGoesAlongTheAxis) {
  const std::string program = hole("2", "TOOL CALL 1 Z S1000\n", "M3");
  Interpreter interpreter(program);
  const auto m = motions(run("", &interpreter));
  ASSERT_EQ(m.size(), 5u);
  expect_point(end_of(m[2]), 10, 20, -5);
  ASSERT_EQ(interpreter.warnings().size(), 1u);
  EXPECT_EQ(interpreter.warnings()[0].code, Code::W3345);
  // A radius given by the caller (CAM comment, --tool: the post gives it
  // before each block, as a TOOL CALL takes it back) makes the helix.
  const std::string no_call = hole("2", "", "M3");
  Interpreter given(no_call);
  given.set_tool_radius(3);
  EXPECT_EQ(motions(run("", &given)).size(), 10u);
  EXPECT_EQ(error_of(hole("2", "TOOL DEF 1 L+0 R+9\nTOOL CALL 1 Z S1000\n", "M3")),
            Code::E3323);  // wider than the hole
}

TEST(KlartextFreeContour, IsRefusedWithItsOwnCode) {
  EXPECT_EQ(error_of("BEGIN PGM T MM\nL X+0 Y+0 F100\nFPOL X+20 Y+30\n"), Code::E3330);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nL X+0 Y+0 F100\nFL LEN 10 AN+15\n"), Code::E3330);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nL X+0 Y+0 F100\nFCT DR- R15\n"), Code::E3330);
}

}  // namespace
}  // namespace vcpost::heidenhain
