// Contact, engagement and target spindle speed at each sample of the path:
// the per-point work of `vcpost post` and `vcpost report`.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string_view>

#include "geometry/diameter_policy.h"
#include "geometry/engagement.h"
#include "geometry/model.h"
#include "postproc/pipeline/pass_tracker.h"
#include "postproc/pipeline/path_normals.h"
#include "postproc/pipeline/path_sampler.h"

namespace vcpost::pipeline {

// Which working diameter sets the spindle speed: geometry's one rule.
using geometry::DiameterPolicy;

// Where the width of cut came from.
enum class AeSource {
  measured,    // from the neighbouring pass of the toolpath
  given,       // --ae (as the override, or where no neighbour was found)
  first_pass,  // no neighbour and no --ae: nothing removed beside this pass
};
std::string_view to_string(AeSource source);

// Where the depth of cut came from.
enum class ApSource : std::uint8_t {
  given,    // --ap (no stock model, or a tilted frame's point)
  stock,    // the in-process stock along the normal at the contact point
  clamped,  // the stock's, held just under the tool's diameter (the engine's limit)
  air,      // the stock has (next to) no material there: the tool cuts nothing
};
std::string_view to_string(ApSource source);

// The material still there before a section: its depth along a direction
// (an in-process stock, postproc/post/stock_timeline.h). Thread-safe reads.
class MaterialDepth {
 public:
  virtual ~MaterialDepth() = default;
  // The distance from p along the unit direction n to where the material
  // ends (0 where p is not in it), at most max_mm.
  virtual double depth_along(const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                             double max_mm) const = 0;
};

// The largest ap the engagement takes, as a share of the tool's diameter:
// at ap >= D the engine finds no rim (every edge of the end is in the stock).
inline constexpr double kMaxApShare = 0.999;

struct PointSettings {
  geometry::Tool tool = geometry::Tool::ball(10);  // any shape (tool_contact.h)
  double ap = 0.3;                                 // mm
  std::optional<double> ae;                        // mm; see ae_override
  bool ae_override = false;                        // use `ae` everywhere instead of measuring
  // The tip, or the tool frame's origin (tool_origin): a ball's centre, the
  // plane of a bull-nose's corner centres, a flat end mill's face.
  geometry::ClPoint cl_point = geometry::ClPoint::tip;
  double contact_tolerance = 0.01;  // mm: |distance error| counted as touching
  DiameterPolicy policy = DiameterPolicy::max;
  double vc = 120;  // nominal cutting speed, m/min
  // Whether results carry the cutting points (the report's d_cut); the
  // tangent policy computes them whatever this says.
  bool cutting_points = true;
};

struct PointResult {
  geometry::BallContact contact;
  Eigen::Vector3d feed = Eigen::Vector3d::Zero();  // F on the tangent plane (zero without contact)
  double ae = 0;
  AeSource ae_source = AeSource::first_pass;
  ApSource ap_source = ApSource::given;
  double ap = 0;  // the depth of cut the engagement took, mm (0 where it was not evaluated)
  geometry::Side side = geometry::Side::left;
  std::optional<geometry::Engagement> engagement;  // when the tool touches (or gouges)
  std::optional<double> d_ref;                     // the policy's diameter, mm
  // 1000 vc / (pi d_ref), rpm; +infinity where d_ref is 0 (the machine caps
  // it); empty where the tool does not cut (no contact, nothing engaged).
  std::optional<double> target_rpm;
  // Without a model: how the normal of the contact was found from the
  // toolpath (path_normals.h); empty where the contact is with the model.
  std::optional<NormalSource> normal_source;
};

// Evaluates the samples of one path in order (the pass tracker needs path
// order). Not thread-safe: one per path (or per chunk with its own tracker).
class PointEvaluator {
 public:
  PointEvaluator(const geometry::SurfaceModel& model, PointSettings settings);

  PointResult evaluate(const PathSample& sample);

  // evaluate() in its three stages, so the first and the last can run on
  // other threads: contact() and engage() are const and thread-safe (each
  // caller with its own hint); place() must see the samples in path order.
  // The hint only makes queries warm (answers agree within 1e-9 mm).
  geometry::BallContact contact(const PathSample& sample, geometry::ContactHint& hint) const;
  // Without a model: the contact the normal found from the toolpath gives
  // (path_normals.h), touching exactly: the tool's point facing the
  // surface along -n (a ball's centre - R n; a bull-nose's core circle
  // point towards -n, then rc along -n). Lifted (no target, like a link in
  // the air) where the normal was kept.
  geometry::BallContact contact(const PathSample& sample, const PathNormal& normal) const;
  // Feed on the tangent plane, the neighbouring pass, ae and side; leaves
  // the engagement empty (and the tool not cutting stays so).
  void place(const PathSample& sample, PointResult& result);
  // Without a model: as place(), ae measured to the earlier pass the
  // normals' read-ahead found beside the sample (path_normals.h), instead
  // of this evaluator's own pass tracker.
  void place(const PathSample& sample, PointResult& result, const EarlierPass& earlier) const;
  // Engagement, d_ref and target of a placed result that cuts.
  void engage(const PathSample& sample, PointResult& result) const;

  // The stock the section cuts (null: --ap everywhere): engage() then takes
  // ap at each untilted point as the material's depth along the normal at
  // the contact point; under `air_mm` of it the tool cuts nothing there.
  void set_material(const MaterialDepth* material, double air_mm) {
    material_ = material;
    air_mm_ = air_mm;
  }

  // Call after a rapid: the next contact point starts a new pass.
  void break_pass() { tracker_.break_pass(); }

  const PointSettings& settings() const { return settings_; }
  const geometry::ContactHint& hint() const { return hint_; }

 private:
  // The point the passes are followed by (place()).
  Eigen::Vector3d tracked(const PathSample& sample, const geometry::BallContact& contact) const;
  // ae, its source and the side from the earlier pass (or none).
  void set_ae(const std::optional<NeighbourPass>& neighbour, PointResult& out) const;
  const geometry::SurfaceModel& model_;
  PointSettings settings_;
  geometry::CuttingPointsWanted cutting_points_;  // decided once from settings_
  geometry::ContactHint hint_;
  PassTracker tracker_;
  bool had_contact_ = false;
  const geometry::RigidTransform* frame_ = nullptr;  // of the last placed sample
  const MaterialDepth* material_ = nullptr;
  double air_mm_ = 0;
};

}  // namespace vcpost::pipeline
