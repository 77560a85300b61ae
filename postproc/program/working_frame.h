// The rotations of the controls' tilted working planes (3+2), as the
// rotation R of a WorkingFrame (events.h): its columns are the tilted
// frame's x, y and z axes in the untilted one. Angles in degrees, turns by
// the right-hand rule; a multiple of 90 degrees gives an exact matrix.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

namespace vcpost::program {

// A turn about the fixed X (axis 0), Y (1) or Z (2).
Eigen::Matrix3d turn_about(int axis, double degrees);

// Heidenhain PLANE SPATIAL SPA SPB SPC (and CYCL DEF 19 A B C): turns about
// the machine's fixed X, then Y, then Z: Rz(c) Ry(b) Rx(a).
Eigen::Matrix3d spatial_angles(double a, double b, double c);

// Euler angles Z-X'-Z'': precession about Z, nutation about the turned X,
// rotation about the twice-turned Z: Rz(first) Rx(second) Rz(third).
// Heidenhain PLANE EULER EULPR EULNU EULROT; Fanuc G68.2 I J K.
Eigen::Matrix3d euler_zxz(double first, double second, double third);

// The angles that give `r` (a rotation), in degrees, in (-180, 180]:
// euler_zxz's (first, second, third), the second in [0, 180], and
// spatial_angles' (a, b, c), b in [-90, 90]. Where the first and third turn
// share an axis (second 0 or 180; b +-90) the third (a) is 0.
Eigen::Vector3d euler_zxz_of(const Eigen::Matrix3d& r);
Eigen::Vector3d spatial_angles_of(const Eigen::Matrix3d& r);

// The frame whose z is `normal` and whose x is `base` made perpendicular to
// it (Heidenhain PLANE VECTOR BX BY BZ NX NY NZ: the control corrects the
// base vector the same way). Empty when either is zero or they are parallel.
std::optional<Eigen::Matrix3d> frame_from_vectors(const Eigen::Vector3d& base,
                                                  const Eigen::Vector3d& normal);

}  // namespace vcpost::program
