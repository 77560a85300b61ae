// The Klartext reader on small programs whose motion is worked out by hand
// (each expected number is derived in the comment beside it), and the block
// information a writer uses. Tolerance: 1e-9 mm for values computed from
// exact inputs, 1e-6 where trigonometry is involved.
#include "postproc/heidenhain/interpreter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "tests/postproc/heidenhain/klartext_support.h"

namespace vcpost::heidenhain {
namespace {

using program::Event;

using testing::end_of;
using testing::error_of;
using testing::expect_point;
using testing::motions;
using testing::program_ends;
using testing::run;

TEST(KlartextInterpreter, LinesFeedsAndRapids) {
  const auto events =
      run("0 BEGIN PGM T MM\n"
          "1 L X+10 Y+20 Z+5 R0 FMAX\n"  // rapid to (10, 20, 5)
          "2 FN 0: Q1 = +250\n"
          "3 L Z-1 FQ1\n"    // feed at Q1 = 250 mm/min to z -1
          "4 L IX+5 IY-2\n"  // incremental: (15, 18, -1), still fed
          "5 L X+0 F MAX\n"  // "F MAX" is a rapid for this block only
          "6 L Y+0\n"        // feeds again at 250
          "7 END PGM T MM\n");
  const auto m = motions(events);
  ASSERT_EQ(m.size(), 5u);
  EXPECT_TRUE(std::holds_alternative<program::StraightTraverse>(m[0]));
  expect_point(end_of(m[0]), 10, 20, 5);
  EXPECT_TRUE(std::holds_alternative<program::StraightFeed>(m[1]));
  expect_point(end_of(m[1]), 10, 20, -1);
  expect_point(end_of(m[2]), 15, 18, -1);
  EXPECT_TRUE(std::holds_alternative<program::StraightTraverse>(m[3]));
  expect_point(end_of(m[3]), 0, 18, -1);
  EXPECT_TRUE(std::holds_alternative<program::StraightFeed>(m[4]));
  expect_point(end_of(m[4]), 0, 0, -1);
  int feeds = 0;
  for (const Event& e : events) {
    if (const auto* f = std::get_if<program::SetFeedRate>(&e)) {
      EXPECT_DOUBLE_EQ(f->rate, 250.0);
      ++feeds;
    }
  }
  EXPECT_EQ(feeds, 1);  // F stays modal across the rapid
  EXPECT_TRUE(std::holds_alternative<program::ProgramEnd>(events.back()));
}

TEST(KlartextInterpreter, CircleAboutCentreAndRadiusArcs) {
  const auto events =
      run("BEGIN PGM T MM\n"
          "L X+10 Y+0 Z+0 F100\n"
          "CC X+0 Y+0\n"
          "C X+0 Y+10 DR+\n"        // quarter circle ccw about the origin
          "CR X-10 Y+0 R+10 DR+\n"  // next quarter: centre left of the chord = origin
          "CR X+10 Y+0 R-10 DR-\n"  // R- : more than half a circle, cw
          "END PGM T MM\n");
  const auto m = motions(events);
  ASSERT_EQ(m.size(), 4u);
  const auto& c = std::get<program::ArcFeed>(m[1]);
  EXPECT_EQ(c.rotation, 1);
  expect_point(c.centre, 0, 0, 0);
  expect_point(c.end, 0, 10, 0);
  const auto& cr = std::get<program::ArcFeed>(m[2]);
  EXPECT_EQ(cr.rotation, 1);
  // chord (0,10)->(-10,0): midpoint (-5,5), half chord sqrt(50), h = sqrt(100-50);
  // left of the chord direction (-1,-1)/sqrt2 is (1,-1)/sqrt2: centre (-5,5)+(5,-5) = origin.
  expect_point(cr.centre, 0, 0, 0, 1e-9);
  const auto& big = std::get<program::ArcFeed>(m[3]);
  EXPECT_EQ(big.rotation, -1);
  // chord (-10,0)->(10,0), h = 0: the centre is the midpoint either way.
  expect_point(big.centre, 0, 0, 0, 1e-9);
}

TEST(KlartextInterpreter, ArcEndOffTheCircleIsRefused) {
  EXPECT_EQ(error_of("BEGIN PGM T MM\nL X+10 Y+0 F100\nCC X+0 Y+0\nC X+0 Y+11 DR+\n"), Code::E3310);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nL X+10 Y+0 F100\nC X+0 Y+10 DR+\n"), Code::E3312);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nL X+10 Y+0 F100\nCR X+30 Y+0 R+5 DR+\n"), Code::E3311);
}

TEST(KlartextInterpreter, ToolCallsAndBareSpeed) {
  Interpreter interpreter(
      "BEGIN PGM T MM\n"
      "TOOL CALL 5 Z S2500 F350\n"
      "TOOL CALL \"JN08001000360199\" Z S5961 DL+0 DR+0\n"
      "TOOL CALL S11127\n"
      "TOOL CALL \"JN08001000360199\" Z S6000\n"
      "END PGM T MM\n");
  const auto events = run("", &interpreter);
  std::vector<int> changes;
  std::vector<double> speeds;
  for (const Event& e : events) {
    if (const auto* c = std::get_if<program::ChangeTool>(&e)) changes.push_back(c->number);
    if (const auto* s = std::get_if<program::SetSpindleSpeed>(&e)) speeds.push_back(s->rpm);
  }
  // Named tools are numbered in the order they are first called; the bare
  // TOOL CALL S changes only the speed.
  EXPECT_EQ(changes, (std::vector<int>{5, 1, 1}));
  EXPECT_EQ(speeds, (std::vector<double>{2500, 5961, 11127, 6000}));
  EXPECT_EQ(interpreter.tool_number("JN08001000360199"), 1);
}

TEST(KlartextInterpreter, SubprogramsAndRepeats) {
  // LBL 1 runs once in sequence, then REP 2 runs it twice more: three
  // passes of IX+1. The subprogram LBL 5 (after M30) is called once: IY+10.
  const auto events =
      run("BEGIN PGM T MM\n"
          "L X+0 Y+0 Z+0 F100\n"
          "LBL 1\n"
          "L IX+1\n"
          "CALL LBL 1 REP2\n"
          "CALL LBL 5\n"
          "L Z+50 FMAX\n"
          "M30\n"
          "LBL 5\n"
          "L IY+10\n"
          "LBL 0\n"
          "END PGM T MM\n");
  const auto m = motions(events);
  ASSERT_EQ(m.size(), 6u);
  expect_point(end_of(m[1]), 1, 0, 0);
  expect_point(end_of(m[2]), 2, 0, 0);
  expect_point(end_of(m[3]), 3, 0, 0);
  expect_point(end_of(m[4]), 3, 10, 0);
  expect_point(end_of(m[5]), 3, 10, 50);
}

TEST(KlartextInterpreter, ConditionalJumpsAndArithmetic) {
  // A loop by FN 9..12: Q1 counts 0, 1, 2 (three moves of IX+2), then
  // FN 12 stops jumping when Q1 = 3.
  const auto events =
      run("BEGIN PGM T MM\n"
          "FN 0: Q1 = +0\n"
          "FN 0: Q2 = +3\n"
          "L X+0 Y+0 Z+0 F100\n"
          "LBL \"loop\"\n"
          "L IX+2\n"
          "FN 1: Q1 = +Q1 + +1\n"
          "FN 12: IF +Q1 LT +Q2 GOTO LBL \"loop\"\n"
          "FN 3: Q3 = +Q1 * +4\n"    // 12
          "FN 4: Q4 = +Q3 DIV +8\n"  // 1.5
          "FN 2: Q5 = +Q4 - +0.5\n"  // 1
          "L Y+Q4 Z-Q5\n"
          "END PGM T MM\n");
  const auto m = motions(events);
  ASSERT_EQ(m.size(), 5u);
  expect_point(end_of(m[3]), 6, 0, 0);
  expect_point(end_of(m[4]), 6, 1.5, -1);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nFN 4: Q1 = +1 DIV +0\n"), Code::E3318);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nLBL 1\nFN 9: IF +0 EQU +0 GOTO LBL 1\n"), Code::E3317);
}

TEST(KlartextInterpreter, IncrementalDatumShiftMovesTheNextPosition) {
  const auto events =
      run("BEGIN PGM T MM\n"
          "L X+0 Y+0 Z+0 F200\n"
          "CYCL DEF 7.0 DATUM SHIFT\n"
          "CYCL DEF 7.1 X+100\n"
          "CYCL DEF 7.0 DATUM SHIFT\n"
          "CYCL DEF 7.1 IX+10\n"
          "L X+1\n"  // 110 + 1
          "CYCL DEF9.1 V.ZEIT1.5\n"
          "END PGM T MM\n");
  const auto m = motions(events);
  ASSERT_EQ(m.size(), 2u);
  expect_point(end_of(m[1]), 111, 0, 0);
  bool dwell = false;
  for (const Event& e : events)
    if (const auto* d = std::get_if<program::Dwell>(&e)) dwell = d->seconds == 1.5;
  EXPECT_TRUE(dwell);
}

TEST(KlartextInterpreter, PolarLinesAndArcs) {
  const auto m =
      motions(run("BEGIN PGM T MM\n"
                  "CC X+0 Y+0\n"
                  "L X+10 Y+0 Z+0 F100\n"
                  "LP PR+10 PA+90\n"       // (0, 10)
                  "LP IPA+90\n"            // radius kept: (-10, 0)
                  "LP IPR+5\n"             // angle kept: (-15, 0)
                  "LP PR+10 PA+180\n"      // back to (-10, 0)
                  "CP IPA+180 DR+\n"       // half a turn ccw: (10, 0)
                  "CP IPA+720 IZ-4 DR+\n"  // two turns of a helix: (10, 0, -4)
                  "END PGM T MM\n"));
  ASSERT_EQ(m.size(), 7u);
  expect_point(end_of(m[1]), 0, 10, 0, 1e-9);
  expect_point(end_of(m[2]), -10, 0, 0, 1e-9);
  expect_point(end_of(m[3]), -15, 0, 0, 1e-9);
  expect_point(end_of(m[4]), -10, 0, 0, 1e-9);
  const auto& half = std::get<program::ArcFeed>(m[5]);
  expect_point(half.end, 10, 0, 0, 1e-9);
  expect_point(half.centre, 0, 0, 0);
  EXPECT_EQ(half.rotation, 1);
  const auto& helix = std::get<program::ArcFeed>(m[6]);
  expect_point(helix.end, 10, 0, -4, 1e-9);
  EXPECT_EQ(helix.rotation, 2);  // two turns started
}

TEST(KlartextInterpreter, RoundedAndChamferedCorners) {
  // A left turn of 90 degrees at (10, 0): RND R2 cuts 2 tan 45 = 2 mm off
  // each line; the arc from (8, 0) to (10, 2) turns about (8, 2).
  const auto m =
      motions(run("BEGIN PGM T MM\n"
                  "L X+0 Y+0 Z+0 F100\n"
                  "L X+10\n"
                  "RND R2\n"
                  "L Y+10\n"
                  "CHF 3\n"  // a right turn at (10, 10): (10, 7) to (13, 10)
                  "L X+20\n"
                  "END PGM T MM\n"));
  ASSERT_EQ(m.size(), 6u);
  expect_point(end_of(m[1]), 8, 0, 0, 1e-9);
  const auto& round = std::get<program::ArcFeed>(m[2]);
  expect_point(round.end, 10, 2, 0, 1e-9);
  expect_point(round.centre, 8, 2, 0, 1e-9);
  EXPECT_EQ(round.rotation, 1);
  expect_point(end_of(m[3]), 10, 7, 0, 1e-9);
  const auto& chamfer = std::get<program::StraightFeed>(m[4]);
  expect_point(chamfer.start, 10, 7, 0, 1e-9);
  expect_point(chamfer.end, 13, 10, 0, 1e-9);
  expect_point(end_of(m[5]), 20, 10, 0, 1e-9);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nL X+0 Y+0 F100\nL X+1\nRND R5\nL Y+10\n"),
            Code::E3314);  // 5 tan 45 = 5 > the 1 mm line
}

TEST(KlartextInterpreter, InchProgram) {
  // Lengths in inch (x 25.4); F in 1/10 inch/min as the TNC takes it:
  // F100 = 10 inch/min = 254 mm/min.
  const auto events = run("BEGIN PGM T INCH\nL X+1 Y+2 Z+0.5 F100\nEND PGM T INCH\n");
  const auto m = motions(events);
  ASSERT_EQ(m.size(), 1u);
  expect_point(end_of(m[0]), 25.4, 50.8, 12.7, 1e-9);
  for (const Event& e : events) {
    if (const auto* f = std::get_if<program::SetFeedRate>(&e)) {
      EXPECT_NEAR(f->rate, 254.0, 1e-9);
    }
  }
}

TEST(KlartextInterpreter, ContinuedDrillingCycle) {
  // Cycle 200 at (10, 10) from Z50: surface 0, clearance 2, depth -10 in
  // plunges of 5, 2nd clearance 20, 0.5 s at the bottom. Worked out:
  // rapid to 2; feed to -5; rapid to 2; rapid to -5 + 2 = -3; feed to -10;
  // dwell; rapid to 2; rapid to 20.
  const auto events =
      run("BEGIN PGM T MM\n"
          "L X+0 Y+0 Z+50 R0 FMAX\n"
          "CYCL DEF 200 DRILLING~\n"
          "    Q200=2 ;SET-UP CLEARANCE~\n"
          "    Q201=-10 ;DEPTH~\n"
          "    Q206=150 ;FEED RATE FOR PLNGNG~\n"
          "    Q202=5 ;PLUNGING DEPTH~\n"
          "    Q210=0 ;DWELL TIME AT TOP~\n"
          "    Q203=+0 ;SURFACE COORDINATE~\n"
          "    Q204=20 ;2ND SET-UP CLEARANCE~\n"
          "    Q211=0.5 ;DWELL TIME AT BOTTOM\n"
          "L X+10 Y+10 R0 FMAX M99\n"
          "END PGM T MM\n");
  std::vector<double> z;
  std::vector<bool> fed;
  const program::CannedCycle* cycle = nullptr;
  double dwell = 0;
  for (const Event& e : events) {
    if (const auto* c = std::get_if<program::CannedCycle>(&e)) cycle = c;
    if (const auto* d = std::get_if<program::Dwell>(&e)) dwell = d->seconds;
    if (program::is_motion(e)) {
      z.push_back(end_of(e).z());
      fed.push_back(std::holds_alternative<program::StraightFeed>(e));
    }
  }
  EXPECT_EQ(z, (std::vector<double>{50, 50, 2, -5, 2, -3, -10, 2, 20}));
  EXPECT_EQ(fed, (std::vector<bool>{false, false, false, true, false, false, true, false, false}));
  EXPECT_DOUBLE_EQ(dwell, 0.5);
  ASSERT_NE(cycle, nullptr);
  EXPECT_EQ(cycle->code, 200);
  EXPECT_EQ(cycle->moves, 7u);
  EXPECT_EQ(cycle->events, 9u);  // 7 moves, the cycle's feed, the dwell
  EXPECT_DOUBLE_EQ(cycle->bottom_z, -10);
  EXPECT_DOUBLE_EQ(cycle->top_z, 20);
}

TEST(KlartextInterpreter, MachineCoordinateMovesAreRetracts) {
  // M92's machine position is unknown: a retract to the highest of the
  // stock top (0.25) and the heights reached (10), X and Y kept.
  const auto m =
      motions(run("BEGIN PGM T MM\n"
                  "BLK FORM 0.1 Z X-95 Y-258 Z-22.25\n"
                  "BLK FORM 0.2 X95 Y258 Z0.25\n"
                  "L Z+0 R0 FMAX M92\n"  // from 0: up to the stock top
                  "L X+5 Y+5 Z+10 R0 FMAX\n"
                  "L Z-5 F100\n"
                  "L Z+0 R0 FMAX M92\n"      // back to 10
                  "L X+0 Y+0 R0 FMAX M92\n"  // no Z: no move
                  "END PGM T MM\n"));
  ASSERT_EQ(m.size(), 4u);
  expect_point(end_of(m[0]), 0, 0, 0.25);
  EXPECT_TRUE(std::get<program::StraightTraverse>(m[0]).machine_frame);
  expect_point(end_of(m[3]), 5, 5, 10);
  EXPECT_TRUE(std::get<program::StraightTraverse>(m[3]).machine_frame);
}

TEST(KlartextInterpreter, BlockInformationForWriters) {
  const std::string text =
      "1 BEGIN PGM T MM\r\n"
      "2 TOOL CALL \"A\" Z S5961 DL+0\r\n"
      "3 CYCL DEF 200 DRILLING~\r\n"
      "    Q200=2 ;SET-UP CLEARANCE~\r\n"
      "    Q201=-5 ;DEPTH\r\n"
      "4 TOOL CALL S11127\r\n"
      "L X+1 FMAX\r\n"
      "5 END PGM T MM\r\n";
  Interpreter interpreter(text);
  std::vector<Event> events;
  ASSERT_TRUE(interpreter.next(events));
  const Block& b1 = interpreter.block();
  EXPECT_EQ(b1.kind, BlockKind::begin_pgm);
  EXPECT_EQ(b1.offset, 0u);
  EXPECT_EQ(b1.end, 16u);  // "1 BEGIN PGM T MM" without "\r\n"
  EXPECT_EQ(b1.eol, "\r\n");
  ASSERT_TRUE(interpreter.next(events));
  const Block& b2 = interpreter.block();
  EXPECT_EQ(b2.kind, BlockKind::tool_call);
  EXPECT_EQ(b2.line, 2u);
  EXPECT_EQ(*b2.number, 2u);
  EXPECT_EQ(text.substr(b2.number_span->begin, b2.number_span->end - b2.number_span->begin), "2");
  ASSERT_TRUE(b2.s_span);
  EXPECT_EQ(text.substr(b2.s_span->begin, b2.s_span->end - b2.s_span->begin), "S5961");
  ASSERT_TRUE(interpreter.next(events));
  const Block& b3 = interpreter.block();
  EXPECT_EQ(b3.kind, BlockKind::cycle_def);
  EXPECT_EQ(b3.line, 3u);
  EXPECT_EQ(b3.lines, 3u);
  EXPECT_EQ(text.substr(b3.offset, b3.end - b3.offset),
            "3 CYCL DEF 200 DRILLING~\r\n    Q200=2 ;SET-UP CLEARANCE~\r\n    Q201=-5 ;DEPTH");
  ASSERT_EQ(b3.cycle_parameters.size(), 2u);
  ASSERT_TRUE(interpreter.next(events));
  const Block& b4 = interpreter.block();
  EXPECT_EQ(b4.line, 6u);
  EXPECT_EQ(text.substr(b4.s_span->begin, b4.s_span->end - b4.s_span->begin), "S11127");
  ASSERT_TRUE(interpreter.next(events));
  EXPECT_FALSE(interpreter.block().number.has_value());  // a block without its number
  EXPECT_EQ(interpreter.block().kind, BlockKind::line);
  ASSERT_TRUE(interpreter.next(events));
  EXPECT_EQ(interpreter.block().kind, BlockKind::end_pgm);
  EXPECT_FALSE(interpreter.next(events));
}

TEST(KlartextInterpreter, IdentityPlanesAndTheirRotaryPositionsAreRead) {
  Interpreter interpreter(
      "BEGIN PGM T MM\n"
      "PLANE SPATIAL SPA+0 SPB+0 SPC+0 STAY SEQ+ TABLE ROT\n"
      "L A+Q120 C+Q122 R0 FMAX M126\n"
      "PLANE RESET STAY\n"
      "END PGM T MM\n");
  std::vector<Event> events;
  while (interpreter.next(events)) {
  }
  ASSERT_TRUE(interpreter.plane());
  EXPECT_EQ(interpreter.plane()->kind, "RESET");
  // No tilt: no WorkingFrame, the events are as before.
  for (const Event& e : events) EXPECT_FALSE(std::holds_alternative<program::WorkingFrame>(e));
  EXPECT_EQ(error_of("BEGIN PGM T MM\nPLANE AXIAL A+30 C+45 STAY\n"), Code::E3320);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nM128\nL A+10 FMAX\n"), Code::E3321);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nPLANE VECTOR BX1 BY0 BZ0 NX1 NY0 NZ0 STAY\n"),
            Code::E3303);  // base vector along the normal
}

const double c45 = std::sqrt(0.5);

// PLANE SPATIAL turns about the machine's fixed X by SPA, then Y by SPB,
// then Z by SPC: R = Rz(SPC) Ry(SPB) Rx(SPA), about the datum of CYCL DEF 7.
// W5246NS01007B10.h, lines 51-59 (its comment: "A-90 C90", an AC table):
// SPA90 SPC-90 make the frame's x = (0,-1,0), y = (0,0,1), z = (-1,0,0):
// the tool comes at the part's -X face. X51.5 Y0 Z50 there is
// 51.5 x + 50 z + datum (-258, 1.5, -11) = (-308, -50, -11).
TEST(KlartextInterpreter, PlaneSpatialAboutTheDatum) {
  const auto events =
      run("BEGIN PGM T MM\n"
          "CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X-258\nCYCL DEF 7.2 Y1.5\nCYCL DEF 7.3 Z-11\n"
          "PLANE SPATIAL SPA90 SPB0 SPC-90 STAY SEQ- TABLE ROT\n"
          "L A+Q120 C+Q122 R0 FMAX M126\n"
          "L X51.5 Y0 Z50 R0 FMAX M3\n"
          "L Z-3 F500\n"
          "CYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X0\nCYCL DEF 7.2 Y0\nCYCL DEF 7.3 Z0\n"
          "PLANE RESET STAY\n"
          "L X1 Y2 Z3 FMAX\n"
          "END PGM T MM\n");
  std::vector<program::WorkingFrame> frames;
  for (const Event& e : events)
    if (const auto* f = std::get_if<program::WorkingFrame>(&e)) frames.push_back(*f);
  ASSERT_EQ(frames.size(), 2u);  // the tilt, the reset
  Eigen::Matrix3d r;
  r << 0, 0, -1, -1, 0, 0, 0, 1, 0;  // columns x, y, z
  EXPECT_EQ(frames[0].rotation, r);
  EXPECT_EQ(frames[0].source.line, 6u);
  EXPECT_TRUE(frames[1].is_identity());
  const auto ends = program_ends(events);
  ASSERT_EQ(ends.size(), 3u);
  expect_point(ends[0], -308, -50, -11);
  expect_point(ends[1], -255, -50, -11);  // 3 mm into the -X face (X -258)
  expect_point(ends[2], 1, 2, 3);
}

// SPB+45: x = (c,0,-c), z = (c,0,c) (a head B+45 leans the tool towards
// +X). RELATIV SPA+90 then turns about the tilted x: z' = Ry(45) Rx(90) z =
// Ry(45) (0,-1,0) = (0,-1,0).
TEST(KlartextInterpreter, PlaneSpatialAndRelativ) {
  const auto events =
      run("BEGIN PGM T MM\n"
          "PLANE SPATIAL SPA+0 SPB+45 SPC+0 MOVE DIST50 F1000\n"
          "L X10 Y0 Z0 FMAX\nL X0 Y0 Z10 F1000\n"
          "PLANE RELATIV SPA+90 STAY\n"
          "L X0 Y0 Z10 FMAX\nL X10 Y0 Z0\n"
          "END PGM T MM\n");
  const auto ends = program_ends(events);
  ASSERT_EQ(ends.size(), 4u);
  expect_point(ends[0], 10 * c45, 0, -10 * c45, 1e-12);
  expect_point(ends[1], 10 * c45, 0, 10 * c45, 1e-12);
  expect_point(ends[2], 0, -10, 0, 1e-12);
  expect_point(ends[3], 10 * c45, 0, -10 * c45, 1e-12);  // x' = Ry(45) Rx(90) x = (c,0,-c)
}

// EULER: Rz(EULPR) Rx(EULNU) Rz(EULROT). PR90 NU45: x = (0,1,0),
// y = (-c,0,c), z = (c,0,c). VECTOR: z the normal, x the base vector made
// perpendicular to it. CYCL DEF 19 B+90 as SPATIAL SPB+90: x = (0,0,-1),
// z = (1,0,0).
TEST(KlartextInterpreter, PlaneEulerVectorAndCycle19) {
  const auto events =
      run("BEGIN PGM T MM\n"
          "PLANE EULER EULPR+90 EULNU45 EULROT0 TURN\n"
          "L X0 Y10 Z0 FMAX\nL X0 Y0 Z10 F1000\n"
          "PLANE VECTOR BX0.3 BY1 BZ0 NX1 NY0 NZ0 STAY\n"
          "L X1 Y2 Z3 FMAX\n"
          "CYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 B+90\n"
          "L X10 Y0 Z5 FMAX\n"
          "CYCL DEF 19.0 WORKING PLANE\nCYCL DEF 19.1 B+0\n"
          "L X1 Y2 Z3 FMAX\n"
          "END PGM T MM\n");
  const auto ends = program_ends(events);
  ASSERT_EQ(ends.size(), 5u);
  expect_point(ends[0], -10 * c45, 0, 10 * c45, 1e-12);
  expect_point(ends[1], 10 * c45, 0, 10 * c45, 1e-12);
  expect_point(ends[2], 3, 1, 2, 1e-12);  // z = (1,0,0), x = (0,1,0), y = (0,0,1)
  expect_point(ends[3], 5, 0, -10, 1e-12);
  expect_point(ends[4], 1, 2, 3, 1e-12);
}

// MOVE, TURN or STAY, the tool's tip is taken to stay where it is on the
// part: the first move after the tilt starts there, in the frame's
// coordinates. At (0,0,100) before SPB+90 (z = (1,0,0), x = (0,0,-1)) it
// is at x = -100, z = 0 in the frame.
TEST(KlartextInterpreter, TheToolStaysOnThePartThroughATilt) {
  const auto events =
      run("BEGIN PGM T MM\n"
          "L X0 Y0 Z100 FMAX\n"
          "PLANE SPATIAL SPA0 SPB+90 SPC0 TURN\n"
          "L Z50 FMAX\n"
          "END PGM T MM\n");
  const auto all = motions(events);
  ASSERT_EQ(all.size(), 2u);
  const auto& second = std::get<program::StraightTraverse>(all[1]);
  expect_point(second.start, -100, 0, 0, 1e-12);
  expect_point(second.end, -100, 0, 50, 1e-12);
  expect_point(program_ends(events)[1], 50, 0, 100, 1e-12);
}

}  // namespace
}  // namespace vcpost::heidenhain
