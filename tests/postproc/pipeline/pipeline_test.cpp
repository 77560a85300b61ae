// Path samples, the neighbouring pass and the per-point evaluation on
// analytic surfaces, where every figure has a closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "geometry/analytic_surfaces.h"
#include "postproc/pipeline/pass_tracker.h"
#include "postproc/pipeline/path_sampler.h"
#include "postproc/pipeline/point_evaluator.h"

namespace vcpost::pipeline {
namespace {

using Eigen::Vector3d;
constexpr double pi = std::numbers::pi;

program::StraightFeed feed_move(Vector3d a, Vector3d b) { return {a, b, {}}; }

TEST(PathSampler, SplitsMovesAndStartsOnlyAfterRapids) {
  PathSampler sampler(0.5);
  std::vector<PathSample> out;
  sampler.add(program::StraightTraverse{{0, 0, 10}, {0, 0, 1}, {}}, 0, out);
  EXPECT_TRUE(out.empty());
  sampler.add(feed_move({0, 0, 1}, {2, 0, 1}), 1, out);  // 4 pieces + its start
  ASSERT_EQ(out.size(), 5u);
  EXPECT_TRUE(out[0].point.isApprox(Vector3d(0, 0, 1)));
  EXPECT_TRUE(out[2].point.isApprox(Vector3d(1, 0, 1)));
  EXPECT_TRUE(out[4].direction.isApprox(Vector3d(1, 0, 0)));
  sampler.add(feed_move({2, 0, 1}, {2, 0.7, 1}), 2, out);  // continues: 2 pieces, no start
  ASSERT_EQ(out.size(), 7u);
  EXPECT_NEAR(out[5].point.y(), 0.35, 1e-15);
  EXPECT_EQ(out[6].move, 2u);
}

TEST(PathSampler, ArcSamplesFollowTheCircleWithTangentDirections) {
  // Quarter circle of radius 10 about the origin, counter-clockwise in XY:
  // length 5 pi = 15.71 -> 16 pieces at 1 mm.
  PathSampler sampler(1.0);
  std::vector<PathSample> out;
  program::ArcFeed arc;
  arc.start = {10, 0, 0};
  arc.end = {0, 10, 0};
  arc.centre = {0, 0, 0};
  arc.rotation = 1;
  sampler.add(arc, 0, out);
  ASSERT_EQ(out.size(), 17u);
  for (const auto& s : out) {
    EXPECT_NEAR(s.point.norm(), 10, 1e-9);
    const Vector3d tangent = Vector3d(-s.point.y(), s.point.x(), 0).normalized();
    EXPECT_NEAR((s.direction - tangent).norm(), 0, 1e-8);
  }
}

// Zig-zag raster on a level plane: passes along x, stepover 0.5 in y.
std::vector<std::pair<Vector3d, Vector3d>> zigzag(int passes, double stepover, double length) {
  std::vector<std::pair<Vector3d, Vector3d>> points;  // (CC, feed)
  for (int k = 0; k < passes; ++k) {
    const double sign = k % 2 == 0 ? 1 : -1;
    for (int i = 0; i <= static_cast<int>(length / 0.5); ++i) {
      const double x = sign > 0 ? 0.5 * i : length - 0.5 * i;
      points.push_back({Vector3d(x, k * stepover, 0), Vector3d(sign, 0, 0)});
    }
  }
  return points;
}

TEST(PassTracker, MeasuresStepoverAndSideOnAZigZagRaster) {
  PassTracker tracker(10, 40, 1000);
  const Vector3d up(0, 0, 1);
  int first_pass_points = 0, measured = 0;
  for (const auto& [cc, feed] : zigzag(4, 0.5, 20)) {
    const auto found = tracker.step(cc, up, feed);
    if (cc.y() == 0) {
      EXPECT_FALSE(found) << cc.transpose();
      ++first_pass_points;
      continue;
    }
    ASSERT_TRUE(found) << cc.transpose();
    EXPECT_NEAR(found->ae, 0.5, 1e-12);
    // The previous pass lies at -y. Along +x, left is +y (N x F): right.
    EXPECT_EQ(found->side, feed.x() > 0 ? geometry::Side::right : geometry::Side::left);
    ++measured;
  }
  EXPECT_EQ(first_pass_points, 41);
  EXPECT_EQ(measured, 3 * 41);
}

// Points of the third of three 41-point passes that find a neighbour, and
// the widths they measure, for a tracker remembering `capacity` points.
std::vector<double> third_pass_widths(std::size_t capacity) {
  PassTracker tracker(10, 40, capacity);
  const Vector3d up(0, 0, 1);
  std::vector<double> widths;
  for (const auto& [cc, feed] : zigzag(3, 0.5, 20)) {
    const auto found = tracker.step(cc, up, feed);
    if (found && cc.y() == 1.0) widths.push_back(found->ae);
  }
  return widths;
}

TEST(PassTracker, MemoryIsBoundedAndOldPassesAreForgotten) {
  // With room for every point the whole third pass finds the second.
  EXPECT_EQ(third_pass_widths(1000).size(), 41U);
  // With 50 (less than one pass + 1) the third pass walks back along the
  // second, whose points it pushes out as it goes: it finds the second
  // pass's last points and loses the rest, and never the first pass (1 mm
  // away), which is gone.
  const std::vector<double> widths = third_pass_widths(50);
  EXPECT_GT(widths.size(), 0U);
  EXPECT_LT(widths.size(), 41U);
  for (const double ae : widths) EXPECT_NEAR(ae, 0.5, 1e-12);
}

geometry::AnalyticModel level_plane() {
  geometry::PlanePatch plane;
  plane.u_min = plane.v_min = -100;
  plane.u_max = plane.v_max = 100;
  return geometry::AnalyticModel({plane});
}

TEST(PointEvaluator, LevelRasterGivesTheRimDiameterAndItsSpindleSpeed) {
  const auto model = level_plane();
  PointSettings settings;
  settings.tool = geometry::Tool::ball(10);
  settings.ap = 0.3;
  settings.vc = 120;
  PointEvaluator evaluator(model, settings);
  // Tip points on the plane z = 0: the ball touches everywhere.
  const double rim = 2 * std::sqrt(0.3 * 9.7);
  for (const auto& [cc, feed] : zigzag(2, 0.5, 10)) {
    const auto r = evaluator.evaluate({cc, feed, 0, 1, {}});
    ASSERT_EQ(r.contact.status, geometry::BallStatus::touching);
    ASSERT_TRUE(r.d_ref && r.target_rpm);
    EXPECT_NEAR(*r.d_ref, rim, 1e-12);  // every rim point of a level cut has r = rho
    EXPECT_NEAR(*r.target_rpm, 120000 / (pi * rim), 1e-6);
    EXPECT_EQ(r.ae_source, cc.y() == 0 ? AeSource::first_pass : AeSource::measured);
    if (cc.y() > 0) {
      EXPECT_NEAR(r.ae, 0.5, 1e-12);
    }
  }
}

TEST(PointEvaluator, GivenAeOverridesAndMissesGiveNoTarget) {
  const auto model = level_plane();
  PointSettings settings;
  settings.ae = 0.8;
  settings.ae_override = true;
  PointEvaluator evaluator(model, settings);
  const auto r = evaluator.evaluate({Vector3d(0, 0, 0), Vector3d(1, 0, 0), 0, 1, {}});
  EXPECT_EQ(r.ae_source, AeSource::given);
  EXPECT_DOUBLE_EQ(r.ae, 0.8);
  const auto lifted = evaluator.evaluate({Vector3d(0, 0, 3), Vector3d(1, 0, 0), 0, 1, {}});
  EXPECT_EQ(lifted.contact.status, geometry::BallStatus::lifted);
  EXPECT_FALSE(lifted.target_rpm);
  // Centre mode: the programmed point is the ball centre, 5 mm up.
  settings.cl_point = geometry::ClPoint::center;
  PointEvaluator centred(model, settings);
  EXPECT_EQ(centred.evaluate({Vector3d(0, 0, 5), Vector3d(1, 0, 0), 0, 1, {}}).contact.status,
            geometry::BallStatus::touching);
}

// The Miko-Beno-Mankova semi-cylinder: radius 100 about the y axis.
geometry::AnalyticModel cusp_height_cylinder() {
  geometry::CylinderPatch cylinder;
  cylinder.axis = {0, 1, 0};
  cylinder.reference = {0, 0, 1};
  cylinder.radius = 100;
  cylinder.h_min = -50;
  cylinder.h_max = 50;
  cylinder.angle_min = -pi / 2;
  cylinder.angle_max = pi / 2;
  return geometry::AnalyticModel({cylinder});
}

TEST(PointEvaluator, MeasuresTheChordAcrossTheFeedOnTheCuspHeightCylinder) {
  // The cusp-height cylinder under a 12 mm ball, passes along the axis (feed angle 0) 0.5 mm apart
  // on the surface: the CC points of neighbouring passes are 2 * 100 * sin(0.0025) apart.
  const geometry::AnalyticModel model = cusp_height_cylinder();
  PointSettings settings;
  settings.tool = geometry::Tool::ball(12);
  settings.ap = 0.2;
  PointEvaluator evaluator(model, settings);
  const double step = 0.5 / 100;
  int measured = 0;
  for (int k = 0; k < 3; ++k) {
    const double angle = k * step;
    const Vector3d outward(std::sin(angle), 0, std::cos(angle));  // reference z, towards +x
    for (int i = 0; i <= 20; ++i) {
      const double y = k % 2 == 0 ? -5 + 0.5 * i : 5 - 0.5 * i;
      const Vector3d tip = Vector3d(0, y, 0) + 106 * outward - Vector3d(0, 0, 6);
      const auto r = evaluator.evaluate({tip, Vector3d(0, k % 2 == 0 ? 1 : -1, 0), 0, 1, {}});
      ASSERT_EQ(r.contact.status, geometry::BallStatus::touching);
      EXPECT_NEAR((r.contact.contact->point - Vector3d(0, y, 0) - 100 * outward).norm(), 0, 1e-9);
      if (k > 0) {
        ASSERT_EQ(r.ae_source, AeSource::measured);
        EXPECT_NEAR(r.ae, 200 * std::sin(step / 2), 1e-9);
        ++measured;
      }
    }
  }
  EXPECT_EQ(measured, 42);
}

// The same cylinder under a bull-nose (D 10, rc 2): its corner's centre
// circle rests at 100 + rc from the axis, so the tool's positions of
// neighbouring passes are a chord of that circle apart, 2 (100 + rc)
// sin(step / 2): the stepover the model's previous pass (this tool moved
// across the feed) needs. The contact points are a chord of radius 100
// apart; on a wavier surface they wander round the rim.
TEST(PointEvaluator, FollowsABullNosesPassesByTheToolsPosition) {
  const geometry::AnalyticModel model = cusp_height_cylinder();
  PointSettings settings;
  settings.tool = geometry::Tool::bull_nose(10, 2);
  settings.ap = 0.2;
  PointEvaluator evaluator(model, settings);
  const double step = 0.5 / 100, rc = 2, r0 = 3;
  int measured = 0;
  for (int k = 0; k < 3; ++k) {
    const double angle = k * step;
    const Vector3d outward(std::sin(angle), 0, std::cos(angle));
    for (int i = 0; i <= 20; ++i) {
      const double y = k % 2 == 0 ? -5 + 0.5 * i : 5 - 0.5 * i;
      // The corner's centre on the side facing the surface sits at 100 + rc
      // along the outward normal; the tip is rc below the corner centres' plane.
      const Vector3d tip = Vector3d(r0, y, -rc) + (100 + rc) * outward;
      const auto r = evaluator.evaluate({tip, Vector3d(0, k % 2 == 0 ? 1 : -1, 0), 0, 1, {}});
      ASSERT_EQ(r.contact.status, geometry::BallStatus::touching) << k << " " << i;
      EXPECT_NEAR((r.contact.contact->point - Vector3d(0, y, 0) - 100 * outward).norm(), 0, 1e-6);
      if (k > 0) {
        ASSERT_EQ(r.ae_source, AeSource::measured);
        EXPECT_NEAR(r.ae, 2 * (100 + rc) * std::sin(step / 2), 1e-9);
        ++measured;
      }
    }
  }
  EXPECT_EQ(measured, 42);
}

// A Z-level ring round a dome (sphere R40, bull-nose D10 rc 2, contact at
// 50 deg from the pole) in 64 straight moves: each chord cuts across the
// level circle by half its turn, 2.8 deg, so its projection onto the
// tangent plane leaves the level by F_z = -0.049 sin(50 deg) sin(40 deg).
// A level move is taken along the tangent plane's level direction: F_z = 0
// exactly and F the ring's tangent at the contact, (-sin, cos, 0) of its
// azimuth. A ramp (Z changing along the move), or a level move 30 deg off
// the level line (beyond 0.1 rad: not following it), keeps the projection.
TEST(PointEvaluator, FeedsALevelMoveLevel) {
  geometry::SpherePatch dome;
  dome.radius = 40;
  dome.max_polar = 1.4;
  dome.material_inside = true;
  const geometry::AnalyticModel model({dome});
  PointSettings settings;
  settings.tool = geometry::Tool::bull_nose(10, 2);
  settings.ap = 0.3;
  PointEvaluator evaluator(model, settings);
  const double polar = 50 * pi / 180, rc = 2, r0 = 3, turn = 2 * pi / 64;
  const auto tip = [&](double azimuth) {
    const Vector3d radial(std::cos(azimuth), std::sin(azimuth), 0);
    return Vector3d(((40 + rc) * std::sin(polar) + r0) * radial +
                    Vector3d(0, 0, (40 + rc) * std::cos(polar) - rc));
  };
  for (int i = 1; i <= 64; ++i) {
    const double azimuth = i * turn;
    const Vector3d chord = (tip(azimuth) - tip(azimuth - turn)).normalized();
    ASSERT_EQ(chord.z(), 0);
    const auto r = evaluator.evaluate({tip(azimuth), chord, 0, 1, {}});
    ASSERT_EQ(r.contact.status, geometry::BallStatus::touching) << i;
    EXPECT_EQ(r.feed.z(), 0) << i;
    EXPECT_NEAR((r.feed - Vector3d(-std::sin(azimuth), std::cos(azimuth), 0)).norm(), 0, 1e-9);
  }
  const double across = turn + pi / 2 + pi / 6;  // 30 deg inwards of the ring's tangent
  for (const Vector3d& move : {Vector3d(-std::sin(turn), std::cos(turn), 0.1).normalized(),
                               Vector3d(std::cos(across), std::sin(across), 0)}) {
    const auto r = evaluator.evaluate({tip(turn), move, 0, 1, {}});
    const Vector3d& n = r.contact.normal;
    EXPECT_NEAR((r.feed - (move - move.dot(n) * n).normalized()).norm(), 0, 1e-12);
  }
}

}  // namespace
}  // namespace vcpost::pipeline
