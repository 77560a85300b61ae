// An analytic dome and an exact drop-cutter raster over it, shared by the
// post and report tests: every figure of the job has a closed form there.
#pragma once

#include <string>

#include "geometry/analytic_surfaces.h"

namespace vcpost::testing {

// The ball radius the raster is written for (a 10 mm ball-end mill).
inline constexpr double dome_ball_radius = 5;

// The sphere of radius 40 about (0, 0, -20): tilts up to ~50 deg over
// |x|, |y| <= 25.
geometry::AnalyticModel dome();

// Zig-zag raster along x with `stepover` in y and `spacing` along x: tool
// tip points of the ball resting on the dome (its centre on the sphere of
// radius 45), with the program's spindle speed `spindle`.
std::string dome_raster(double stepover, double spacing, int spindle);

// The same raster for a bull-nose end mill of diameter D and corner radius
// rc resting on the dome: its core disc (radius R0 = D/2 - rc, rc above
// the tip) at distance 40 + rc from the sphere's centre.
std::string bull_nose_dome_raster(double stepover, double spacing, int spindle, double diameter,
                                  double corner_radius);

}  // namespace vcpost::testing
