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

std::vector<program::Event> all_events(std::string_view text) {
  Interpreter interpreter(text, fanuc_dialect());
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

Reading read(std::string_view text) {
  Reading r;
  program::WorkingFrame frame;
  for (const auto& e : all_events(text)) {
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
  EXPECT_EQ(code_of("G68.2 P1 X0 Y0 Z0 I0 J30 K0\nM30\n"), Code::unsupported_code);
  EXPECT_EQ(code_of("G68.2 X0 Y0 Z0 I0 J30 K0\nG68.2 X0 Y0 Z0 I0 J30 K0\nM30\n"),
            Code::unsupported_code);
  // G69 alone changes nothing: no frame event.
  const Reading r = read("G69\nG0 X1 Y2 Z3\nM30\n");
  EXPECT_TRUE(r.frames.empty());
}

}  // namespace
}  // namespace vcpost::gcode
