// Fanuc's tilted working plane (G68.2 X Y Z I J K, G53.1, G69), worked out
// by hand: the events are in the tilted frame's coordinates after a
// WorkingFrame whose rotation is Rz(I) Rx(J) Rz(K) (Euler Z-X'-Z'') and
// whose origin is X Y Z. Tolerance 1e-12 mm (exact at multiples of 90
// degrees, one rounding of a sine otherwise).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "postproc/gcode/interpreter.h"

namespace vcpost::gcode {
namespace {

std::vector<program::Event> all_events(std::string_view text, Dialect dialect = fanuc_dialect()) {
  Interpreter interpreter(text, dialect);
  std::vector<program::Event> events;
  while (interpreter.next(events)) {
  }
  return events;
}

// Each motion's end in the program frame, and the frames met.
struct Reading {
  std::vector<Eigen::Vector3d> ends, starts;  // ends in the program frame; starts as given
  std::vector<program::WorkingFrame> frames;
};

Reading read(std::string_view text, Dialect dialect = fanuc_dialect()) {
  Reading r;
  program::WorkingFrame frame;
  for (const auto& e : all_events(text, dialect)) {
    if (const auto* f = std::get_if<program::WorkingFrame>(&e)) {
      frame = *f;
      r.frames.push_back(*f);
    } else if (const auto* t = std::get_if<program::StraightTraverse>(&e)) {
      r.ends.push_back(frame.to_program(t->end));
      r.starts.push_back(t->start);
    } else if (const auto* m = std::get_if<program::StraightFeed>(&e)) {
      r.ends.push_back(frame.to_program(m->end));
      r.starts.push_back(m->start);
    }
  }
  return r;
}

void expect_near(const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  EXPECT_LT((p - q).norm(), 1e-12) << p.transpose() << " vs " << q.transpose();
}

// J90 alone: Rx(90), x = (1,0,0), y = (0,0,1), z = (0,-1,0) (the -Y face).
// X5 Y5 Z20 there is (10,0,0) + 5 x + 5 y + 20 z = (15,-20,5). The tool at
// (0,0,100) before stays there: in the frame, R^T ((0,0,100) - (10,0,0)) =
// (-10, 100, 0).
TEST(FanucTiltedPlane, G682EulerAnglesAboutItsOrigin) {
  const Reading r = read(
      "G21 G90 G17\nG0 X0 Y0 Z100.\n"
      "G68.2 X10. Y0 Z0 I0 J90. K0\nG53.1\n"
      "G0 X5. Y5. Z20.\nG1 Z0 F500\n"
      "G69\nG0 X1. Y2. Z3.\nM30\n");
  ASSERT_EQ(r.frames.size(), 2u);
  Eigen::Matrix3d rx90;
  rx90 << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  EXPECT_EQ(r.frames[0].rotation, rx90);
  EXPECT_EQ(r.frames[0].origin, Eigen::Vector3d(10, 0, 0));
  EXPECT_EQ(r.frames[0].source.line, 3u);
  EXPECT_TRUE(r.frames[1].is_identity());
  ASSERT_EQ(r.ends.size(), 4u);
  expect_near(r.ends[0], {0, 0, 100});
  expect_near(r.starts[1], {-10, 100, 0});
  expect_near(r.ends[1], {15, -20, 5});
  expect_near(r.ends[2], {15, 0, 5});  // down the frame's z to the face Y 0
  expect_near(r.ends[3], {1, 2, 3});
}

// I90 J45 K0: Rz(90) Rx(45): x = (0,1,0), y = (-c,0,c), z = (c,0,c), the
// same tilt as Heidenhain's PLANE EULER EULPR90 EULNU45 EULROT0.
TEST(FanucTiltedPlane, CompoundAngles) {
  const double c = std::sqrt(0.5);
  const Reading r = read("G21 G90\nG68.2 X0 Y0 Z0 I90. J45. K0\nG0 X0 Y10. Z10.\nG69\nM30\n");
  ASSERT_EQ(r.frames.size(), 2u);
  expect_near(r.frames[0].rotation.col(2), {c, 0, c});
  ASSERT_EQ(r.ends.size(), 1u);
  expect_near(r.ends[0], {10 * c - 10 * c, 0, 10 * c + 10 * c});
}

TEST(FanucTiltedPlane, OtherFormsAreRefused) {
  auto code_of = [](std::string_view text) {
    try {
      all_events(text);
    } catch (const GcodeError& e) {
      return e.diagnostic().code;
    }
    return Code{};
  };
  EXPECT_EQ(code_of("G68.2 P1 X0 Y0 Z0 I0 J30 K0\nM30\n"), Code::E1404);
  EXPECT_EQ(code_of("G68.2 X0 Y0 Z0 I0 J30 K0\nG68.2 X0 Y0 Z0 I0 J30 K0\nM30\n"), Code::E1404);
  // G69 alone changes nothing: no frame event.
  const Reading r = read("G69\nG0 X1 Y2 Z3\nM30\n");
  EXPECT_TRUE(r.frames.empty());
}

// Sinumerik CYCLE800 axis by axis. _MODE 57 (X Y Z) with B90 about the
// reference point X0 10: Ry(90), x = (0,0,-1), y = (0,1,0), z = (1,0,0)
// (the +X face), origin (10,0,0). The tool at (0,0,100) stays: in the
// frame R^T ((0,0,100) - (10,0,0)) = (-100, 0, -10). X5 Y5 Z20 there is
// (10,0,0) + 5 x + 5 y + 20 z = (30, 5, -5). Added to it (_ST 1) a turn
// of 90 about the frame's Z: Ry(90) Rz(90), x = (0,1,0), y = (0,0,1), z
// = (1,0,0), the same origin: X1 Y2 Z3 at (13, 1, 2). _MODE 27 (Z Y X)
// with A90 C90 and the new zero Z1 5: Rz(90) Rx(90), the same axes,
// origin R (0,0,5) = (5,0,0): X1 Y2 Z3 at (8, 1, 2). CYCLE800() ends it.
TEST(SinumerikSwivel, Cycle800AxisByAxis) {
  const Reading r = read(
      "G0 X0 Y0 Z100\n"
      "CYCLE800(1,\"TC1\",0,57,10,0,0,0,90,0,0,0,0,1)\n"
      "G1 X5 Y5 Z20 F100\n"
      "CYCLE800(0,\"TC1\",1,57,0,0,0,0,0,90,0,0,0,1)\n"
      "G0 X1 Y2 Z3\n"
      "CYCLE800(1,\"\",0,27,0,0,0,90,0,90,0,0,5,-1,0,1)\n"
      "G0 X1 Y2 Z3\n"
      "CYCLE800()\n"
      "G0 X0 Y0 Z100\n"
      "M30\n",
      sinumerik_dialect());
  ASSERT_EQ(r.frames.size(), 4u);
  Eigen::Matrix3d ry90;
  ry90 << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  EXPECT_EQ(r.frames[0].rotation, ry90);
  EXPECT_EQ(r.frames[0].origin, Eigen::Vector3d(10, 0, 0));
  EXPECT_EQ(r.frames[0].source.line, 2u);
  Eigen::Matrix3d turned;
  turned << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  expect_near(r.frames[1].rotation.col(0), turned.col(0));
  expect_near(r.frames[1].rotation.col(2), turned.col(2));
  expect_near(r.frames[1].origin, {10, 0, 0});
  expect_near(r.frames[2].rotation.col(0), turned.col(0));
  expect_near(r.frames[2].rotation.col(1), turned.col(1));
  expect_near(r.frames[2].origin, {5, 0, 0});
  EXPECT_TRUE(r.frames[3].is_identity());
  ASSERT_EQ(r.ends.size(), 5u);
  expect_near(r.starts[1], {-100, 0, -10});
  expect_near(r.ends[1], {30, 5, -5});
  expect_near(r.ends[2], {13, 1, 2});
  expect_near(r.ends[3], {8, 1, 2});
  expect_near(r.ends[4], {0, 0, 100});
}

TEST(SinumerikSwivel, OtherFormsAreRefused) {
  auto code_of = [](std::string_view text) {
    try {
      all_events(text, sinumerik_dialect());
    } catch (const GcodeError& e) {
      return e.diagnostic().code;
    }
    return Code{};
  };
  // Projection angles (64), solid angle (128), rotary axes direct (192).
  EXPECT_EQ(code_of("CYCLE800(1,\"TC1\",0,64,0,0,0,10,20,0,0,0,0,1)\nM30\n"), Code::E1404);
  EXPECT_EQ(code_of("CYCLE800(1,\"TC1\",0,192,0,0,0,10,20,0,0,0,0,1)\nM30\n"), Code::E1404);
  EXPECT_EQ(code_of("CYCLE800(1,\"TC1\",0,56,0,0,0,10,20,0,0,0,0,1)\nM30\n"), Code::E1513);
  EXPECT_EQ(code_of("CYCLE800(1,\"TC1\",2,57,0,0,0,10,20,0,0,0,0,1)\nM30\n"), Code::E1513);
  EXPECT_EQ(code_of("MCALL CYCLE800(1,\"TC1\",0,57,0,0,0,10,20,0,0,0,0,1)\nM30\n"), Code::E1404);
  EXPECT_EQ(code_of("CYCLE800(1,\"TC1,0,57)\nM30\n"), Code::E1201);
}

}  // namespace
}  // namespace vcpost::gcode
