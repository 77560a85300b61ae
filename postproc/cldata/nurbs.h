// The NURBS curves of CL data: an NX CLSF NURBS/ record as a B-spline
// (program/bspline.h evaluates and flattens it).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>

#include "postproc/program/bspline.h"

namespace vcpost::cldata {

using program::BSpline;
using program::evaluate;
using program::flatten;

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

}  // namespace vcpost::cldata
