// A model placed in the program's frame by a rigid transform: the part's
// model exported in its own frame (a VERICUT or hyperMILL set-up turns and
// lifts it), or a tilted working plane (3+2, one transform per frame).
//
// The transform maps model coordinates to program coordinates:
// p_program = rotation * p_model + shift. Units: mm and degrees in text,
// mm and radians in code.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "core/error.h"
#include "geometry/model.h"

namespace vcpost::geometry {

struct RigidTransform {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // orthonormal, det +1
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();         // mm

  Eigen::Vector3d apply(const Eigen::Vector3d& point) const { return rotation * point + shift; }
  // The inverse map: program coordinates to model coordinates.
  Eigen::Vector3d unapply(const Eigen::Vector3d& point) const {
    return rotation.transpose() * (point - shift);
  }
  // `next` applied after this one.
  RigidTransform then(const RigidTransform& next) const {
    return {next.rotation * rotation, next.rotation * shift + next.shift};
  }
  RigidTransform inverse() const { return {rotation.transpose(), -(rotation.transpose() * shift)}; }
  bool is_identity() const { return rotation == Eigen::Matrix3d::Identity() && shift.isZero(0); }
};

// A turn by `degrees` about the program frame's X (axis 0), Y (1) or Z (2),
// counter-clockwise seen from the axis' positive end (right-hand rule).
// Multiples of 90 degrees are exact (no round-off in the matrix).
RigidTransform turn_about(int axis, double degrees);

// How far a 4x4 matrix may be from a rigid one and still be taken as one
// (each entry of R^T R - I, and of the bottom row against 0 0 0 1): matrices
// typed with 6 decimals pass; the rotation is then made exactly orthonormal.
inline constexpr double kRigidTolerance = 1e-5;

// E4110: the text is not a list of steps; E4111: a matrix that scales,
// shears, mirrors or projects.
class TransformError : public vcpost::Error {
 public:
  TransformError(Code code, const std::string& message) : vcpost::Error(code, message) {}
};

// The rigid transform of a 4x4 matrix (row-major text order: r11 r12 r13
// x, r21 ... y, r31 ... z, 0 0 0 1). Throws TransformError (not_rigid) when
// it is not one within kRigidTolerance, or the shift reaches beyond
// kMaxReachMm.
RigidTransform rigid_from_matrix(const Eigen::Matrix4d& matrix);

// Parses `--model-transform` text: comma-separated steps applied to the
// model in the order written, each about the program frame's fixed axes:
//   rx=DEG, ry=DEG, rz=DEG   a turn about X, Y or Z (right-hand rule)
//   x=MM, y=MM, z=MM         a shift along X, Y or Z
//   matrix=m11,m12,...,m44   a whole 4x4 matrix, 16 numbers row by row
// e.g. "rz=-90" or "rx=180,rz=180,z=-22". Keys are case-insensitive;
// spaces around items are allowed. Throws TransformError.
RigidTransform parse_rigid_transform(std::string_view text);

// The steps of `transform` as text parse_rigid_transform reads back: the
// matrix form, or "identity".
std::string to_string(const RigidTransform& transform);

// The model `base` as seen after `placement`: every query is turned into the
// base's frame and every answer (point, normal, curvature directions, the
// hint's query point) back out; distances, curvatures, faces and (u,v) are
// unchanged, so hints stay valid. Bounds: the box of the base box's eight
// corners placed (exact for turns by multiples of 90 degrees, larger for
// others). Thread safety as the base's.
class TransformedModel final : public SurfaceModel {
 public:
  // REQUIRES: base not null.
  TransformedModel(std::shared_ptr<const SurfaceModel> base, const RigidTransform& placement);

  std::optional<ModelContact> closest_point(const Eigen::Vector3d& point, double max_distance,
                                            ContactHint* hint) const override;
  Eigen::AlignedBox3d bounds() const override;
  int face_count() const override { return base_->face_count(); }
  bool faceted() const override { return base_->faceted(); }

  const RigidTransform& placement() const { return placement_; }

 private:
  std::shared_ptr<const SurfaceModel> base_;
  RigidTransform placement_;
};

}  // namespace vcpost::geometry
