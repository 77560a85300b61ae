// vcpost moves prints the motion of a tilted working frame where it is in
// the program frame (the part's), worked out by hand below.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "postproc/program/transcript.h"

namespace vcpost::program {
namespace {

// boss.apt's tilted operation: the frame's x, y, z are the program's Y, Z,
// X, so a frame point (x, y, z) is at (z, x, y); its arc clockwise about
// the frame's z is clockwise about +X: an ARC_FEED in the YZ plane.
TEST(TranscriberFrames, TiltedMotionIsPrintedInTheProgramFrame) {
  WorkingFrame frame;
  frame.rotation << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  Transcriber print;
  std::string out;
  print.append(out, frame);
  print.append(out, StraightTraverse{{0, 0, 0}, {24.9625, -30.35, 120}, {}});
  print.append(out, StraightFeed{{24.9625, -30.35, 120}, {0, -56.75, 92}, {}});
  ArcFeed arc;
  arc.start = {0, -56.75, 92};
  arc.end = {3.25, -60, 92};
  arc.centre = {0, -60, 92};
  arc.rotation = -1;
  print.append(out, arc);
  print.append(out, WorkingFrame{});
  print.append(out, StraightFeed{{0, 0, 0}, {1, 2, 3}, {}});
  EXPECT_EQ(out,
            "SET_WORKING_FRAME(0.0000, 0.0000, 0.0000, 0.0000, 1.0000, 0.0000, 1.0000, 0.0000, "
            "0.0000)\n"
            "STRAIGHT_TRAVERSE(120.0000, 24.9625, -30.3500, 0.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_FEED(92.0000, 0.0000, -56.7500, 0.0000, 0.0000, 0.0000)\n"
            "ARC_FEED(3.2500, -60.0000, 0.0000, -60.0000, -1, 92.0000, 0.0000, 0.0000, 0.0000)\n"
            "SET_WORKING_FRAME(0.0000, 0.0000, 0.0000, 1.0000, 0.0000, 0.0000, 0.0000, 0.0000, "
            "1.0000)\n"
            "STRAIGHT_FEED(1.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)\n");
}

// 45 degrees about Y, origin (10, 0, 5): the frame's x is (c, 0, -c), its
// z (c, 0, c). A quarter circle of radius 10 about the frame's origin,
// counterclockwise in its XY plane from (10, 0) to (0, 10): it ends at
// origin + 10 y = (10, 10, 5), centre the origin, axis the frame's z.
TEST(TranscriberFrames, ArcOfACompoundTiltIsPrintedIn3d) {
  const double c = std::sqrt(0.5);
  WorkingFrame frame;
  frame.rotation << c, 0, c, 0, 1, 0, -c, 0, c;
  frame.origin = {10, 0, 5};
  Transcriber print;
  std::string out;
  print.append(out, frame);
  ArcFeed arc;
  arc.start = {10, 0, 0};
  arc.end = {0, 10, 0};
  arc.centre = {0, 0, 0};
  arc.rotation = 1;
  print.append(out, arc);
  print.append(out, StraightFeed{{0, 10, 0}, {0, 10, -2}, {}});
  EXPECT_EQ(out.substr(out.find('\n') + 1),
            "ARC_FEED_3D(10.0000, 10.0000, 5.0000, 10.0000, 0.0000, 5.0000, 0.7071, 0.0000, "
            "0.7071, 1)\n"
            "STRAIGHT_FEED(8.5858, 10.0000, 3.5858, 0.0000, 0.0000, 0.0000)\n");
}

}  // namespace
}  // namespace vcpost::program
