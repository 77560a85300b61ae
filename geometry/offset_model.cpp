#include "geometry/offset_model.h"

#include <algorithm>
#include <cmath>

namespace vcpost::geometry {
namespace {

// Below this 1 + s k the offset's curvature 1/(1/k + s) is no longer a
// number worth handing on (a radius under 1e-9 of the allowance's scale).
constexpr double kFoldMargin = 1e-9;

}  // namespace

double Allowance::along(const Eigen::Vector3d& normal) const {
  if (is_uniform()) return axial;
  const double across = std::min(1.0, normal.head<2>().norm());
  return axial + (radial - axial) * across;
}

OffsetModel::OffsetModel(std::shared_ptr<const SurfaceModel> base, const Allowance& allowance)
    : base_(std::move(base)),
      allowance_(allowance),
      reach_(std::max(std::abs(allowance.radial), std::abs(allowance.axial))) {}

std::optional<ModelContact> OffsetModel::closest_point(const Eigen::Vector3d& point,
                                                       double max_distance,
                                                       ContactHint* hint) const {
  // The offset surface lies within reach_ of the base: any of its points
  // within max_distance has its base point within max_distance + reach_.
  std::optional<ModelContact> contact = base_->closest_point(point, max_distance + reach_, hint);
  if (!contact) return contact;
  const double s = allowance_.along(contact->normal);
  // Signed: the query behind the base surface (in the material) is negative.
  const double side = (point - contact->point).dot(contact->normal) < 0 ? -1.0 : 1.0;
  const double distance = std::abs(side * contact->distance - s);
  if (!(distance <= max_distance)) return std::nullopt;
  contact->point += s * contact->normal;
  contact->distance = distance;
  if (contact->curvature) {
    PrincipalCurvatures& c = *contact->curvature;
    const double fold1 = 1 + s * c.k1, fold2 = 1 + s * c.k2;
    if (fold1 <= kFoldMargin || fold2 <= kFoldMargin) {
      contact->curvature.reset();  // the offset folds over here: no smooth point
    } else {
      c.k1 /= fold1;
      c.k2 /= fold2;
      // k/(1 + s k) keeps the order of k1 >= k2 where both folds are positive.
    }
  }
  return contact;
}

Eigen::AlignedBox3d OffsetModel::bounds() const {
  Eigen::AlignedBox3d box = base_->bounds();
  const double grow = std::max({allowance_.radial, allowance_.axial, 0.0});
  if (!box.isEmpty() && grow > 0) {
    box.min().array() -= grow;
    box.max().array() += grow;
  }
  return box;
}

}  // namespace vcpost::geometry
