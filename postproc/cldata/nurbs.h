// B-spline (NURBS) curves of CL data and their conversion to straight lines
// within a chordal tolerance.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace vcpost::cldata {

// A clamped B-spline of any degree, rational when weights differ from 1.
// Control points are homogeneous: (w*x, w*y, w*z, w), mm.
struct BSpline {
  int degree = 3;
  std::vector<double> knots;             // full vector: control.size() + degree + 1 values
  std::vector<Eigen::Vector4d> control;  // weights > 0
};

// The curve of an NX CLSF NURBS/ record: it starts at the current tool
// position `start` (the first control point), continues through the CNTRL/
// points (x,y,z or x,y,z,w), and KNOT/ lists the parameter at the end of each
// polynomial span (the knots at 0 are not written; the last is the end,
// usually 1). The degree follows from the counts: 1 + cntrl - spans (3 in
// every NX file seen). Returns an empty optional and sets `error` when the
// data do not make a valid curve (degree < 1 or > 9, knots not increasing,
// weights <= 0, a CNTRL point beyond geometry::kMaxReachMm on an axis).
std::optional<BSpline> nx_nurbs(const Eigen::Vector3d& start, std::span<const double> span_ends,
                                std::span<const Eigen::Vector4d> cntrl, std::string& error);

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

}  // namespace vcpost::cldata
