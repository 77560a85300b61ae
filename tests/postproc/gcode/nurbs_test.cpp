// G5.2/G5.3 NURBS curves (nurbs.h): the polyline against curves worked by
// hand (a quarter circle from weights, a clamped quadratic B-spline's
// values) and against an independent Cox-de Boor evaluation on rs274's knot
// vector; the interpreter's reading of the blocks as rs274 reads them
// (rs274's own transcripts are compared in rs274_compare_test.cpp with
// programs/nurbs.ngc) and its refusals with their codes and columns.
#include "postproc/gcode/nurbs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "postproc/gcode/interpreter.h"
#include "postproc/gcode/splines.h"
#include "postproc/program/arc.h"

namespace vcpost::gcode {
namespace {

// ---- the curve ---------------------------------------------------------------

// B-spline basis function N(i, k) (order k) by the Cox-de Boor recursion,
// written from its textbook definition (0/0 taken as 0), half-open spans
// with the last span closed.
double basis(const std::vector<double>& t, std::size_t i, std::size_t k, double u) {
  if (k == 1) {
    const bool last = u == t.back() && t[i] < t[i + 1] && t[i + 1] == t.back();
    return (t[i] <= u && u < t[i + 1]) || last ? 1.0 : 0.0;
  }
  double value = 0.0;
  if (t[i + k - 1] > t[i]) value += (u - t[i]) / (t[i + k - 1] - t[i]) * basis(t, i, k - 1, u);
  if (t[i + k] > t[i + 1])
    value += (t[i + k] - u) / (t[i + k] - t[i + 1]) * basis(t, i + 1, k - 1, u);
  return value;
}

// The knot vector as LinuxCNC's documentation of G5.2 states it (uniform,
// clamped: the curve starts and ends on its end points), built here from
// that rule, not from nurbs_knots().
std::vector<double> clamped_uniform(std::size_t points, std::size_t order) {
  std::vector<double> t(order, 0.0);
  const std::size_t inner = points - order;
  for (std::size_t j = 1; j <= inner; ++j) t.push_back(static_cast<double>(j));
  t.insert(t.end(), order, static_cast<double>(inner + 1));
  return t;
}

Eigen::Vector2d curve_point(const std::vector<NurbsControlPoint>& c, std::size_t order, double u) {
  const auto t = clamped_uniform(c.size(), order);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double weights = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double n = basis(t, i, order, u) * c[i].weight;
    sum += n * c[i].at;
    weights += n;
  }
  return sum / weights;
}

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 == 0 ? 0.0 : std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return (a + s * ab - p).norm();
}

double distance_to_polyline(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& line) {
  double best = 1e300;
  for (std::size_t k = 0; k + 1 < line.size(); ++k)
    best = std::min(best, distance_to_segment(p, line[k], line[k + 1]));
  return best;
}

TEST(NurbsKnots, Rs274UniformClampedVector) {
  EXPECT_EQ(nurbs_knots(3, 3), (std::vector<double>{0, 0, 0, 1, 1, 1}));
  EXPECT_EQ(nurbs_knots(4, 3), (std::vector<double>{0, 0, 0, 1, 2, 2, 2}));
  EXPECT_EQ(nurbs_knots(6, 4), (std::vector<double>{0, 0, 0, 0, 1, 2, 3, 3, 3, 3}));
  EXPECT_EQ(nurbs_knots(5, 5), clamped_uniform(5, 5));
}

// The reference evaluation against values worked by hand: the quadratic
// on knots 0 0 0 1 2 2 2 has N0 = (1-u)^2, N1 = 2u - 1.5u^2, N2 = u^2 / 2
// on its first span, so C(0.5) = 0.25 P0 + 0.625 P1 + 0.125 P2, and C(1)
// = (P1 + P2) / 2.
TEST(Nurbs, ReferenceEvaluationMatchesHandWorkedValues) {
  const std::vector<NurbsControlPoint> c = {{{0, 0}, 1}, {{4, 8}, 1}, {{12, 8}, 1}, {{16, 0}, 1}};
  EXPECT_LT((curve_point(c, 3, 0.5) - Eigen::Vector2d(4, 6)).norm(), 1e-12);
  EXPECT_LT((curve_point(c, 3, 1.0) - Eigen::Vector2d(8, 8)).norm(), 1e-12);
  EXPECT_LT((curve_point(c, 3, 2.0) - Eigen::Vector2d(16, 0)).norm(), 1e-12);
}

// The polyline of curves of order 3 to 6, weights 1 and not: every point of
// the curve (8,001 samples of the reference) lies within kSplineTolerance of
// it, its vertices lie on the curve, and it ends exactly on the last control
// point (the clamped curve's end).
TEST(Nurbs, PolylineFollowsTheCurveWithinTheTolerance) {
  struct Case {
    std::vector<NurbsControlPoint> control;
    int order;
  };
  const std::vector<Case> cases = {
      {{{{0, 0}, 1}, {{4, 8}, 1}, {{12, 8}, 1}, {{16, 0}, 1}}, 3},
      {{{{1, 2}, 2}, {{5, 20}, 1}, {{10, 25}, 3}, {{20, 20}, 0.5}, {{25, 10}, 1}, {{15, 0}, 2}}, 4},
      {{{{0, 0}, 1}, {{50, 40}, 0.2}, {{-10, 40}, 5}, {{40, 0}, 1}, {{60, -30}, 1}}, 5},
      {{{{0, 0}, 1}, {{10, 0}, 1}, {{10, 10}, 1}, {{0, 10}, 1}, {{0, 0}, 1}, {{5, 5}, 1}}, 6},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE("order " + std::to_string(c.order));
    std::vector<Eigen::Vector2d> out;
    ASSERT_TRUE(nurbs_polyline(c.control, c.order, kSplineTolerance, out, 1'000'000));
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out.back(), c.control.back().at);
    std::vector<Eigen::Vector2d> line{c.control.front().at};
    line.insert(line.end(), out.begin(), out.end());
    const double umax = static_cast<double>(c.control.size()) - c.order + 1;
    std::vector<Eigen::Vector2d> dense;
    for (int k = 0; k <= 8000; ++k)
      dense.push_back(curve_point(c.control, c.order, umax * k / 8000));
    EXPECT_LT((dense.front() - c.control.front().at).norm(), 1e-12);
    EXPECT_LT((dense.back() - c.control.back().at).norm(), 1e-12);
    double worst = 0.0;
    for (const auto& p : dense) worst = std::max(worst, distance_to_polyline(p, line));
    EXPECT_LE(worst, kSplineTolerance);
    // A vertex off the curve would sit between the dense samples: their
    // chords are within a few um of the curve here.
    double off = 0.0;
    for (const auto& v : out) off = std::max(off, distance_to_polyline(v, dense));
    EXPECT_LT(off, 5e-3 * kSplineTolerance) << "a vertex off the curve";
  }
}

// A parabola 50 m high, its middle control point 100 m off the chord:
// the flattening halves a piece until its control polygon lies within
// 1 um of its chord, and each halving quarters that distance, so 1e5 mm /
// 4^d <= 1e-3 mm takes d = 14 halvings, 16,384 chords. Weights 1e320
// apart leave the first point's weight 0 in double arithmetic: a point at
// infinity.
TEST(Nurbs, TooManyMovesOrNoFiniteCurveIsRefused) {
  const std::vector<NurbsControlPoint> far = {{{0, 0}, 1}, {{1e5, 1e5}, 1}, {{2e5, 0}, 1}};
  std::vector<Eigen::Vector2d> out;
  EXPECT_FALSE(nurbs_polyline(far, 3, kSplineTolerance, out, 1000));
  out.clear();
  EXPECT_TRUE(nurbs_polyline(far, 3, kSplineTolerance, out, 20000));
  EXPECT_EQ(out.size(), 16384u);
  const std::vector<NurbsControlPoint> apart = {{{0, 0}, 1e-320}, {{1, 1}, 1e300}, {{2, 0}, 1}};
  out.clear();
  EXPECT_FALSE(nurbs_polyline(apart, 3, kSplineTolerance, out, 1000));
}

// ---- the interpreter -----------------------------------------------------------

struct Outcome {
  std::vector<program::StraightFeed> feeds;
  std::vector<program::SetFeedRate> rates;
  std::vector<Diagnostic> warnings;
  std::optional<Diagnostic> error;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

Outcome run(const std::string& text, const Dialect& dialect = rs274ngc_dialect()) {
  Interpreter interpreter(text, dialect);
  Outcome out;
  std::vector<program::Event> events;
  try {
    while (interpreter.next(events)) {
      for (const auto& e : events) {
        if (const auto* f = std::get_if<program::StraightFeed>(&e)) out.feeds.push_back(*f);
        if (const auto* r = std::get_if<program::SetFeedRate>(&e)) out.rates.push_back(*r);
      }
      events.clear();
      out.position = interpreter.state().position;
    }
  } catch (const GcodeError& e) {
    out.error = e.diagnostic();
  }
  out.warnings = interpreter.warnings();
  return out;
}

// The chords' in-plane coordinates (a, b) and the third axis.
struct Chords {
  std::vector<Eigen::Vector2d> points;  // start, then each chord's end
  std::vector<double> third;
};
Chords chords(const Outcome& r, program::Plane plane) {
  const auto ax = program::plane_axes(plane);
  Chords c;
  for (std::size_t k = 0; k < r.feeds.size(); ++k) {
    if (k == 0) c.points.emplace_back(r.feeds[0].start[ax[0]], r.feeds[0].start[ax[1]]);
    c.points.emplace_back(r.feeds[k].end[ax[0]], r.feeds[k].end[ax[1]]);
    c.third.push_back(r.feeds[k].end[ax[2]]);
  }
  return c;
}

// A quadratic NURBS with the middle weight cos 45 deg is a quarter circle:
// from (10, 0) through the corner (10, 10) to (0, 10), radius 10 about
// the origin, in each plane (rs274's axis order: X Y, Z X, Y Z). Its
// vertices lie on the circle; the chords' midpoints lie at most the
// tolerance inside it (the sagitta); the fewest chords of sagitta 0.001
// mm on a 90 deg arc of radius 10 are 56.
TEST(Nurbs, QuarterCircleFromWeights) {
  struct Case {
    const char* plane;
    program::Plane which;
    const char* program;
  };
  const Case cases[] = {
      {"G17", program::Plane::xy,
       "G21 G17 G90 F500\nG0 X10 Y0 Z3\nG5.2 X10 Y10 P0.7071067811865476\nX0 Y10 P1\nG5.3\nM2\n"},
      {"G18", program::Plane::xz,
       "G21 G18 G90 F500\nG0 Z10 X0 Y3\nG5.2 Z10 X10 P0.7071067811865476\nZ0 X10 P1\nG5.3\nM2\n"},
      {"G19", program::Plane::yz,
       "G21 G19 G90 F500\nG0 Y10 Z0 X3\nG5.2 Y10 Z10 P0.7071067811865476\nY0 Z10 P1\nG5.3\nM2\n"},
  };
  const double min_chords = std::ceil((std::numbers::pi / 2) / (2 * std::acos(1 - 1e-4)));
  ASSERT_EQ(min_chords, 56.0);
  for (const Case& c : cases) {
    SCOPED_TRACE(c.plane);
    const Outcome r = run(c.program);
    ASSERT_FALSE(r.error.has_value()) << r.error->message;
    const Chords ch = chords(r, c.which);
    ASSERT_GE(ch.points.size(), 2u);
    EXPECT_EQ(ch.points.front(), Eigen::Vector2d(10, 0));
    EXPECT_EQ(ch.points.back(), Eigen::Vector2d(0, 10));
    for (double z : ch.third) EXPECT_EQ(z, 3.0);
    const auto n = static_cast<double>(ch.points.size() - 1);
    EXPECT_GE(n, min_chords);
    EXPECT_LE(n, 4 * min_chords);
    for (std::size_t k = 0; k < ch.points.size(); ++k) {
      EXPECT_NEAR(ch.points[k].norm(), 10.0, 1e-9);
      if (k > 0) {
        EXPECT_LE(10.0 - (0.5 * (ch.points[k - 1] + ch.points[k])).norm(), 1e-3);
      }
    }
    const auto ax = program::plane_axes(c.which);
    EXPECT_EQ(r.position[ax[0]], 0.0);
    EXPECT_EQ(r.position[ax[1]], 10.0);
    EXPECT_EQ(r.position[ax[2]], 3.0);
  }
}

// G93: the F of the G5.3 block gives the curve 1/F minutes, the path rate
// F times its length (the polyline's; the arc's is 5 pi = 15.708 mm).
TEST(Nurbs, InverseTimeRateIsTheCurvesLength) {
  const Outcome r =
      run("G21 G17 G90 F500\nG0 X10 Y0\nG93\nG5.2 X10 Y10 P0.7071067811865476\nX0 Y10 "
          "P1\nG5.3 F2\nM2\n");
  ASSERT_FALSE(r.error.has_value()) << r.error->message;
  const auto rate = std::find_if(r.rates.begin(), r.rates.end(), [](const auto& f) {
    return f.mode == program::FeedMode::inverse_time;
  });
  ASSERT_NE(rate, r.rates.end());
  ASSERT_TRUE(rate->path_rate.has_value());
  EXPECT_EQ(rate->rate, 2.0);
  double length = 0.0;
  for (const auto& f : r.feeds) length += (f.end - f.start).norm();
  EXPECT_NEAR(*rate->path_rate, 2 * length, 1e-9);
  EXPECT_NEAR(length, 5 * std::numbers::pi, 1e-3);
}

// rs274's reading, worked by hand: the tool stays at the curve's start
// while points are given (G91 points count from it); Z in a G17 curve
// moves nothing; G5.3 with axis words ends the curve and opens the next at
// its end; S and F between the points come before the curve.
TEST(Nurbs, ReadAsRs274ReadsIt) {
  {
    const Outcome r =
        run("G21 F100\nG0 X1 Y2\nG91 G5.2 X0 Y10 P1\nX10 Y10 P1\nX10 Y0 P1\nG5.3\nM2\n");
    ASSERT_FALSE(r.error.has_value()) << r.error->message;
    EXPECT_EQ(r.position, Eigen::Vector3d(11, 2, 0));
    EXPECT_EQ(r.feeds.front().start, Eigen::Vector3d(1, 2, 0));
  }
  {
    const Outcome r = run("F100\nG0 X1 Y2\nG5.2 X0 Y10 Z5 P1\nX10 Y10 Z3 P1\nG5.3\nM2\n");
    ASSERT_FALSE(r.error.has_value()) << r.error->message;
    EXPECT_EQ(r.position, Eigen::Vector3d(10, 10, 0));
    for (const auto& f : r.feeds) EXPECT_EQ(f.end.z(), 0.0);
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_EQ(r.warnings[0].code, Code::W1516);
    EXPECT_EQ(r.warnings[0].column, 13u);
  }
  {
    const Outcome r =
        run("F100\nG0 X1 Y2\nG5.2 X0 Y10 P1\nX10 Y10 P1\nG5.3 X5 Y5 P2\nX7 Y7 P1\nX8 Y8 P1\nG5.3\n"
            "M2\n");
    ASSERT_FALSE(r.error.has_value()) << r.error->message;
    EXPECT_EQ(r.position, Eigen::Vector3d(8, 8, 0));
    // The first curve ends at (10, 10) on line 5, the second starts there.
    std::size_t first = 0;
    while (first < r.feeds.size() && r.feeds[first].source.line == 5) ++first;
    ASSERT_GT(first, 0u);
    ASSERT_LT(first, r.feeds.size());
    EXPECT_EQ(r.feeds[first - 1].end, Eigen::Vector3d(10, 10, 0));
    EXPECT_EQ(r.feeds[first].start, Eigen::Vector3d(10, 10, 0));
    EXPECT_EQ(r.feeds.back().source.line, 8u);
  }
  {
    // The first point's weight from a P alone, L4: four points, one span,
    // a cubic Bezier curve with weights 2, 1, 1, 1.
    const Outcome r =
        run("F100\nG0 X0 Y0\nG5.2 P2 L4\nX0 Y10 P1\nX10 Y10 P1\nX10 Y0 P1\nG5.3\nM2\n");
    ASSERT_FALSE(r.error.has_value()) << r.error->message;
    // At t = 1/2: (2*1/8 (0,0) + 3/8 (0,10) + 3/8 (10,10) + 1/8 (10,0)) / (2/8 + 7/8).
    const Eigen::Vector2d mid = Eigen::Vector2d(5.0, 7.5) / (9.0 / 8.0);
    double best = 1e300;
    for (const auto& f : r.feeds) {
      const Eigen::Vector2d a = f.start.head<2>(), b = f.end.head<2>();
      best = std::min(best, distance_to_segment(mid, a, b));
    }
    EXPECT_LE(best, kSplineTolerance);
  }
}

// rs274's refusals, each with its code and column (and where vcpost is
// stricter: a missing or non-positive P, a frame change inside a curve).
TEST(Nurbs, RefusalsWithCodeAndColumn) {
  struct Case {
    const char* program;
    const char* code;
    std::uint32_t line, column;
    const char* message;
  };
  const Case cases[] = {
      {"F10\nG5.2 X1\nX5 Y5 P1\nG5.3\nM2\n", "E1507", 2, 6, "both X and Y"},
      {"F10\nG18\nG5.2 X1 Y1 P1\nG5.3\nM2\n", "E1507", 3, 6, "both X and Z"},
      {"F10\nG5.2 X0 Y10 P1\nX10 Y10 P1\nG1 X3\nG5.2 P3\nX5 Y5 P1\nG5.3\nM2\n", "E1507", 5, 6,
       "Can specify P without X and Y only for the first control point"},
      {"F10\nG5.2 X0 Y10 P1\nX10 Y10 P1\nG1 X3\nG5.2 X4 Y4\nM2\n", "E1514", 5, 1,
       "Must specify positive weight P"},
      {"F10\nG5.2 X1 Y1\nX5 Y5 P1\nG5.3\nM2\n", "E1514", 2, 1, "needs its weight P"},
      {"F10\nG5.2 X1 Y1 P0\nM2\n", "E1511", 2, 12, "must be positive"},
      {"F10\nG5.2 X1 Y1 P1\nX2 Y2 P-1\nM2\n", "E1511", 3, 7, "must be positive"},
      {"G0 X1 F0\nG5.2 X1 Y1 P2\nM2\n", "E1505", 2, 1, "Cannot make a NURBS with 0 feedrate"},
      {"F10\nG5.2 X1 Y1 P2 L2.5\nM2\n", "E1511", 2, 15, "whole number"},
      {"F10\nG5.2 X1 Y1 P2 L21\nM2\n", "E1511", 2, 15, "above 20"},
      {"F10\nG5.2 X0 Y10 P1 L4\nX10 Y10 P1\nG5.3\nM2\n", "E1515", 4, 1,
       "at least equal to the order L = 4"},
      {"F10\nG5.2 X0 Y10 P1\nX10 Y10 P1\nG1 X3\nG5.3\nM2\n", "E1515", 5, 1,
       "Cannot use G5.3 without G5.2 first"},
      {"F10\nG5.3\nM2\n", "E1515", 2, 1, "without G5.2 first"},
      {"F10\nG5.2 X0 Y10 P1\nX10 Y10 P1\nG5.3 G1 X1\nM2\n", "E1403", 4, 6,
       "only additional G5.2 codes"},
      {"F10\nG5.2 X0 Y10 P1\nP3\nM2\n", "E1009", 3, 1, "P word with no"},
      {"F10\nG5.2 X0 Y10 P1\nX3 Y3 P1 I2\nM2\n", "E1009", 3, 10, "I word with no"},
      {"F10\nG5.2 X0 Y10 P1\nQ3\nM2\n", "E1009", 3, 1, "Q word with no"},
      {"F10\nG5.2 X0 Y10 P1\nG20\nX1 Y1 P1\nM2\n", "E1515", 4, 1, "since the G5.2 on line 2"},
      {"F10\nG5.2 X0 Y10 P1\nX1 Y1 P1\nG18\nG5.3\nM2\n", "E1515", 5, 1, "mix two frames"},
      {"F10\nG5.2 X0 Y10 P1\nG92 X5\nX1 Y1 P1\nM2\n", "E1515", 4, 1, "mix two frames"},
      {"F10\nG93\nG5.2 X0 Y10 P1\nX1 Y1 P1\nG5.3\nM2\n", "E1505", 5, 1, "inverse time"},
      {"F10\nG53 G5.2 X0 Y10 P1\nM2\n", "E1404", 2, 1, "G53 needs G0 or G1"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.program);
    const Outcome r = run(c.program);
    ASSERT_TRUE(r.error.has_value());
    EXPECT_EQ(to_string(r.error->code), c.code);
    EXPECT_EQ(r.error->line, c.line);
    EXPECT_EQ(r.error->column, c.column);
    EXPECT_NE(r.error->message.find(c.message), std::string::npos) << r.error->message;
  }
}

// G5.2 is LinuxCNC's: the Fanuc-like dialects refuse it as before.
TEST(Nurbs, FanucDialectsRefuseIt) {
  const Outcome r = run("G0 X0 Y0 F100\nG5.2 X1 Y1 P1\nX2 Y0 P1\nG5.3\nM30\n", fanuc_dialect());
  ASSERT_TRUE(r.error.has_value());
  EXPECT_EQ(r.error->code, Code::E1404);
  EXPECT_NE(r.error->message.find("NURBS"), std::string::npos);
}

}  // namespace
}  // namespace vcpost::gcode
