#include "geometry/revolved_engagement.h"

#include <stdexcept>

namespace vcpost::geometry {

// Being written: until then non-ball tools are refused loudly.
Engagement evaluate_revolved_engagement(const Tool&, const CutSetup&) {
  throw std::logic_error("bull-nose and flat engagement not available yet");
}

std::optional<double> revolved_mean_diameter(const Tool&, const CutSetup&) {
  throw std::logic_error("bull-nose and flat engagement not available yet");
}

}  // namespace vcpost::geometry
