// The facet normal of a mesh triangle, for the index's build and its queries.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vcpost::mesh {

// Unit normal of the triangle a, b, c (counterclockwise seen from outside);
// +z for a degenerate one. The one expression every user of a facet normal
// goes through, so they agree bit for bit.
inline Eigen::Vector3d unit_normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double len = n.norm();
  return len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::UnitZ();
}

}  // namespace vcpost::mesh
