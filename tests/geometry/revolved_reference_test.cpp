// The bull-nose and flat engine's D_max and D_min against the reference of
// revolved_reference_support.h on random set-ups: the random cases of
// revolved_cases.h and the finishing cases of
// bench/revolved_engagement_bench.cpp (same generators, same seeds).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>

#include "geometry/engagement.h"
#include "geometry/revolved_engagement.h"
#include "revolved_cases.h"
#include "revolved_reference_support.h"

namespace vcpost::geometry {
namespace {

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

// revolved_engagement_bench.cpp's finishing cases: D = 10, bull-nose rc = 2.
RandomCase finishing_case(std::mt19937& random, bool flat) {
  std::uniform_real_distribution<double> unit(0, 1);
  RandomCase c;
  c.diameter = 10;
  c.corner = flat ? 0 : 2;
  c.normal = normal_from_angles(60 * kPi / 180 * unit(random), 2 * kPi * unit(random));
  c.ap = 0.1 + 0.4 * unit(random);
  c.ae = 0.2 + 0.8 * unit(random);
  c.feed = feed_from_angle(2 * kPi * unit(random), c.normal);
  c.side = unit(random) < 0.5 ? Side::left : Side::right;
  return c;
}

// A random case whose feed is nearly parallel to the flat face: F_z =
// +-10^-k, k = 2..11, the face seen almost edge-on (a floor's normal from a
// model is rarely exactly vertical). The engine takes |F_z| <= 1e-12 as
// edge-on (the face leads), the reference only F_z = 0: the two part there.
RandomCase nearly_level_feed_case(std::mt19937& random, bool flat) {
  std::uniform_real_distribution<double> unit(0, 1);
  RandomCase c = random_case(random, flat);
  c.normal = normal_from_angles(30 * kPi / 180 * unit(random), 2 * kPi * unit(random));
  const Vector3d level = c.normal.cross(Vector3d::UnitZ()).normalized();  // F_z = 0
  const Vector3d slope = c.normal.cross(level);                           // unit, in the plane
  const double f_z =
      std::pow(10.0, -2 - std::floor(10 * unit(random))) * (unit(random) < 0.5 ? -1 : 1);
  const double angle = std::asin(std::clamp(f_z / slope.z(), -1.0, 1.0));
  c.feed =
      std::cos(angle) * (unit(random) < 0.5 ? level : Vector3d(-level)) + std::sin(angle) * slope;
  return c;
}

std::string describe(const RandomCase& c) {
  char text[400];
  std::snprintf(text, sizeof text,
                "D %.17g rc %.17g ap %.17g ae %.17g N (%.17g, %.17g, %.17g) F (%.17g, %.17g, "
                "%.17g) %s",
                c.diameter, c.corner, c.ap, c.ae, c.normal.x(), c.normal.y(), c.normal.z(),
                c.feed.x(), c.feed.y(), c.feed.z(), c.side == Side::left ? "left" : "right");
  return text;
}

struct Agreement {
  int cases = 0, over = 0;  // over: cases off by more than the tolerance
  int refined = 0;          // first reference missed, the finer one agrees
  double worst_max = 0, worst_min = 0;
};

// Engine vs reference on `count` cases of one generator; reports the cases
// off by more than `tolerance` (mm) in D_max or D_min.
template <class Generator>
Agreement compare(const Generator& generate, int count, unsigned seed, double tolerance,
                  testing::ReferenceResolution resolution, bool print) {
  std::mt19937 random(seed);
  Agreement out;
  for (int i = 0; i < count; ++i) {
    const RandomCase c = generate(random, i % 3 == 0);
    const Tool tool = tool_of(c);
    const CutSetup s = setup_of(c);
    const Engagement e = evaluate_revolved_engagement(tool, s);
    const auto reference = [&](testing::ReferenceResolution at) {
      return testing::reference_extremes(c.diameter, c.corner, c.ap, c.ae, c.normal, c.feed,
                                         c.side == Side::left, at);
    };
    const auto differs = [&](const testing::ReferenceExtremes& r) {
      return e.d_max.has_value() != r.any ||
             (r.any && (std::abs(*e.d_max - r.d_max) > tolerance ||
                        std::abs(*e.d_min - r.d_min) > tolerance ||
                        e.flags.has(EngagementFlag::shank_engaged) != r.shank));
    };
    testing::ReferenceExtremes ref = reference(resolution);
    // A sliver finer than the reference's grid can escape it: a
    // disagreement is decided by a reference 4 and 8 times finer.
    if (differs(ref)) {
      const testing::ReferenceExtremes fine = reference({200, 1024});
      if (!differs(fine)) ++out.refined;
      if (print) {
        std::printf("case %d %s: engine %.12f %.12f reference %.12f %.12f, finer %.12f %.12f\n", i,
                    describe(c).c_str(), e.d_max.value_or(-1), e.d_min.value_or(-1), ref.d_max,
                    ref.d_min, fine.d_max, fine.d_min);
      }
      ref = fine;
    }
    ++out.cases;
    EXPECT_EQ(e.d_max.has_value(), ref.any) << i << " " << describe(c);
    if (!e.d_max || !ref.any) continue;
    const double dmax = std::abs(*e.d_max - ref.d_max), dmin = std::abs(*e.d_min - ref.d_min);
    out.worst_max = std::max(out.worst_max, dmax);
    out.worst_min = std::max(out.worst_min, dmin);
    if (dmax > tolerance || dmin > tolerance) ++out.over;
    EXPECT_EQ(e.flags.has(EngagementFlag::shank_engaged), ref.shank) << i << " " << describe(c);
  }
  return out;
}

void report(const char* name, const Agreement& a) {
  std::printf(
      "%s: %d cases, max |dD_max| %.2e mm, max |dD_min| %.2e mm, %d over tolerance (%d decided "
      "by the finer reference)\n",
      name, a.cases, a.worst_max, a.worst_min, a.over, a.refined);
}

// The engine within 1e-6 mm of the reference on D_max and D_min, on
// `count` cases of each generator (random, finishing, nearly level feed)
// drawn with its seed.
struct Draw {
  int count;
  unsigned seed;
};
void expect_agreement(Draw random, Draw finishing, Draw level,
                      testing::ReferenceResolution resolution) {
  constexpr double kTolerance = 1e-6;  // mm
  const std::pair<const char*, Agreement> runs[] = {
      {"random", compare(random_case, random.count, random.seed, kTolerance, resolution, true)},
      {"finishing",
       compare(finishing_case, finishing.count, finishing.seed, kTolerance, resolution, true)},
      {"nearly level feed",
       compare(nearly_level_feed_case, level.count, level.seed, kTolerance, resolution, true)}};
  for (const auto& [name, agreement] : runs) {
    report(name, agreement);
    EXPECT_EQ(agreement.over, 0) << name;
  }
}

// The reference itself: with rc = R it describes the ball mill, whose
// engine is closed form (ball_engagement.cpp); the two agree to 1e-9 mm.
TEST(RevolvedReference, ReferenceMatchesTheBallClosedForm) {
  std::mt19937 random(19);
  double worst = 0;
  for (int i = 0; i < 60; ++i) {
    const RandomCase c = random_case(random, false);
    const CutSetup s = setup_of(c);
    const Engagement ball = evaluate_engagement(Tool::ball(c.diameter), s);
    const testing::ReferenceExtremes ref = testing::reference_extremes(
        c.diameter, c.diameter / 2, c.ap, c.ae, c.normal, c.feed, c.side == Side::left, {16, 64});
    ASSERT_EQ(ball.d_max.has_value(), ref.any) << describe(c);
    if (!ref.any) continue;
    EXPECT_NEAR(*ball.d_max, ref.d_max, 1e-9) << describe(c);
    EXPECT_NEAR(*ball.d_min, ref.d_min, 1e-9) << describe(c);
    EXPECT_EQ(ball.flags.has(EngagementFlag::shank_engaged), ref.shank) << describe(c);
    worst = std::max({worst, std::abs(*ball.d_max - ref.d_max), std::abs(*ball.d_min - ref.d_min)});
  }
  std::printf("ball: largest |closed form - reference| %.2e mm\n", worst);
}

// MODELS.md's floor cases: bull-nose rim diameter 2 (R0 + sqrt(ap (2 rc -
// ap))), the face centre engaged (edge-on, in the stock); the flat mill's
// periphery cuts with D.
TEST(RevolvedReference, ReferenceOnTheFloor) {
  const Vector3d up(0, 0, 1), along(1, 0, 0);
  const testing::ReferenceExtremes bull =
      testing::reference_extremes(10, 2, 0.5, 12, up, along, true);
  ASSERT_TRUE(bull.any);
  EXPECT_NEAR(bull.d_max, 2 * (3 + std::sqrt(0.5 * 3.5)), 1e-9);
  EXPECT_NEAR(bull.d_min, 0, 1e-12);
  EXPECT_FALSE(bull.shank);
  const testing::ReferenceExtremes flat =
      testing::reference_extremes(10, 0, 1, 20, up, along, true);
  ASSERT_TRUE(flat.any);
  EXPECT_NEAR(flat.d_max, 10, 1e-12);
  EXPECT_NEAR(flat.d_min, 0, 1e-12);
  EXPECT_TRUE(flat.shank);
}

// The unit suite's check: 300 cases at a coarser reference grid (which
// still finds the extremes to 1e-9 mm on these), the engine within 1e-6 mm
// on D_max and D_min. (Before the corner's fibres stopped counting lines
// 1e-9 R off as touching it, two of these were off by 2.5e-6 and 1.2e-5 mm,
// checked by brute force on the circles of the tool.)
TEST(RevolvedReference, EngineAgreesWithTheReference) {
  expect_agreement({200, 41}, {100, 43}, {100, 47}, {16, 64});
}

// Two set-ups of the long run (seed 1000) that a faster boundary search
// got wrong, D_min off by 1.6e-5 and 1.0e-4 mm: F_z = 1e-11, where c(phi)
// is steep enough that a Newton step of 1e-14 still misses, and F_z =
// 1e-6, where c(phi) jumps across the face and a secant of the bracket's
// ends crawled for 200 steps.
// And one of the finishing run (seed 2), on a nearly level surface (N_z
// = 1 - 3.4e-10) with a nearly level feed (F_z = -1.1e-5): a boundary
// solve that ended on a small Halley step where c' doubles over that step
// put the face's centre in the groove, D_min 0 for 3.559 mm.
TEST(RevolvedReference, NearlyLevelFeedsWhereTheBoundarySearchSlipped) {
  const RandomCase cases[] = {
      {17.707648906840291, 2.7872248082610862, 2.7444811175865524, 7.0025944413845496,
       Vector3d(0.11522363940851117, 0.13465154582781788, 0.98417095777493679),
       Vector3d(0.75979158707903771, -0.65016670493337114, 9.9999999999999994e-12), Side::left},
      {17.97940572934818, 2.9197395128450707, 0.39206320375925069, 8.2366443778392213,
       Vector3d(-0.12659781866645711, -0.48156039815618706, 0.86722118011297988),
       Vector3d(-0.96713762976088735, 0.25425342691789404, 9.9999999999999995e-07), Side::left},
      {10, 2, 0.29968554049518187, 0.50271451649113907,
       Vector3d(3.1749479161495048e-06, -2.5914986275993933e-05, 0.99999999965916664),
       Vector3d(-0.85437318390954842, -0.51965994890948075, -1.0754390087970717e-05), Side::right}};
  for (const RandomCase& c : cases) {
    const Engagement e = evaluate_revolved_engagement(tool_of(c), setup_of(c));
    const testing::ReferenceExtremes ref = testing::reference_extremes(
        c.diameter, c.corner, c.ap, c.ae, c.normal, c.feed, c.side == Side::left);
    ASSERT_TRUE(e.d_max && ref.any) << describe(c);
    EXPECT_NEAR(*e.d_max, ref.d_max, 1e-6) << describe(c);
    EXPECT_NEAR(*e.d_min, ref.d_min, 1e-6) << describe(c);
  }
}

// A finishing set-up where the shifted silhouette's point of least r lies
// on the corner 1.3e-4 mm beyond the face's rim: the face plane's root
// there is within 1e-9 R of the corner too, and taking it for the
// corner's gave D_min 5.3e-8 mm low. The reference at 1, 4 and 16 times
// its resolution: 6.000267626425615 mm.
TEST(RevolvedReference, FacePlaneRootBeyondTheRimIsNotTheCorners) {
  const RandomCase c{10,
                     2,
                     0.11882610663615609,
                     0.25378939283313817,
                     Vector3d(-0.018953614697608572, 0.10924054604250671, 0.99383462587607074),
                     Vector3d(-0.31136794078991203, 0.94393708458448977, -0.10969405541953374),
                     Side::right};
  const Engagement e = evaluate_revolved_engagement(tool_of(c), setup_of(c));
  const testing::ReferenceExtremes ref = testing::reference_extremes(
      c.diameter, c.corner, c.ap, c.ae, c.normal, c.feed, c.side == Side::left);
  ASSERT_TRUE(e.d_max && ref.any);
  EXPECT_NEAR(*e.d_max, ref.d_max, 1e-9);
  EXPECT_NEAR(*e.d_min, ref.d_min, 1e-9);
}

// The long run (VCPOST_REFERENCE_CASES cases of each generator, 10000 by
// default): --gtest_also_run_disabled_tests --gtest_filter='*ManyCases*'.
TEST(RevolvedReference, DISABLED_ManyCases) {
  const char* env = std::getenv("VCPOST_REFERENCE_CASES");
  const int count = env ? std::atoi(env) : 10000;
  const char* seed_env = std::getenv("VCPOST_REFERENCE_SEED");
  const unsigned seed = seed_env ? static_cast<unsigned>(std::atoi(seed_env)) : 1;
  expect_agreement({count, seed}, {count, seed + 1}, {count, seed + 2}, {});
}

}  // namespace
}  // namespace vcpost::geometry
