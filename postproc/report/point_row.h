// One evaluated toolpath point as the report sees it: the post job's point
// (sample, contact, engagement, S before and after) turned into cutting
// speeds, their deviation from nominal, flags and the predicted surface
// quality (MODELS.md sections 2 and 3). Pure values, no I/O.
//
// Units: mm, rpm, m/min, s; deviations as fractions (0.05 = +5 %); cusp
// height and roughness in micrometres (the report's unit for them).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "postproc/pipeline/point_evaluator.h"
#include "postproc/post/post_job.h"

namespace vcpost::report {

// What the report needs to know about the job besides the points.
struct ReportInputs {
  std::string program, program_kind;  // file name, "gcode" | "cldata"
  std::string model, model_kind, model_description;
  std::string machine, tool, policy, cl_point;
  // The tool (the first section's) and which of its points the program
  // gives: the surface-quality columns (MODELS.md section 3) model its
  // outline across the feed (a point's own section's tool where the job
  // gives it, PointRecord::tool), their histograms span up to its radius.
  geometry::Tool tool_shape = geometry::Tool::ball(10);
  geometry::ClPoint cl_kind = geometry::ClPoint::tip;
  double vc_nominal = 120;  // m/min, > 0
  double ap_mm = 0.3;
  std::optional<double> ae_mm;
  bool ae_override = false, adjust_feed = false;
  double spacing_mm = 0.5;
  double n_min_rpm = 0, n_max_rpm = 0;  // the machine's spindle range
  // Plan-view extent of the top views, mm (the model's bounds grown by the
  // tool radius); points outside are drawn on the border cells.
  Eigen::Vector2d plan_min = Eigen::Vector2d::Zero(), plan_max = Eigen::Vector2d::Ones();
};

// Flags of a point, in the order the CSV lists them.
enum class PointFlag : std::uint32_t {
  no_contact = 1u << 0,         // ball lifted off or far from the model
  gouge = 1u << 1,              // ball reaches into the model
  no_cut = 1u << 2,             // touching, but nothing engaged (no working diameter)
  clamped_max = 1u << 3,        // planned S held at n_max (vc under nominal)
  clamped_min = 1u << 4,        // planned S held at n_min (vc over nominal)
  slew = 1u << 5,               // the spindle's acceleration limit decided S
  rate = 1u << 6,               // the S-word rate limit decided S
  hysteresis = 1u << 7,         // S kept within the change threshold
  program_s = 1u << 8,          // the block keeps the program's S (no target)
  spindle_off = 1u << 9,        // spindle off
  first_pass = 1u << 10,        // no neighbouring pass and no --ae: full-width groove
  before_over_max = 1u << 11,   // the program's S is above n_max (the machine clamps it)
  before_under_min = 1u << 12,  // the program's S is below n_min
  stretch = 1u << 13,           // one S holds the stretch between two stops (stop-aware plan)
};

// "no_contact|clamped_max|slew"; empty when no flag is set.
std::string flags_text(std::uint32_t flags);
std::string_view to_string(PointFlag flag);

struct PointRow {
  std::uint32_t line = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // programmed point
  std::optional<Eigen::Vector3d> cc, normal;        // contact point and tool-side normal
  Eigen::Vector3d feed = Eigen::Vector3d::Zero();   // F on the tangent plane (zero without contact)
  double ae = 0;
  pipeline::AeSource ae_source = pipeline::AeSource::first_pass;
  // The depth of cut the engagement took (--ap, or the in-process stock's:
  // docs/stock.md), and where it came from; empty where not evaluated.
  std::optional<double> ap;
  pipeline::ApSource ap_source = pipeline::ApSource::given;
  geometry::BallStatus status = geometry::BallStatus::missed;
  std::optional<double> d_ref, d_max, d_min, d_cut;  // mm
  double s_before = 0, s_after = 0;                  // rpm
  std::optional<double> vc_before, vc_after;         // m/min at d_ref; empty without d_ref
  std::optional<double> dev_before, dev_after;       // vc / vc_nominal - 1
  double time_s = 0;                                 // program time at the point
  double weight_s = 0;                               // cutting time it stands for
  plan::Bound bound = plan::Bound::none;
  std::uint32_t flags = 0;
  std::optional<double> cusp_um, ra_um, rz_um;  // predicted, where the ball cuts
  // Without a model: how the normal was found from the toolpath
  // (path_normals.h); then no cusp, Ra or Rz. Empty: the model's normal.
  std::optional<pipeline::NormalSource> normal_source;

  bool has(PointFlag f) const { return (flags & static_cast<std::uint32_t>(f)) != 0; }
};

// Cusp height across the feed (um) for a ball of radius R, passes ae apart
// on the surface, with the surface's normal curvature k across the feed
// (1/mm, > 0 convex, < 0 concave, 0 flat). Empty where the model does not
// apply: ae <= 0, ae >= 2R, a hollow tighter than the ball, no overlap.
std::optional<double> cusp_height_um(double radius, double ae, double curvature_across);

// Builds the row of one point. d_ref and both speeds come from the point;
// flags from its contact, engagement and the plan's bound.
PointRow make_row(const pipeline::PathSample& sample, const pipeline::PointResult& result,
                  const post::PointRecord& record, const ReportInputs& inputs);

}  // namespace vcpost::report
