// STEP models through OpenCASCADE, as a geometry::SurfaceModel.
//
// This header has no OpenCASCADE in it (geometry/occt/shape_model.h builds a
// model from an OCCT shape in process). Units: every length in mm whatever
// the STEP file declares (inch, metre, ...): OCCT's reader converts on
// transfer and the declared unit is reported in StepInfo.
//
// Queries: a BVH over a tessellation of the faces gives candidate faces and
// start points; Newton's method on the exact face surface refines, warm
// started from the hint's face and (u,v); the trim is checked on the face's
// boundary curves in (u,v), and a point outside it goes to the closest point
// of the face's edges (edge or vertex contact). Other faces are checked by
// the BVH with the tessellation's deflection as a safety margin, so the
// answer is the global closest point, up to one limitation: on each face
// Newton's method trusts the local minimum it converges to (from the hint,
// or from the nearest tessellation triangle). Non-rational B-spline faces
// are evaluated as one polynomial per knot span (power basis about the
// span's centre), built at load.
//
// Thread safety: everything a query reads is built at load and never
// changed (no caches filled on demand, no mutable members, no OCCT
// adaptors with their own caches: surfaces and curves are evaluated through
// Geom_* objects, whose evaluation in OCCT 7.6 writes no shared state).
#pragma once

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/error.h"
#include "geometry/model.h"

namespace vcpost::occt {

// Thrown by the loaders; what() is "<path>: error[E41xx]: <message>".
class ModelError : public vcpost::Error {
 public:
  ModelError(Code code, const std::string& path, const std::string& message);
};

// The farthest a model's point may lie from the origin, mm (the part's
// reach, geometry/model.h). Beyond it the model is refused (E4107) before
// meshing.
inline constexpr double kMaxModelReachMm = geometry::kMaxReachMm;

struct BrepOptions {
  // Largest chord deviation of the tessellation that feeds the BVH, mm;
  // <= 0: 1/1000 of the model's box diagonal, within [0.002, 0.2] mm (and
  // at least 1/20000 of it, which only models over 4 m reach). It
  // only steers the search: answers are exact on the faces.
  double deflection = 0;
  // A model without solids (open faces or shells, as surface models often
  // are) does not say where its material is. true: each such face is
  // oriented so that its mean normal points up (+z), the side a 3-axis
  // tool comes from; false: the faces' own orientation is kept.
  bool orient_open_faces_up = true;
};

struct StepInfo {
  std::string length_unit;  // as declared by the file, e.g. "MILLIMETRE", "INCH"; empty if none
  int faces = 0;
  int triangles = 0;
  double deflection = 0;  // mm, used for the tessellation
};

class BrepModel final : public geometry::SurfaceModel {
 public:
  // Reads a STEP file (AP203/AP214/AP242). Throws ModelError.
  static BrepModel load_step(const std::filesystem::path& path, const BrepOptions& options = {});

  BrepModel(BrepModel&&) noexcept;
  BrepModel& operator=(BrepModel&&) noexcept;
  ~BrepModel() override;

  std::optional<geometry::ModelContact> closest_point(const Eigen::Vector3d& point,
                                                      double max_distance,
                                                      geometry::ContactHint* hint) const override;
  Eigen::AlignedBox3d bounds() const override;
  int face_count() const override;

  const StepInfo& info() const;

  struct Impl;
  explicit BrepModel(std::unique_ptr<Impl> impl);

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace vcpost::occt
