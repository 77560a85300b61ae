// The cusp and transverse roughness of bull-nose and flat end mills
// (revolved_cusp) against closed forms on a level floor, the ball's own
// formulas in the limit rc = R, and an independent profile on tilted and
// curved surfaces: the tool's outline seen along the feed by convex
// duality from its support function, not from the engine's silhouette.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <tuple>

#include "geometry/engagement.h"
#include "geometry/revolved_engagement.h"
#include "geometry/surface_quality.h"
#include "tool_outline.h"

namespace vcpost::geometry {
namespace {

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

CutSetup level_setup(double ae) { return {0.3, ae, {0, 0, 1}, {1, 0, 0}, Side::left}; }

// A bull-nose on a level floor, passes ae apart: its outline across the
// feed is the face (2 R0 wide) between two quarter circles of radius rc,
// so the cusp is rc - sqrt(rc^2 - (ae / 2 - R0)^2), and none while the
// faces overlap (ae <= 2 R0). The flat mill's faces always overlap.
TEST(RevolvedCusp, LevelFloorClosedForm) {
  const Tool tool = Tool::bull_nose(10, 2);  // R0 = 3
  for (const double ae : {6.5, 7.0, 8.0, 9.5}) {
    const RevolvedCusp cusp = revolved_cusp(tool, level_setup(ae), 0);
    const double expected = 2 - std::sqrt(4 - std::pow(ae / 2 - 3, 2));
    ASSERT_TRUE(cusp.height && cusp.rz) << ae;
    EXPECT_NEAR(*cusp.height, expected, 1e-9) << ae;
    EXPECT_NEAR(*cusp.rz, expected, 1e-9) << ae;
  }
  for (const double ae : {0.5, 3.0, 5.9}) {
    const RevolvedCusp cusp = revolved_cusp(tool, level_setup(ae), 0);
    ASSERT_TRUE(cusp.height) << ae;
    EXPECT_NEAR(*cusp.height, 0, 1e-9) << ae;
    EXPECT_NEAR(*cusp.ra, 0, 1e-9) << ae;
  }
  const RevolvedCusp flat = revolved_cusp(Tool::flat(10), level_setup(4), 0);
  ASSERT_TRUE(flat.height);
  EXPECT_NEAR(*flat.height, 0, 1e-9);
  // Beyond the tool's width the outlines never meet.
  EXPECT_FALSE(revolved_cusp(tool, level_setup(10.5), 0).height);
}

// A face resting on a convex crest, 0.11 mm in from its end, the next
// pass 0.077 mm over: the previous tool's face covers the contact too, no
// cusp; also where the model's normal and feed are level only within
// round-off (N_xy, F_z 2e-14) or the contact's tolerance (5e-10), crests of
// the wavy sample, which once moved the contact to the face's edge or
// took the previous tool's from its middle (cusps of 15 and 400 um).
TEST(RevolvedCusp, FaceOnACrestLeavesNone) {
  const Tool tool = Tool::bull_nose(10, 2);
  const Vector3d offset(0.72228490319577077, 2.8891169999998496, -2.0000000773805766);
  for (const auto& [normal, feed] :
       {std::pair{Vector3d(0, 0, 1), Vector3d(1, 0, 0)},
        std::pair{Vector3d(2.1316281248069938e-14, -7.1054270826899791e-15, 1),
                  Vector3d(1, 1.5146128208227269e-28, -2.1316281248069938e-14)},
        std::pair{Vector3d(4.8816766221359115e-10, -6.5718088711834259e-11, 1),
                  Vector3d(1, -3.2081445731601526e-20, 4.8816766221359115e-10)}}) {
    const CutSetup s{0.3, 0.077459, normal, feed, Side::right};
    const RevolvedCusp cusp = revolved_cusp(tool, s, 0.023165545943025438, offset);
    ASSERT_TRUE(cusp.height);
    EXPECT_NEAR(*cusp.height, 0, 1e-9);
  }
}

// Ra by layers on the level floor against the profile integrated in b:
// the face (z = 0) for |b| <= R0 and the corner's arc beyond, one period
// [0, ae] of the profile min(z(b), z(b - ae)), Simpson's rule on 200,000
// panels (the profile has two kinks, where its error is O(h^2)).
TEST(RevolvedCusp, LevelFloorRoughnessByLayersMatchesTheProfile) {
  const double r0 = 3, rc = 2;
  const auto outline = [&](double b) {  // the tool's lower outline above its face
    const double x = std::max(0.0, std::abs(b) - r0);
    return x >= rc ? rc : rc - std::sqrt(rc * rc - x * x);
  };
  for (const double ae : {6.4, 7.5, 9.0}) {
    const auto z = [&](double b) { return std::min(outline(b), outline(b - ae)); };
    const int n = 200000;
    const auto simpson = [&](const std::function<double(double)>& f) {
      const double h = ae / n;
      double sum = f(0) + f(ae);
      for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * f(i * h);
      return sum * h / 3;
    };
    const double mean = simpson(z) / ae;
    const double ra = simpson([&](double b) { return std::abs(z(b) - mean); }) / ae;
    const RevolvedCusp cusp = revolved_cusp(Tool::bull_nose(10, 2), level_setup(ae), 0);
    ASSERT_TRUE(cusp.ra) << ae;
    EXPECT_NEAR(*cusp.ra, ra, 1e-9) << ae;
  }
}

// The limit rc = R (R0 = 0) is the ball: on the plane the ball's cusp and
// its arc profile's Ra and Rz; on a curved surface the ball's circle
// construction, whose ae is the arc between the contacts, where the pass
// tracker's ae between the tools' positions is the chord of the centres'
// circle: 2 (rho + R) sin(s / (2 rho)) convex, 2 (rho - R) sin(...) concave.
TEST(RevolvedCusp, BallLimitMatchesTheBallFormulas) {
  const double radius = 5;
  const Tool tool{ToolKind::bull_nose, 2 * radius, radius};
  for (const double tilt : {0.0, 0.4, 1.0}) {
    const Vector3d n = normal_from_angles(tilt, 0.3);
    for (const double ae : {0.3, 1.2, 4.0}) {
      const CutSetup s{0.3, ae, n, feed_from_angle(1.1, n), Side::right};
      const RevolvedCusp cusp = revolved_cusp(tool, s, 0);
      const Roughness ball = transverse_roughness(radius, ae);
      ASSERT_TRUE(cusp.height && cusp.ra && cusp.rz);
      EXPECT_NEAR(*cusp.height, flat_cusp_height(radius, ae), 1e-9);
      EXPECT_NEAR(*cusp.rz, ball.rz, 1e-9);
      EXPECT_NEAR(*cusp.ra, ball.ra, 1e-9 + 1e-7 * ball.ra);
    }
  }
  for (const double rho : {8.0, 30.0}) {
    for (const auto kind : {Curvature::convex, Curvature::concave}) {
      const double k = kind == Curvature::convex ? 1 / rho : -1 / rho;
      const double arc = 1.5;
      const double chord =
          2 * (kind == Curvature::convex ? rho + radius : rho - radius) * std::sin(arc / (2 * rho));
      const CutSetup s{0.3, chord, normal_from_angles(0.5, 1.0), {1, 0, 0}, Side::left};
      const RevolvedCusp cusp = revolved_cusp(tool, s, k);
      ASSERT_TRUE(cusp.height);
      EXPECT_NEAR(*cusp.height, curved_cusp_height(radius, arc, rho, kind), 1e-9) << rho;
    }
  }
}

// Random tilted and curved set-ups (bull-nose and flat, either side),
// against the tool's outline from its support function (tool_outline.h):
// the cusp where this tool's outline meets the previous one's (on a curved
// surface shifted to touch the circle where the tools are ae apart across
// the feed, the contact the support point in the surface's normal), its
// height above the plane or the circle, within 1e-7 mm; Ra and Rz of the
// plane's profile by Simpson's rule (split at its kink and where it
// crosses its mean line) within 1e-7 mm.
TEST(RevolvedCusp, TiltedAndCurvedAgainstTheToolsOutline) {
  std::mt19937 random(17);  // NOLINT(cert-msc32-c,cert-msc51-cpp): the same set-ups each run
  std::uniform_real_distribution<double> unit(0, 1);
  int checked = 0, roughness = 0;
  for (int i = 0; i < 60; ++i) {
    const double diameter = 6 + 10 * unit(random);
    const Tool tool = i % 3 == 2
                          ? Tool::flat(diameter)
                          : Tool::bull_nose(diameter, diameter / 2 * (0.1 + 0.8 * unit(random)));
    const Vector3d n = normal_from_angles(1.2 * unit(random), 2 * kPi * unit(random));
    const Vector3d f = feed_from_angle(2 * kPi * unit(random), n);
    const Side side = unit(random) < 0.5 ? Side::left : Side::right;
    const double ae = diameter * (0.01 + 0.6 * unit(random) * unit(random));
    // Convex down to a radius of D, concave down to 1.6 R.
    const double k = i % 2 ? 0.0 : (1.6 * unit(random) - 1.2) / diameter;
    const CutSetup s{0.3, ae, n, f, side};
    const RevolvedCusp cusp = revolved_cusp(tool, s, k);
    // e points to the previous pass: N x F on the left.
    const Vector3d e = (side == Side::left ? 1.0 : -1.0) * n.cross(f).normalized();
    const testing::ToolOutline outline{tool, e, n};
    // The contact: the lowest point along N, the support point in -N.
    const auto support_point = [&](const Vector3d& normal) {
      const Vector3d u = -normal;
      const double flat = std::hypot(u.x(), u.y());
      const Vector3d radial =
          flat > 1e-12 ? Vector3d(u.x() / flat, u.y() / flat, 0) : Vector3d(0, 0, 0);
      return Vector3d(tool.flat_radius() * radial + tool.corner_radius * u);
    };
    const Vector3d cc = support_point(n);
    const double b_cc = e.dot(cc), c_cc = n.dot(cc);
    // The previous tool's shift across the feed (db, dc) and its contact's b.
    double db = ae, dc = 0, b_next = b_cc + ae;
    if (k != 0) {
      const auto shift = [&](double arc) {
        const double turn = k * arc;
        const Vector3d normal = std::cos(turn) * n + std::sin(turn) * e;
        const Vector3d touch = cc + std::sin(turn) / k * e - (1 - std::cos(turn)) / k * n;
        const Vector3d d = touch - support_point(normal);
        return std::tuple{e.dot(d), n.dot(d), e.dot(touch)};
      };
      // Out to where the normal has turned a quarter turn: beyond, no pass.
      const double quarter = kPi / 2 / std::abs(k);
      double lo = 1e-9, hi = std::min(ae, quarter);
      const auto far = [&](double arc) {
        const auto [x, y, b] = shift(arc);
        return std::hypot(x, y) >= ae;
      };
      while (!far(hi) && hi < quarter) hi = std::min(2 * hi, quarter);
      if (!far(hi)) {
        EXPECT_FALSE(cusp.height) << i;
        continue;
      }
      for (int j = 0; j < 200; ++j) {
        const double mid = 0.5 * (lo + hi);
        const auto [x, y, b] = shift(mid);
        (std::hypot(x, y) < ae ? lo : hi) = mid;
      }
      std::tie(db, dc, b_next) = shift(0.5 * (lo + hi));
    }
    // Where the outlines meet: b between the contacts, bisected (the
    // difference of a convex outline and its translate grows with b).
    const auto gap = [&](double b) { return outline.lowest(b) - (outline.lowest(b - db) + dc); };
    double lo = b_cc, hi = b_next;
    if (!(gap(lo) < 0 && gap(hi) > 0)) continue;  // faces overlapping, or beyond reach
    for (int j = 0; j < 100; ++j) (gap(0.5 * (lo + hi)) < 0 ? lo : hi) = 0.5 * (lo + hi);
    const double b = 0.5 * (lo + hi), c = outline.lowest(b);
    double height = c - c_cc;
    if (k != 0) {
      const double from_centre = std::hypot(b - b_cc, c - c_cc + 1 / k);
      height = k > 0 ? from_centre - 1 / k : -1 / k - from_centre;
    }
    ASSERT_TRUE(cusp.height) << i;
    EXPECT_NEAR(*cusp.height, height, 1e-7) << i;
    if (k == 0) {
      // The profile over one period from CC, measured from it, its kink at
      // the cusp b and where it crosses its mean line split out for
      // Simpson's rule.
      const auto z = [&](double x) {
        return std::min(outline.lowest(x), outline.lowest(x - ae)) - c_cc;
      };
      const auto simpson = [&](const auto& g, double from, double to) {
        const int panels = 400;
        const double h = (to - from) / panels;
        double sum = g(from) + g(to);
        for (int j = 1; j < panels; ++j) sum += (j % 2 ? 4 : 2) * g(from + j * h);
        return sum * h / 3;
      };
      const double mean = (simpson(z, b_cc, b) + simpson(z, b, b_cc + ae)) / ae;
      const auto crossing = [&](double from, double to) {  // z - mean changes sign once
        const bool rising = z(from) < z(to);
        for (int j = 0; j < 100; ++j)
          ((z(0.5 * (from + to)) < mean) == rising ? from : to) = 0.5 * (from + to);
        return 0.5 * (from + to);
      };
      const double x1 = crossing(b_cc, b), x2 = crossing(b, b_cc + ae);
      const auto deviation = [&](double x) { return std::abs(z(x) - mean); };
      const double ra = (simpson(deviation, b_cc, x1) + simpson(deviation, x1, b) +
                         simpson(deviation, b, x2) + simpson(deviation, x2, b_cc + ae)) /
                        ae;
      ASSERT_TRUE(cusp.ra && cusp.rz) << i;
      EXPECT_NEAR(*cusp.rz, height, 1e-7) << i;
      EXPECT_NEAR(*cusp.ra, ra, 1e-7) << i;
      ++roughness;
    }
    ++checked;
  }
  EXPECT_GE(checked, 50);
  EXPECT_GE(roughness, 25);
}

}  // namespace
}  // namespace vcpost::geometry
