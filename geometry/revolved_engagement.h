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

}  // namespace vcpost::geometry
