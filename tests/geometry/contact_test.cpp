// Contact with analytic models: closed-form closest points, normals and
// curvatures (1e-9), corner/edge/vertex contacts of a ball, and the
// MODELS.md section 1 classification (touching / lifted / gouging / missed).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

#include "geometry/analytic_surfaces.h"
#include "geometry/model.h"

namespace vcpost::geometry {
namespace {

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;
constexpr double kTol = 1e-9;

void expect_near(const Vector3d& actual, const Vector3d& expected, double tol) {
  EXPECT_LE((actual - expected).norm(), tol)
      << "actual " << actual.transpose() << "\nexpected " << expected.transpose();
}

PlanePatch plane(const Vector3d& origin, const Vector3d& u, const Vector3d& v, double u0, double u1,
                 double v0, double v1) {
  PlanePatch p;
  p.origin = origin;
  p.u_axis = u;
  p.v_axis = v;
  p.u_min = u0;
  p.u_max = u1;
  p.v_min = v0;
  p.v_max = v1;
  return p;
}

TEST(AnalyticContact, PlaneInteriorEdgeVertex) {
  const PlanePatch p = plane({1, 2, 3}, Vector3d::UnitX(), Vector3d::UnitY(), -10, 10, -5, 5);
  const ModelContact in = closest_point_on(p, {4, -1, 7});
  expect_near(in.point, {4, -1, 3}, kTol);
  expect_near(in.normal, Vector3d::UnitZ(), kTol);
  EXPECT_NEAR(in.distance, 4, kTol);
  EXPECT_EQ(in.type, ContactType::face);
  EXPECT_NEAR(in.uv.x(), 3, kTol);
  EXPECT_NEAR(in.uv.y(), -3, kTol);
  // Beyond the u edge at x = 11: the edge point, distance sqrt(2^2 + 4^2).
  const ModelContact edge = closest_point_on(p, {13, 0, 7});
  expect_near(edge.point, {11, 0, 3}, kTol);
  EXPECT_NEAR(edge.distance, std::sqrt(20.0), kTol);
  EXPECT_EQ(edge.type, ContactType::edge);
  const ModelContact corner = closest_point_on(p, {-20, -20, 3});
  expect_near(corner.point, {-9, -3, 3}, kTol);
  EXPECT_EQ(corner.type, ContactType::vertex);
  ASSERT_TRUE(in.curvature);
  EXPECT_EQ(in.curvature->k1, 0);
  EXPECT_EQ(in.curvature->k2, 0);
}

TEST(AnalyticContact, SphereOutsideInsideAndBowl) {
  SpherePatch s;
  s.center = {1, 1, 1};
  s.radius = 10;
  // (3, 4, 12) from the centre has length 13: CC at 10/13 of it.
  const ModelContact out = closest_point_on(s, Vector3d(1, 1, 1) + Vector3d(3, 4, 12));
  expect_near(out.point, Vector3d(1, 1, 1) + Vector3d(3, 4, 12) * 10.0 / 13.0, kTol);
  expect_near(out.normal, Vector3d(3, 4, 12) / 13.0, kTol);
  EXPECT_NEAR(out.distance, 3, kTol);
  ASSERT_TRUE(out.curvature);
  EXPECT_NEAR(out.curvature->k1, 0.1, kTol);
  EXPECT_NEAR(out.curvature->k2, 0.1, kTol);
  EXPECT_NEAR(out.curvature->d1.cross(out.curvature->d2).dot(out.normal), 1, kTol);
  EXPECT_NEAR(out.curvature->d1.dot(out.normal), 0, kTol);

  // A concave bowl (material outside): the normal points to the centre.
  s.material_inside = false;
  const ModelContact bowl = closest_point_on(s, Vector3d(1, 1, 1) + Vector3d(0, 0, -4));
  expect_near(bowl.point, {1, 1, -9}, kTol);
  expect_near(bowl.normal, Vector3d::UnitZ(), kTol);
  EXPECT_NEAR(bowl.distance, 6, kTol);
  EXPECT_NEAR(bowl.curvature->k1, -0.1, kTol);
  EXPECT_NEAR(bowl.curvature->k2, -0.1, kTol);
}

TEST(AnalyticContact, SphereCapRim) {
  SpherePatch dome;
  dome.radius = 20;
  dome.max_polar = kPi / 3;  // rim at z = 10, radius 20 sin 60
  // A point at polar angle 90 deg: the nearest cap point is on the rim
  // towards it, at (20 sin 60, 0, 20 cos 60).
  const ModelContact c = closest_point_on(dome, {30, 0, 0});
  expect_near(c.point, {20 * std::sin(kPi / 3), 0, 10}, kTol);
  EXPECT_EQ(c.type, ContactType::edge);
  EXPECT_NEAR(c.distance, (Vector3d(30, 0, 0) - c.point).norm(), kTol);
  const ModelContact inside = closest_point_on(dome, {0, 5, 30});
  expect_near(inside.point, Vector3d(0, 5, 30).normalized() * 20, kTol);
  EXPECT_EQ(inside.type, ContactType::face);
}

TEST(AnalyticContact, SemiCylinderLikeTheCuspExperiment) {
  // Radius 100 about the x axis, upper half (angles 0..pi from +z... via
  // reference +y and side axis x reference = x cross y = +z).
  CylinderPatch c;
  c.axis = Vector3d::UnitX();
  c.reference = Vector3d::UnitY();
  c.radius = 100;
  c.h_min = 0;
  c.h_max = 200;
  c.angle_min = 0;
  c.angle_max = kPi;
  const Vector3d p(50, 30, 40);  // 50 from the axis, inside the cylinder
  const ModelContact in = closest_point_on(c, p);
  expect_near(in.point, {50, 60, 80}, kTol);
  expect_near(in.normal, Vector3d(0, 0.6, 0.8), kTol);
  EXPECT_NEAR(in.distance, 50, kTol);
  EXPECT_NEAR(in.uv.x(), std::atan2(0.8, 0.6), kTol);
  EXPECT_NEAR(in.uv.y(), 50, kTol);
  ASSERT_TRUE(in.curvature);
  EXPECT_NEAR(in.curvature->k1, 0.01, kTol);
  EXPECT_NEAR(in.curvature->k2, 0, kTol);
  expect_near(in.curvature->d2.cwiseAbs(), Vector3d::UnitX(), kTol);  // straight along the axis
  // Below the lower half: angle -30 deg is nearer the end at 0 (y axis).
  const ModelContact below = closest_point_on(c, {10, 100 * std::cos(kPi / 6), -50});
  expect_near(below.point, {10, 100, 0}, kTol);
  EXPECT_EQ(below.type, ContactType::edge);
  // Past the end and below: a vertex.
  const ModelContact corner = closest_point_on(c, {-5, -80, -1});
  expect_near(corner.point, {0, -100, 0}, kTol);
  EXPECT_EQ(corner.type, ContactType::vertex);
  // A concave mould (material outside, the tool inside): k = -1/100.
  c.material_inside = false;
  const ModelContact mould = closest_point_on(c, p);
  expect_near(mould.normal, Vector3d(0, -0.6, -0.8), kTol);
  EXPECT_NEAR(mould.curvature->k1, 0, kTol);
  EXPECT_NEAR(mould.curvature->k2, -0.01, kTol);
}

TEST(AnalyticContact, TorusPointsAndCurvatures) {
  TorusSurface t;
  t.center = {0, 0, 5};
  t.major = 30;
  t.minor = 10;
  // Outer equator: k = 1/10 (meridian) and 1/40 (parallel).
  const ModelContact outer = closest_point_on(t, {50, 0, 5});
  expect_near(outer.point, {40, 0, 5}, kTol);
  expect_near(outer.normal, Vector3d::UnitX(), kTol);
  EXPECT_NEAR(outer.curvature->k1, 0.1, kTol);
  EXPECT_NEAR(outer.curvature->k2, 1.0 / 40, kTol);
  // Inner equator: saddle, k2 = -1/20.
  const ModelContact inner = closest_point_on(t, {0, 25, 5});
  expect_near(inner.point, {0, 20, 5}, kTol);
  expect_near(inner.normal, -Vector3d::UnitY(), kTol);
  EXPECT_NEAR(inner.curvature->k2, -1.0 / 20, kTol);
  // Top circle: parallel curvature 0, point at 45 deg in the tube.
  const ModelContact top = closest_point_on(t, {0, -30, 25});
  expect_near(top.point, {0, -30, 15}, kTol);
  EXPECT_NEAR(top.curvature->k2, 0, kTol);
  const Vector3d q(30 + 20 / std::sqrt(2.0), 0, 5 + 20 / std::sqrt(2.0));
  const ModelContact diag = closest_point_on(t, q);
  expect_near(diag.point, {30 + 10 / std::sqrt(2.0), 0, 5 + 10 / std::sqrt(2.0)}, kTol);
  EXPECT_NEAR(diag.distance, 10, kTol);
}

// For random points, the answer is on the surface (implicit equation), the
// offset is along the normal, and no point of a dense parametric grid is
// nearer (independent of the closed form).
TEST(AnalyticContact, RandomPointsAgainstImplicitFormsAndDenseGrid) {
  TorusSurface t;
  t.major = 25;
  t.minor = 8;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-45, 45);
  for (int i = 0; i < 50; ++i) {
    const Vector3d p(coord(rng), coord(rng), coord(rng) / 2);
    const ModelContact c = closest_point_on(t, p);
    const double rho = std::hypot(c.point.x(), c.point.y());
    EXPECT_NEAR(std::hypot(rho - 25, c.point.z()), 8, kTol);
    EXPECT_LT((p - c.point).cross(c.normal).norm(), kTol * std::max(1.0, c.distance));
    double grid_min = 1e300;
    for (int a = 0; a < 360; ++a) {
      for (int b = 0; b < 360; ++b) {
        const double u = a * kPi / 180, v = b * kPi / 180;
        const Vector3d s((25 + 8 * std::cos(v)) * std::cos(u), (25 + 8 * std::cos(v)) * std::sin(u),
                         8 * std::sin(v));
        grid_min = std::min(grid_min, (p - s).norm());
      }
    }
    EXPECT_LE(c.distance, grid_min + kTol);
    // Grid steps are at most 33 mm * 1 deg = 0.58 mm by 8 mm * 1 deg = 0.14 mm.
    EXPECT_GT(c.distance, grid_min - 0.3);
  }
}

// Concave corner: floor z = 0 (x >= 0) and a wall x = 0 (z >= 0).
AnalyticModel concave_corner() {
  return AnalyticModel({plane({0, 0, 0}, Vector3d::UnitX(), Vector3d::UnitY(), 0, 100, -50, 50),
                        plane({0, 0, 0}, Vector3d::UnitY(), Vector3d::UnitZ(), -50, 50, 0, 100)});
}

TEST(BallContact, ConcaveCornerTouchesBothFaces) {
  const AnalyticModel model = concave_corner();
  const double radius = 5;
  // Centre at (5, 0, 5): both faces at distance R; either CC is right and
  // N must match the one chosen.
  const BallContact both = ball_contact(model, {5, 0, 5}, radius, 1e-9, 1, nullptr);
  ASSERT_EQ(both.status, BallStatus::touching);
  ASSERT_TRUE(both.contact);
  EXPECT_NEAR(both.distance_error, 0, kTol);
  if (both.contact->face == 0) {
    expect_near(both.contact->point, {5, 0, 0}, kTol);
    expect_near(both.normal, Vector3d::UnitZ(), kTol);
  } else {
    expect_near(both.contact->point, {0, 0, 5}, kTol);
    expect_near(both.normal, Vector3d::UnitX(), kTol);
  }
  // Slightly higher: the wall is the contact, the floor 0.5 mm below.
  const BallContact wall = ball_contact(model, {5, 3, 5.5}, radius, 1e-6, 1, nullptr);
  EXPECT_EQ(wall.status, BallStatus::touching);
  EXPECT_EQ(wall.contact->face, 1);
  expect_near(wall.contact->point, {0, 3, 5.5}, kTol);
  expect_near(wall.normal, Vector3d::UnitX(), kTol);
  // Pushed 1 mm into the wall: a gouge of 1 mm.
  const BallContact gouge = ball_contact(model, {4, 0, 6}, radius, 1e-6, 1, nullptr);
  EXPECT_EQ(gouge.status, BallStatus::gouging);
  EXPECT_NEAR(gouge.distance_error, -1, kTol);
}

TEST(BallContact, ConvexEdgeAndVertex) {
  const double radius = 6;
  // Top z = 0 over x <= 0 and a side wall x = 0 below it (normal +x).
  const AnalyticModel edge_model(
      {plane({0, 0, 0}, Vector3d::UnitX(), Vector3d::UnitY(), -100, 0, -50, 50),
       plane({0, 0, 0}, Vector3d::UnitY(), Vector3d::UnitZ(), -50, 50, -100, 0)});
  const Vector3d dir(std::cos(kPi / 6), 0, std::sin(kPi / 6));
  const BallContact edge =
      ball_contact(edge_model, Vector3d(0, 7, 0) + radius * dir, radius, 1e-9, 1, nullptr);
  ASSERT_EQ(edge.status, BallStatus::touching);
  expect_near(edge.contact->point, {0, 7, 0}, kTol);
  expect_near(edge.normal, dir, kTol);
  EXPECT_EQ(edge.contact->type, ContactType::edge);

  // The corner of a box: top z = 0 (x, y <= 0), walls x = 0 and y = 0.
  const AnalyticModel corner_model(
      {plane({0, 0, 0}, Vector3d::UnitX(), Vector3d::UnitY(), -100, 0, -100, 0),
       plane({0, 0, 0}, Vector3d::UnitY(), Vector3d::UnitZ(), -100, 0, -100, 0),
       plane({0, 0, 0}, Vector3d::UnitZ(), Vector3d::UnitX(), -100, 0, -100, 0)});
  const Vector3d diag = Vector3d(1, 1, 1).normalized();
  const BallContact vertex = ball_contact(corner_model, radius * diag, radius, 1e-9, 1, nullptr);
  ASSERT_EQ(vertex.status, BallStatus::touching);
  expect_near(vertex.contact->point, Vector3d::Zero(), kTol);
  expect_near(vertex.normal, diag, kTol);
  EXPECT_EQ(vertex.contact->type, ContactType::vertex);
}

TEST(BallContact, CenterFromClPointAndLiftedMissedStates) {
  const Vector3d tip(1, 2, 3);
  expect_near(ball_center(tip, 5, ClPoint::tip), {1, 2, 8}, 0);
  expect_near(ball_center(tip, 5, ClPoint::center), tip, 0);

  const AnalyticModel floor(
      {plane({0, 0, 0}, Vector3d::UnitX(), Vector3d::UnitY(), -10, 10, -10, 10)});
  ContactHint hint;
  const BallContact lifted = ball_contact(floor, {1, 2, 5.25}, 5, 0.01, 1, &hint);
  EXPECT_EQ(lifted.status, BallStatus::lifted);
  EXPECT_NEAR(lifted.distance_error, 0.25, kTol);
  EXPECT_EQ(hint.face, 0);
  EXPECT_NEAR(hint.uv.x(), 1, kTol);
  EXPECT_NEAR(hint.uv.y(), 2, kTol);
  // 5 + 1 mm of search reaches no surface from 7 mm above it.
  const BallContact missed = ball_contact(floor, {0, 0, 7}, 5, 0.01, 1, &hint);
  EXPECT_EQ(missed.status, BallStatus::missed);
  EXPECT_FALSE(missed.contact);
  // Centre under the floor (in the material): error -(depth + R).
  const BallContact deep = ball_contact(floor, {0, 0, -2}, 5, 0.01, 10, &hint);
  EXPECT_EQ(deep.status, BallStatus::gouging);
  EXPECT_NEAR(deep.distance_error, -7, kTol);
  expect_near(deep.normal, Vector3d::UnitZ(), kTol);
}

TEST(AnalyticModel, BoundsAndFaceCount) {
  const AnalyticModel model = concave_corner();
  EXPECT_EQ(model.face_count(), 2);
  const Eigen::AlignedBox3d box = model.bounds();
  expect_near(box.min(), {0, -50, 0}, kTol);
  expect_near(box.max(), {100, 50, 100}, kTol);
}

}  // namespace
}  // namespace vcpost::geometry
