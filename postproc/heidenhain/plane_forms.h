// The rotations of PLANE PROJECTED, PLANE POINTS and PLANE AXIAL (the other
// forms are program/working_frame.h's), as a WorkingFrame's R: its columns
// the tilted x, y, z in the untilted frame. Angles in degrees.
#pragma once

#include <Eigen/Core>
#include <optional>

namespace vcpost::heidenhain {

// PROJECTED PROPR PROMIN ROT: the plane through the traces of angle PROPR
// in the ZX plane (turned about Y) and PROMIN in the YZ plane (turned about
// X), the right-hand rule giving the sign as for SPATIAL's SPB and SPA (one
// angle alone gives the same frame as SPATIAL with it: assumed, see
// docs/heidenhain.md); x along the ZX trace, then turned by ROT about the
// new z. Empty when the traces are parallel (both angles +-90).
std::optional<Eigen::Matrix3d> projected_angles(double principal, double minor, double rot);

// POINTS: x from P1 to P2, z by the right-hand rule from (P2 - P1) x
// (P3 - P1). Empty when the points lie on one line.
std::optional<Eigen::Matrix3d> plane_through(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                                             const Eigen::Vector3d& p3);

}  // namespace vcpost::heidenhain
