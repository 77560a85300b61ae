// The cusp, Ra and Rz a bull-nose or flat end mill leaves across the feed
// (docs/models.md §3).
#include "geometry/revolved_groove.h"

namespace vcpost::geometry::revolved {

// Ra of the transverse profile on the tangent plane, whose peak is the
// cusp at the width level c* (the profile repeats every ae: this tool's right boundary up to the
// cusp, the previous one's left down from it, and a face seen edge-on in
// between at the bottom). Its mean line m and Ra = (1 / ae) int |z - m| db
// over a period, twice the part above m (z - m sums to 0). Below the feet
// the boundaries are Q's silhouette, and in its parameter phi, int z db =
// int (c(phi) - c_min) b'(phi) dphi takes no root (only where z crosses
// m); above a foot, where the profile's sides are rays, by layers: above
// the level t over CC the profile spans w(t) = ae - width(c_min + t) of
// the period, so m = (1 / ae) int_0^rz w and Ra = (2 / ae) int_m^rz w,
// rz = c* - c_min.
double Groove::plane_roughness(const WidthLevel& cusp) const {
  const double top = cusp.c, rz = top - c_min_;
  const BoundaryPoint &left = cusp.left, &right = cusp.right;
  const double scale = 1e-12 * radius_ * ae_;
  if (left.ray == 0 && right.ray == 0) {
    const auto piece = [&](double from, double to, double mean) {
      const auto z_db = [&](double phi) {
        const auto [cos_phi, sin_phi] = cos_sin(phi);
        const auto [p, dp] = silhouette_and_tangent(cos_phi, sin_phi);
        return std::array<double, 1>{std::abs(normal_.dot(p) - c_min_ - mean) * side_.dot(dp)};
      };
      return integrate_capped<1>(z_db, from, to, 1e-8, scale, 64)[0];
    };
    const double bottom = phi_bottom_;
    const double mean = (piece(left.phi, bottom, 0) + piece(bottom, right.phi, 0)) / ae_;
    // z - m sums to 0 over a period: |z - m| to twice its part above m.
    const double left_m = boundary(c_min_ + mean, true).phi,
                 right_m = boundary(c_min_ + mean, false).phi;
    return 2 * (piece(left.phi, left_m, mean) + piece(right_m, right.phi, mean)) / ae_;
  }
  // In u = sqrt(c - c_min): Q's width grows as sqrt(c - c_min) from its
  // bottom (a curve's or a face's ends), w(c) dc = w 2 u du is smooth.
  const auto w = [&](double u) {
    const double c = c_min_ + u * u;
    return std::array<double, 1>{2 * u * (ae_ - (boundary(c, false).b - boundary(c, true).b))};
  };
  // The boundaries bend where they pass onto the shank's rays.
  const auto layers = [&](double from, double to) {
    std::vector<double> feet;
    for (const double c_foot : c_foot_) {
      if (c_foot > c_min_) feet.push_back(std::sqrt(c_foot - c_min_));
    }
    return integrate_capped<1>(
        w, breaks_within(feet, std::sqrt(from - c_min_), std::sqrt(to - c_min_)), 1e-8, scale,
        64)[0];
  };
  const double mean = std::clamp(layers(c_min_, top) / ae_, 0.0, rz);
  return 2 / ae_ * layers(c_min_ + mean, top);
}

// Seen along F both tools are Q: this one touching the surface at its
// bottom CC, the previous one shifted by D across the feed to where it
// touches too, and the cusp is where their outlines meet between the
// contacts: the end X of the chord of Q parallel to D and as long (X and
// X - D both on its boundary), the lower of the two. That chord is the
// width level of the same Q seen in the frame turned about F to e' = D /
// |D| (N' normal to it): the groove with ae' = |D| and no stock level.
// - D: on the tangent plane (ae, 0). On the circle of curvature k the
//   previous pass touches at the arc s from CC, where the surface's normal
//   has turned by k s about F, so with the point of Q whose outward normal
//   is minus that one (its silhouette at phi_bottom - k s): D(s) = CC(s) -
//   that point, and s is where |D(s)| = ae (the pass tracker's ae is the
//   distance across the feed between the tools' positions).
// - The height: above CC on the tangent plane, radially above the circle
//   on a curved surface.
// - Rz: the cusp's height on the tangent plane (D = (ae, 0)); Ra:
//   plane_roughness.
RevolvedCusp Groove::cusp(const Tool& tool, double k, std::optional<double> contact_b) const {
  RevolvedCusp out;
  if (!(ae_ > 0)) return out;
  const double bottom_lo = boundary(c_min_, true).b, bottom_hi = boundary(c_min_, false).b;
  const double b_cc =
      contact_b ? std::clamp(*contact_b, bottom_lo, bottom_hi) : 0.5 * (bottom_lo + bottom_hi);
  // The chord's end X for the shift (db, dc): empty where no chord of Q
  // is that long (ae beyond the tools' reach, or a frame turned past the
  // horizontal).
  const auto meeting = [&](double db, double dc) -> std::optional<WidthLevel> {
    const double length = length_of(db, dc);
    const Vector3d along = (db * side_ + dc * normal_) / length;
    const Vector3d across = (db * normal_ - dc * side_) / length;
    if (!(across.z() > 0)) return std::nullopt;
    // No stock level in reach: ap beyond the feet by twice the tool's width.
    const double ap = std::max(c_foot_[0], c_foot_[1]) - c_min_ + 4 * radius_;
    const Groove turned(tool, feed_, across, along, ap, length);
    const WidthLevel level = turned.width_level();
    if (!(level.c < turned.c0_)) return std::nullopt;
    return level;
  };
  // On the tangent plane (the turned frame is this one): Rz and Ra.
  const std::optional<WidthLevel> flat = meeting(ae_, 0);
  if (!flat) return out;
  out.rz = flat->c - c_min_;
  out.ra = *out.rz > 0 ? plane_roughness(*flat) : 0.0;
  if (!(std::abs(k) > 1e-9 / radius_)) {
    out.height = out.rz;
    return out;
  }
  // D(s), this tool at the origin.
  const auto shift = [&](double s) {
    const auto [cos_ks, sin_ks] = cos_sin_small(k * s);
    const Vector3d p = silhouette(phi_bottom_ - k * s);
    return std::array<double, 2>{b_cc + sin_ks / k - side_.dot(p),
                                 c_min_ - (1 - cos_ks) / k - normal_.dot(p)};
  };
  const auto miss = [&](double s) {
    const auto [db, dc] = shift(s);
    return length_of(db, dc) - ae_;
  };
  // With its slope: D'(s) = (cos ks, -sin ks) + k (e.S', N.S') at phi_bottom - k s.
  const auto miss_and_slope = [&](double s) {
    const auto [db, dc] = shift(s);
    const auto [cos_ks, sin_ks] = cos_sin_small(k * s);
    const auto [cos_phi, sin_phi] = cos_sin(phi_bottom_ - k * s);
    const Vector3d tangent = silhouette_and_tangent(cos_phi, sin_phi).second;
    const double length = length_of(db, dc);
    const double d_db = cos_ks + k * side_.dot(tangent), d_dc = -sin_ks + k * normal_.dot(tangent);
    return std::pair{length - ae_, (db * d_db + dc * d_dc) / length};
  };
  // s from just beside CC (where a face seen edge-on may already reach
  // ae: the previous tool's face then covers CC, no cusp) out to where the
  // normal has turned a quarter turn (a previous pass beyond is none).
  // Just beside: the normal turned by 1e-10, as boundary() steps beside
  // the bottom (a face level within round-off, N_xy 1e-14, took the
  // previous tool's touching point from its middle for its end).
  const double tolerance = 1e-12 * radius_;
  const double s_lo = std::max(tolerance, 1e-10 / std::abs(k)), s_max = kPi / 2 / std::abs(k);
  const double g_lo = miss(s_lo);
  if (g_lo >= 0) {
    out.height = 0;
    return out;
  }
  double s_hi = std::min(ae_, s_max), g_hi = miss(s_hi);
  while (g_hi < 0 && s_hi < s_max) {
    s_hi = std::min(2 * s_hi, s_max);
    g_hi = miss(s_hi);
  }
  if (g_hi < 0) return out;  // the previous pass beyond the model's reach
  const double s = newton_root(miss_and_slope, s_lo, s_hi, g_lo, g_hi, tolerance);
  const auto [db, dc] = shift(s);
  const std::optional<WidthLevel> level = meeting(db, dc);
  if (!level) return out;
  // X, radially above the circle through CC, centre (b_cc, c_min - 1 / k).
  const Vector3d& x = level->right.p;
  const double from_centre = length_of(side_.dot(x) - b_cc, normal_.dot(x) - c_min_ + 1 / k);
  out.height = k > 0 ? from_centre - 1 / k : -1 / k - from_centre;
  return out;
}

}  // namespace vcpost::geometry::revolved
