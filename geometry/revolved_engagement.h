// Engagement of the bull-nose and flat end mills (the ball has its own
// closed form in engagement.cpp). Same definitions and outputs as
// evaluate_engagement / engaged_mean_diameter in geometry/engagement.h.
#pragma once

#include <optional>

#include "geometry/engagement.h"

namespace vcpost::geometry {

// REQUIRES: tool.kind is bull_nose or flat, setup as for evaluate_engagement.
Engagement evaluate_revolved_engagement(const Tool& tool, const CutSetup& setup,
                                        CuttingPointsWanted points = CuttingPointsWanted::yes);
std::optional<double> revolved_mean_diameter(const Tool& tool, const CutSetup& setup);

// The cusp and the transverse roughness a bull-nose or flat end mill
// leaves between this pass and the previous one (docs/models.md §3, the
// ball's construction for any revolved tool in 3 axes): seen along the
// feed the tool is its profile Q, the previous pass the same profile
// shifted across the feed to where it touches the surface, and the cusp is
// where the two meet. All in mm; empty where the profiles do not meet (ae
// beyond the tool's width) or the set-up is degenerate (evaluate_engagement's
// fatal flags, ae = 0).
struct RevolvedCusp {
  // Above the surface, whose section across the feed is a circle of
  // signed curvature curvature_across (1/mm, convex > 0; 0 the tangent
  // plane) through the contact point, measured along its radius; the
  // previous pass touches it at the arc where the tools' positions are ae
  // apart across the feed.
  std::optional<double> height;
  // Of the profile on the tangent plane, repeating every ae: Rz its peak
  // to valley (the cusp on the plane), Ra its mean deviation from its mean
  // line (by quadrature to a relative 1e-8).
  std::optional<double> ra, rz;
};
// contact_offset: the contact point less the tool frame's origin (tool.h),
// where the model gave it: it places the contact on a flat face seen
// edge-on (a level surface under the face); empty, the bottom's middle.
// REQUIRES: as evaluate_revolved_engagement.
RevolvedCusp revolved_cusp(const Tool& tool, const CutSetup& setup, double curvature_across,
                           const std::optional<Eigen::Vector3d>& contact_offset = std::nullopt);

}  // namespace vcpost::geometry
