#include "postproc/heidenhain/plane_forms.h"

#include "postproc/program/working_frame.h"

namespace vcpost::heidenhain {

std::optional<Eigen::Matrix3d> projected_angles(double principal, double minor, double rot) {
  const Eigen::Vector3d x = program::turn_about(1, principal) * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d v = program::turn_about(0, minor) * Eigen::Vector3d::UnitY();
  const Eigen::Vector3d normal = x.cross(v);
  if (normal.norm() < 1e-9) return std::nullopt;
  const auto frame = program::frame_from_vectors(x, normal);
  if (!frame) return std::nullopt;
  return Eigen::Matrix3d(*frame * program::turn_about(2, rot));
}

std::optional<Eigen::Matrix3d> plane_through(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                                             const Eigen::Vector3d& p3) {
  const Eigen::Vector3d x = p2 - p1;
  const Eigen::Vector3d normal = x.cross(p3 - p1);
  if (normal.norm() < 1e-9 * std::max(1.0, x.squaredNorm())) return std::nullopt;
  return program::frame_from_vectors(x, normal);
}

}  // namespace vcpost::heidenhain
