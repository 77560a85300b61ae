// The model offset by the allowance a CAM system left (stock to leave):
// the surface the tool actually touches (MODELS.md section 5,
// docs/models.md section 5). Positive: material left for a later pass;
// negative: the tool cuts into the finished surface (glue gaps, EDM spark
// gaps).
//
// A ball (or any tool with one value) touches the surface offset by s along
// its normal: the closest point of the offset surface to a query is CC + s N
// with the same normal N, its principal curvatures k / (1 + s k) in the
// same directions, its distance the base's less s. A bull-nose or flat end
// mill may have a radial value (the CAM enlarges the tool's side by it) and
// an axial one (it lowers the tool's bottom): the tool with radius R +
// radial, corner radius rc + axial, tip lowered by axial. Seen from the
// surface that is an offset by s(N) = axial + (radial - axial) |N_xy|
// along the normal (N_xy: the normal's part across the tool axis, +z):
// axial under the flat bottom, radial against the side, blended round the
// corner. Exact for equal values and wherever N is constant (planes); on a
// curved face with unequal values the offset's own normal tilts from N by
// about |radial - axial| times the curvature across the tool axis, which
// is left out.
//
// Where 1 + s k <= 0 for a principal curvature k (a convex radius smaller
// than a negative allowance, a concave one smaller than a positive one) the
// offset surface folds over itself: there is no smooth offset point, and
// the contact carries no curvatures (the engagement is then worked out as
// on a facet). A ball whose centre is closest to a concave point never
// meets the concave case (its radius plus s is at most 1/|k| there).
#pragma once

#include <memory>
#include <optional>

#include "geometry/model.h"

namespace vcpost::geometry {

// Stock to leave, mm: one value for every direction, or a radial and an
// axial one (bull-nose and flat end mills).
struct Allowance {
  double radial = 0, axial = 0;

  static Allowance uniform(double mm) { return {mm, mm}; }
  bool is_zero() const { return radial == 0 && axial == 0; }
  bool is_uniform() const { return radial == axial; }
  // The offset along a unit surface normal N (tool axis +z).
  double along(const Eigen::Vector3d& normal) const;
};

// The base model offset by `allowance`. Queries and hints pass through to
// the base (hints stay valid: faces and (u,v) are the base's). Bounds: the
// base's grown by the largest positive value. Thread safety as the base's.
class OffsetModel final : public SurfaceModel {
 public:
  // REQUIRES: base not null, allowance values finite.
  OffsetModel(std::shared_ptr<const SurfaceModel> base, const Allowance& allowance);

  std::optional<ModelContact> closest_point(const Eigen::Vector3d& point, double max_distance,
                                            ContactHint* hint) const override;
  Eigen::AlignedBox3d bounds() const override;
  int face_count() const override { return base_->face_count(); }
  bool faceted() const override { return base_->faceted(); }

  const Allowance& allowance() const { return allowance_; }

 private:
  std::shared_ptr<const SurfaceModel> base_;
  Allowance allowance_;
  double reach_;  // the largest |value|: how much farther the base may lie
};

}  // namespace vcpost::geometry
