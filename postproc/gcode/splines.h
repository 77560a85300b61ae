// LinuxCNC's G5 (cubic) and G5.1 (quadratic) splines in the XY plane as
// straight feed moves. rs274 hands the control a Bezier curve (NURBS_FEED
// with 4 or 3 control points, weights 1); vcpost follows it as a polyline
// whose chords stay within kSplineTolerance of the curve.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace vcpost::gcode {

// Largest distance (mm) between a spline and the polyline that replaces it.
inline constexpr double kSplineTolerance = 0.001;
// Chords of one spline at most: a spline whose control polygon spans a
// kilometre still ends within the tolerance's order; more would only be
// memory.
inline constexpr int kMaxSplineChords = 20000;

// The points after the first of the polyline for the Bezier curve with
// `control` points (3: quadratic, 4: cubic); the last is the curve's end.
// The chords are uniform in the parameter: with n of them, a curve of
// second derivative at most M departs from a chord by at most M / (8 n^2),
// so n is the least that keeps this within `tolerance` (at most
// kMaxSplineChords).
std::vector<Eigen::Vector2d> spline_polyline(const std::vector<Eigen::Vector2d>& control,
                                             double tolerance = kSplineTolerance);

// The Bezier curve with `control` points at parameter t in [0, 1] (de
// Casteljau).
Eigen::Vector2d bezier_point(const std::vector<Eigen::Vector2d>& control, double t);

}  // namespace vcpost::gcode
