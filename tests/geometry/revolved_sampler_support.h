// A brute-force evaluation of the bull-nose and flat end mills' engaged
// zone, written from the definitions of MODELS.md section 2 in the tool
// frame and sharing no code with the engine: dense grids on the flat face,
// the torus corner and the shank, each grid point tested for the stock
// layer, the leading side and the previous pass (the swept volume tested by
// minimising over the sweep parameter), then the extreme points refined by
// zooming the grid around them.
#pragma once

#include <Eigen/Core>

namespace vcpost::testing {

struct RevolvedSample {
  bool any = false;    // some grid point is engaged
  bool shank = false;  // some shank point above z = 0 is engaged
  double d_max = 0, d_min = 0, d_mean = 0;
  double spacing = 0;  // largest distance between neighbouring coarse grid points, mm
  double c0 = 0;       // the stock plane's level N.P, mm
  Eigen::Vector3d p_min = Eigen::Vector3d::Zero(), p_max = Eigen::Vector3d::Zero();  // where
};

// corner_radius = 0 gives the flat end mill. `resolution` = grid cells per
// quarter turn and per radius (a few dozen is plenty with the zoom).
RevolvedSample sample_revolved(double diameter, double corner_radius, double ap, double ae,
                               const Eigen::Vector3d& normal, const Eigen::Vector3d& feed,
                               bool previous_on_left, int resolution);

// The area-weighted mean of 2r by circles: on each horizontal circle of
// the tool (face, corner, shank: `circles` of each, midpoint rule) r is
// constant, and the engaged angles are found on `cells` cells per turn with
// bisection to 1e-12 rad where the definitions' test changes. 0 when
// nothing is engaged.
double mean_by_circles(double diameter, double corner_radius, double ap, double ae,
                       const Eigen::Vector3d& normal, const Eigen::Vector3d& feed,
                       bool previous_on_left, int circles, int cells);

// Whether tool point p lies strictly inside the volume the tool sweeps along
// the line through `offset` parallel to `feed` (unit).
bool inside_sweep(double diameter, double corner_radius, const Eigen::Vector3d& p,
                  const Eigen::Vector3d& offset, const Eigen::Vector3d& feed);

}  // namespace vcpost::testing
