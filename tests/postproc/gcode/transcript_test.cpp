// The event printer against lines copied from `rs274 -g` (LinuxCNC 2.9,
// Debian 12) output, and the arc geometry against hand-computed values.
#include "postproc/program/transcript.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "postproc/program/arc.h"

namespace vcpost::program {
namespace {

TEST(Transcript, StraightMovesMatchRs274Format) {
  // rs274: "STRAIGHT_FEED(10.1235, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)" for X10.12345 Y2 Z3.
  EXPECT_EQ(transcript(StraightFeed{{0, 0, 0}, {10.12345, 2, 3}, {}}),
            "STRAIGHT_FEED(10.1235, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)\n");
  EXPECT_EQ(transcript(StraightTraverse{{0, 0, 0}, {1, 2, 3}, {}}),
            "STRAIGHT_TRAVERSE(1.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)\n");
  // rs274 prints X-0.00001 as -0.0000 (printf "%.4f").
  EXPECT_EQ(transcript(StraightFeed{{0, 0, 0}, {-0.00001, 1234567.123456, 0}, {}}),
            "STRAIGHT_FEED(-0.0000, 1234567.1235, 0.0000, 0.0000, 0.0000, 0.0000)\n");
}

TEST(Transcript, ArcFeedArgumentOrderPerPlane) {
  // G17 from X10 Y2 Z3: G2 X20 Y2 I5 J0 -> rs274 "ARC_FEED(20.0000, 2.0000, 15.0000, 2.0000,
  // -1, 3.0000, ...)".
  EXPECT_EQ(transcript(ArcFeed{{10, 2, 3}, {20, 2, 3}, {15, 2, 3}, Plane::xy, -1, {}}),
            "ARC_FEED(20.0000, 2.0000, 15.0000, 2.0000, -1, 3.0000, 0.0000, 0.0000, 0.0000)\n");
  // G18 from X10 Y2 Z-1: G2 X0 Z0 I-5 K0.5 -> "ARC_FEED(0.0000, 0.0000, -0.5000, 5.0000,
  // -1, 2.0000, ...)".
  EXPECT_EQ(transcript(ArcFeed{{10, 2, -1}, {0, 2, 0}, {5, 2, -0.5}, Plane::xz, -1, {}}),
            "ARC_FEED(0.0000, 0.0000, -0.5000, 5.0000, -1, 2.0000, 0.0000, 0.0000, 0.0000)\n");
  // G19 from X0 Y2 Z0: G3 Y0 Z1 J-1 K0.5 P2 -> "ARC_FEED(0.0000, 1.0000, 1.0000, 0.5000, 2, 0.0000,
  // ...)".
  EXPECT_EQ(transcript(ArcFeed{{0, 2, 0}, {0, 0, 1}, {0, 1, 0.5}, Plane::yz, 2, {}}),
            "ARC_FEED(0.0000, 1.0000, 1.0000, 0.5000, 2, 0.0000, 0.0000, 0.0000, 0.0000)\n");
}

TEST(Transcript, OtherCallsAndSource) {
  EXPECT_EQ(transcript(SetSpindleSpeed{1000, {}}), "SET_SPINDLE_SPEED(0, 1000.0000)\n");
  EXPECT_EQ(transcript(SetFeedRate{500, FeedMode::per_minute, {}}), "SET_FEED_RATE(500.0000)\n");
  EXPECT_EQ(transcript(SpindleOn{SpindleDirection::counterclockwise, {}}),
            "START_SPINDLE_COUNTERCLOCKWISE(0)\n");
  EXPECT_EQ(transcript(Dwell{2.5, {}}), "DWELL(2.5000)\n");
  EXPECT_EQ(transcript(SelectPlane{Plane::yz, {}}), "SELECT_PLANE(CANON_PLANE_YZ)\n");
  EXPECT_EQ(transcript(Message{" hi there", {}}), "MESSAGE(\" hi there\")\n");
  const TranscriptOptions options{true, "a.nc"};
  EXPECT_EQ(transcript(Coolant{CoolantChange::off, {7, 3, 40}}, options),
            "MIST_OFF()  # a.nc:7:3\nFLOOD_OFF()  # a.nc:7:3\n");
}

TEST(Arc, SweepLengthAndPoints) {
  // Quarter circle G3 from (1,0) to (0,1) about the origin, radius 1.
  const ArcFeed quarter{{1, 0, 0}, {0, 1, 0}, {0, 0, 0}, Plane::xy, 1, {}};
  EXPECT_NEAR(arc_sweep(quarter), std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(arc_length(quarter), std::numbers::pi / 2, 1e-12);
  const Eigen::Vector3d mid = arc_point(quarter, 0.5);
  EXPECT_NEAR(mid.x(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(mid.y(), std::sqrt(0.5), 1e-12);
  // The same end points clockwise: three quarters, negative.
  ArcFeed cw = quarter;
  cw.rotation = -1;
  EXPECT_NEAR(arc_sweep(cw), -1.5 * std::numbers::pi, 1e-12);
  // Full helical turn in XZ (G18) of radius 2 rising 3 along Y, two turns:
  // length = hypot(2 turns * 2*pi*2, 3).
  const ArcFeed helix{{2, 0, 0}, {2, 3, 0}, {0, 0, 0}, Plane::xz, 2, {}};
  EXPECT_NEAR(arc_sweep(helix), 4 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(arc_length(helix), std::hypot(8 * std::numbers::pi, 3.0), 1e-12);
  // In XZ counterclockwise runs from Z towards X: a quarter turn from
  // (x=2, z=0) reaches (x=0, z=-2)... check: first axis Z, second X, start
  // angle atan2(x=2, z=0) = 90 deg; +90 deg -> (z=-2, x=0).
  const Eigen::Vector3d q = arc_point(helix, 0.125);
  EXPECT_NEAR(q.x(), 0.0, 1e-12);
  EXPECT_NEAR(q.z(), -2.0, 1e-12);
  EXPECT_NEAR(q.y(), 0.375, 1e-12);
}

}  // namespace
}  // namespace vcpost::program
