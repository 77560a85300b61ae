// Analytic surface patches with closed-form closest points, and a model made
// of them: exact answers for tests, samples and the generator's truth.
//
// Units: mm and radians. Axes and reference directions must be unit vectors
// and, where two are given, perpendicular (not checked). Every patch is one
// face.
// `material_inside` tells which side is the material: the normal of the
// contact points away from it (a solid ball: true; a bowl-shaped mould: false).
#pragma once

#include <Eigen/Core>
#include <variant>
#include <vector>

#include "geometry/model.h"

namespace vcpost::geometry {

// The rectangle origin + x*u_axis + y*v_axis, x in [u_min, u_max], y in
// [v_min, v_max]; normal u_axis x v_axis (the material is behind it).
// (u,v) of a contact = (x, y).
struct PlanePatch {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d u_axis = Eigen::Vector3d::UnitX(), v_axis = Eigen::Vector3d::UnitY();
  double u_min = -1, u_max = 1, v_min = -1, v_max = 1;
};

// The part of the sphere |P - center| = radius within max_polar of `pole`
// (max_polar >= pi: the whole sphere). (u,v) = (azimuth about the pole from
// `reference`, polar angle from the pole).
struct SpherePatch {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 1;
  Eigen::Vector3d pole = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d reference = Eigen::Vector3d::UnitX();  // perpendicular to pole
  double max_polar = 4;                                  // rad
  bool material_inside = true;
};

// Points origin + h*axis + radius*(cos a * reference + sin a * (axis x
// reference)), h in [h_min, h_max], a in [angle_min, angle_max] (a span of
// 2 pi or more: the whole circle). (u,v) = (a, h).
struct CylinderPatch {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d reference = Eigen::Vector3d::UnitX();  // perpendicular to axis
  double radius = 1;
  double h_min = -1, h_max = 1;
  double angle_min = 0, angle_max = 7;  // rad
  bool material_inside = true;
};

// The whole torus center + (major + minor*cos v)*e(u) + minor*sin v*axis,
// e(u) = cos u*reference + sin u*(axis x reference). REQUIRES major > minor.
struct TorusSurface {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d reference = Eigen::Vector3d::UnitX();
  double major = 2, minor = 1;
  bool material_inside = true;
};

using AnalyticSurface = std::variant<PlanePatch, SpherePatch, CylinderPatch, TorusSurface>;

// The exact closest point of one patch to `point` (face index 0), with its
// normal and principal curvatures. Ties (a point on an axis) pick any one.
ModelContact closest_point_on(const AnalyticSurface& surface, const Eigen::Vector3d& point);

// A box holding the patch (not necessarily tight), mm.
Eigen::AlignedBox3d bounds_of(const AnalyticSurface& surface);

// A model made of analytic patches; face i is surfaces[i]. Queries are
// exact and cost one closed-form evaluation per face (no index: meant for
// a handful of faces). Ties between faces pick the lowest index.
class AnalyticModel final : public SurfaceModel {
 public:
  explicit AnalyticModel(std::vector<AnalyticSurface> surfaces);

  std::optional<ModelContact> closest_point(const Eigen::Vector3d& point, double max_distance,
                                            ContactHint* hint) const override;
  Eigen::AlignedBox3d bounds() const override;
  int face_count() const override { return static_cast<int>(surfaces_.size()); }

  const std::vector<AnalyticSurface>& surfaces() const { return surfaces_; }

 private:
  std::vector<AnalyticSurface> surfaces_;
};

}  // namespace vcpost::geometry
