// Engagement of the bull-nose and flat end mills (docs/models.md §2): the
// frame and degenerate set-ups, the Mgherony-Miko cutting points, and the
// entry points of revolved_engagement.h over the groove
// (revolved_groove.h) and its parts (revolved_extremes.cpp,
// revolved_means.cpp, revolved_cusp.cpp).
#include "geometry/revolved_engagement.h"

#include "geometry/revolved_groove.h"

namespace vcpost::geometry {
namespace {

using Eigen::Vector3d;
using revolved::Groove;
using revolved::length_of;

struct Prepared {
  Engagement out;
  std::optional<Groove> groove;
  double ae = 0;
};

// Frame and degenerate-input flags, as evaluate_engagement documents them.
Prepared prepare(const Tool& tool, const CutSetup& setup) {
  Prepared prepared;
  Engagement& out = prepared.out;
  if (!(setup.ap > 0)) out.flags.set(EngagementFlag::zero_ap);
  if (!(setup.ae > 0)) out.flags.set(EngagementFlag::zero_ae);
  if (setup.ap >= tool.diameter) out.flags.set(EngagementFlag::ap_exceeds_d);
  const double n_length = setup.normal.norm();
  if (!(n_length > 0) || !(setup.normal.z() / n_length > 0)) {
    out.flags.set(EngagementFlag::undercut);
  } else {
    const Vector3d normal = setup.normal / n_length;
    const Vector3d tangent = setup.feed - setup.feed.dot(normal) * normal;
    if (!(tangent.norm() > 1e-9 * setup.feed.norm())) {
      out.flags.set(EngagementFlag::feed_along_normal);
    } else {
      out.normal = normal;
      out.feed_dir = tangent.normalized();
      out.side_dir = normal.cross(out.feed_dir);
    }
  }
  const std::uint32_t fatal = static_cast<std::uint32_t>(EngagementFlag::zero_ap) |
                              static_cast<std::uint32_t>(EngagementFlag::ap_exceeds_d) |
                              static_cast<std::uint32_t>(EngagementFlag::undercut) |
                              static_cast<std::uint32_t>(EngagementFlag::feed_along_normal);
  if ((out.flags.bits & fatal) == 0) {
    // With ae = 0 the rim still exists: build the groove with ae = 0 for the points.
    const double sign = setup.side == Side::left ? 1.0 : -1.0;
    prepared.ae = std::max(0.0, setup.ae);
    prepared.groove.emplace(tool, out.feed_dir, out.normal, sign * out.side_dir, setup.ap,
                            prepared.ae);
  }
  return prepared;
}

CuttingPoint cutting_point(const Vector3d& p) { return {p, 2 * length_of(p.x(), p.y())}; }

// The Mgherony-Miko points on the rim c = c0, in S0 = side_dir coordinates.
CuttingPoints cutting_points(const Groove& groove, const Engagement& out, Side side, double ae) {
  const bool left = side == Side::left;
  using Fibre = std::optional<std::pair<Vector3d, Vector3d>>;  // front and back
  Vector3d low, high;           // the rim points of least and greatest s
  std::array<Fibre, 2> primes;  // the fibres at s_min + ae and s_max - ae
  if (groove.edge_on()) {
    const LevelRim rim = level_rim(groove.level_cut());
    std::tie(low, high, primes[0], primes[1]) =
        std::tuple{rim.low, rim.high, rim.beside_low, rim.beside_high};
  } else {
    // e = +S0 when left: the smallest s is the left boundary; else the right.
    low = groove.top(left).p;
    high = groove.top(!left).p;
    const double s_min = out.side_dir.dot(low), s_max = out.side_dir.dot(high);
    // The primes' fibres beside the low and the high top (b = bL + ae
    // beside the left top, bR - ae beside the right one); outside (s_min,
    // s_max) there are none.
    if (ae > 0 && s_min + ae < s_max) {
      const auto beside = [&](bool left_top) {
        return left_top ? groove.inner_top_fibre(false)
                        : groove.fibre_beside(groove.top(false), -ae, false);
      };
      primes = {beside(left), beside(!left)};
    }
  }
  CuttingPoints points;
  points.p1 = cutting_point(low);
  points.p2 = cutting_point(high);
  // Without a fibre the far rim point stands for both primes.
  const std::array<Vector3d, 2> fallback{high, low};
  std::array<std::pair<CuttingPoint, CuttingPoint>, 2> pairs;
  for (std::size_t i = 0; i < 2; ++i) {
    pairs[i] = primes[i]
                   ? std::pair{cutting_point(primes[i]->first), cutting_point(primes[i]->second)}
                   : std::pair{cutting_point(fallback[i]), cutting_point(fallback[i])};
  }
  std::tie(points.p1a, points.p1b) = pairs[0];
  std::tie(points.p2a, points.p2b) = pairs[1];
  points.cut = left ? points.p1 : points.p2;
  return points;
}

}  // namespace

Engagement evaluate_revolved_engagement(const Tool& tool, const CutSetup& setup,
                                        CuttingPointsWanted points) {
  Prepared prepared = prepare(tool, setup);
  Engagement& out = prepared.out;
  if (!prepared.groove) {
    out.flags.set(EngagementFlag::nothing_engaged);
    return out;
  }
  const Groove& groove = *prepared.groove;
  if (points == CuttingPointsWanted::yes)
    out.points = cutting_points(groove, out, setup.side, prepared.ae);
  if (!(prepared.ae > 0)) {
    out.flags.set(EngagementFlag::nothing_engaged);
    return out;
  }
  const RadiusExtremes extremes = groove.edge_on() ? groove.level_extremes() : groove.extremes();
  if (!(extremes.r_max >= extremes.r_min)) {
    out.flags.set(EngagementFlag::nothing_engaged);
    return out;
  }
  out.d_min = 2 * extremes.r_min;
  out.d_max = 2 * extremes.r_max;
  if (extremes.z_max > 1e-9 * groove.radius()) {
    // The shank's points are at r = R up to round-off of their position.
    out.flags.set(EngagementFlag::shank_engaged);
    out.d_max = tool.diameter;
  }
  return out;
}

RevolvedCusp revolved_cusp(const Tool& tool, const CutSetup& setup, double curvature_across,
                           const std::optional<Eigen::Vector3d>& contact_offset) {
  // A contact inside the end face: the surface touches the face's plane
  // there, its normal is the axis (a crest's model normal may stand off it
  // by the contact's round-off, 1e-14..5e-10, which tilted the face and
  // moved the contact to its edge: cusps of 2-400 um on the wavy sample's
  // crests).
  CutSetup level = setup;
  // (The face: radius R0, rc below the frame's origin; R and 0 for a flat mill.)
  const double slack = 1e-6 * tool.radius();
  if (contact_offset && std::abs(contact_offset->z() + tool.corner_radius) <= slack &&
      length_of(contact_offset->x(), contact_offset->y()) < tool.flat_radius() - slack) {
    level.normal = Vector3d::UnitZ();
  }
  const Prepared prepared = prepare(tool, level);
  if (!prepared.groove) return {};
  const Groove& groove = *prepared.groove;
  std::optional<double> contact_b;
  if (contact_offset) contact_b = groove.side().dot(*contact_offset);
  return groove.cusp(tool, curvature_across, contact_b);
}

std::optional<double> revolved_mean_diameter(const Tool& tool, const CutSetup& setup) {
  const Prepared prepared = prepare(tool, setup);
  if (!prepared.groove || !(prepared.ae > 0)) return std::nullopt;
  if (tool.kind == ToolKind::bull_nose) {
    const Groove& groove = *prepared.groove;
    switch (groove.mean_route()) {
      case Groove::MeanRoute::boundary:
        return groove.mean_over_boundary(1e-5, 16);
      case Groove::MeanRoute::fine_boundary:
        return groove.mean_over_boundary(1e-6, 32);
      case Groove::MeanRoute::level:
        return groove.mean_when_level();
    }
  }
  // The flat mill: along the profile when level, else circle by circle.
  if (prepared.groove->mean_route() == Groove::MeanRoute::level)
    return prepared.groove->mean_when_level();
  return prepared.groove->mean_diameter();
}

}  // namespace vcpost::geometry
