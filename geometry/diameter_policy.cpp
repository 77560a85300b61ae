#include "geometry/diameter_policy.h"

#include <limits>

namespace vcpost::geometry {

std::string_view to_string(DiameterPolicy policy) {
  switch (policy) {
    case DiameterPolicy::max:
      return "max";
    case DiameterPolicy::tangent:
      return "tangent";
    case DiameterPolicy::mean:
      return "mean";
  }
  return "?";
}

std::optional<DiameterPolicy> parse_diameter_policy(std::string_view text) {
  for (const DiameterPolicy policy :
       {DiameterPolicy::max, DiameterPolicy::tangent, DiameterPolicy::mean}) {
    if (text == to_string(policy)) return policy;
  }
  return std::nullopt;
}

double target_rpm(double vc_m_per_min, double d_ref_mm) {
  return d_ref_mm > 0 ? spindle_speed_for(vc_m_per_min, d_ref_mm)
                      : std::numeric_limits<double>::infinity();
}

}  // namespace vcpost::geometry
