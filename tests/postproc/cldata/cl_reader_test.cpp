// CL records -> motion events: the semantics of each word, checked by hand.
#include "postproc/cldata/cl_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iterator>
#include <numbers>
#include <sstream>
#include <string_view>
#include <utility>

#include "postproc/cldata/nurbs.h"
#include "postproc/program/arc.h"
#include "tests/postproc/cldata/cl_support.h"

namespace vcpost::cldata {
namespace {

using namespace vcpost::program;
using testing::read_events;

template <class T>
std::vector<T> only(const std::vector<Event>& events) {
  std::vector<T> out;
  for (const auto& e : events) {
    if (const auto* t = std::get_if<T>(&e)) out.push_back(*t);
  }
  return out;
}

Code code_of(const std::string& text) {
  try {
    read_events(text);
  } catch (const ClError& e) {
    return e.code();
  }
  ADD_FAILURE() << "no error for: " << text;
  return Code::W3150;
}

TEST(ClReader, FedratBothWordOrdersAndUnits) {
  const auto feeds = only<SetFeedRate>(
      read_events("FEDRAT/MMPM,250\nFEDRAT/300,MMPM\nFEDRAT/10,IPM\nFEDRAT/0.1,MMPR\nUNITS/INCHES\n"
                  "FEDRAT/20\nFINI\n"));
  ASSERT_EQ(feeds.size(), 5u);
  EXPECT_DOUBLE_EQ(feeds[0].rate, 250.0);
  EXPECT_DOUBLE_EQ(feeds[1].rate, 300.0);
  EXPECT_DOUBLE_EQ(feeds[2].rate, 254.0);  // 10 in/min
  EXPECT_EQ(feeds[3].mode, FeedMode::per_revolution);
  EXPECT_DOUBLE_EQ(feeds[3].rate, 0.1);
  EXPECT_DOUBLE_EQ(feeds[4].rate, 508.0);  // 20 per minute in inches
}

TEST(ClReader, RepeatedFedratOfTheSameValueIsOneEvent) {
  EXPECT_EQ(only<SetFeedRate>(read_events("FEDRAT/250,MMPM\nFEDRAT/MMPM,250\nFINI\n")).size(), 1u);
}

TEST(ClReader, SpindlInAnyOrder) {
  const auto events =
      read_events("SPINDL/3500,RPM,CLW\nSPINDL / RPM, 2000.0,  CCLW\nSPINDL/OFF\nFINI\n");
  const auto speeds = only<SetSpindleSpeed>(events);
  const auto on = only<SpindleOn>(events);
  ASSERT_EQ(speeds.size(), 2u);
  EXPECT_DOUBLE_EQ(speeds[0].rpm, 3500);
  EXPECT_DOUBLE_EQ(speeds[1].rpm, 2000);
  ASSERT_EQ(on.size(), 2u);
  EXPECT_EQ(on[0].direction, SpindleDirection::clockwise);
  EXPECT_EQ(on[1].direction, SpindleDirection::counterclockwise);
  EXPECT_EQ(only<SpindleOff>(events).size(), 1u);
}

TEST(ClReader, SurfaceSpeedUsesTheCutterDiameter) {
  // 120 m/min on D = 10 mm: n = 120000 / (pi * 10) = 3819.72 rpm.
  const auto speeds = only<SetSpindleSpeed>(read_events("CUTTER/10,5\nSPINDL/SMM,120,CLW\nFINI\n"));
  ASSERT_EQ(speeds.size(), 1u);
  EXPECT_NEAR(speeds[0].rpm, 3819.7186, 1e-4);
  EXPECT_EQ(code_of("SPINDL/SMM,120\nFINI\n"), Code::E3115);
}

TEST(ClReader, CutterParametersBecomeTools) {
  std::istringstream in(
      "CUTTER/10\nCUTTER/10,5\nCUTTER/12,2\nCUTTER/6.,0,3.,0,0,0,51.\n"
      "CUTTER/4.,0,2.,1.201721,31.,0,83.\nTLDATA/MILL,30.0000,15.0000,75.0000,0.0000,0.0000\n"
      "UNITS/INCHES\nCUTTER/0.5,0.25\nFINI\n");
  ClReader reader(in, "t.cl");
  while (reader.next()) {
  }
  const auto& c = reader.cutters();
  ASSERT_EQ(c.size(), 7u);
  EXPECT_EQ(geometry::to_string(*c[0].tool), "flat:10");
  EXPECT_EQ(geometry::to_string(*c[1].tool), "ball:10");
  EXPECT_EQ(geometry::to_string(*c[2].tool), "bull:12:2");
  EXPECT_EQ(geometry::to_string(*c[3].tool), "flat:6");
  EXPECT_FALSE(c[4].tool.has_value());  // 118 deg drill point
  EXPECT_NE(c[4].why_not.find("31 deg"), std::string::npos);
  EXPECT_EQ(geometry::to_string(*c[5].tool), "ball:30");
  ASSERT_TRUE(c[6].tool.has_value());
  EXPECT_DOUBLE_EQ(c[6].tool->diameter, 12.7);
  EXPECT_EQ(c[6].tool->kind, geometry::ToolKind::ball);
  ASSERT_EQ(reader.warnings().size(), 1u);
  EXPECT_EQ(reader.warnings()[0].code, Code::W3153);
  EXPECT_EQ(reader.warnings()[0].line, 5u);
}

TEST(ClReader, GotoRapidFromAndMultiplePoints) {
  const auto events = read_events(
      "FROM/0,0,100\nRAPID\nGOTO/10,20,30\nGOTO/10,20,5,0,0,1\nGOTO/1,1,1,2,2,2,3,3,3\n"
      "GOTO / 4,4,4\n  5,5,5\nFINI\n");
  const auto traverses = only<StraightTraverse>(events);
  const auto feeds = only<StraightFeed>(events);
  ASSERT_EQ(traverses.size(), 1u);
  EXPECT_EQ(traverses[0].start, Eigen::Vector3d(0, 0, 100));
  EXPECT_EQ(traverses[0].end, Eigen::Vector3d(10, 20, 30));
  ASSERT_EQ(feeds.size(), 6u);  // RAPID applies to one record only
  EXPECT_EQ(feeds[0].end, Eigen::Vector3d(10, 20, 5));
  EXPECT_EQ(feeds[1].end, Eigen::Vector3d(1, 1, 1));
  EXPECT_EQ(feeds[3].start, Eigen::Vector3d(2, 2, 2));
  EXPECT_EQ(feeds[3].end, Eigen::Vector3d(3, 3, 3));
  EXPECT_EQ(feeds[5].end, Eigen::Vector3d(5, 5, 5));
  EXPECT_EQ(feeds[5].source.line, 7u);
}

TEST(ClReader, GodltaAndInchUnits) {
  const auto feeds = only<StraightFeed>(
      read_events("UNITS/INCHES\nGOTO/1,2,3\nGODLTA/0.5,0,0\nGODLTA/-1\nFINI\n"));
  ASSERT_EQ(feeds.size(), 3u);
  EXPECT_TRUE(feeds[0].end.isApprox(Eigen::Vector3d(25.4, 50.8, 76.2)));
  EXPECT_TRUE(feeds[1].end.isApprox(Eigen::Vector3d(38.1, 50.8, 76.2)));
  EXPECT_TRUE(feeds[2].end.isApprox(Eigen::Vector3d(38.1, 50.8, 50.8)));
  EXPECT_EQ(code_of("GODLTA/1,0,0\nFINI\n"), Code::E3114);
}

TEST(ClReader, AptCircleTurnsCounterclockwiseAboutItsAxis) {
  // Quarter circle r = 5 about (0,0): (5,0) -> (0,5) CCW about +Z = G3.
  const auto arcs = only<ArcFeed>(read_events(
      "GOTO/5,0,0\nCIRCLE/0,0,0,0,0,1,5\nGOTO/0,5,0\nCIRCLE/0,0,0,0,0,-1.,5\nGOTO/5,0,-1\nFINI\n"));
  ASSERT_EQ(arcs.size(), 2u);
  EXPECT_EQ(arcs[0].plane, Plane::xy);
  EXPECT_EQ(arcs[0].rotation, 1);
  EXPECT_NEAR(arc_sweep(arcs[0]), std::numbers::pi / 2, 1e-12);
  EXPECT_EQ(arcs[1].rotation, -1);  // back CW, helical down by 1
  EXPECT_NEAR(arc_sweep(arcs[1]), -std::numbers::pi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(arcs[1].end.z(), -1.0);
  EXPECT_DOUBLE_EQ(arcs[1].centre.z(), 0.0);  // = start's axis coordinate
}

TEST(ClReader, NxCircleFormTurnsClockwiseAboutItsAxis) {
  // The first arc of _1_KONTUR_NAR_40_N2.cls: 45.1 deg clockwise.
  const auto arcs = only<ArcFeed>(read_events(
      "GOTO/1221.5423,14.3929,466.0000\n"
      "CIRCLE/1245.5000,-458.0000,466.0000,0.0000000,0.0000000,1.0000000,473.0000,0.0600,0.5000,"
      "40.0000,1.0000\nGOTO/1563.1794,-107.5591,466.0000\nFINI\n"));
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_EQ(arcs[0].rotation, -1);
  const double a0 = std::atan2(14.3929 + 458.0, 1221.5423 - 1245.5);
  const double a1 = std::atan2(-107.5591 + 458.0, 1563.1794 - 1245.5);
  EXPECT_NEAR(arc_sweep(arcs[0]), a1 - a0, 1e-9);
  EXPECT_NEAR((a0 - a1) * 180 / std::numbers::pi, 45.1, 0.05);
}

TEST(ClReader, SideAxisCircleIsAnArcInItsPlaneAndTiltedOneBecomesLines) {
  const auto yz =
      only<ArcFeed>(read_events("GOTO/0,5,0\nCIRCLE/0,0,0,1,0,0,5\nGOTO/0,0,5\nFINI\n"));
  ASSERT_EQ(yz.size(), 1u);
  EXPECT_EQ(yz[0].plane, Plane::yz);
  EXPECT_EQ(yz[0].rotation, 1);  // Y towards Z about +X
  ClReadOptions options;
  options.chord_tolerance = 0.01;
  // Axis (0, -sqrt(1/2), sqrt(1/2)).
  const auto lines = only<StraightFeed>(read_events(
      "GOTO/5,0,0\nCIRCLE/0,0,0,0,-0.70710678,0.70710678,5\nGOTO/0,3.5355339,3.5355339\nFINI\n",
      options));
  // 90 deg at r = 5 within 0.01: step 2*acos(1 - 0.01/5) = 0.12650 rad -> 13 lines,
  // after the first GOTO (a move from the unknown start, i.e. of length 0).
  ASSERT_EQ(lines.size(), 14u);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto& l = lines[i];
    const Eigen::Vector3d mid = 0.5 * (l.start + l.end);
    EXPECT_LE(5.0 - mid.norm(), 0.01 + 1e-9);
    EXPECT_NEAR(l.end.norm(), 5.0, 1e-6);
  }
}

TEST(ClReader, InconsistentArcIsRefused) {
  EXPECT_EQ(code_of("GOTO/5,0,0\nCIRCLE/0,0,0,0,0,1,5\nGOTO/0,5.1,0\nFINI\n"), Code::E3109);
  EXPECT_EQ(code_of("GOTO/5,0,0\nCIRCLE/0,0,0,0,0,1,6\nGOTO/0,5,0\nFINI\n"), Code::E3109);
  EXPECT_EQ(code_of("GOTO/5,0,0\nCIRCLE/0,0,0,0,0,1,5\nFINI\n"), Code::E3110);
}

TEST(ClReader, FiveAxisPointIsRefusedAtTheAxisValue) {
  try {
    read_events("GOTO/1,2,3\nGOTO/1,2,3,0,0.6,0.8\nFINI\n");
    FAIL();
  } catch (const ClError& e) {
    EXPECT_EQ(e.code(), Code::E3108);
    EXPECT_EQ(e.diagnostic().line, 2u);
    EXPECT_EQ(e.diagnostic().column, 12u);
  }
}

TEST(ClReader, DrillCycleIsExpandedLikeG81WithRetract) {
  const auto events = read_events(
      "FEDRAT/500,MMPM\nRAPID\nGOTO/29.06066,116.93934,25.\nCYCLE/INIT\n"
      "CYCLE/DRILL,FEDTO,10.,MMPM,275.59,RAPTO,3.,RTRCTO,25.,DWELL,0\n"
      "GOTO/29.06066,116.93934,0\nGOTO/76.93934,116.93934,0\nCYCLE/OFF\nGOTO/0,0,25\nFINI\n");
  const auto feeds = only<StraightFeed>(events);
  const auto traverses = only<StraightTraverse>(events);
  const auto rates = only<SetFeedRate>(events);
  ASSERT_EQ(feeds.size(), 3u);
  EXPECT_TRUE(feeds[0].start.isApprox(Eigen::Vector3d(29.06066, 116.93934, 3)));
  EXPECT_TRUE(feeds[0].end.isApprox(Eigen::Vector3d(29.06066, 116.93934, -10)));
  EXPECT_TRUE(feeds[1].end.isApprox(Eigen::Vector3d(76.93934, 116.93934, -10)));
  // rapid in, top -> clearance, back out per hole, plus the first RAPID.
  ASSERT_EQ(traverses.size(), 7u);
  EXPECT_TRUE(traverses[6].end.isApprox(Eigen::Vector3d(76.93934, 116.93934, 25)));
  ASSERT_EQ(rates.size(), 3u);  // 500, the cycle's 275.59, 500 again after CYCLE/OFF
  EXPECT_DOUBLE_EQ(rates[1].rate, 275.59);
  EXPECT_DOUBLE_EQ(rates[2].rate, 500);
  EXPECT_EQ(code_of("CYCLE/DRILL,THRU,RAPTO,3,FEDTO,0,MMPM,250\nFINI\n"), Code::E3112);
  EXPECT_EQ(code_of("CYCLE/CSINK,10,90,MMPM,100\nFINI\n"), Code::E3112);
  EXPECT_EQ(code_of("CYCLE/TAP,FEDTO,10,RAPTO,3\nFINI\n"), Code::E3112);  // no feed
}

// SolidWorks CAM writes CYCLE/CLEAR before a cycle: read as CYCLE/INIT is,
// the same holes with the same moves.
TEST(ClReader, CycleClearReadsAsCycleInit) {
  const auto program = [](const std::string& marker) {
    return "FEDRAT/500,MMPM\nRAPID\nGOTO/29.06066,116.93934,25.\nCYCLE/" + marker +
           "\nCYCLE/DRILL,FEDTO,10.,MMPM,275.59,RAPTO,3.,RTRCTO,25.,DWELL,0\n"
           "GOTO/29.06066,116.93934,0\nCYCLE/OFF\nFINI\n";
  };
  const auto with_init = read_events(program("INIT"));
  const auto with_clear = read_events(program("CLEAR"));
  const auto feeds = only<StraightFeed>(with_clear);
  ASSERT_EQ(feeds.size(), 1u);
  EXPECT_TRUE(feeds[0].start.isApprox(Eigen::Vector3d(29.06066, 116.93934, 3)));
  EXPECT_TRUE(feeds[0].end.isApprox(Eigen::Vector3d(29.06066, 116.93934, -10)));
  ASSERT_EQ(with_clear.size(), with_init.size());
  EXPECT_EQ(only<StraightTraverse>(with_clear).size(), only<StraightTraverse>(with_init).size());
}

// The z levels of a hole's moves, in order: 'r' rapid, 'f' feed.
std::string z_levels(const std::vector<Event>& events) {
  std::string out;
  char buffer[32];
  for (const auto& e : events) {
    if (const auto* t = std::get_if<StraightTraverse>(&e)) {
      std::snprintf(buffer, sizeof buffer, "r%.3f ", t->end.z());
    } else if (const auto* f = std::get_if<StraightFeed>(&e)) {
      std::snprintf(buffer, sizeof buffer, "f%.3f ", f->end.z());
    } else if (const auto* on = std::get_if<SpindleOn>(&e)) {
      std::snprintf(buffer, sizeof buffer, "%s ",
                    on->direction == SpindleDirection::clockwise ? "M3" : "M4");
    } else if (std::holds_alternative<SpindleOff>(e)) {
      std::snprintf(buffer, sizeof buffer, "M5 ");
    } else if (const auto* d = std::get_if<Dwell>(&e)) {
      std::snprintf(buffer, sizeof buffer, "d%.1f ", d->seconds);
    } else {
      continue;
    }
    out += buffer;
  }
  return out;
}

// SolidWorks' DEEP2: the first peck 3 mm below RAPTO, then 2 mm each, back
// to RAPTO in rapid after each and down again to 0.254 mm above the last
// bottom (G83 as rs274 makes it), RTRCTO at the end.
TEST(ClReader, DeepCycleWithFirstAndLaterPecks) {
  const auto events = read_events(
      "RAPID\nGOTO/10,20,25\nCYCLE/INIT\n"
      "CYCLE/DEEP2,FEDTO,7,1STPECK,3.,SUBPECK,2.,MMPM,100,RAPTO,3.,RTRCTO,25.\n"
      "GOTO/10,20,0\nCYCLE/OFF\nFINI\n");
  EXPECT_EQ(z_levels(events),
            "r25.000 r25.000 r3.000 f0.000 r3.000 r0.254 f-2.000 r3.000 r-1.746 f-4.000 r3.000 "
            "r-3.746 f-6.000 r3.000 r-5.746 f-7.000 r25.000 ");
  for (const auto& f : only<StraightFeed>(events)) {
    EXPECT_EQ(f.end.x(), 10);
    EXPECT_EQ(f.end.y(), 20);
  }
  EXPECT_DOUBLE_EQ(only<SetFeedRate>(events).at(0).rate, 100);
}

// NX's DRILL,BRKCHP with STEP: short back-off of 0.254 mm between pecks;
// without RTRCTO the tool returns to RAPTO.
TEST(ClReader, ChipBreakCycleBacksOffBetweenPecks) {
  const auto events = read_events(
      "GOTO/0,0,10\nCYCLE/DRILL,BRKCHP,FEDTO,5,STEP,2,RAPTO,2,MMPM,80\nGOTO/0,0,0\n"
      "CYCLE/OFF\nFINI\n");
  EXPECT_EQ(z_levels(events),
            "f10.000 r2.000 f0.000 r0.254 f-2.000 r-1.746 f-4.000 r-3.746 f-5.000 r2.000 ");
}

// CAMWorks' positional form, CYCLE/ON before it, the retract repeated
// without a comma: pecks of 5 then 2 mm below RAPTO.
TEST(ClReader, CamworksPeckingCycle) {
  const auto events = read_events(
      "RAPID/\nGOTO/ -30.000000,-15.000000,25.000000\nCYCLE/ ON\n"
      "CYCLE/ DRILL,G98,6.001610,PECKING,5.000000,2.000000,MMPM,1101.555340,3.000000,"
      "25.000000 25.000000 DWELL,0.000000\nGOTO/ -30.000000,-15.000000,-0.000000\nCYCLE/ OFF\n"
      "FINI\n");
  EXPECT_EQ(z_levels(events),
            "r25.000 r25.000 r3.000 f-2.000 r3.000 r-1.746 f-4.000 r3.000 r-3.746 f-6.000 r3.000 "
            "r-5.746 f-6.002 "
            "r25.000 ");
  EXPECT_EQ(code_of("CYCLE/ DRILL,G98,6,MMPM,100,3,25,20\nFINI\n"), Code::E3112);
}

// Tapping reverses the spindle at the bottom and restores it at the top;
// BORE6 stops it and leaves in rapid; BORE9 dwells and feeds out.
TEST(ClReader, TapAndBoreCyclesDriveTheSpindle) {
  EXPECT_EQ(z_levels(read_events("SPINDL/500,RPM,CLW\nGOTO/0,0,3\n"
                                 "CYCLE/TAP,FEDTO,10,MMPR,1.5,RAPTO,3\nGOTO/0,0,0\nFINI\n")),
            "M3 f3.000 r3.000 f-10.000 M5 M4 f3.000 M5 M3 ");
  const auto tap = read_events("CYCLE/TAP,FEDTO,10,MMPR,1.5,RAPTO,3\nGOTO/0,0,0\nFINI\n");
  ASSERT_EQ(only<SetFeedRate>(tap).size(), 1u);
  EXPECT_EQ(only<SetFeedRate>(tap)[0].mode, FeedMode::per_revolution);
  EXPECT_DOUBLE_EQ(only<SetFeedRate>(tap)[0].rate, 1.5);
  EXPECT_EQ(z_levels(read_events("SPINDL/500,RPM,CCLW\nGOTO/0,0,20\n"
                                 "CYCLE/BORE6,FEDTO,4,MMPM,50,RAPTO,1,RTRCTO,20,DWELL,0.5\n"
                                 "GOTO/0,0,0\nFINI\n")),
            "M4 f20.000 r20.000 r1.000 f-4.000 d0.5 M5 r20.000 M4 ");
  EXPECT_EQ(z_levels(read_events("GOTO/0,0,20\nCYCLE/BORE9,FEDTO,4,MMPM,50,RAPTO,1,DWELL,2\n"
                                 "GOTO/0,0,0\nFINI\n")),
            "f20.000 r1.000 f-4.000 d2.0 f1.000 ");
  // A hole below the tool's position: up first, then across.
  const auto across = only<StraightTraverse>(read_events(
      "GOTO/5,5,-1\nCYCLE/DRILL,FEDTO,2,MMPM,50,RAPTO,1,RTRCTO,10\nGOTO/0,0,0\nFINI\n"));
  ASSERT_GE(across.size(), 2u);
  EXPECT_EQ(across[0].end, Eigen::Vector3d(5, 5, 10));
  EXPECT_EQ(across[1].end, Eigen::Vector3d(0, 0, 10));
}

// NX's helical ramp: CIRCLE/...,TIMES,2 turns twice around before the arc
// of 90 deg itself; z falls linearly over 4.5 pi: 5 - 5 * 4/9 after the
// first turn, 5 - 5 * 8/9 after the second.
TEST(ClReader, NxCircleTimesAddsFullTurns) {
  const auto arcs = only<ArcFeed>(read_events(
      "GOTO/10,0,5\nCIRCLE/0,0,0,0,0,-1,10,0.06,0.5,40,1,TIMES,2\nGOTO/0,10,0\nFINI\n"));
  ASSERT_EQ(arcs.size(), 3u);
  for (const auto& a : arcs) {
    EXPECT_EQ(a.plane, Plane::xy);
    EXPECT_EQ(a.rotation, 1);
    EXPECT_NEAR(a.centre.x(), 0, 1e-12);
    EXPECT_NEAR(a.centre.y(), 0, 1e-12);
  }
  EXPECT_TRUE(arcs[0].end.isApprox(Eigen::Vector3d(10, 0, 5 - 5 * 4.0 / 9)));
  EXPECT_TRUE(arcs[1].end.isApprox(Eigen::Vector3d(10, 0, 5 - 5 * 8.0 / 9)));
  EXPECT_TRUE(arcs[2].end.isApprox(Eigen::Vector3d(0, 10, 0)));
  // CAMWorks names the direction; CLOCKWISE turns the other way about i,j,k.
  const auto cw = only<ArcFeed>(read_events(
      "GOTO/10,0,0\nCIRCLE/ 0,0,0,0,0,1,10,CLOCKWISE\nGOTO/0,10,0\nCIRCLE/ 0,0,0,0,0,1,10,"
      "COUNTERCLOCKWISE\nGOTO/-10,0,0\nCUTTER/ 10.000000,0.000000,5.000000,0,0,0,130.000000,\n"
      "FINI\n"));
  ASSERT_EQ(cw.size(), 2u);
  EXPECT_EQ(cw[0].rotation, -1);
  EXPECT_EQ(cw[1].rotation, 1);
}

TEST(ClReader, NurbsBecomesLinesWithinTheTolerance) {
  const std::string text =
      "GOTO/-254.9774,466.5681,206.8891\nNURBS/\n"
      "KNOT/0.0416667,0.3750000,0.6250000,0.9583333,1.0000000\n"
      "CNTRL/-254.9774,466.2698,206.9401\nCNTRL/-254.9775,463.5692,207.2380\n"
      "CNTRL/-254.9776,459.2589,209.0136\nCNTRL/-254.9778,454.6135,213.9021\n"
      "CNTRL/-254.9779,453.0599,218.2973\nCNTRL/-254.9779,452.9000,221.0096\n"
      "CNTRL/-254.9779,452.8642,221.3100\nPAINT/COLOR,31\nGOTO/-254.9779,452.7940,223.3200\n"
      "FINI\n";
  ClReadOptions options;
  options.chord_tolerance = 0.001;
  const auto lines = only<StraightFeed>(read_events(text, options));
  ASSERT_GE(lines.size(), 3u);
  // The curve is clamped: it ends on the last CNTRL point, then the GOTO.
  EXPECT_TRUE(lines[lines.size() - 2].end.isApprox(Eigen::Vector3d(-254.9779, 452.8642, 221.31)));
  // Independent check: sample the cubic B-spline densely and measure the
  // distance to the polyline.
  std::string error;
  std::vector<Eigen::Vector4d> cntrl = {
      {-254.9774, 466.2698, 206.9401, 1}, {-254.9775, 463.5692, 207.2380, 1},
      {-254.9776, 459.2589, 209.0136, 1}, {-254.9778, 454.6135, 213.9021, 1},
      {-254.9779, 453.0599, 218.2973, 1}, {-254.9779, 452.9000, 221.0096, 1},
      {-254.9779, 452.8642, 221.3100, 1}};
  std::vector<double> knots = {0.0416667, 0.375, 0.625, 0.9583333, 1.0};
  const auto curve = nx_nurbs({-254.9774, 466.5681, 206.8891}, knots, cntrl, error);
  ASSERT_TRUE(curve) << error;
  EXPECT_EQ(curve->degree, 3);
  double worst = 0;
  for (int i = 0; i <= 20000; ++i) {
    const Eigen::Vector3d p = evaluate(*curve, i / 20000.0);
    double best = 1e9;
    for (std::size_t k = 0; k + 1 < lines.size(); ++k) {
      const Eigen::Vector3d a = lines[k].start, b = lines[k].end;
      const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      best = std::min(best, (p - (a + t * (b - a))).norm());
    }
    worst = std::max(worst, best);
  }
  EXPECT_LE(worst, 0.001);
  EXPECT_GT(worst, 0.0001);  // not wastefully fine
}

TEST(ClReader, NumbersBeyondOneTrillionAreRefused) {
  // cldata_fuzz: FROM/0,1e308,3.775 after UNITS/INCHES became an infinite
  // coordinate (1e308 x 25.4). A parameter beyond 1e12 is no number: E3103
  // at its column, with the bound in the message; 1e12 itself is read (in
  // inches: 2.54e13 mm, finite).
  std::string message;
  try {
    read_events("UNITS/INCHES\nFROM/0,1e308,3.775\nFINI\n");
  } catch (const ClError& e) {
    EXPECT_EQ(e.code(), Code::E3103);
    message = e.what();
  }
  EXPECT_NE(message.find(":2:8:"), std::string::npos) << message;
  EXPECT_NE(message.find("'1e308' is out of range (at most 1e12 either way)"), std::string::npos)
      << message;
  EXPECT_EQ(code_of("GOTO/0,-1000000000000.5,0\nFINI\n"), Code::E3103);
  const auto moves = only<StraightFeed>(read_events("UNITS/INCHES\nGOTO/0,1e12,0\nFINI\n"));
  ASSERT_EQ(moves.size(), 1u);
  EXPECT_DOUBLE_EQ(moves[0].end.y(), 2.54e13);
}

TEST(ClReader, NurbsPointBeyondTheMachineReachIsRefused) {
  // cldata_fuzz found a NURBS pulled out to Y = 14,843,522 mm and back: it
  // flattened into 321,000 lines at 1 um (0.5 s here, over 5 s under the
  // sanitizers). A CNTRL point beyond 100 m on an axis is refused, as a
  // model's point is (E4107); at 100 m it is read.
  const auto nurbs = [](const std::string& y) {
    return "GOTO/0,0,0\nNURBS/\nKNOT/1\nCNTRL/0," + y + ",0\nCNTRL/10," + y +
           ",0\nCNTRL/10,0,0\nGOTO/20,0,0\nFINI\n";
  };
  std::string message;
  try {
    read_events(nurbs("1.5E7"));
  } catch (const ClError& e) {
    EXPECT_EQ(e.code(), Code::E3111);
    message = e.what();
  }
  EXPECT_NE(message.find(":2:1:"), std::string::npos) << message;
  EXPECT_NE(message.find("a CNTRL point lies beyond 100000 mm (100 m) from the origin"),
            std::string::npos)
      << message;
  EXPECT_EQ(code_of(nurbs("-100000.001")), Code::E3111);
  const auto lines = only<StraightFeed>(read_events(nurbs("100000")));
  EXPECT_TRUE(lines.back().end.isApprox(Eigen::Vector3d(20, 0, 0)));
}

TEST(ClReader, MessagesToolsCoolantCompensationDelay) {
  const auto events = read_events(
      "PARTNO/1\nPPRINT hello\nLOADTL/8\nLOAD/TOOL,14\nSELECT/TOOL,13\nCOOLNT/FLOOD\n"
      "COOLNT/OFF\nCUTCOM/LEFT\nCUTCOM/OFF\nSPINDL/1000\nDELAY/1.5\nDELAY/REV,10\nFINI\n");
  const auto messages = only<Message>(events);
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[0].text, "PARTNO 1");
  EXPECT_EQ(messages[1].text, "hello");
  const auto changes = only<ChangeTool>(events);
  ASSERT_EQ(changes.size(), 2u);
  EXPECT_EQ(changes[0].number, 8);
  EXPECT_EQ(changes[1].number, 14);
  EXPECT_EQ(only<SelectTool>(events).at(0).number, 13);
  EXPECT_EQ(only<Coolant>(events).at(1).change, CoolantChange::off);
  EXPECT_EQ(only<CutterCompensation>(events).at(0).side, CompensationSide::left);
  const auto dwells = only<Dwell>(events);
  ASSERT_EQ(dwells.size(), 2u);
  EXPECT_DOUBLE_EQ(dwells[0].seconds, 1.5);
  EXPECT_DOUBLE_EQ(dwells[1].seconds, 0.6);  // 10 rev at 1000 rpm
  EXPECT_EQ(only<ProgramEnd>(events).size(), 1u);
}

TEST(ClReader, VendorRecordsAreKnownAndMissingFiniIsReported) {
  std::istringstream in(
      "CSI_SET_FLUTE_LENGTH/54.\nCSI_SET_EXTENSION_LENGTH/16.\nBOX/ 0,1.5,0,90,3,55\n"
      "TRNTYP/WORLD,0,0,0\nCSYS/1.,0,0,0,0,1.,0,0,0,0,1.,0\nGOTO/1,2,3\n");
  ClReader reader(in, "t.cl");
  std::size_t ends = 0;
  while (auto e = reader.next()) ends += std::holds_alternative<ProgramEnd>(*e) ? 1 : 0;
  EXPECT_EQ(ends, 1u);
  ASSERT_EQ(reader.warnings().size(), 1u);
  EXPECT_EQ(reader.warnings()[0].code, Code::W3151);
}

// Every record is translated or refused: an unknown word is an error (its
// text in the message), and so is a frame that would move the points.
TEST(ClReader, UnknownRecordsAndFramesThatMoveThePointsAreRefused) {
  try {
    read_events("GOTO/1,2,3\nSPINDLE_WARMUP/5,MIN\nFINI\n");
    FAIL() << "no error";
  } catch (const ClError& e) {
    EXPECT_EQ(e.code(), Code::E3118);
    EXPECT_EQ(e.diagnostic().line, 2u);
    EXPECT_NE(std::string(e.what()).find("SPINDLE_WARMUP/5,MIN"), std::string::npos) << e.what();
  }
  EXPECT_EQ(code_of("TRNTYP/WORLD,0,0,5\nFINI\n"), Code::E3119);
  EXPECT_EQ(code_of("TRNTYP/LOCAL\nFINI\n"), Code::E3119);
  EXPECT_EQ(code_of("CSYS/1,0,0,10,0,1,0,0,0,0,3,0\nFINI\n"), Code::E3119);
  EXPECT_EQ(code_of("ORIGIN/0,0,-5\nFINI\n"), Code::E3119);
  EXPECT_EQ(code_of("ROTABL/ 1.570796,AAXIS,TABLE,CCLW\nFINI\n"), Code::E3108);
  EXPECT_EQ(code_of("GOHOME\nFINI\n"), Code::E3117);
  EXPECT_EQ(code_of("CUTCOM/LEFT,YZPLAN\nFINI\n"), Code::E3105);
  EXPECT_EQ(code_of("LOAD/TOOL,3,ADJUST,4\nFINI\n"), Code::E3105);
  // Accepted: identity frames, ROTABL by zero, NX MSYS anywhere, CAMWorks' CUTCOM/ON.
  const auto events = read_events(
      "ORIGIN/0,0,0\nROTABL/ -0.000000,BAXIS,TABLE,CCLW\n"
      "MSYS/10,0,0,1,0,0,0,1,0\nCUTCOM/ ON\nCUTCOM/ LEFT\nCUTCOM/RIGHT,XYPLAN,12\n"
      "LOAD/TOOL,3,ADJUST,3\nOPFEATSTART/Drill1-Hole1\nOPSKIP/ON\nFINI\n");
  const auto comp = only<CutterCompensation>(events);
  ASSERT_EQ(comp.size(), 2u);
  EXPECT_EQ(comp[0].side, CompensationSide::left);
  EXPECT_EQ(comp[1].side, CompensationSide::right);
  ASSERT_EQ(only<ChangeTool>(events).size(), 1u);
  const auto notes = only<Message>(events);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_EQ(notes[0].text, "OPFEATSTART/Drill1-Hole1");
  EXPECT_EQ(notes[1].text, "OPSKIP/ON");
}

// `$$` comment records become messages (comments in the output), without
// the blanks around the text; Creo's `$$-> CUTTER` line too, which also
// gives the cutter; empty ones and those after FINI are dropped.
TEST(ClReader, CommentRecordsBecomeMessages) {
  std::istringstream in(
      "$$ centerline data\nGOTO/1,2,3\n$$-> CUTTER / 0.375000\n$$   \nFINI\n$$ after the end\n");
  ClReader reader(in, "t.cl");
  std::vector<Event> events;
  while (auto e = reader.next()) events.push_back(std::move(*e));
  const auto messages = only<Message>(events);
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[0].text, "centerline data");
  EXPECT_EQ(messages[0].source.line, 1u);
  EXPECT_EQ(messages[1].text, "-> CUTTER / 0.375000");
  EXPECT_EQ(messages[1].source.line, 3u);
  ASSERT_EQ(reader.cutters().size(), 1u);
  EXPECT_DOUBLE_EQ(reader.cutters()[0].diameter(), 0.375);
}

// CSYS with a translation and a rotation about Z is applied to the points
// that follow: p' = R p + t, the 3x4 matrix given row by row; each CSYS
// replaces the last. Other rotations and scalings are refused.
TEST(ClReader, CsysTranslationAndRotationAboutZAreApplied) {
  // 90 deg about +Z, then by (100, 50, -10): (x, y, z) -> (100 - y, 50 + x, z - 10).
  const auto events = read_events(
      "CSYS/0,-1,0,100,1,0,0,50,0,0,1,-10\nFROM/0,0,20\nGOTO/10,0,5\nGODLTA/0,5,0\n"
      "CIRCLE/10,10,5,0,0,1,5\nGOTO/15,10,5\n"
      "CSYS/1,0,0,5,0,1,0,6,0,0,1,7\nGOTO/1,2,3\n"
      "CSYS/1,0,0,0,0,1,0,0,0,0,1,0\nGOTO/1,2,3\nFINI\n");
  const auto lines = only<StraightFeed>(events);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_TRUE(lines[0].start.isApprox(Eigen::Vector3d(100, 50, 10))) << lines[0].start.transpose();
  EXPECT_TRUE(lines[0].end.isApprox(Eigen::Vector3d(100, 60, -5))) << lines[0].end.transpose();
  EXPECT_TRUE(lines[1].end.isApprox(Eigen::Vector3d(95, 60, -5))) << lines[1].end.transpose();
  EXPECT_TRUE(lines[2].end.isApprox(Eigen::Vector3d(6, 8, 10))) << lines[2].end.transpose();
  EXPECT_TRUE(lines[3].end.isApprox(Eigen::Vector3d(1, 2, 3))) << lines[3].end.transpose();
  const auto arcs = only<ArcFeed>(events);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_EQ(arcs[0].plane, Plane::xy);
  EXPECT_EQ(arcs[0].rotation, 1);
  EXPECT_NEAR(arcs[0].centre.x(), 90, 1e-9);
  EXPECT_NEAR(arcs[0].centre.y(), 60, 1e-9);
  EXPECT_TRUE(arcs[0].start.isApprox(Eigen::Vector3d(95, 60, -5))) << arcs[0].start.transpose();
  EXPECT_TRUE(arcs[0].end.isApprox(Eigen::Vector3d(90, 65, -5))) << arcs[0].end.transpose();
  try {
    read_events("GOTO/0,0,0\nCSYS/-1,0,0,0,0,1,0,0,0,0,1,0\nFINI\n");  // a mirror
    FAIL() << "no error";
  } catch (const ClError& e) {
    EXPECT_EQ(std::string(e.what()),
              "test.cl:2:1: error[E3119]: CSYS mirrors or scales (its 3x3 part is not a rotation "
              "within 1e-6): the points it places are not a rigid set-up's");
  }
  EXPECT_EQ(code_of("CSYS/2,0,0,0,0,2,0,0,0,0,1,0\nFINI\n"), Code::E3119);
  EXPECT_EQ(code_of("CSYS/0,1,0,0,1,0,0,0,0,0,1,0\nFINI\n"), Code::E3119);  // mirror
  // A turn about Z after another leaves no WorkingFrame: the events stay untilted.
  EXPECT_TRUE(only<WorkingFrame>(events).empty());
}

// A tilted CSYS (3+2) as SolidWorks CAM writes it (boss.apt's fourth
// operation): the GOTOs and their tool axis stay in the base frame, the
// events are in the frame's coordinates after a WorkingFrame. R's columns
// are the frame's axes: x = (0,1,0), y = (0,0,1), z = (1,0,0), so a base
// point (x, y, z) is (y, z, x) in the frame; the circle's axis -X is the
// frame's -z (clockwise in its XY plane).
TEST(ClReader, TiltedCsysIsAWorkingFrameWithThePointsInItsCoordinates) {
  const auto events = read_events(
      "GOTO/10,20,30\n"
      "CSYS/0,0,1.,0,1.,0,0,0,0,1.,0,0\nRAPID/\nGOTO/120.,24.9625,-30.35,1.,0,0\n"
      "GOTO/92.,0,-56.75,1.,0,0\n"
      "CIRCLE/92.,0,-60.,-1.,0,0\nGOTO/92.,3.25,-60.,1.,0,0\n"
      "CSYS/1.,0,0,0,0,1.,0,0,0,0,1.,0\nGOTO/1,2,3\nFINI\n");
  const auto frames = only<WorkingFrame>(events);
  ASSERT_EQ(frames.size(), 2u);
  Eigen::Matrix3d r;
  r << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  EXPECT_EQ(frames[0].rotation, r);
  EXPECT_EQ(frames[0].origin, Eigen::Vector3d::Zero());
  EXPECT_EQ(frames[0].source.line, 2u);
  EXPECT_TRUE(frames[1].is_identity());
  const auto rapids = only<StraightTraverse>(events);
  ASSERT_EQ(rapids.size(), 1u);
  EXPECT_EQ(rapids[0].end, Eigen::Vector3d(24.9625, -30.35, 120));
  const auto lines = only<StraightFeed>(events);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].end, Eigen::Vector3d(10, 20, 30));
  EXPECT_EQ(lines[1].end, Eigen::Vector3d(0, -56.75, 92));
  EXPECT_EQ(lines[2].end, Eigen::Vector3d(1, 2, 3));
  const auto arcs = only<ArcFeed>(events);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_EQ(arcs[0].plane, Plane::xy);
  EXPECT_EQ(arcs[0].rotation, -1);
  EXPECT_NEAR(arcs[0].centre.x(), 0, 1e-12);
  EXPECT_NEAR(arcs[0].centre.y(), -60, 1e-12);
  EXPECT_EQ(arcs[0].end, Eigen::Vector3d(3.25, -60, 92));
  // Each event is where the file puts it once turned back: R e + t.
  EXPECT_EQ(frames[0].to_program(rapids[0].end), Eigen::Vector3d(120, 24.9625, -30.35));
  EXPECT_EQ(frames[0].to_program(arcs[0].end), Eigen::Vector3d(92, 3.25, -60));
}

// In a tilted frame the tool axis must stay its z: one that changes along
// the path is 5-axis simultaneous, refused with the frame's axis named.
TEST(ClReader, ToolAxisOtherThanTheFramesIsRefused) {
  try {
    read_events("CSYS/0,0,1.,0,1.,0,0,0,0,1.,0,0\nGOTO/120,0,0,1,0,0\nGOTO/120,0,0,0.8,0,0.6\n");
    FAIL() << "no error";
  } catch (const ClError& e) {
    EXPECT_EQ(e.code(), Code::E3108);
    EXPECT_EQ(e.diagnostic().line, 3u);
    EXPECT_NE(std::string(e.what()).find("(1.0000, 0.0000, 0.0000)"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("5-axis simultaneous"), std::string::npos) << e.what();
  }
  // Untilted: the axis must be +Z, and the message says how a tilt is given.
  EXPECT_EQ(code_of("GOTO/0,0,0,1,0,0\nFINI\n"), Code::E3108);
  // 45 degrees about Y, moved to (5, 6, 7): the axis i,j,k given is R z.
  const double c = std::sqrt(0.5);
  const std::string csys = "CSYS/" + std::to_string(c) + ",0," + std::to_string(c) + ",5,0,1,0,6," +
                           std::to_string(-c) + ",0," + std::to_string(c) + ",7\n";
  const auto events = read_events(csys + "GOTO/5,6,7," + std::to_string(c) + ",0," +
                                  std::to_string(c) + "\nGOTO/15,6,7\nFINI\n");
  const auto lines = only<StraightFeed>(events);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NEAR((lines[0].end - Eigen::Vector3d::Zero()).norm(), 0, 1e-9);
  // (10, 0, 0) in the base: along the frame's x (c, 0, -c) and z (c, 0, c).
  EXPECT_NEAR((lines[1].end - Eigen::Vector3d(10 * c, 0, 10 * c)).norm(), 0, 1e-5);
}

// Tool changes without LOAD/TOOL: TOOLNO/n before the next motion is the
// change to tool n (CATIA writes LOADTL after it: then that is the one
// change); a cutter record of another shape after the section's first
// motion (a second CUTTER, NX's TOOL PATH with its TLDATA) is a change to
// the tool TOOLNO or SELECT/TOOL named, refused when none did; SELECT/TOOL
// alone preselects the next tool (SolidWorks CAM writes it while the
// current tool still cuts); the same cutter again is no change.
TEST(ClReader, ToolChangesWithoutLoadTool) {
  const auto events = read_events(
      "CUTTER/10\nTOOLNO/4\nGOTO/0,0,10\n"
      "CUTTER/10\nGOTO/0,0,20\n"
      "SELECT/TOOL,7\nGOTO/0,0,30\n"
      "CUTTER/6,3\nGOTO/0,0,40\n"
      "TOOL PATH/OP2,TOOL,BALL_8\nTLDATA/MILL,8,4,50,0,0\nTOOLNO/9\nGOTO/0,0,50\n"
      "TOOL PATH/OP3,TOOL,BALL_8\nTLDATA/MILL,8,4,50,0,0\nGOTO/0,0,60\n"
      "CUTTER/12\nTOOLNO/5\nLOADTL/5\nGOTO/0,0,70\nFINI\n");
  std::vector<std::pair<int, std::uint32_t>> changes;  // number, line
  for (const auto& c : only<ChangeTool>(events)) changes.emplace_back(c.number, c.source.line);
  EXPECT_EQ(changes,
            (std::vector<std::pair<int, std::uint32_t>>{{4, 3}, {7, 9}, {9, 13}, {5, 19}}));
  ASSERT_EQ(only<SelectTool>(events).size(), 1u);
  // Each change comes before its motion.
  std::size_t change_at = 0;
  for (std::size_t i = 0; i < events.size(); ++i)
    if (std::holds_alternative<ChangeTool>(events[i])) change_at = i;
  ASSERT_LT(change_at + 1, events.size());
  EXPECT_TRUE(std::holds_alternative<StraightFeed>(events[change_at + 1]));
  try {
    read_events("CUTTER/10\nLOADTL/1\nGOTO/0,0,10\nCUTTER/6,3\nGOTO/0,0,20\nFINI\n");
    FAIL() << "no error";
  } catch (const ClError& e) {
    EXPECT_EQ(std::string(e.what()),
              "test.cl:4:1: error[E3120]: CUTTER/6,3 is another tool than the one cutting, but "
              "no LOAD/TOOL, LOADTL, TOOLNO or SELECT/TOOL gives its number: the tool change "
              "cannot be written (give the tool numbers in the CAM system)");
  }
}

}  // namespace
}  // namespace vcpost::cldata
