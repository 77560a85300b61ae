// A reference for D_max and D_min of the bull-nose and flat end mills,
// written from the definitions of MODELS.md section 2 and sharing no code
// with the engine (geometry/revolved_engagement.cpp) or the grid sampler
// (revolved_sampler_support.h), precise to about 1e-9 mm.
//
// r is constant on every horizontal circle of the tool, and grows (weakly)
// along the stack of circles: face (rho 0..R0), corner (psi 0..pi/2), shank
// (z from 0 up to the stock). So D_max = 2 r at the highest circle that
// holds an engaged point and D_min = 2 r at the lowest: a 1-D search over
// the stack for the level where "some engaged point on this circle"
// switches. On a circle the stock and the leading side are arcs in closed
// form; on them the previous pass is tested by its definition (the least,
// over the sweep line, of a convex function that is negative exactly inside
// the tool), sampled densely and every sampled local maximum refined by
// golden section. The stack is walked on a grid from the end inwards (every
// sampled local maximum between levels refined the same way: an engaged
// sliver between grid levels), and the switch found by bisection to 1e-15
// of a piece, each level first searched next to the angle engaged on the
// last (near the end the engaged arc is far narrower than the samples).
// Checked against the ball's closed form (rc = R) to 2e-12 mm.
#pragma once

#include <Eigen/Core>

namespace vcpost::testing {

struct ReferenceResolution {
  int levels = 48;   // grid levels per piece of the stack
  int angles = 128;  // samples per circle
};

struct ReferenceExtremes {
  bool any = false;    // some edge point is engaged
  bool shank = false;  // an engaged shank point above z = 0 (then d_max = D)
  double d_max = 0, d_min = 0;
};

// corner_radius = 0 gives the flat end mill.
ReferenceExtremes reference_extremes(double diameter, double corner_radius, double ap, double ae,
                                     const Eigen::Vector3d& normal, const Eigen::Vector3d& feed,
                                     bool previous_on_left, ReferenceResolution resolution = {});

}  // namespace vcpost::testing
