#include "geometry/occt/brep_model.h"

#include <string>

#include "geometry/occt/brep_faces.h"

namespace vcpost::occt {

ModelError::ModelError(Code code, const std::string& path, const std::string& message)
    : vcpost::Error(code, format_diagnostic(code, {path}, message), {path}) {}

BrepModel::BrepModel(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
BrepModel::BrepModel(BrepModel&&) noexcept = default;
BrepModel& BrepModel::operator=(BrepModel&&) noexcept = default;
BrepModel::~BrepModel() = default;

std::optional<geometry::ModelContact> BrepModel::closest_point(const Eigen::Vector3d& point,
                                                               double max_distance,
                                                               geometry::ContactHint* hint) const {
  return impl_->query(point, max_distance, hint);
}

Eigen::AlignedBox3d BrepModel::bounds() const { return impl_->bounds; }
int BrepModel::face_count() const { return static_cast<int>(impl_->faces.size()); }
const StepInfo& BrepModel::info() const { return impl_->info; }

}  // namespace vcpost::occt
