#include "geometry/small_angle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace vcpost::geometry {
namespace {

// The series against long double's cosl and sinl, on half a million angles
// in [-0.5, 0.5], a third of them below 1e-3 (the late Newton steps): cos
// within an ulp of 1 (1.1e-16; 8.4e-17 seen), sin within an ulp of itself
// (2.2e-16 relative; 1.2e-16 seen).
TEST(SmallAngle, SeriesWithinAnUlpOfTheTruth) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> angle(-0.5, 0.5);
  double worst_cos = 0, worst_sin = 0;
  for (int i = 0; i < 500000; ++i) {
    const double x = i % 3 == 0 ? 1e-3 * angle(random) : angle(random);
    const auto [c, s] = cos_sin_small(x);
    const long double true_cos = cosl(x), true_sin = sinl(x);
    worst_cos = std::max(worst_cos, static_cast<double>(fabsl(c - true_cos)));
    if (x != 0)
      worst_sin = std::max(worst_sin, static_cast<double>(fabsl((s - true_sin) / true_sin)));
  }
  EXPECT_LE(worst_cos, 1.12e-16);
  EXPECT_LE(worst_sin, 2.23e-16);
}

// atan2_small against long double's atan2l on half a million turns with
// |y| <= 0.1 x, a third of them below 1e-5, within an ulp of the angle
// (2.2e-16 relative), and libm's own answer elsewhere.
TEST(SmallAngle, ArcTangentOfSmallTurns) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> ratio(-0.1, 0.1), length(0.01, 100);
  double worst = 0;
  for (int i = 0; i < 500000; ++i) {
    const double x = length(random), y = (i % 3 == 0 ? 1e-4 : 1.0) * ratio(random) * x;
    const long double truth = atan2l(y, x);
    if (y != 0)
      worst = std::max(worst, static_cast<double>(fabsl((atan2_small(y, x) - truth) / truth)));
  }
  EXPECT_LE(worst, 2.23e-16);
  for (const auto& [y, x] : {std::pair{1.0, 2.0}, {0.5, -1.0}, {-3.0, 0.0}, {0.0, -1.0}})
    EXPECT_EQ(atan2_small(y, x), std::atan2(y, x));
}

// Beyond half a radian libm's values; at 0 exactly 1 and 0.
TEST(SmallAngle, LibmBeyondHalfARadianAndExactAtZero) {
  for (const double x : {0.6, -2.0, 10.0}) {
    const auto [c, s] = cos_sin_small(x);
    EXPECT_EQ(c, std::cos(x));
    EXPECT_EQ(s, std::sin(x));
  }
  const auto [c, s] = cos_sin_small(0.0);
  EXPECT_EQ(c, 1.0);
  EXPECT_EQ(s, 0.0);
}

// Turning (cos a, sin a) by x gives (cos(a + x), sin(a + x)) within 4
// ulps of 1 (4.5e-16): the given pair's rounding, the series' and that of
// the products and their sum (3.3e-16 seen).
TEST(SmallAngle, RotatedIsTheAngleSum) {
  std::mt19937 random(6);
  std::uniform_real_distribution<double> angle(-3.0, 3.0), step(-0.5, 0.5);
  for (int i = 0; i < 10000; ++i) {
    const double a = angle(random), x = step(random);
    const auto [c, s] = rotated(std::cos(a), std::sin(a), x);
    EXPECT_NEAR(c, std::cos(a + x), 4.5e-16);
    EXPECT_NEAR(s, std::sin(a + x), 4.5e-16);
  }
}

}  // namespace
}  // namespace vcpost::geometry
