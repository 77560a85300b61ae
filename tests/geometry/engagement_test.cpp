// The ball engine against hand-computed values, MODELS.md's checks and the
// paper's figures, and against a brute-force sampler on random set-ups.
#include "geometry/engagement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "ball_sampler_support.h"

namespace vcpost::geometry {
namespace {

constexpr double pi = std::numbers::pi;
double deg(double degrees) { return degrees * pi / 180; }

CutSetup setup(double ap, double ae, Eigen::Vector3d n, Eigen::Vector3d f, Side side = Side::left) {
  return {ap, ae, n, f, side};
}

// Feed straight up the slope of a surface tilted by beta about y, normal
// leaning to +x: uphill is -x.
Eigen::Vector3d tilted_normal(double beta) { return {std::sin(beta), 0, std::cos(beta)}; }
Eigen::Vector3d uphill(double beta) { return {-std::cos(beta), 0, std::sin(beta)}; }

// The tool makers' formula for the largest 2r of the whole cap (MODELS.md).
double cap_max_diameter(double d, double ap, double beta) {
  const double angle = beta + std::acos((d - 2 * ap) / d);
  return angle >= pi / 2 ? d : d * std::sin(angle);
}

TEST(BallEngagement, HorizontalRimDiameterAndSpindleSpeed) {
  // D = 10, ap = 0.3: rim diameter 2 sqrt(0.3 * 9.7) = 3.411744; the tip cuts.
  const auto e = evaluate_engagement(Tool::ball(10), setup(0.3, 5, {0, 0, 1}, {1, 0, 0}));
  ASSERT_TRUE(e.d_max && e.d_min && e.points);
  EXPECT_NEAR(*e.d_max, 2 * std::sqrt(0.3 * 9.7), 1e-12);
  EXPECT_NEAR(*e.d_max, 3.4117, 5e-5);
  EXPECT_NEAR(*e.d_min, 0, 1e-12);
  EXPECT_EQ(std::lround(spindle_speed_for(120, *e.d_max)), 11196);  // 120000 / (pi 3.411744)
  EXPECT_NEAR(cutting_speed(*e.d_max, 11196), 120, 0.01);
  EXPECT_FALSE(e.flags.has(EngagementFlag::shank_engaged));
}

TEST(BallEngagement, HorizontalCuttingPointsByHand) {
  // F = +x, N = +z: S0 = N x F = +y; rim radius rho = sqrt(2.91) at z = -4.7.
  const double rho = std::sqrt(0.3 * 9.7), ae = 0.5;
  const auto e = evaluate_engagement(Tool::ball(10), setup(0.3, ae, {0, 0, 1}, {1, 0, 0}));
  ASSERT_TRUE(e.points);
  const auto& p = *e.points;
  EXPECT_TRUE(p.p1.position.isApprox(Eigen::Vector3d(0, -rho, -4.7), 1e-12));
  EXPECT_TRUE(p.p2.position.isApprox(Eigen::Vector3d(0, rho, -4.7), 1e-12));
  const double b1 = -rho + ae, a1 = std::sqrt(rho * rho - b1 * b1);
  EXPECT_TRUE(p.p1a.position.isApprox(Eigen::Vector3d(a1, b1, -4.7), 1e-12));
  EXPECT_TRUE(p.p1b.position.isApprox(Eigen::Vector3d(-a1, b1, -4.7), 1e-12));
  EXPECT_TRUE(p.p2a.position.isApprox(Eigen::Vector3d(a1, -b1, -4.7), 1e-12));
  EXPECT_TRUE(p.p2b.position.isApprox(Eigen::Vector3d(-a1, -b1, -4.7), 1e-12));
  EXPECT_NEAR(p.p1a.diameter, 2 * rho, 1e-12);  // every rim point of a level cut has r = rho
  EXPECT_TRUE(p.cut.position.isApprox(p.p1.position));  // previous pass left -> point 1
  const auto right =
      evaluate_engagement(Tool::ball(10), setup(0.3, ae, {0, 0, 1}, {1, 0, 0}, Side::right));
  EXPECT_TRUE(right.points->cut.position.isApprox(p.p2.position));
}

TEST(BallEngagement, WithoutCuttingPointsTheDiametersAreTheSame) {
  // The hand-checked level cut above (D_max 2 sqrt(0.3 * 9.7)) and a tilted
  // one, with the points left out: D_max, D_min and the flags do not move
  // by a bit; only `points` is empty. A bull-nose mill drops them too.
  for (const CutSetup& s : {setup(0.3, 0.5, {0, 0, 1}, {1, 0, 0}),
                            setup(0.3, 2, tilted_normal(deg(40)), uphill(deg(40)))}) {
    const auto all = evaluate_engagement(Tool::ball(10), s);
    const auto bare = evaluate_engagement(Tool::ball(10), s, CuttingPointsWanted::no);
    ASSERT_TRUE(all.points && all.d_max && bare.d_max && bare.d_min);
    EXPECT_FALSE(bare.points);
    EXPECT_EQ(*bare.d_max, *all.d_max);
    EXPECT_EQ(*bare.d_min, *all.d_min);
    EXPECT_EQ(bare.flags.bits, all.flags.bits);
  }
  EXPECT_NEAR(*evaluate_engagement(Tool::ball(10), setup(0.3, 0.5, {0, 0, 1}, {1, 0, 0}),
                                   CuttingPointsWanted::no)
                   .d_max,
              2 * std::sqrt(0.3 * 9.7), 1e-12);
  const Tool bull = Tool::bull_nose(10, 2);
  const auto bull_all = evaluate_engagement(bull, setup(0.3, 0.5, {0, 0, 1}, {1, 0, 0}));
  const auto bull_bare =
      evaluate_engagement(bull, setup(0.3, 0.5, {0, 0, 1}, {1, 0, 0}), CuttingPointsWanted::no);
  ASSERT_TRUE(bull_all.points && bull_all.d_max && bull_bare.d_max);
  EXPECT_FALSE(bull_bare.points);
  EXPECT_EQ(*bull_bare.d_max, *bull_all.d_max);
}

TEST(BallEngagement, PrimesFallOntoOppositePointPastTheGrooveWidth) {
  const double rho = std::sqrt(0.3 * 9.7);
  const auto e =
      evaluate_engagement(Tool::ball(10), setup(0.3, 2 * rho + 0.1, {0, 0, 1}, {1, 0, 0}));
  EXPECT_TRUE(e.points->p1a.position.isApprox(e.points->p2.position));
  EXPECT_TRUE(e.points->p2b.position.isApprox(e.points->p1.position));
}

TEST(BallEngagement, TiltedUpTheSlopeReachesTheCapMaximumWithAWideStepover) {
  const double d = 10, ap = 0.3, rho = std::sqrt(ap * (d - ap));
  for (const double beta_deg : {5.0, 15.0, 25.0, 45.0, 60.0, 75.0}) {
    const double beta = deg(beta_deg);
    const auto wide =
        evaluate_engagement(Tool::ball(d), setup(ap, rho, tilted_normal(beta), uphill(beta)));
    ASSERT_TRUE(wide.d_max);
    EXPECT_NEAR(*wide.d_max, cap_max_diameter(d, ap, beta), 1e-9) << beta_deg;
    // A narrower stepover leaves that point inside the previous pass.
    const auto narrow =
        evaluate_engagement(Tool::ball(d), setup(ap, 0.9 * rho, tilted_normal(beta), uphill(beta)));
    if (cap_max_diameter(d, ap, beta) < d) {
      EXPECT_LT(*narrow.d_max, cap_max_diameter(d, ap, beta) - 1e-6);
    }
  }
}

TEST(BallEngagement, EngagedMaximumNeverExceedsTheCapFormula) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(0, 2 * pi), tilt(0, deg(85)), ap(0.05, 2),
      ae(0.01, 3);
  for (int i = 0; i < 2000; ++i) {
    const double beta = tilt(rng), a = ap(rng);
    const auto n = normal_from_angles(beta, angle(rng));
    const auto e = evaluate_engagement(
        Tool::ball(10),
        setup(a, ae(rng), n, feed_from_angle(angle(rng), n), i % 2 ? Side::left : Side::right));
    ASSERT_TRUE(e.d_max);
    EXPECT_LE(*e.d_max, cap_max_diameter(10, a, beta) + 1e-9);
  }
}

TEST(BallEngagement, PaperTableOneMaximumAt45Degrees) {
  // r = R sin(45 deg + acos(4.7 / 5)) = 4.530 mm (the paper's Table 1, a radius).
  const double beta = deg(45);
  const auto e =
      evaluate_engagement(Tool::ball(10), setup(0.3, 2, tilted_normal(beta), uphill(beta)));
  EXPECT_NEAR(*e.d_max / 2, 5 * std::sin(beta + std::acos(4.7 / 5)), 1e-9);
  EXPECT_NEAR(*e.d_max / 2, 4.530, 5e-4);
  EXPECT_NEAR(*e.d_max, 9.059, 5e-4);
  EXPECT_NEAR(cutting_speed(*e.d_max / 2, 3820), 54.36, 0.02);  // the paper's "vc max" from r
}

TEST(BallEngagement, PaperTrendsUpSlopeBeatsDownSlopeAndDepthWidens) {
  for (const double beta_deg : {10.0, 25.0, 45.0}) {
    const double beta = deg(beta_deg);
    const Eigen::Vector3d n = tilted_normal(beta);
    const auto up = evaluate_engagement(Tool::ball(10), setup(0.3, 0.5, n, uphill(beta)));
    const auto down = evaluate_engagement(Tool::ball(10), setup(0.3, 0.5, n, -uphill(beta)));
    EXPECT_GT(*up.d_max, *down.d_max) << beta_deg;
    double previous = 0;
    for (const double depth : {0.1, 0.2, 0.3, 0.5, 1.0}) {
      const auto e = evaluate_engagement(Tool::ball(10), setup(depth, 0.5, n, uphill(beta)));
      EXPECT_GT(*e.d_max, previous) << beta_deg << " " << depth;
      previous = *e.d_max;
    }
  }
}

TEST(BallEngagement, PaperFigure8RangeOfTheTangentPointsOverFeedAngles) {
  // D = 10, tilt 25, azimuth 35, ap = 1: r at points 1 and 2 spans
  // R sin(acos(0.8) - 25 deg) = 1.028 .. R sin(25 deg + acos(0.8)) = 4.410.
  const Eigen::Vector3d n = normal_from_angles(deg(25), deg(35));
  double lo = INFINITY, hi = -INFINITY;
  for (int step = 0; step < 3600; ++step) {
    const auto e =
        evaluate_engagement(Tool::ball(10), setup(1, 0.5, n, feed_from_angle(deg(step * 0.1), n)));
    for (const auto* p : {&e.points->p1, &e.points->p2}) {
      lo = std::min(lo, p->diameter / 2);
      hi = std::max(hi, p->diameter / 2);
    }
  }
  EXPECT_NEAR(lo, 5 * std::sin(std::acos(0.8) - deg(25)), 1e-4);
  EXPECT_NEAR(hi, 5 * std::sin(deg(25) + std::acos(0.8)), 1e-4);
  EXPECT_NEAR(lo, 1.03, 0.005);
  EXPECT_NEAR(hi, 4.41, 0.005);
}

TEST(BallEngagement, MeanDiameterOfAHalfCapInClosedForm) {
  // Level surface, stepover wider than the groove: the engaged zone is the
  // leading half of the cap, polar angle alpha <= a0 = acos((R - ap) / R);
  // mean r = R (a0/2 - sin(2 a0)/4) / (1 - cos a0).
  for (const double ap : {0.1, 0.3, 1.0, 2.5}) {
    const double R = 5, a0 = std::acos((R - ap) / R);
    const double expected = 2 * R * (a0 / 2 - std::sin(2 * a0) / 4) / (1 - std::cos(a0));
    const auto mean =
        engaged_mean_diameter(Tool::ball(10), setup(ap, 20, {0, 0, 1}, {0.6, 0.8, 0}));
    ASSERT_TRUE(mean);
    EXPECT_NEAR(*mean, expected, 1e-6) << ap;
  }
}

TEST(BallEngagement, DegenerateInputIsFlaggedNotThrown) {
  const Tool ball = Tool::ball(10);
  const auto flags = [&](CutSetup s) { return evaluate_engagement(ball, s).flags; };
  EXPECT_TRUE(flags(setup(0.3, 0, {0, 0, 1}, {1, 0, 0})).has(EngagementFlag::zero_ae));
  EXPECT_TRUE(flags(setup(0.3, 0, {0, 0, 1}, {1, 0, 0})).has(EngagementFlag::nothing_engaged));
  EXPECT_TRUE(flags(setup(0, 0.5, {0, 0, 1}, {1, 0, 0})).has(EngagementFlag::zero_ap));
  EXPECT_TRUE(flags(setup(10, 0.5, {0, 0, 1}, {1, 0, 0})).has(EngagementFlag::ap_exceeds_d));
  EXPECT_TRUE(flags(setup(0.3, 0.5, {1, 0, 0}, {0, 1, 0})).has(EngagementFlag::undercut));
  EXPECT_TRUE(flags(setup(0.3, 0.5, {0, 0.3, -1}, {0, 1, 0})).has(EngagementFlag::undercut));
  EXPECT_TRUE(flags(setup(0.3, 0.5, {0, 0, 1}, {0, 0, 2})).has(EngagementFlag::feed_along_normal));
  const auto zero_ae = evaluate_engagement(ball, setup(0.3, 0, {0, 0, 1}, {1, 0, 0}));
  EXPECT_FALSE(zero_ae.d_max);
  EXPECT_TRUE(zero_ae.points);  // the rim and its points exist without a previous pass
  EXPECT_FALSE(engaged_mean_diameter(ball, setup(0.3, 0, {0, 0, 1}, {1, 0, 0})));
}

TEST(BallEngagement, SteepWallEngagesTheShankUnlessThePreviousShankTookTheStock) {
  // Contour pass on an 80 deg wall, previous pass above (left): sin(beta) >=
  // 1 - ap/R puts stock above the equator. With ae = 3 the shank cuts (D_max
  // = D); with ae = 1 the previous pass's shank already swept that stock.
  const double beta = deg(80);
  const auto wide =
      evaluate_engagement(Tool::ball(10), setup(1, 3, tilted_normal(beta), {0, 1, 0}));
  EXPECT_TRUE(wide.flags.has(EngagementFlag::shank_engaged));
  EXPECT_DOUBLE_EQ(*wide.d_max, 10);
  const auto narrow =
      evaluate_engagement(Tool::ball(10), setup(1, 1, tilted_normal(beta), {0, 1, 0}));
  EXPECT_FALSE(narrow.flags.has(EngagementFlag::shank_engaged));
  EXPECT_LT(*narrow.d_max, 10);
  const auto sampled = testing::sample_ball(10, 1, 1, tilted_normal(beta), {0, 1, 0}, true, 600);
  EXPECT_FALSE(sampled.shank);
  EXPECT_NEAR(*narrow.d_max, sampled.d_max, 6 * sampled.spacing);
}

// Every cutting point lies on the rim (the tool surface in the stock plane)
// at the lateral position its definition gives, 1' ahead of 1''.
TEST(BallEngagement, CuttingPointsLieOnTheRimWhereTheirDefinitionsPutThem) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < 2000; ++i) {
    const double R = 5, ap = R * (0.02 + 0.9 * unit(rng)), ae = R * 1.5 * unit(rng);
    const Eigen::Vector3d n = normal_from_angles(deg(85) * unit(rng), 2 * pi * unit(rng));
    const Eigen::Vector3d f = feed_from_angle(2 * pi * unit(rng), n);
    const auto e = evaluate_engagement(Tool::ball(2 * R), setup(ap, ae, n, f));
    ASSERT_TRUE(e.points);
    const Eigen::Vector3d s0 = n.cross(e.feed_dir);
    auto on_rim = [&](const CuttingPoint& p) {
      const Eigen::Vector3d x = p.position;
      const double surface = x.z() <= 0 ? x.norm() - R : x.head<2>().norm() - R;
      return std::abs(n.dot(x) + (R - ap)) < 1e-9 && std::abs(surface) < 1e-9 &&
             std::abs(p.diameter - 2 * x.head<2>().norm()) < 1e-12;
    };
    const auto& p = *e.points;
    for (const auto* point : {&p.p1, &p.p2, &p.p1a, &p.p1b, &p.p2a, &p.p2b}) {
      EXPECT_TRUE(on_rim(*point)) << i << " " << point->position.transpose();
    }
    const double s1 = s0.dot(p.p1.position), s2 = s0.dot(p.p2.position);
    EXPECT_LE(s1, s2);
    if (s1 + ae < s2) {
      EXPECT_NEAR(s0.dot(p.p1a.position), s1 + ae, 1e-9);
      EXPECT_NEAR(s0.dot(p.p1b.position), s1 + ae, 1e-9);
      EXPECT_NEAR(s0.dot(p.p2a.position), s2 - ae, 1e-9);
      EXPECT_GE(e.feed_dir.dot(p.p1a.position), e.feed_dir.dot(p.p1b.position));
      EXPECT_GE(e.feed_dir.dot(p.p2a.position), e.feed_dir.dot(p.p2b.position));
    }
  }
}

TEST(MillingMode, ClockwiseSpindleWithPreviousPassOnTheLeftIsClimb) {
  EXPECT_EQ(milling_mode(Side::left, SpindleDirection::clockwise), MillingMode::down);
  EXPECT_EQ(milling_mode(Side::right, SpindleDirection::clockwise), MillingMode::up);
  EXPECT_EQ(milling_mode(Side::left, SpindleDirection::counter_clockwise), MillingMode::up);
  EXPECT_EQ(milling_mode(Side::right, SpindleDirection::counter_clockwise), MillingMode::down);
}

TEST(BallEngagement, AgreesWithBruteForceOnRandomSetups) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> unit(0, 1);
  int compared = 0;
  for (int i = 0; i < 300; ++i) {
    const double d = 2 + 18 * unit(rng), R = d / 2;
    // ap up to 1.7 R: the rim above the ball centre exercises the upper branches.
    const double ap = R * (0.02 + 1.7 * unit(rng)), ae = R * (0.02 + 1.2 * unit(rng));
    const Eigen::Vector3d n = normal_from_angles(deg(80) * unit(rng), 2 * pi * unit(rng));
    const Eigen::Vector3d f = feed_from_angle(2 * pi * unit(rng), n);
    const bool left = unit(rng) < 0.5;
    const CutSetup s = setup(ap, ae, n, f, left ? Side::left : Side::right);
    const auto exact = evaluate_engagement(Tool::ball(d), s);
    const auto sampled = testing::sample_ball(d, ap, ae, n, f, left, 300);
    SCOPED_TRACE(::testing::Message()
                 << "case " << i << " d=" << d << " ap=" << ap << " ae=" << ae
                 << " n=" << n.transpose() << " f=" << f.transpose() << " left=" << left);
    ASSERT_TRUE(exact.d_max);
    ASSERT_TRUE(sampled.any);
    // Every sampled engaged point lies within the exact range...
    EXPECT_LE(sampled.d_max, *exact.d_max + 1e-9);
    EXPECT_GE(sampled.d_min, *exact.d_min - 1e-9);
    // ...and the range is reached within a few grid spacings (2r is 2-Lipschitz).
    const double tolerance = 2 * 3 * sampled.spacing;
    EXPECT_NEAR(sampled.d_max, *exact.d_max, tolerance);
    EXPECT_NEAR(sampled.d_min, *exact.d_min, tolerance);
    if (sampled.shank) {
      EXPECT_TRUE(exact.flags.has(EngagementFlag::shank_engaged));
    }
    const auto mean = engaged_mean_diameter(Tool::ball(d), s);
    ASSERT_TRUE(mean);
    EXPECT_NEAR(*mean, sampled.d_mean, 0.01 * d);
    EXPECT_LT((exact.points->p1.position - sampled.p1).norm(), 1e-3 * d);
    EXPECT_LT((exact.points->p2.position - sampled.p2).norm(), 1e-3 * d);
    ++compared;
  }
  EXPECT_EQ(compared, 300);
}

}  // namespace
}  // namespace vcpost::geometry
