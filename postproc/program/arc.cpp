#include "postproc/program/arc.h"

#include <cmath>
#include <numbers>

namespace vcpost::program {

std::array<int, 3> plane_axes(Plane plane) {
  switch (plane) {
    case Plane::xy:
      return {0, 1, 2};
    case Plane::xz:
      return {2, 0, 1};
    case Plane::yz:
      return {1, 2, 0};
  }
  return {0, 1, 2};
}

namespace {

struct Polar {
  double angle;
  double radius;
};

Polar polar(const Eigen::Vector3d& p, const Eigen::Vector3d& c, const std::array<int, 3>& ax) {
  const double a = p[ax[0]] - c[ax[0]];
  const double b = p[ax[1]] - c[ax[1]];
  return {std::atan2(b, a), std::hypot(a, b)};
}

}  // namespace

double arc_sweep(const ArcFeed& arc) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  // Below this the end angle is taken as the start angle: a full circle.
  constexpr double same_angle = 1e-9;
  const auto ax = plane_axes(arc.plane);
  const double a0 = polar(arc.start, arc.centre, ax).angle;
  const double a1 = polar(arc.end, arc.centre, ax).angle;
  const int turns = arc.rotation == 0 ? 1 : std::abs(arc.rotation);
  double d = a1 - a0;
  if (arc.rotation >= 0) {
    if (d <= same_angle) d += two_pi;
    return d + two_pi * (turns - 1);
  }
  if (d >= -same_angle) d -= two_pi;
  return d - two_pi * (turns - 1);
}

double arc_length(const ArcFeed& arc) {
  const auto ax = plane_axes(arc.plane);
  const double r0 = polar(arc.start, arc.centre, ax).radius;
  const double r1 = polar(arc.end, arc.centre, ax).radius;
  const double planar = std::abs(arc_sweep(arc)) * 0.5 * (r0 + r1);
  const double axial = arc.end[ax[2]] - arc.start[ax[2]];
  return std::hypot(planar, axial);
}

Eigen::Vector3d arc_point(const ArcFeed& arc, double u) {
  const auto ax = plane_axes(arc.plane);
  const Polar p0 = polar(arc.start, arc.centre, ax);
  const Polar p1 = polar(arc.end, arc.centre, ax);
  if (u <= 0.0) return arc.start;
  if (u >= 1.0) return arc.end;
  const double angle = p0.angle + u * arc_sweep(arc);
  const double radius = p0.radius + u * (p1.radius - p0.radius);
  Eigen::Vector3d p;
  p[ax[0]] = arc.centre[ax[0]] + radius * std::cos(angle);
  p[ax[1]] = arc.centre[ax[1]] + radius * std::sin(angle);
  p[ax[2]] = arc.start[ax[2]] + u * (arc.end[ax[2]] - arc.start[ax[2]]);
  return p;
}

}  // namespace vcpost::program
