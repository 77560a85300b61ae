// G5 and G5.1 splines: the polyline vcpost follows stays within its
// tolerance of the Bezier curve rs274 hands the control (checked against
// the curve's closed form, sampled densely), and the interpreter builds the
// control points as rs274 does (start, start + IJ, end + PQ, end).
#include "postproc/gcode/splines.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "postproc/gcode/interpreter.h"

namespace vcpost::gcode {
namespace {

// The cubic and quadratic Bezier curves by their Bernstein form.
Eigen::Vector2d bernstein(const std::vector<Eigen::Vector2d>& c, double t) {
  const double u = 1.0 - t;
  if (c.size() == 3) return u * u * c[0] + 2 * u * t * c[1] + t * t * c[2];
  return u * u * u * c[0] + 3 * u * u * t * c[1] + 3 * u * t * t * c[2] + t * t * t * c[3];
}

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 == 0 ? 0.0 : std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// The largest distance from the curve (10,001 samples) to the polyline's
// chord of the same parameter span (the chords are uniform in t).
double worst_departure(const std::vector<Eigen::Vector2d>& control,
                       const std::vector<Eigen::Vector2d>& points) {
  const auto n = static_cast<double>(points.size());
  double worst = 0.0;
  for (int k = 0; k <= 10000; ++k) {
    const double t = k / 10000.0;
    const auto chord = std::min(static_cast<std::size_t>(t * n), points.size() - 1);
    const Eigen::Vector2d a = chord == 0 ? control.front() : points[chord - 1];
    worst = std::max(worst, distance_to_segment(bernstein(control, t), a, points[chord]));
  }
  return worst;
}

TEST(Splines, PolylineStaysWithinTheToleranceOfTheCurve) {
  const std::vector<std::vector<Eigen::Vector2d>> curves = {
      {{0, 0}, {0, 30}, {40, 30}, {40, 0}},    // an arch
      {{0, 0}, {50, 40}, {-10, 40}, {40, 0}},  // a loop
      {{1, 2}, {2, 3}, {3, 2}},                // quadratic, G5.1 X3 Y2 I1 J1 from (1, 2)
      {{0, 0}, {1, 0}, {2, 0}, {3, 0}},        // a straight line: one chord
  };
  for (const auto& c : curves) {
    const auto points = spline_polyline(c);
    ASSERT_FALSE(points.empty());
    EXPECT_EQ(points.back(), c.back());
    EXPECT_LE(worst_departure(c, points), kSplineTolerance);
    const auto n = static_cast<double>(points.size());
    for (std::size_t k = 0; k < points.size(); ++k)
      EXPECT_NEAR((points[k] - bernstein(c, (static_cast<double>(k) + 1.0) / n)).norm(), 0.0, 1e-9);
  }
  EXPECT_EQ(spline_polyline(curves[3]).size(), 1u);
  // Not far more chords than needed: halving their number breaks the tolerance.
  const auto arch = spline_polyline(curves[0]);
  std::vector<Eigen::Vector2d> half;
  for (std::size_t k = 1; k < arch.size(); k += 2) half.push_back(arch[k]);
  if (arch.size() % 2 == 1) half.push_back(arch.back());
  EXPECT_GT(worst_departure(curves[0], half), kSplineTolerance);
}

std::vector<program::StraightFeed> feeds_of(const std::string& text) {
  Interpreter interpreter(text, rs274ngc_dialect());
  std::vector<program::Event> events;
  std::vector<program::StraightFeed> feeds;
  while (interpreter.next(events)) {
    for (const auto& e : events)
      if (const auto* f = std::get_if<program::StraightFeed>(&e)) feeds.push_back(*f);
    events.clear();
  }
  return feeds;
}

TEST(Splines, G5AndG51TakeTheirControlPointsAsRs274Does) {
  // G5 from (0, 0): control points (0, 0), (0, 30), (40, 30), (40, 0); at
  // t = 1/2 the curve is at (P0 + 3 P1 + 3 P2 + P3) / 8 = (20, 22.5).
  const auto arch = feeds_of("G0 X0 Y0 Z2\nF500 G5 I0 J30 P0 Q30 X40 Y0\nM2\n");
  ASSERT_GE(arch.size(), 2u);
  EXPECT_EQ(arch.size() % 2, 0u);
  EXPECT_NEAR(arch[arch.size() / 2 - 1].end.x(), 20.0, 1e-9);
  EXPECT_NEAR(arch[arch.size() / 2 - 1].end.y(), 22.5, 1e-9);
  EXPECT_DOUBLE_EQ(arch.back().end.x(), 40.0);
  EXPECT_DOUBLE_EQ(arch.back().end.y(), 0.0);
  for (const auto& f : arch) EXPECT_DOUBLE_EQ(f.end.z(), 2.0);
  // A G5 without I and J continues the last: (I, J) = -(P, Q) of it, the
  // mirror of the arch from (40, 0) to (80, 0), down to y = -22.5.
  const auto wave = feeds_of("G0 X0 Y0\nF500 G5 I0 J30 P0 Q30 X40 Y0\nG5 P0 Q-30 X80 Y0\nM2\n");
  ASSERT_EQ(wave.size(), 2 * arch.size());
  EXPECT_NEAR(wave[arch.size() + arch.size() / 2 - 1].end.x(), 60.0, 1e-9);
  EXPECT_NEAR(wave[arch.size() + arch.size() / 2 - 1].end.y(), -22.5, 1e-9);
  // G5.1 from (1, 2) with I1 J1 to (3, 2): the curve (1 + 2t, 2 + 2t(1 - t)).
  const auto quadratic = feeds_of("G0 X1 Y2\nF500 G5.1 X3 Y2 I1 J1\nM2\n");
  ASSERT_GE(quadratic.size(), 2u);
  const auto n = static_cast<double>(quadratic.size());
  for (std::size_t k = 0; k < quadratic.size(); ++k) {
    const double t = (static_cast<double>(k) + 1.0) / n;
    EXPECT_NEAR(quadratic[k].end.x(), 1.0 + 2.0 * t, 1e-9);
    EXPECT_NEAR(quadratic[k].end.y(), 2.0 + 2.0 * t * (1.0 - t), 1e-9);
  }
}

}  // namespace
}  // namespace vcpost::gcode
