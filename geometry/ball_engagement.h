// Closed-form engagement of a ball-end mill (docs/models.md §2).
#pragma once

#include <optional>

#include "geometry/cut_frame.h"
#include "geometry/engagement.h"

namespace vcpost::geometry {

// REQUIRES: check.frame present (see check_cut). Fills d_max, d_min, the
// cutting points (when wanted) and shank_engaged / nothing_engaged into `out`.
void evaluate_ball(double radius, const CutSetup& setup, const CutCheck& check,
                   CuttingPointsWanted points, Engagement& out);

// Area-weighted mean of 2r over the engaged zone (ball and shank).
// REQUIRES: check.can_engage.
double ball_mean_diameter(double radius, const CutSetup& setup, const CutFrame& frame);

}  // namespace vcpost::geometry
