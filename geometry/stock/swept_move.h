// One straight tip move seen from the cells it passes over, and the exact
// lowest point of the cutter swept along it over a cell centre.
//
// In the move's frame a cell centre is at s along the move's horizontal
// direction u (from the start) and e across it. The tool at travel sigma
// in [0, L] has its tip at z0 + slope * sigma and reaches the centre at the
// along-offset w = s - sigma, so the swept cutter's lowest point there is
//   z0 + slope * s + min g(w),  g(w) = -slope * w + h(sqrt(w^2 + e^2)),
// over w in [max(s - L, -W), min(s, W)], W = sqrt(R^2 - e^2). h is convex
// and non-decreasing and sqrt(w^2 + e^2) is convex, so g is convex: its
// minimum over the interval is its free minimiser w* clamped to the
// interval. w* is closed form for the ball (slope * W / sqrt(1 + slope^2)),
// the flat end (the interval's uphill end) and the cone (e * slope /
// sqrt(k^2 - slope^2), or the uphill end when the move is steeper than the
// cone); for the torus it is the root of a quartic, found by bisection on
// a bracket where its sign changes once (torus_minimiser).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "geometry/stock/cutter_profile.h"

namespace vcpost::geometry::stock {

struct MoveFrame {
  Eigen::Vector2d start = Eigen::Vector2d::Zero();  // the tip's xy at s = 0
  Eigen::Vector2d u = Eigen::Vector2d::UnitX();     // unit; +x for a vertical move
  double length = 0;                                // L, horizontal; 0 for a vertical move
  double z0 = 0;     // the tip's z at s = 0 (vertical: the lower end)
  double slope = 0;  // dz/ds (0 for a vertical move)
  // How far beyond its start (s < 0) and its end (s > L) the move's
  // interior still gives the lowest point over a cell: there the caps of
  // its ends do not stand for it.
  double reach_before = 0, reach_after = 0;
  double lowest_tip = 0;  // the lowest tip z along the move
  // The minimisers' factors: w* = ball_factor * W (ball), cone_factor * |e|
  // (cone, unless steep: then the uphill end).
  double ball_factor = 0, cone_factor = 0;
  bool steeper_than_cone = false;
};

// The move from tip a to tip b. Below a horizontal length of 1e-9 mm the
// move is vertical: the cutter at its lower end. A slope whose height
// change over the cutter's radius is below 1e-7 mm counts as level for the
// reaches (the caps stand in for the interior there within that).
MoveFrame frame_of(const CutterProfile& profile, const Eigen::Vector3d& a,
                   const Eigen::Vector3d& b);

// The torus' free minimiser w* for a sloped move (see above), |e| <= R.
double torus_minimiser(const CutterProfile& profile, double slope, double e_abs);

inline constexpr double kNoCut = std::numeric_limits<double>::infinity();

// The underside's height over radial distance sqrt(r_sq) (r_sq <= R^2), for
// the kernels below: no branch, so that their loops vectorise.
template <ProfileKind Kind>
inline double underside(const CutterProfile& profile, double r_sq) {
  if constexpr (Kind == ProfileKind::ball) {
    return profile.radius - std::sqrt(std::max(0.0, profile.radius * profile.radius - r_sq));
  } else if constexpr (Kind == ProfileKind::torus) {
    const double d = std::max(0.0, std::sqrt(r_sq) - profile.flat_radius);
    const double rc = profile.corner_radius;
    return rc - std::sqrt(std::max(0.0, rc * rc - d * d));
  } else if constexpr (Kind == ProfileKind::cone) {
    return profile.cone_slope * std::sqrt(r_sq);
  } else {
    return 0.0;
  }
}

// The lowest point of a level (or standing) move's cutter over the cell
// centre at (s, e) in its frame: the cutter at the nearest tip; kNoCut
// where the cutter does not pass over it.
template <ProfileKind Kind>
inline double lowest_level(const CutterProfile& profile, const MoveFrame& move, double s,
                           double e) {
  const double r = profile.radius;
  const double beyond = std::min(s, 0.0) + std::max(s - move.length, 0.0);
  const double d_sq = e * e + beyond * beyond;
  const double z = move.z0 + underside<Kind>(profile, std::min(d_sq, r * r));
  return d_sq <= r * r ? z : kNoCut;
}

// The same for a sloped move: the minimiser clamped (see above).
template <ProfileKind Kind>
inline double lowest_sloped(const CutterProfile& profile, const MoveFrame& move, double s,
                            double e) {
  const double r = profile.radius;
  const double w_sq_max = r * r - e * e;
  const double w_max = std::sqrt(std::max(0.0, w_sq_max));
  const double lo = std::max(s - move.length, -w_max);
  const double hi = std::min(s, w_max);
  double w = 0;
  if constexpr (Kind == ProfileKind::ball) {
    w = move.ball_factor * w_max;
  } else if constexpr (Kind == ProfileKind::flat) {
    w = move.slope > 0 ? hi : lo;
  } else if constexpr (Kind == ProfileKind::cone) {
    w = move.steeper_than_cone ? (move.slope > 0 ? hi : lo) : move.cone_factor * std::abs(e);
  } else {
    w = w_sq_max >= 0 ? torus_minimiser(profile, move.slope, std::abs(e)) : 0.0;
  }
  w = std::min(std::max(w, lo), hi);
  const double z =
      move.z0 + move.slope * (s - w) + underside<Kind>(profile, std::min(w * w + e * e, r * r));
  return w_sq_max >= 0 && lo <= hi ? z : kNoCut;
}

template <ProfileKind Kind>
inline double lowest_over(const CutterProfile& profile, const MoveFrame& move, double s, double e) {
  return move.slope == 0 ? lowest_level<Kind>(profile, move, s, e)
                         : lowest_sloped<Kind>(profile, move, s, e);
}

// Lowers the cells [i0, i1] of one row (Strided: every stride-th cell from
// line on, a column) to the swept cutter; the cell i0's centre is at
// (s0, e0) in the move's frame, each next one (ds, de) on.
template <ProfileKind Kind, bool Strided>
void cut_cells(const CutterProfile& profile, const MoveFrame& move, float* line,
               std::ptrdiff_t stride, int i0, int i1, double s0, double e0, double ds, double de) {
  const auto at = [&](int i) -> float& { return line[Strided ? i * stride : i]; };
  if (move.slope == 0) {
    for (int i = i0; i <= i1; ++i) {
      const double step = i - i0;
      const double z = lowest_level<Kind>(profile, move, s0 + step * ds, e0 + step * de);
      at(i) = std::min(at(i), static_cast<float>(z));
    }
    return;
  }
  for (int i = i0; i <= i1; ++i) {
    const double step = i - i0;
    const double z = lowest_sloped<Kind>(profile, move, s0 + step * ds, e0 + step * de);
    at(i) = std::min(at(i), static_cast<float>(z));
  }
}

// Calls f with the profile's kind as a compile-time constant.
template <class F>
void with_kind(ProfileKind kind, F&& f) {
  switch (kind) {
    case ProfileKind::ball:
      f(std::integral_constant<ProfileKind, ProfileKind::ball>{});
      return;
    case ProfileKind::torus:
      f(std::integral_constant<ProfileKind, ProfileKind::torus>{});
      return;
    case ProfileKind::flat:
      f(std::integral_constant<ProfileKind, ProfileKind::flat>{});
      return;
    case ProfileKind::cone:
      f(std::integral_constant<ProfileKind, ProfileKind::cone>{});
      return;
  }
}

}  // namespace vcpost::geometry::stock
