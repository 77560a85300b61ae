// Which working diameter sets the spindle speed, and the speed it asks for
// (docs/models.md, section 2): the one rule `vcpost deff`, `post` and
// `report` share.
#pragma once

#include <optional>
#include <string_view>

#include "geometry/engagement.h"

namespace vcpost::geometry {

enum class DiameterPolicy {
  max,      // D_max: no engaged edge point runs faster than vc (default)
  tangent,  // the paper's cutting point on the working side
  mean,     // D_mean, area-weighted over the engaged zone
};
std::string_view to_string(DiameterPolicy policy);
std::optional<DiameterPolicy> parse_diameter_policy(std::string_view text);

// The reference diameter d_ref under `policy`, mm: D_max; the tangent
// cutting point's diameter (the engagement must carry the cutting points);
// D_mean from `mean()`, called for that policy only (its quadrature costs
// more than the rest). Empty where nothing is engaged.
template <class MeanDiameter>
std::optional<double> reference_diameter(DiameterPolicy policy, const Engagement& engagement,
                                         MeanDiameter&& mean) {
  switch (policy) {
    case DiameterPolicy::max:
      return engagement.d_max;
    case DiameterPolicy::tangent:
      if (engagement.points && engagement.d_max) return engagement.points->cut.diameter;
      return std::nullopt;
    case DiameterPolicy::mean:
      return mean();
  }
  return std::nullopt;
}

// The spindle speed that gives vc at d_ref, rpm: 1000 vc / (pi d_ref), and
// +infinity at d_ref = 0 (the tool's axis cuts: no speed reaches vc there;
// the machine's maximum caps it).
double target_rpm(double vc_m_per_min, double d_ref_mm);

}  // namespace vcpost::geometry
