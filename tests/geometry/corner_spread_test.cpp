// The spread of a hierarchy node's corners merged from its children's:
// figures worked out by hand, and agreement with the direct two-pass spread
// far from the origin (where sums of squares would cancel).
#include "geometry/mesh/corner_spread.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace vcpost::mesh {
namespace {

CornerSpread direct(const std::vector<Eigen::Vector3d>& points, std::size_t begin,
                    std::size_t end) {
  std::vector<double> x, y, z;
  for (std::size_t i = begin; i < end; ++i) {
    x.push_back(points[i].x());
    y.push_back(points[i].y());
    z.push_back(points[i].z());
  }
  return spread_of(x.data(), y.data(), z.data(), x.size());
}

TEST(CornerSpread, TwoSetsMergedByHand) {
  // {(0,0,0), (2,0,0)} and {(4,4,0)}: mean (2, 4/3, 0); about it x spreads
  // 0, 2, 4 -> 4 + 0 + 4 = 8, y 0, 0, 4 -> 2 (4/3)^2 + (8/3)^2 = 32/3,
  // xy (-2)(-4/3) + 0 + 2 (8/3) = 8.
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {2, 0, 0}, {4, 4, 0}};
  const CornerSpread s = merged(direct(points, 0, 2), direct(points, 2, 3));
  EXPECT_EQ(s.count, 3);
  EXPECT_NEAR(s.mean.x(), 2, 1e-15);
  EXPECT_NEAR(s.mean.y(), 4.0 / 3, 1e-15);
  EXPECT_EQ(s.mean.z(), 0);
  EXPECT_NEAR(s.scatter(0, 0), 8, 1e-14);
  EXPECT_NEAR(s.scatter(1, 1), 32.0 / 3, 1e-14);
  EXPECT_NEAR(s.scatter(0, 1), 8, 1e-14);
  EXPECT_NEAR(s.scatter(1, 0), 8, 1e-14);
  EXPECT_EQ(s.scatter(2, 2), 0);
  EXPECT_EQ(s.lo, Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(s.hi, Eigen::Vector3d(4, 4, 0));
  // An empty side changes nothing.
  const CornerSpread same = merged(CornerSpread{}, s);
  EXPECT_EQ(same.count, 3);
  EXPECT_EQ(same.scatter, s.scatter);
}

TEST(CornerSpread, MergedAsAHierarchyAgreesWithTheDirectSpreadFarFromTheOrigin) {
  // 3,000 corners of a 0.5 mm patch 10 m from the origin, merged pairwise
  // as the hierarchy merges its nodes (halves of halves, down to 6).
  std::mt19937_64 random(7);  // NOLINT(cert-msc32-c,cert-msc51-cpp): the same points each run
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 3000; ++i)
    points.emplace_back(1e4 + u(random), -1e4 + u(random), 5e3 + 0.01 * u(random));
  const auto tree = [&](const auto& self, std::size_t begin, std::size_t end) -> CornerSpread {
    if (end - begin <= 6) return direct(points, begin, end);
    const std::size_t mid = begin + (end - begin) / 2;
    return merged(self(self, begin, mid), self(self, mid, end));
  };
  const CornerSpread m = tree(tree, 0, points.size());
  const CornerSpread d = direct(points, 0, points.size());
  EXPECT_EQ(m.count, 3000);
  // Both means round: the direct sum of 3,000 coordinates of ~1.7e4 by up
  // to ~3000 ulps of 1.7e4 (~1e-8), divided by 3,000; 1e-10 is ~30 ulps.
  EXPECT_NEAR((m.mean - d.mean).norm(), 0, 1e-10);
  // The scatter's entries are ~60 (x, y) and ~6e-3 (z): agreement to ~1e-12
  // of the largest, and the thin direction's own to 1e-9 relative.
  EXPECT_NEAR((m.scatter - d.scatter).cwiseAbs().maxCoeff(), 0, 1e-10);
  EXPECT_NEAR(m.scatter(2, 2) / d.scatter(2, 2), 1, 1e-9);
  EXPECT_EQ(m.lo, d.lo);
  EXPECT_EQ(m.hi, d.hi);
}

}  // namespace
}  // namespace vcpost::mesh
