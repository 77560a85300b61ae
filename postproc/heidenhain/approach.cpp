#include "postproc/heidenhain/approach.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "core/units.h"

namespace vcpost::heidenhain {

namespace {

Eigen::Vector2d turned(const Eigen::Vector2d& v, double degrees) {
  return Eigen::Rotation2Dd(degrees * kDeg) * v;
}

// CT and LCT: the arc's centre beside the contour point and its direction.
// RL with R+ turns counterclockwise about a centre left of the contour, RR
// with R+ clockwise about one on its right; R- the other way (the TNC
// manual's table of compensation, sign of R and direction).
bool arc_beside(const LinkInput& in, const Eigen::Vector2d& at, const Eigen::Vector2d& tangent,
                LinkPath& path, std::string& why) {
  if (in.side == 0) {
    why = "needs the radius compensation RL or RR (it says on which side the arc runs)";
    return false;
  }
  if (in.radius == 0) {
    why = "needs the arc's radius R (not 0)";
    return false;
  }
  path.centre = at + in.side * in.radius * left_normal(tangent);
  path.rotation = in.side * (in.radius > 0 ? 1 : -1);
  return true;
}

// The point where a line through `outside` touches the circle about
// `centre` of radius r, on the side that the circle's `rotation` leaves
// towards it (departing) or arrives from (approaching).
bool touching_point(const Eigen::Vector2d& centre, double r, const Eigen::Vector2d& outside,
                    int rotation, bool approaching, Eigen::Vector2d& out, std::string& why) {
  const Eigen::Vector2d d = outside - centre;
  const double distance = d.norm();
  if (distance <= r + 1e-9) {
    why = "its start or end point lies within the arc's circle: no line touches it";
    return false;
  }
  const double phi = std::atan2(d.y(), d.x());
  const double alpha = std::acos(r / distance);
  const double sign = (approaching ? 1.0 : -1.0) * static_cast<double>(rotation);
  const double theta = phi + sign * alpha;
  out = centre + r * Eigen::Vector2d(std::cos(theta), std::sin(theta));
  return true;
}

bool check_len(const LinkInput& in, std::string& why) {
  if (in.len <= 0 && in.link == ContourLink::line_tangent) {
    why = "needs LEN, the distance of the auxiliary point, above 0";
    return false;
  }
  if (in.link == ContourLink::line_normal && in.side == 0) {
    why = "needs the radius compensation RL or RR (it says on which side the line runs)";
    return false;
  }
  if (in.link == ContourLink::circle_tangent && !(in.cca > 0 && in.cca <= 360)) {
    why = "needs the centre angle CCA above 0 and up to 360";
    return false;
  }
  return true;
}

}  // namespace

std::optional<LinkPath> approach_path(const LinkInput& in, const Eigen::Vector2d& start,
                                      const Eigen::Vector2d& first, const Eigen::Vector2d& tangent,
                                      std::string& why) {
  if (!check_len(in, why)) return std::nullopt;
  LinkPath path;
  path.end = first;
  switch (in.link) {
    case ContourLink::line_tangent:
      path.auxiliary = first - in.len * tangent;
      break;
    case ContourLink::line_normal:
      path.auxiliary = first + in.side * in.len * left_normal(tangent);
      break;
    case ContourLink::circle_tangent:
      if (!arc_beside(in, first, tangent, path, why)) return std::nullopt;
      path.auxiliary = *path.centre + turned(first - *path.centre, -path.rotation * in.cca);
      break;
    case ContourLink::line_circle:
      if (!arc_beside(in, first, tangent, path, why)) return std::nullopt;
      if (!touching_point(*path.centre, std::abs(in.radius), start, path.rotation, true,
                          path.auxiliary, why))
        return std::nullopt;
      break;
  }
  return path;
}

std::optional<LinkPath> departure_path(const LinkInput& in, const Eigen::Vector2d& last,
                                       const Eigen::Vector2d& tangent, const Eigen::Vector2d& end,
                                       std::string& why) {
  if (!check_len(in, why)) return std::nullopt;
  LinkPath path;
  switch (in.link) {
    case ContourLink::line_tangent:
      path.auxiliary = last + in.len * tangent;
      break;
    case ContourLink::line_normal:
      path.auxiliary = last + in.side * in.len * left_normal(tangent);
      break;
    case ContourLink::circle_tangent:
      if (!arc_beside(in, last, tangent, path, why)) return std::nullopt;
      path.auxiliary = *path.centre + turned(last - *path.centre, path.rotation * in.cca);
      break;
    case ContourLink::line_circle:
      if (!arc_beside(in, last, tangent, path, why)) return std::nullopt;
      if (!touching_point(*path.centre, std::abs(in.radius), end, path.rotation, false,
                          path.auxiliary, why))
        return std::nullopt;
      path.end = end;
      return path;
  }
  path.end = path.auxiliary;
  return path;
}

}  // namespace vcpost::heidenhain
