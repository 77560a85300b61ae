// The engaged zone of a bull-nose or flat end mill fed parallel to its end
// face (F_z = 0: Z-level passes, rasters over floors): docs/models.md section
// 2's zone, whose area and mean working diameter then reduce to one
// integral along the tool's profile of closed-form terms.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace vcpost::geometry {

// One level cut, in the tool's frame: the axis along z, lengths in mm from
// the axis at the height of the corner's centre (the end face at z =
// -corner).
struct LevelCut {
  double flat_radius = 0;  // R0, the end face's radius (R for a flat mill)
  double corner = 0;       // rc, 0 for a flat mill
  double ae = 0;           // the previous pass lies ae along `side`
  double stock_level = 0;  // c0: the stock is N.P <= c0
  // Unit and normal to each other; feed level (its z is ignored).
  Eigen::Vector3d normal, side, feed;
  bool face_leads = true;  // whether the end face counts as leading
};

// The engaged points' least and greatest distance r from the axis and
// greatest z, running over the points met (add); r_min > r_max when
// nothing is engaged.
struct RadiusExtremes {
  double r_min = std::numeric_limits<double>::infinity();
  double r_max = -std::numeric_limits<double>::infinity();
  double z_max = -std::numeric_limits<double>::infinity();
  void add(double r, double z) {
    r_min = std::min(r_min, r);
    r_max = std::max(r_max, r);
    z_max = std::max(z_max, z);
  }
  void add(const Eigen::Vector3d& p) { add(std::sqrt(p.x() * p.x() + p.y() * p.y()), p.z()); }
};
RadiusExtremes level_extremes(const LevelCut& cut);

// docs/models.md's rim points for the cutting points: the rim's (the tool cut
// by the stock plane) points with the least and the greatest s = S0.P (S0
// = N x F; where the rim runs along F over the end face, the middle of
// that chord), and the fibres' front and back rim points at s_min + ae
// and s_max - ae, when those lie between (else empty).
struct LevelRim {
  Eigen::Vector3d low, high;
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> beside_low, beside_high;
};
LevelRim level_rim(const LevelCut& cut);

// The engaged zone's area (mm^2) and the integral of 2r over it (mm^3).
std::array<double, 2> level_area_and_moment(const LevelCut& cut);

}  // namespace vcpost::geometry
