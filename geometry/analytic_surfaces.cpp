#include "geometry/analytic_surfaces.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace vcpost::geometry {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

// Principal curvatures from the two values along d1 and the normal; d2
// completes the right-handed frame (d1 x d2 = N).
PrincipalCurvatures principal(double k_a, const Eigen::Vector3d& d_a, double k_b,
                              const Eigen::Vector3d& normal) {
  PrincipalCurvatures c;
  c.k1 = k_a;
  c.d1 = d_a;
  c.k2 = k_b;
  c.d2 = normal.cross(d_a);
  if (c.k1 < c.k2) {
    std::swap(c.k1, c.k2);
    c.d1 = c.d2;
    c.d2 = normal.cross(c.d1);
  }
  return c;
}

// Clamps x to [lo, hi] and counts a clamp.
double clamp_counted(double x, double lo, double hi, int& clamps) {
  if (x < lo) {
    ++clamps;
    return lo;
  }
  if (x > hi) {
    ++clamps;
    return hi;
  }
  return x;
}

// Angle a brought into [lo, lo + 2 pi); outside [lo, hi] it goes to the
// nearer end of the arc (by angular distance), counting a clamp.
double clamp_angle(double a, double lo, double hi, int& clamps) {
  if (hi - lo >= kTwoPi) return a;
  a = lo + std::fmod(std::fmod(a - lo, kTwoPi) + kTwoPi, kTwoPi);
  if (a <= hi) return a;
  ++clamps;
  return (a - hi) <= (lo + kTwoPi - a) ? hi : lo;
}

ContactType type_of(int clamps) {
  return clamps == 0 ? ContactType::face : clamps == 1 ? ContactType::edge : ContactType::vertex;
}

ModelContact on_plane(const PlanePatch& s, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - s.origin;
  int clamps = 0;
  const double x = clamp_counted(d.dot(s.u_axis), s.u_min, s.u_max, clamps);
  const double y = clamp_counted(d.dot(s.v_axis), s.v_min, s.v_max, clamps);
  ModelContact c;
  c.point = s.origin + x * s.u_axis + y * s.v_axis;
  c.normal = s.u_axis.cross(s.v_axis);
  c.uv = {x, y};
  c.type = type_of(clamps);
  c.curvature = principal(0, s.u_axis, 0, c.normal);
  return c;
}

ModelContact on_sphere(const SpherePatch& s, const Eigen::Vector3d& p) {
  const Eigen::Vector3d side = s.pole.cross(s.reference);
  Eigen::Vector3d d = p - s.center;
  if (d.norm() == 0) d = s.pole;  // the centre: every point is closest
  const double polar_raw = std::atan2(d.cross(s.pole).norm(), d.dot(s.pole));
  double azimuth = std::atan2(d.dot(side), d.dot(s.reference));
  int clamps = 0;
  const double polar = clamp_counted(polar_raw, 0, s.max_polar, clamps);
  if (polar_raw == std::numbers::pi) azimuth = 0;
  const Eigen::Vector3d radial =
      std::cos(polar) * s.pole +
      std::sin(polar) * (std::cos(azimuth) * s.reference + std::sin(azimuth) * side);
  ModelContact c;
  c.point = s.center + s.radius * radial;
  c.normal = s.material_inside ? radial : Eigen::Vector3d(-radial);
  c.uv = {azimuth, polar};
  c.type = type_of(clamps);
  const double k = (s.material_inside ? 1 : -1) / s.radius;
  const Eigen::Vector3d any_tangent =
      (std::abs(radial.dot(s.reference)) < 0.9 ? s.reference : side).cross(radial).normalized();
  c.curvature = principal(k, any_tangent, k, c.normal);
  return c;
}

ModelContact on_cylinder(const CylinderPatch& s, const Eigen::Vector3d& p) {
  const Eigen::Vector3d side = s.axis.cross(s.reference);
  const Eigen::Vector3d d = p - s.origin;
  int clamps = 0;
  const double angle =
      clamp_angle(std::atan2(d.dot(side), d.dot(s.reference)), s.angle_min, s.angle_max, clamps);
  const double h = clamp_counted(d.dot(s.axis), s.h_min, s.h_max, clamps);
  const Eigen::Vector3d radial = std::cos(angle) * s.reference + std::sin(angle) * side;
  ModelContact c;
  c.point = s.origin + h * s.axis + s.radius * radial;
  c.normal = s.material_inside ? radial : Eigen::Vector3d(-radial);
  c.uv = {angle, h};
  c.type = type_of(clamps);
  const double k = (s.material_inside ? 1 : -1) / s.radius;
  c.curvature = principal(k, s.axis.cross(radial), 0, c.normal);
  return c;
}

ModelContact on_torus(const TorusSurface& s, const Eigen::Vector3d& p) {
  const Eigen::Vector3d side = s.axis.cross(s.reference);
  const Eigen::Vector3d d = p - s.center;
  const double u = std::atan2(d.dot(side), d.dot(s.reference));
  const Eigen::Vector3d e = std::cos(u) * s.reference + std::sin(u) * side;
  const Eigen::Vector3d w = d - s.major * e;  // from the tube's centre circle
  const double v = std::atan2(w.dot(s.axis), w.dot(e));
  const Eigen::Vector3d tube = std::cos(v) * e + std::sin(v) * s.axis;
  ModelContact c;
  c.point = s.center + s.major * e + s.minor * tube;
  c.normal = s.material_inside ? tube : Eigen::Vector3d(-tube);
  c.uv = {u, v};
  c.type = ContactType::face;
  // Convex-positive curvatures for the outward tube normal: 1/minor along
  // the meridian, cos v / (major + minor cos v) along the parallel.
  const double sign = s.material_inside ? 1 : -1;
  const Eigen::Vector3d meridian = -std::sin(v) * e + std::cos(v) * s.axis;
  const double k_parallel = std::cos(v) / (s.major + s.minor * std::cos(v));
  c.curvature = principal(sign / s.minor, meridian, sign * k_parallel, c.normal);
  return c;
}

Eigen::AlignedBox3d box_around(const Eigen::Vector3d& center, double half) {
  const Eigen::Vector3d h = Eigen::Vector3d::Constant(half);
  return {center - h, center + h};
}

}  // namespace

ModelContact closest_point_on(const AnalyticSurface& surface, const Eigen::Vector3d& point) {
  ModelContact c = std::visit(
      [&point](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, PlanePatch>) return on_plane(s, point);
        if constexpr (std::is_same_v<T, SpherePatch>) return on_sphere(s, point);
        if constexpr (std::is_same_v<T, CylinderPatch>) return on_cylinder(s, point);
        if constexpr (std::is_same_v<T, TorusSurface>) return on_torus(s, point);
      },
      surface);
  c.distance = (point - c.point).norm();
  c.face = 0;
  return c;
}

Eigen::AlignedBox3d bounds_of(const AnalyticSurface& surface) {
  return std::visit(
      [](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        Eigen::AlignedBox3d box;
        if constexpr (std::is_same_v<T, PlanePatch>) {
          for (double x : {s.u_min, s.u_max}) {
            for (double y : {s.v_min, s.v_max}) box.extend(s.origin + x * s.u_axis + y * s.v_axis);
          }
        } else if constexpr (std::is_same_v<T, SpherePatch>) {
          box = box_around(s.center, s.radius);
        } else if constexpr (std::is_same_v<T, CylinderPatch>) {
          box = box_around(s.origin + s.h_min * s.axis, s.radius);
          box.extend(box_around(s.origin + s.h_max * s.axis, s.radius));
        } else {
          box = box_around(s.center, s.major + s.minor);
        }
        return box;
      },
      surface);
}

AnalyticModel::AnalyticModel(std::vector<AnalyticSurface> surfaces)
    : surfaces_(std::move(surfaces)) {}

std::optional<ModelContact> AnalyticModel::closest_point(const Eigen::Vector3d& point,
                                                         double max_distance,
                                                         ContactHint* hint) const {
  std::optional<ModelContact> best;
  for (std::size_t i = 0; i < surfaces_.size(); ++i) {
    ModelContact c = closest_point_on(surfaces_[i], point);
    if (c.distance > max_distance) continue;
    if (!best || c.distance < best->distance) {
      c.face = static_cast<int>(i);
      best = c;
    }
  }
  if (best && hint && !hint->curvature) best->curvature.reset();
  if (hint) {
    ++hint->warm_queries;
    if (best) {
      hint->face = best->face;
      hint->uv = best->uv;
    }
  }
  return best;
}

Eigen::AlignedBox3d AnalyticModel::bounds() const {
  Eigen::AlignedBox3d box;
  for (const auto& s : surfaces_) box.extend(bounds_of(s));
  return box;
}

}  // namespace vcpost::geometry
