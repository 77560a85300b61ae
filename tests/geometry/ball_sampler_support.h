// A brute-force evaluation of the ball's engaged zone, written from the
// definitions of MODELS.md section 2 in world coordinates and sharing no
// code with the engine: dense grids on the ball cap and the shank, each
// point tested for stock, leading side and the previous pass's cylinder.
#pragma once

#include <Eigen/Core>

namespace vcpost::testing {

struct SampledEngagement {
  bool any = false;    // some grid point is engaged
  bool shank = false;  // some shank grid point is engaged
  double d_max = 0, d_min = 0, d_mean = 0;
  double spacing = 0;      // largest distance between neighbouring grid points, mm
  Eigen::Vector3d p1, p2;  // rim points of smallest and largest s = S0.P
};

SampledEngagement sample_ball(double diameter, double ap, double ae, const Eigen::Vector3d& normal,
                              const Eigen::Vector3d& feed, bool previous_on_left, int resolution);

}  // namespace vcpost::testing
