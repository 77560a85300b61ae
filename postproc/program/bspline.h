// Rational B-spline curves (NURBS) and their conversion to straight lines
// within a chordal tolerance: the curves of CL data (cldata/nurbs.h) and of
// LinuxCNC's G5.2/G5.3 (gcode/nurbs.h).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace vcpost::program {

// A clamped B-spline of any degree, rational when weights differ from 1.
// Control points are homogeneous: (w*x, w*y, w*z, w), mm.
struct BSpline {
  int degree = 3;
  std::vector<double> knots;             // full vector: control.size() + degree + 1 values
  std::vector<Eigen::Vector4d> control;  // weights > 0
};

// The curve at parameter u (de Boor), projected to 3-D.
Eigen::Vector3d evaluate(const BSpline& curve, double u);

// Appends to `out` the end points of straight segments that follow the
// curve from its start (not appended) to its end (appended) such that no
// point of the curve is farther than `tolerance` (mm, > 0) from the polyline.
// The bound is rigorous: each span is split into Bezier pieces until their
// control polygon lies within `tolerance` of the chord (convex hull property,
// positive weights). Returns false, with `out` partly filled, when more than
// max_points would be needed (absurd coordinates or tolerance).
bool flatten(const BSpline& curve, double tolerance, std::vector<Eigen::Vector3d>& out,
             std::size_t max_points = 1'000'000);

}  // namespace vcpost::program
