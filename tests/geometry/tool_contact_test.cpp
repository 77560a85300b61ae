// Contact of the bull-nose and flat end mills with analytic surfaces, against
// the closed-form truth: the core disc's closest point to a plane is the rim
// point against the normal's horizontal part, to a solid sphere the disc
// point nearest its centre, to a bowl (the inside of a sphere) the disc
// point farthest from its centre.
#include "geometry/tool_contact.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "geometry/analytic_surfaces.h"
#include "geometry/engagement.h"

namespace vcpost::geometry {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

void expect_near(const Vector3d& actual, const Vector3d& expected, double tolerance) {
  EXPECT_LE((actual - expected).norm(), tolerance)
      << "actual " << actual.transpose() << "\nexpected " << expected.transpose();
}

double disc_radius(const Tool& tool) {
  return tool.kind == ToolKind::flat ? tool.radius() : tool.flat_radius();
}
double corner(const Tool& tool) { return tool.kind == ToolKind::flat ? 0.0 : tool.corner_radius; }

// The disc point nearest to p: p's projection onto the disc's plane, pulled
// onto the disc.
Vector3d nearest_disc_point(const Vector3d& origin, double radius, const Vector3d& p) {
  Vector2d q = (p - origin).head<2>();
  if (q.norm() > radius) q *= radius / q.norm();
  return origin + Vector3d(q.x(), q.y(), 0);
}

struct Expected {
  Vector3d cc, normal;
  double error;
};

void check(const SurfaceModel& model, const Tool& tool, const Vector3d& origin,
           const Expected& expected, double tolerance = 1e-7) {
  SCOPED_TRACE(::testing::Message() << to_string(tool) << " origin " << origin.transpose());
  ContactHint hint;
  const BallContact contact = tool_contact(model, tool, origin, 0.01, tool.diameter, &hint);
  ASSERT_TRUE(contact.contact);
  EXPECT_NEAR(contact.distance_error, expected.error, tolerance);
  expect_near(contact.contact->point, expected.cc, 1e3 * tolerance);
  expect_near(contact.normal, expected.normal, 1e3 * tolerance);
  // Warm from its own answer: the same contact again.
  const BallContact again = tool_contact(model, tool, origin, 0.01, tool.diameter, &hint);
  EXPECT_NEAR(again.distance_error, contact.distance_error, 1e-9);
}

TEST(ToolContact, TiltedPlaneTouchesAtTheRimAgainstTheNormal) {
  std::mt19937 random(1);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const Tool& tool : {Tool::bull_nose(10, 2), Tool::bull_nose(16, 0.5), Tool::flat(12)}) {
    for (int i = 0; i < 20; ++i) {
      const Vector3d n = normal_from_angles(1.2 * unit(random), 6.3 * unit(random));
      const Vector3d u = n.unitOrthogonal(), v = n.cross(u);
      PlanePatch plane;
      plane.u_axis = u;
      plane.v_axis = v;
      plane.u_min = plane.v_min = -100;
      plane.u_max = plane.v_max = 100;
      const AnalyticModel model({plane});
      const Vector3d origin(10 * unit(random) - 5, 10 * unit(random) - 5, 3 * unit(random) - 1);
      const double radius = disc_radius(tool);
      const Vector2d away = -n.head<2>().normalized();
      const Vector3d q = origin + radius * Vector3d(away.x(), away.y(), 0);
      const double height = n.dot(q);  // signed distance of the disc's lowest point
      check(model, tool, origin, {q - height * n, n, height - corner(tool)});
    }
  }
}

TEST(ToolContact, SolidSphereTouchesTheDiscPointNearestItsCentre) {
  SpherePatch sphere;
  sphere.center = {1, -2, -30};
  sphere.radius = 25;
  const AnalyticModel model({sphere});
  std::mt19937 random(2);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const Tool& tool : {Tool::bull_nose(10, 2), Tool::bull_nose(20, 3), Tool::flat(12)}) {
    for (int i = 0; i < 30; ++i) {
      // Over the crest (the face's inside touches) and down the sides (the rim).
      const double reach = i < 10 ? 2.0 : 20.0;
      const Vector3d origin(1 + reach * (2 * unit(random) - 1), -2 + reach * (2 * unit(random) - 1),
                            -4 + 2 * unit(random));
      const Vector3d q = nearest_disc_point(origin, disc_radius(tool), sphere.center);
      const Vector3d n = (q - sphere.center).normalized();
      check(model, tool, origin,
            {sphere.center + sphere.radius * n, n,
             (q - sphere.center).norm() - sphere.radius - corner(tool)});
    }
  }
}

// Down the sphere's side along a path, each contact warm from the last (as
// a post asks): on the rim at every point, and as exact as a cold start.
TEST(ToolContact, WarmAlongAPathStaysExactOnTheRim) {
  SpherePatch sphere;
  sphere.center = {1, -2, -30};
  sphere.radius = 25;
  const AnalyticModel model({sphere});
  for (const Tool& tool : {Tool::bull_nose(10, 2), Tool::bull_nose(20, 3), Tool::flat(12)}) {
    ContactHint hint;
    for (int i = 0; i <= 200; ++i) {
      // A spiral round the crest, 6-16 mm out, 1 mm above the surface's level there.
      const double angle = 0.05 * i, reach = 6 + 0.05 * i;
      const Vector3d origin(1 + reach * std::cos(angle), -2 + reach * std::sin(angle),
                            -30 + std::sqrt(25.0 * 25.0 - reach * reach) - 1);
      const Vector3d q = nearest_disc_point(origin, disc_radius(tool), sphere.center);
      const double expected = (q - sphere.center).norm() - sphere.radius - corner(tool);
      const BallContact contact = tool_contact(model, tool, origin, 0.01, tool.diameter, &hint);
      ASSERT_TRUE(contact.contact) << i;
      EXPECT_NEAR(contact.distance_error, expected, 1e-9) << to_string(tool) << " point " << i;
    }
  }
}

TEST(ToolContact, BowlTouchesTheDiscPointFarthestFromItsCentre) {
  SpherePatch bowl;
  bowl.center = {0, 0, 40};
  bowl.radius = 45;
  bowl.material_inside = false;
  const AnalyticModel model({bowl});
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const Tool& tool : {Tool::bull_nose(10, 2), Tool::flat(8)}) {
    for (int i = 0; i < 20; ++i) {
      const Vector3d origin(20 * unit(random) - 10, 20 * unit(random) - 10, -2 + unit(random));
      const Vector2d away = (origin - bowl.center).head<2>().normalized();
      const Vector3d q = origin + disc_radius(tool) * Vector3d(away.x(), away.y(), 0);
      const Vector3d n = (bowl.center - q).normalized();
      check(model, tool, origin,
            {bowl.center - bowl.radius * n, n,
             bowl.radius - (q - bowl.center).norm() - corner(tool)});
    }
  }
}

// A valley of two flanks, steep (60 deg) and shallow (20 deg): the tool
// rests on the shallow one and clears the steep one by 0.5 mm. Warm-started
// on the steep side, the descent stops in that flank's own minimum (the
// rim point against its normal: 0.5 mm, as if lifted); the contact is the
// least distance over the disc, on the shallow flank.
// The bull-nose over a V valley, resting on the shallow flank with its
// disc point on the steep side `lift` mm farther than rc from the steep
// flank: the descent warm-started there stops on that flank, lifted.
void expect_valley_contact_on_the_shallow_flank(double lift) {
  constexpr double kPi = 3.14159265358979323846;
  const double steep = 60 * kPi / 180, shallow = 20 * kPi / 180;
  PlanePatch left, right;  // meeting along the y axis at z = 0
  left.u_axis = {-std::cos(steep), 0, std::sin(steep)};
  left.v_axis = {0, -1, 0};
  right.u_axis = {std::cos(shallow), 0, std::sin(shallow)};
  right.v_axis = {0, 1, 0};
  for (PlanePatch* flank : {&left, &right}) {
    flank->u_min = 0;
    flank->u_max = 100;
    flank->v_min = -100;
    flank->v_max = 100;
  }
  const AnalyticModel model({left, right});
  const Tool tool = Tool::bull_nose(10, 2);  // R0 3, rc 2
  // Origin (x, 0, z): the disc point (x + 3, 0, z) at rc from the shallow
  // flank, (x - 3, 0, z) at rc + lift from the steep one.
  const Vector3d n_shallow(-std::sin(shallow), 0, std::cos(shallow));
  const Vector3d n_steep(std::sin(steep), 0, std::cos(steep));
  Eigen::Matrix2d a;
  a << n_shallow.x(), n_shallow.z(), n_steep.x(), n_steep.z();
  const Eigen::Vector2d b(2 - 3 * n_shallow.x(), 2 + lift + 3 * n_steep.x());
  const Eigen::Vector2d xz = a.lu().solve(b);
  const Vector3d origin(xz.x(), 0, xz.y());
  ContactHint hint;
  hint.rim = {-3, 0};  // the last contact was on the steep flank
  const BallContact contact = tool_contact(model, tool, origin, 0.01, tool.diameter, &hint);
  ASSERT_TRUE(contact.contact);
  EXPECT_NEAR(contact.distance_error, 0, 1e-9);
  expect_near(contact.normal, n_shallow, 1e-9);
  expect_near(contact.contact->point, origin + Vector3d(3, 0, 0) - 2 * n_shallow, 1e-9);
  EXPECT_NEAR(hint.rim.x(), 3, 1e-9);
}

TEST(ToolContact, ValleyFindsTheFlankItRestsOn) { expect_valley_contact_on_the_shallow_flank(0.5); }

// Lifted by 5e-3 mm, within the 0.01 mm tolerance: still the wrong flank
// (on the wavy raster 200 of 200,912 contacts stopped on one so).
TEST(ToolContact, ValleyFindsTheFlankItRestsOnWhenTheOtherIsWithinTolerance) {
  expect_valley_contact_on_the_shallow_flank(5e-3);
}

// A bull-nose D12 R0.5 (R0 5.5) over a pocket's floor, 1.5 mm above it,
// beside its wall at x = -6.5: the rim point (-5.5, 0) is 1 mm from the
// wall, the tool 0.5 mm from it (its contact); every disc point is 2 mm
// above the floor. From the centre and the opposite rim point (+5.5, 0)
// the floor is nearest and its distance has no gradient across the disc:
// those searches stopped at 1.5 mm (a real roughing program on its design
// STL: 743 of 5,871 points lifted by up to 0.9 mm too much).
TEST(ToolContact, WallBeyondTheRimOverAFloorIsTheContact) {
  PlanePatch floor, wall;
  floor.u_min = -6.5;
  floor.u_max = 50;
  floor.v_min = -50;
  floor.v_max = 50;
  wall.origin = {-6.5, 0, 0};
  wall.u_axis = {0, 1, 0};
  wall.v_axis = {0, 0, 1};  // normal u x v = +x, out of the material at x < -6.5
  wall.u_min = -50;
  wall.u_max = 50;
  wall.v_min = 0;
  wall.v_max = 20;
  const AnalyticModel model({floor, wall});
  const Tool tool = Tool::bull_nose(12, 0.5);
  for (const Vector3d& origin : {Vector3d(0, 0, 2), Vector3d(0, 3, 2)}) {
    check(model, tool, origin, {{-6.5, origin.y(), 2}, {1, 0, 0}, 0.5});
  }
}

// The ball goes through ball_contact unchanged; tool_origin puts the tip rc
// below the origin.
TEST(ToolContact, BallIsBallContactAndOriginsFromTheTip) {
  SpherePatch sphere;
  sphere.radius = 10;
  const AnalyticModel model({sphere});
  const Vector3d centre(3, 4, 12);
  const BallContact ball = tool_contact(model, Tool::ball(6), centre, 0.01, 6, nullptr);
  const BallContact reference = ball_contact(model, centre, 3, 0.01, 6, nullptr);
  EXPECT_EQ(ball.distance_error, reference.distance_error);
  EXPECT_EQ(ball.normal, reference.normal);
  expect_near(tool_origin({1, 2, 3}, Tool::bull_nose(10, 2), ClPoint::tip), {1, 2, 5}, 0);
  expect_near(tool_origin({1, 2, 3}, Tool::ball(10), ClPoint::tip), {1, 2, 8}, 0);
  expect_near(tool_origin({1, 2, 3}, Tool::flat(10), ClPoint::tip), {1, 2, 3}, 0);
  expect_near(tool_origin({1, 2, 3}, Tool::bull_nose(10, 2), ClPoint::center), {1, 2, 3}, 0);
}

}  // namespace
}  // namespace vcpost::geometry
