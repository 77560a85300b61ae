#include "geometry/stock/swept_move.h"

namespace vcpost::geometry::stock {

namespace {

// Below this horizontal length a move is vertical (mm).
constexpr double kVerticalLength = 1e-9;
// A height change over the cutter's radius below this counts as level for
// the reaches (mm).
constexpr double kLevelRise = 1e-7;

}  // namespace

MoveFrame frame_of(const CutterProfile& profile, const Eigen::Vector3d& a,
                   const Eigen::Vector3d& b) {
  MoveFrame move;
  move.start = a.head<2>();
  const Eigen::Vector2d d = b.head<2>() - a.head<2>();
  const double length = d.norm();
  const double r = profile.radius;
  move.lowest_tip = std::min(a.z(), b.z());
  if (!(length >= kVerticalLength)) {
    move.z0 = move.lowest_tip;
    move.reach_before = move.reach_after = r;
    return move;
  }
  move.u = d / length;
  move.length = length;
  move.z0 = a.z();
  move.slope = (b.z() - a.z()) / length;
  const double rise = std::abs(move.slope);
  move.ball_factor = move.slope / std::sqrt(1 + move.slope * move.slope);
  const double k = profile.cone_slope;
  move.steeper_than_cone = rise >= k;
  if (!move.steeper_than_cone)
    move.cone_factor = move.slope / std::sqrt(k * k - move.slope * move.slope);
  double reach = r;  // the flat end and the torus: the leading rim
  if (rise * r < kLevelRise) {
    reach = 0;
  } else if (profile.kind == ProfileKind::ball) {
    reach = r * std::abs(move.ball_factor);
  } else if (profile.kind == ProfileKind::cone && !move.steeper_than_cone) {
    reach = std::min(r, r * std::abs(move.cone_factor));
  }
  (move.slope > 0 ? move.reach_after : move.reach_before) = reach;
  return move;
}

double torus_minimiser(const CutterProfile& profile, double slope, double e_abs) {
  // The grazing point: tube angle alpha (u = sin alpha) and azimuth phi
  // from the move's direction with tan(alpha) cos(phi) = |slope| and
  // (R0 + rc u) sin(phi) = |e|; squared and times u^2, the quartic
  // P(u) = (R0 + rc u)^2 ((1 + m^2) u^2 - m^2) - e^2 u^2, negative at
  // u = |m| / sqrt(1 + m^2) and >= 0 at u = 1 (|e| <= R), its sign
  // changing once between (|e| grows with u along the grazing curve).
  const double m2 = slope * slope;
  const double r0 = profile.flat_radius, rc = profile.corner_radius;
  const double e2 = e_abs * e_abs;
  double lo = std::abs(slope) / std::sqrt(1 + m2), hi = 1;
  for (int i = 0; i < 44; ++i) {
    const double u = 0.5 * (lo + hi);
    const double rho = r0 + rc * u;
    const double p = rho * rho * ((1 + m2) * u * u - m2) - e2 * u * u;
    (p < 0 ? lo : hi) = u;
  }
  const double u = 0.5 * (lo + hi);
  const double w = (r0 + rc * u) * std::abs(slope) * std::sqrt(std::max(0.0, 1 - u * u)) / u;
  return slope > 0 ? w : -w;
}

}  // namespace vcpost::geometry::stock
