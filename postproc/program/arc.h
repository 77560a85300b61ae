// Geometry of an ArcFeed event: plane axes, swept angle, length and points
// along it, so that later stages can sample arcs without knowing G-code.
#pragma once

#include <Eigen/Core>
#include <array>

#include "postproc/program/events.h"

namespace vcpost::program {

// Indices (0 = X, 1 = Y, 2 = Z) of the plane's first and second in-plane
// axes and its normal axis, in rs274's order: XY -> (X, Y, Z),
// XZ -> (Z, X, Y), YZ -> (Y, Z, X). Rotation is counted counterclockwise
// from first towards second.
std::array<int, 3> plane_axes(Plane plane);

// Signed swept angle in radians: positive counterclockwise (rotation > 0).
// start == end (in the plane) is a full turn; each extra turn of
// |rotation| adds 2*pi. Never zero.
double arc_sweep(const ArcFeed& arc);

// Length in mm of the (helical) path.
double arc_length(const ArcFeed& arc);

// The point at parameter u in [0, 1] (0 = start, 1 = end); angle, radius
// and axis coordinate all vary linearly in u (the radius so that a start
// and end radius that differ within tolerance still join exactly).
Eigen::Vector3d arc_point(const ArcFeed& arc, double u);

}  // namespace vcpost::program
