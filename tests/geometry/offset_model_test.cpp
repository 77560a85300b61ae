// The model offset by an allowance: against the same surfaces offset by
// hand (a sphere of radius r + s, a plane moved by s), the fold where
// 1 + s k <= 0, and the radial and axial allowance of a bull-nose against
// a floor, a wall and a 45 degree slope worked out by hand.
#include "geometry/offset_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/analytic_surfaces.h"
#include "geometry/tool_contact.h"

namespace vcpost::geometry {
namespace {

using Eigen::Vector3d;
constexpr double kTol = 1e-9;

void expect_near(const Vector3d& actual, const Vector3d& expected, double tol) {
  EXPECT_LE((actual - expected).norm(), tol)
      << "actual " << actual.transpose() << "\nexpected " << expected.transpose();
}

std::shared_ptr<const SurfaceModel> model_of(AnalyticSurface surface) {
  return std::make_shared<AnalyticModel>(std::vector<AnalyticSurface>{std::move(surface)});
}

SpherePatch sphere(double radius, bool material_inside) {
  SpherePatch s;
  s.center = {1, 2, -20};
  s.radius = radius;
  s.max_polar = 1.4;
  s.material_inside = material_inside;
  return s;
}

TEST(OffsetModel, SphereOffsetEqualsTheSphereOfRadiusPlusAllowance) {
  for (const double s : {0.3, -1.2}) {
    for (const bool convex : {true, false}) {
      SCOPED_TRACE(::testing::Message() << "s " << s << (convex ? " convex" : " concave"));
      const OffsetModel offset(model_of(sphere(40, convex)), Allowance::uniform(s));
      // A solid ball's outside grows by s; a bowl's inside shrinks by s.
      const AnalyticModel by_hand({sphere(convex ? 40 + s : 40 - s, convex)});
      for (const Vector3d& q : {Vector3d(3, 4, 27), Vector3d(-10, 5, 22), Vector3d(15, -8, 16)}) {
        const auto a = offset.closest_point(q, 100, nullptr);
        const auto b = by_hand.closest_point(q, 100, nullptr);
        ASSERT_TRUE(a && b);
        expect_near(a->point, b->point, kTol);
        expect_near(a->normal, b->normal, kTol);
        EXPECT_NEAR(a->distance, b->distance, kTol);
        ASSERT_TRUE(a->curvature && b->curvature);
        // k / (1 + s k): 1/(r + s) on the ball, -1/(r - s) in the bowl.
        EXPECT_NEAR(a->curvature->k1, b->curvature->k1, kTol);
        EXPECT_NEAR(a->curvature->k2, b->curvature->k2, kTol);
      }
    }
  }
}

TEST(OffsetModel, SearchDistanceAndSidesAreTheOffsetSurfaces) {
  PlanePatch plane;
  plane.u_min = plane.v_min = -10;
  plane.u_max = plane.v_max = 10;
  const OffsetModel above(model_of(plane), Allowance::uniform(0.5));
  // 2 mm over the base is 1.5 mm over the offset plane at z = 0.5.
  const auto c = above.closest_point({1, 1, 2}, 1.6, nullptr);
  ASSERT_TRUE(c);
  expect_near(c->point, {1, 1, 0.5}, kTol);
  EXPECT_NEAR(c->distance, 1.5, kTol);
  EXPECT_FALSE(above.closest_point({1, 1, 2}, 1.4, nullptr));
  // Between the base and the offset plane: behind the offset surface.
  const auto between = above.closest_point({1, 1, 0.2}, 1, nullptr);
  ASSERT_TRUE(between);
  EXPECT_NEAR(between->distance, 0.3, kTol);
  EXPECT_LT((Vector3d(1, 1, 0.2) - between->point).dot(between->normal), 0);
  // A negative allowance: 2 mm over the base is 3.2 over the offset plane.
  const OffsetModel into(model_of(plane), Allowance::uniform(-1.2));
  const auto d = into.closest_point({1, 1, 2}, 3.3, nullptr);
  ASSERT_TRUE(d);
  expect_near(d->point, {1, 1, -1.2}, kTol);
  EXPECT_NEAR(d->distance, 3.2, kTol);
  // Bounds: grown by a positive allowance, kept for a negative one.
  EXPECT_NEAR(above.bounds().max().z(), 0.5, kTol);
  EXPECT_NEAR(above.bounds().min().x(), -10.5, kTol);
  EXPECT_NEAR(into.bounds().min().x(), -10, kTol);
}

TEST(OffsetModel, WhereTheOffsetFoldsTheContactHasNoCurvature) {
  // A convex radius of 1 under an allowance of -1.5: 1 + s k = -0.5.
  const OffsetModel folded(model_of(sphere(1, true)), Allowance::uniform(-1.5));
  const auto c = folded.closest_point({1, 2, -17}, 10, nullptr);
  ASSERT_TRUE(c);
  EXPECT_FALSE(c->curvature);
  // The point is still CC + s N: 1.5 mm below the top of the ball, past its centre.
  expect_near(c->point, {1, 2, -20.5}, kTol);
  // Short of the fold (s = -0.5: 1 + s k = 0.5) the curvature is 1/(1 - 0.5) = 2.
  const OffsetModel short_of(model_of(sphere(1, true)), Allowance::uniform(-0.5));
  const auto d = short_of.closest_point({1, 2, -17}, 10, nullptr);
  ASSERT_TRUE(d && d->curvature);
  EXPECT_NEAR(d->curvature->k1, 2, kTol);
}

TEST(OffsetModel, RadialAndAxialAllowanceOfABullNose) {
  // D 10, rc 2 (core disc radius 3); radial 0.2, axial 0.1.
  const Tool tool = Tool::bull_nose(10, 2);
  const Allowance stock{0.2, 0.1};
  EXPECT_NEAR(stock.along(Vector3d::UnitZ()), 0.1, kTol);
  EXPECT_NEAR(stock.along(Vector3d::UnitX()), 0.2, kTol);
  const Vector3d slope = Vector3d(1, 0, 1).normalized();
  EXPECT_NEAR(stock.along(slope), 0.1 + 0.1 * std::sqrt(0.5), kTol);

  // The floor z = 0: the face touches with its tip 0.1 above it (the tool
  // frame's origin rc = 2 above the tip).
  PlanePatch floor;
  floor.u_min = floor.v_min = -50;
  floor.u_max = floor.v_max = 50;
  const OffsetModel on_floor(model_of(floor), stock);
  const BallContact f = tool_contact(on_floor, tool, {0, 0, 2.1}, 0.001, 10, nullptr);
  EXPECT_EQ(f.status, BallStatus::touching);
  EXPECT_NEAR(f.distance_error, 0, 1e-9);

  // The wall x = 0 facing +x: the side stands 0.2 off it (origin at x = R + 0.2).
  PlanePatch wall;
  wall.u_axis = Vector3d::UnitY();
  wall.v_axis = Vector3d::UnitZ();
  wall.u_min = wall.v_min = -50;
  wall.u_max = wall.v_max = 50;
  const OffsetModel on_wall(model_of(wall), stock);
  const BallContact w = tool_contact(on_wall, tool, {5.2, 0, 0}, 0.001, 10, nullptr);
  EXPECT_EQ(w.status, BallStatus::touching);
  EXPECT_NEAR(w.distance_error, 0, 1e-9);

  // A 45 degree slope through the origin, normal (1, 0, 1)/sqrt 2: the
  // corner touches it at normal distance rc + 0.1 + 0.1 sin 45 from the
  // rim of the core disc (the rim point (-3, 0) from the origin).
  PlanePatch ramp;
  ramp.u_axis = Vector3d(1, 0, -1).normalized();
  ramp.v_axis = Vector3d::UnitY();
  ramp.u_min = ramp.v_min = -50;
  ramp.u_max = ramp.v_max = 50;
  const OffsetModel on_ramp(model_of(ramp), stock);
  const double reach = 2 + stock.along(slope);
  // Origin o with the rim point o + (-3, 0, 0) at distance `reach` along the normal.
  const Vector3d origin = Vector3d(3, 0, 0) + reach * slope;
  const BallContact r = tool_contact(on_ramp, tool, origin, 0.001, 10, nullptr);
  EXPECT_EQ(r.status, BallStatus::touching);
  EXPECT_NEAR(r.distance_error, 0, 1e-8);
  expect_near(r.normal, slope, 1e-8);
}

}  // namespace
}  // namespace vcpost::geometry
