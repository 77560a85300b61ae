// The swept cutters' exact lowest points against an independent brute
// force: every cell of a grid over the move against the minimum over dense
// positions of the tool along the move (each position's lowest point over
// the cell from the tool's own shape), for ball, bull-nose, flat and drill
// on level, diagonal, sloped, steep and vertical moves. And cut_path, with
// its bands, joint wedges, caps, pruning and tiles, against cut() move by
// move on random polylines.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "geometry/stock/height_field.h"

namespace vcpost::geometry::stock {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr std::size_t kGigabyte = std::size_t{1} << 30;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct NamedCutter {
  const char* name;
  Cutter cutter;
};

std::vector<NamedCutter> cutters() {
  return {{"ball D10", Cutter{Tool::ball(10)}},
          {"bull D12 rc2", Cutter{Tool::bull_nose(12, 2)}},
          {"bull D16 rc0.8", Cutter{Tool::bull_nose(16, 0.8)}},
          {"flat D8", Cutter{Tool::flat(8)}},
          {"drill D10 118", Cutter::drill(10, 118)}};
}

// The tool's underside at radial distance r from its axis, above its tip;
// infinite beyond the radius.
double underside(const Cutter& cutter, double r) {
  const double radius = cutter.tool.diameter / 2;
  if (r > radius) return kInf;
  if (cutter.point_angle_deg > 0)
    return r / std::tan(cutter.point_angle_deg * std::numbers::pi / 360);
  const double rc = cutter.tool.corner_radius;
  const double flat = radius - rc;
  if (r <= flat) return 0;
  return rc - std::sqrt(std::max(0.0, rc * rc - (r - flat) * (r - flat)));
}

double tool_over(const Cutter& cutter, const Vector3d& tip, const Vector2d& q) {
  return tip.z() + underside(cutter, (q - tip.head<2>()).norm());
}

// The lowest tool point over q among 1001 positions along the move, then
// 1001 more around the best (the lowest point is a convex function of the
// travel, so the true minimum lies within one step of the best sample).
double brute_force(const Cutter& cutter, const Vector3d& a, const Vector3d& b, const Vector2d& q) {
  constexpr int kSamples = 1000;
  double best = kInf, best_t = 0;
  for (int k = 0; k <= kSamples; ++k) {
    const double t = static_cast<double>(k) / kSamples;
    const double z = tool_over(cutter, a + t * (b - a), q);
    if (z < best) best = z, best_t = t;
  }
  for (int k = 0; k <= kSamples; ++k) {
    const double t = std::clamp(best_t + (2.0 * k / kSamples - 1) / kSamples, 0.0, 1.0);
    best = std::min(best, tool_over(cutter, a + t * (b - a), q));
  }
  return best;
}

double distance_to_segment(const Vector2d& q, const Vector2d& a, const Vector2d& b) {
  const Vector2d d = b - a;
  const double t =
      d.squaredNorm() == 0 ? 0 : std::clamp((q - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (q - a - t * d).norm();
}

struct Move {
  const char* name;
  Vector3d a, b;
};

std::vector<Move> moves() {
  return {{"level along x", {10.13, 15.07, 0}, {29.9, 15.07, 0}},
          {"level diagonal", {10.3, 8.2, 1}, {27.1, 21.7, 1}},
          {"level along y (by columns)", {20.1, 8.2, 0}, {20.1, 21.9, 0}},
          {"sloped along y (by columns)", {19.3, 21.1, 3}, {20.2, 8.3, 0}},
          {"sloped up", {10.3, 12.2, 0}, {28.1, 18.7, 3.3}},
          {"sloped down", {28.1, 18.7, 3.3}, {10.3, 12.2, 0}},
          {"steep up", {18.2, 14.9, 0}, {21.5, 16.1, 9.6}},
          {"steep down", {21.5, 16.1, 9.6}, {18.2, 14.9, 0}},
          {"plunge", {20.05, 15.02, 8}, {20.05, 15.02, -1}},
          {"short sloped", {20.11, 15.23, 2}, {20.53, 15.01, 1.8}}};
}

// Within 1e-4 mm of the brute force (its sampling error is below 5e-5 mm
// on these moves), and never above it by more than the float tops' rounding.
TEST(StockEnvelope, EachCutterOnEachMoveAgreesWithBruteForce) {
  constexpr double kTop = 50;
  for (const NamedCutter& c : cutters()) {
    const double radius = c.cutter.tool.diameter / 2;
    for (const Move& m : moves()) {
      HeightField field = HeightField::block({0, 0, -20}, {40, 30, kTop}, 0.4, kGigabyte);
      field.cut(c.cutter, m.a, m.b);
      const Grid& g = field.grid();
      int reached = 0, worst_ix = 0, worst_iy = 0;
      double worst = 0;
      for (std::uint32_t iy = 0; iy < g.ny; ++iy) {
        for (std::uint32_t ix = 0; ix < g.nx; ++ix) {
          const Vector2d q = g.min + Vector2d(ix + 0.5, iy + 0.5) * g.cell_mm;
          const double top = field.top(ix, iy);
          const double distance = distance_to_segment(q, m.a.head<2>(), m.b.head<2>());
          if (distance > radius + 1e-9) {
            ASSERT_EQ(top, kTop) << c.name << ", " << m.name << " cut beyond its reach at "
                                 << q.transpose();
            continue;
          }
          const double expected = std::min(kTop, brute_force(c.cutter, m.a, m.b, q));
          if (expected == kInf) {
            // Only the rim's last micrometre can escape the samples.
            ASSERT_GT(distance, radius - 1e-3) << c.name << ", " << m.name;
            continue;
          }
          ++reached;
          ASSERT_LE(top, expected + 1e-5) << c.name << ", " << m.name << " at " << q.transpose();
          if (expected - top > worst) worst = expected - top, worst_ix = ix, worst_iy = iy;
        }
      }
      EXPECT_LT(worst, 1e-4) << c.name << ", " << m.name << " at cell " << worst_ix << " "
                             << worst_iy;
      EXPECT_GT(reached, 100) << c.name << ", " << m.name;
    }
  }
}

// A random walk of short moves: level ones turning a little, sharp turns
// and reversals, slopes, plunges, repeated points, steep moves, slopes too
// small to count, and moves in the air above the block (pruned), over a
// grid of 2 x 2 tiles (of 256 x 256 cells).
std::vector<Vector3d> random_walk(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Vector3d> tips{{20.03, 14.97, 0}};
  double heading = 0.3;
  for (int i = 0; i < count; ++i) {
    Vector3d p = tips.back();
    const double kind = unit(rng);
    double step = 0.3 + 0.7 * unit(rng), dz = 0;
    if (kind < 0.5) {
      heading += 0.6 * (unit(rng) - 0.5);
    } else if (kind < 0.6) {
      heading += std::numbers::pi * (2 * unit(rng) - 1);
    } else if (kind < 0.7) {
      dz = 0.6 * (unit(rng) - 0.5);
    } else if (kind < 0.75) {
      step = 0, dz = 4 * (unit(rng) - 0.5);
    } else if (kind < 0.8) {
      step = 0;
    } else if (kind < 0.85) {
      step = 0.05, dz = 2 * (unit(rng) - 0.5);
    } else if (kind < 0.9) {
      dz = 1e-9;
    } else {
      heading += 0.3 * (unit(rng) - 0.5), dz = 0.5 * (unit(rng) - 0.5);
    }
    p += Vector3d(step * std::cos(heading), step * std::sin(heading), dz);
    if (p.x() < 6 || p.x() > 34 || p.y() < 6 || p.y() > 28) {
      heading += std::numbers::pi;
      p = tips.back();
    }
    p.z() = std::clamp(p.z(), -3.0, 3.0);
    tips.push_back(p);
  }
  return tips;
}

TEST(StockEnvelope, CutPathEqualsCutMoveByMove) {
  std::mt19937 rng(44);
  for (const NamedCutter& c : cutters()) {
    for (int trial = 0; trial < 2; ++trial) {
      const std::vector<Vector3d> tips = random_walk(rng, 250);
      HeightField path = HeightField::block({0, 0, -20}, {40, 30, 1}, 0.1, kGigabyte);
      HeightField reference = path;
      path.cut_path(c.cutter, tips);
      for (std::size_t i = 0; i + 1 < tips.size(); ++i)
        reference.cut(c.cutter, tips[i], tips[i + 1]);
      const Grid& g = path.grid();
      ASSERT_GT(g.nx, 256u);  // more than one tile each way
      ASSERT_GT(g.ny, 256u);
      int lowered = 0;
      for (std::uint32_t iy = 0; iy < g.ny; ++iy) {
        for (std::uint32_t ix = 0; ix < g.nx; ++ix) {
          ASSERT_NEAR(path.top(ix, iy), reference.top(ix, iy), 1e-5)
              << c.name << " trial " << trial << " at cell " << ix << " " << iy;
          lowered += reference.top(ix, iy) < 1;
        }
      }
      EXPECT_GT(lowered, 8000) << c.name;
    }
  }
}

TEST(StockEnvelope, OnePointPathIsTheCutterStandingThere) {
  HeightField path = HeightField::block({0, 0, -20}, {40, 30, 1}, 0.2, kGigabyte);
  HeightField reference = path;
  const Vector3d p(20.01, 15.03, -2);
  const std::vector<Vector3d> tips{p, p};
  path.cut_path(Cutter{Tool::ball(10)}, tips);
  reference.cut(Cutter{Tool::ball(10)}, p, p);
  // The cell holding p has its centre at (20.1, 15.1): the ball 0.114 mm off its axis.
  const double r2 = 0.09 * 0.09 + 0.07 * 0.07;
  EXPECT_NEAR(path.top_at(20.01, 15.03), -2 + 5 - std::sqrt(25 - r2), 1e-5);
  for (std::uint32_t iy = 0; iy < path.grid().ny; ++iy) {
    for (std::uint32_t ix = 0; ix < path.grid().nx; ++ix) {
      ASSERT_EQ(path.top(ix, iy), reference.top(ix, iy));
    }
  }
}

}  // namespace
}  // namespace vcpost::geometry::stock
