#include "geometry/surface_quality.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace vcpost::geometry {
namespace {

constexpr double kPi = std::numbers::pi;
double deg(double degrees) { return degrees * kPi / 180; }

// Composite Simpson rule with n (even) intervals.
double simpson(const std::function<double(double)>& f, double lo, double hi, int n) {
  const double h = (hi - lo) / n;
  double sum = f(lo) + f(hi);
  for (int i = 1; i < n; ++i) sum += f(lo + i * h) * (i % 2 == 1 ? 4 : 2);
  return sum * h / 3;
}

// Root of an increasing-or-decreasing f on [lo, hi] (sign change), by bisection.
double bisect(const std::function<double(double)>& f, double lo, double hi) {
  const bool rising = f(lo) < 0;
  for (int i = 0; i < 200; ++i) {
    const double mid = (lo + hi) / 2;
    if ((f(mid) < 0) == rising) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return (lo + hi) / 2;
}

// Ra of the arc profile by numerical integration over half a period: the
// mean line from the integral of z, the crossing by bisection, then |z - m|
// integrated on both sides of the crossing (Simpson, 20000 intervals each).
double numeric_ra(double radius, double spacing) {
  const double a = spacing / 2;
  const auto z = [radius](double x) { return radius - std::sqrt(radius * radius - x * x); };
  const double mean = simpson(z, 0, a, 20000) / a;
  const double x0 = bisect([&](double x) { return z(x) - mean; }, 0, a);
  const double below = simpson([&](double x) { return mean - z(x); }, 0, x0, 20000);
  const double above = simpson([&](double x) { return z(x) - mean; }, x0, a, 20000);
  return (below + above) / a;
}

// Cusp on a circle of radius rho (curvature centre at the origin): the
// point of the bisector at distance R from the ball centre at angle
// +ae/(2 rho), found by bisection between the centre's foot on the bisector
// and the nominal surface; its radial distance from the surface.
double numeric_curved_cusp(double radius, double stepover, double rho, bool convex) {
  const double half_angle = stepover / rho / 2;
  const double centre_radius = convex ? rho + radius : rho - radius;
  const Eigen::Vector2d centre =
      centre_radius * Eigen::Vector2d(std::cos(half_angle), std::sin(half_angle));
  const auto outside_ball = [&](double r) {
    return (Eigen::Vector2d(r, 0) - centre).norm() - radius;
  };
  const double foot = centre.x();  // inside the ball
  const double r = bisect(outside_ball, foot, rho);
  return std::abs(r - rho);
}

// Distance on the plane z = x tan(slope) between two passes whose plan views
// run at angle A from the level line (the y axis) and lie stepover apart.
double numeric_spacing_on_plane(double stepover, double slope, double feed_angle) {
  const double t = std::tan(slope);
  const auto lift = [t](double x, double y) { return Eigen::Vector3d(x, y, x * t); };
  const Eigen::Vector3d f = lift(std::sin(feed_angle), std::cos(feed_angle));
  const Eigen::Vector3d w = lift(stepover * std::cos(feed_angle), -stepover * std::sin(feed_angle));
  return w.cross(f).norm() / f.norm();
}

TEST(FlatCusp, MatchesHandValues) {
  // 5 - sqrt(25 - 0.0625) = 5 - 4.99374608885954...
  EXPECT_NEAR(flat_cusp_height(5, 0.5), 0.0062539111404556, 1e-15);
  EXPECT_NEAR(flat_cusp_height(5, 8), 2.0, 1e-14);  // 5 - sqrt(25 - 16)
  EXPECT_EQ(flat_cusp_height(5, 0), 0.0);
}

TEST(FlatCusp, RejectsMeaninglessInput) {
  EXPECT_THROW(flat_cusp_height(0, 0.5), std::invalid_argument);
  EXPECT_THROW(flat_cusp_height(-5, 0.5), std::invalid_argument);
  EXPECT_THROW(flat_cusp_height(5, -0.1), std::invalid_argument);
  EXPECT_THROW(flat_cusp_height(5, 10), std::invalid_argument);
  EXPECT_THROW(flat_cusp_height(5, std::numeric_limits<double>::quiet_NaN()),
               std::invalid_argument);
}

TEST(InclinedCusp, PaperAlpha3Values) {
  // Mikó, Beňo, Maňková: alpha1 = 36.9 deg gives alpha3 = 36.9 at A = 0 and
  // 27.96 at A = 45 deg.
  EXPECT_NEAR(inclined_cusp(6, 0.5, deg(36.9), 0).alpha3, deg(36.9), 1e-12);
  EXPECT_NEAR(inclined_cusp(6, 0.5, deg(36.9), deg(45)).alpha3, deg(27.96), deg(0.005));
}

TEST(InclinedCusp, ExactSpacingBesideThePapers) {
  // alpha1 = A = 45 deg: exact sqrt(2/1.5) = 1.1547 ae, paper sqrt(1.5) = 1.2247 ae.
  const InclinedCusp cusp = inclined_cusp(5, 0.5, deg(45), deg(45));
  EXPECT_NEAR(cusp.exact_spacing / 0.5, 2 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(cusp.exact_spacing / 0.5, 1.155, 5e-4);
  EXPECT_NEAR(cusp.paper_spacing / 0.5, 1.225, 5e-4);
  EXPECT_NEAR(cusp.exact_height, flat_cusp_height(5, 0.5 * 2 / std::sqrt(3.0)), 1e-15);
  ASSERT_TRUE(cusp.paper_height.has_value());
  EXPECT_NEAR(*cusp.paper_height, flat_cusp_height(5, 0.5 * std::sqrt(1.5)), 1e-15);
  EXPECT_LT(cusp.exact_height, *cusp.paper_height);
}

TEST(InclinedCusp, ExactSpacingIsTheDistanceOfTheLiftedPasses) {
  for (double slope : {0.0, 10.0, 36.9, 45.0, 70.0}) {
    for (double angle : {0.0, 20.0, 45.0, 63.0, 90.0, 135.0}) {
      const InclinedCusp cusp = inclined_cusp(5, 0.4, deg(slope), deg(angle));
      EXPECT_NEAR(cusp.exact_spacing, numeric_spacing_on_plane(0.4, deg(slope), deg(angle)), 1e-12)
          << "slope " << slope << " A " << angle;
      EXPECT_LE(cusp.exact_spacing, cusp.paper_spacing + 1e-12);
    }
  }
}

TEST(InclinedCusp, LimitsReduceToKnownCases) {
  const double flat = flat_cusp_height(5, 0.5);
  // Ramping: passes side by side on the level, no effect of the slope.
  const InclinedCusp ramp = inclined_cusp(5, 0.5, deg(40), deg(90));
  EXPECT_NEAR(ramp.alpha3, 0, 1e-15);
  EXPECT_NEAR(ramp.exact_height, flat, 1e-15);
  EXPECT_NEAR(*ramp.paper_height, flat, 1e-15);
  // Contouring: both readings give ae / cos(alpha1).
  const InclinedCusp contour = inclined_cusp(5, 0.5, deg(40), 0);
  EXPECT_NEAR(contour.exact_spacing, 0.5 / std::cos(deg(40)), 1e-14);
  EXPECT_NEAR(contour.paper_spacing, 0.5 / std::cos(deg(40)), 1e-14);
  // Zero slope: the flat cusp at every feed angle.
  for (double angle : {0.0, 30.0, 90.0}) {
    const InclinedCusp level = inclined_cusp(5, 0.5, 0, deg(angle));
    EXPECT_NEAR(level.exact_height, flat, 1e-15);
    EXPECT_NEAR(*level.paper_height, flat, 1e-15);
  }
}

TEST(InclinedCusp, PaperHeightEmptyWhereItsSpacingExceedsTheBall) {
  // R = 1, alpha1 = A = 45 deg, ae = 1.7: exact 1.963 < 2 <= paper 2.082.
  const InclinedCusp cusp = inclined_cusp(1, 1.7, deg(45), deg(45));
  EXPECT_FALSE(cusp.paper_height.has_value());
  EXPECT_NEAR(cusp.exact_height, flat_cusp_height(1, 1.7 * 2 / std::sqrt(3.0)), 1e-14);
  EXPECT_THROW(inclined_cusp(1, 1.8, deg(45), deg(45)), std::invalid_argument);
  EXPECT_THROW(inclined_cusp(1, 0.5, deg(90), 0), std::invalid_argument);
  EXPECT_THROW(inclined_cusp(1, 0.5, -0.1, 0), std::invalid_argument);
  EXPECT_THROW(inclined_cusp(0, 0.5, 0.1, 0), std::invalid_argument);
}

TEST(CurvedCusp, MikoBenoMankovaSemiCylinder) {
  // 12 mm ball on a convex semi-cylinder of radius 100 mm.
  for (double ae : {0.2, 0.5, 0.8}) {
    const double h = curved_cusp_height(6, ae, 100, Curvature::convex);
    EXPECT_NEAR(h, numeric_curved_cusp(6, ae, 100, true), 1e-13) << "ae " << ae;
    // Leading term ae^2 (rho + R) / (8 R rho) = 0.000883, 0.00552, 0.01413 mm,
    // within its O(ae^2/R^2) relative error.
    EXPECT_NEAR(h, ae * ae * 106 / 4800, ae * ae * 106 / 4800 * 2e-3) << "ae " << ae;
    EXPECT_GT(h, flat_cusp_height(6, ae));
  }
}

TEST(CurvedCusp, ConcaveMatchesTheCircleIntersection) {
  for (double rho : {6.5, 20.0, 100.0}) {
    for (double ae : {0.2, 0.8, 2.0}) {
      EXPECT_NEAR(curved_cusp_height(6, ae, rho, Curvature::concave),
                  numeric_curved_cusp(6, ae, rho, false), 1e-13)
          << "rho " << rho << " ae " << ae;
    }
  }
}

TEST(CurvedCusp, ConvexAboveFlatAboveConcave) {
  for (double rho : {8.0, 30.0, 300.0}) {
    const double flat = flat_cusp_height(5, 0.6);
    EXPECT_GT(curved_cusp_height(5, 0.6, rho, Curvature::convex), flat);
    EXPECT_LT(curved_cusp_height(5, 0.6, rho, Curvature::concave), flat);
  }
}

TEST(CurvedCusp, InfiniteRadiusGivesTheFlatCusp) {
  const double flat = flat_cusp_height(5, 0.5);
  for (double rho : {1e6, 1e9, 1e12}) {
    // Deviation ~ flat * R / rho.
    EXPECT_NEAR(curved_cusp_height(5, 0.5, rho, Curvature::convex), flat, flat * 10 / rho);
    EXPECT_NEAR(curved_cusp_height(5, 0.5, rho, Curvature::concave), flat, flat * 10 / rho);
  }
}

TEST(CurvedCusp, EdgeCasesAndRejections) {
  // A hollow of the ball's own radius is cut without a cusp.
  EXPECT_NEAR(curved_cusp_height(5, 1.0, 5, Curvature::concave), 0, 1e-15);
  EXPECT_EQ(curved_cusp_height(5, 0, 50, Curvature::convex), 0.0);
  EXPECT_THROW(curved_cusp_height(5, 1.0, 4.9, Curvature::concave), std::invalid_argument);
  EXPECT_THROW(curved_cusp_height(5, 1.0, 0, Curvature::convex), std::invalid_argument);
  // Convex rho = 1, ae = 2: centres 6 mm from the axis, 2 rad apart, so
  // 2 * 6 sin(1) = 10.1 mm > 2R: the balls do not overlap.
  EXPECT_THROW(curved_cusp_height(5, 2.0, 1, Curvature::convex), std::invalid_argument);
  EXPECT_THROW(curved_cusp_height(5, -0.1, 50, Curvature::convex), std::invalid_argument);
}

TEST(Roughness, RzIsTheFlatCusp) {
  EXPECT_NEAR(transverse_roughness(5, 0.5).rz, 0.0062539111404556, 1e-15);
}

TEST(Roughness, RaMatchesNumericalIntegrationOfTheArcProfile) {
  const double cases[][2] = {{5, 0.5}, {5, 2}, {5, 8}, {3, 5.9}, {0.5, 0.01}, {6, 0.8}};
  for (const auto& c : cases) {
    const double expected = numeric_ra(c[0], c[1]);
    EXPECT_NEAR(arc_profile_roughness(c[0], c[1]).ra, expected, 1e-9 * expected)
        << "R " << c[0] << " spacing " << c[1];
  }
}

TEST(Roughness, RatioTendsToTheParabolaLimit) {
  const double limit = 4 / (9 * std::sqrt(3.0));  // 0.2566
  EXPECT_NEAR(limit, 0.2566, 1e-4);
  const Roughness fine = arc_profile_roughness(5, 5e-3);  // ae = 1e-3 R
  EXPECT_NEAR(fine.ra / fine.rz, limit, 1e-4);
  EXPECT_NEAR(fine.ra / fine.rz, limit, 1e-6);
  // Far from the Rz/4..5 rule of thumb for coarse stepovers too, but not the limit.
  const Roughness coarse = arc_profile_roughness(5, 8);
  EXPECT_GT(std::abs(coarse.ra / coarse.rz - limit), 1e-3);
}

TEST(Roughness, LongitudinalAndObliqueUseTheirSpacings) {
  const Roughness lon = longitudinal_roughness(5, 0.12);
  EXPECT_NEAR(lon.ra, numeric_ra(5, 0.12), 1e-9 * lon.ra);
  const Roughness obl = oblique_roughness(5, 0.5, deg(30));
  EXPECT_NEAR(obl.rz, flat_cusp_height(5, 0.5 / std::cos(deg(30))), 1e-15);
  EXPECT_NEAR(obl.ra, numeric_ra(5, 0.5 / std::cos(deg(30))), 1e-9 * obl.ra);
  EXPECT_EQ(transverse_roughness(5, 0).ra, 0.0);
  EXPECT_THROW(arc_profile_roughness(5, 10), std::invalid_argument);
  EXPECT_THROW(oblique_roughness(5, 6, deg(60)), std::invalid_argument);  // 12 mm > 2R
  EXPECT_THROW(arc_profile_roughness(-1, 0.1), std::invalid_argument);
}

TEST(FeedMarks, MartellottiByHand) {
  // fz = 0.1, Reff = 3, z = 2: fz z / pi = 0.0636620;
  // up 0.01 / (8 * 3.0636620) = 4.0800846e-4, down 0.01 / (8 * 2.9363380) = 4.2570031e-4.
  const double up = feed_mark_height(0.1, 3, 2, MillingMode::up);
  const double down = feed_mark_height(0.1, 3, 2, MillingMode::down);
  EXPECT_NEAR(up, 4.0800845827235e-4, 1e-15);
  EXPECT_NEAR(down, 4.2570030776759e-4, 1e-15);
  // The minus sign of down milling makes its marks the higher ones.
  EXPECT_GT(down, up);
  EXPECT_EQ(feed_mark_height(0, 3, 2, MillingMode::down), 0.0);
}

TEST(FeedMarks, RejectsMeaninglessInput) {
  EXPECT_THROW(feed_mark_height(0.1, 0, 2, MillingMode::up), std::invalid_argument);
  EXPECT_THROW(feed_mark_height(-0.1, 3, 2, MillingMode::up), std::invalid_argument);
  EXPECT_THROW(feed_mark_height(0.1, 3, 0, MillingMode::up), std::invalid_argument);
  // fz z / pi = 0.3 * 4 / pi = 0.38 >= Reff = 0.3.
  EXPECT_THROW(feed_mark_height(0.3, 0.3, 4, MillingMode::down), std::invalid_argument);
  EXPECT_NO_THROW(feed_mark_height(0.3, 0.3, 4, MillingMode::up));
}

TEST(RunoutBand, OffsetAndTiltByHand) {
  // rho = 5 um, tau = 1 mrad, overhang 40 mm, cutting 1 mm above the tip:
  // rho_eff = 0.005 + 39 sin(0.001) = 0.0439999935; band 8 -+ 0.087999987.
  const RunoutBand band = runout_band(8, {0.005, 1e-3, 40, 1});
  EXPECT_NEAR(band.effective_offset, 0.0439999935, 1e-12);
  EXPECT_NEAR(band.d_min, 7.912000013, 1e-11);
  EXPECT_NEAR(band.d_max, 8.087999987, 1e-11);
  EXPECT_TRUE(band.marks_once_per_revolution);
}

TEST(RunoutBand, ClampedAtZeroAndExactWithoutErrors) {
  const RunoutBand small = runout_band(0.05, {0.03, 0, 30, 0});  // 0.05 - 0.06 < 0
  EXPECT_EQ(small.d_min, 0.0);
  EXPECT_NEAR(small.d_max, 0.11, 1e-15);
  const RunoutBand none = runout_band(8, {0, 0, 30, 2});
  EXPECT_EQ(none.d_min, 8.0);
  EXPECT_EQ(none.d_max, 8.0);
  EXPECT_FALSE(none.marks_once_per_revolution);
  EXPECT_THROW(runout_band(8, {0, 0.01, 30, 31}), std::invalid_argument);
  EXPECT_THROW(runout_band(8, {-0.01, 0, 30, 0}), std::invalid_argument);
  EXPECT_THROW(runout_band(8, {0, 0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(runout_band(-1, {0, 0, 30, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace vcpost::geometry
