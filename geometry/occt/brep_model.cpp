#include "geometry/occt/brep_model.h"

#include <string>

#include "geometry/occt/brep_faces.h"

namespace vcpost::occt {

// The enumerators are the codes' numbers: the id is the table's own.
std::string_view code_of(ModelErrorCode code) {
  return code_info("E" + std::to_string(static_cast<int>(code))).id;
}

ModelError::ModelError(ModelErrorCode code, const std::string& path, const std::string& message)
    : vcpost::Error(code_of(code), format_diagnostic(code_of(code), {path}, message), {path}),
      code_(code) {}

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
