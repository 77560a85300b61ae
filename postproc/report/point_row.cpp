#include "postproc/report/point_row.h"

#include <array>
#include <cmath>
#include <stdexcept>

#include "geometry/revolved_engagement.h"
#include "geometry/surface_quality.h"
#include "geometry/tool_contact.h"

namespace vcpost::report {
namespace {

constexpr std::array<std::pair<PointFlag, std::string_view>, 14> kFlagNames{{
    {PointFlag::no_contact, "no_contact"},
    {PointFlag::gouge, "gouge"},
    {PointFlag::no_cut, "no_cut"},
    {PointFlag::clamped_max, "clamped_max"},
    {PointFlag::clamped_min, "clamped_min"},
    {PointFlag::slew, "slew"},
    {PointFlag::rate, "rate"},
    {PointFlag::hysteresis, "hysteresis"},
    {PointFlag::program_s, "program_s"},
    {PointFlag::spindle_off, "spindle_off"},
    {PointFlag::first_pass, "first_pass"},
    {PointFlag::before_over_max, "before_over_max"},
    {PointFlag::before_under_min, "before_under_min"},
    {PointFlag::stretch, "stretch"},
}};

// Below this |k| (1/mm, a radius of 1 km) a surface counts as flat.
constexpr double kFlatCurvature = 1e-6;

}  // namespace

std::string_view to_string(PointFlag flag) {
  for (const auto& [f, name] : kFlagNames) {
    if (f == flag) return name;
  }
  return "?";
}

std::string flags_text(std::uint32_t flags) {
  std::string out;
  for (const auto& [f, name] : kFlagNames) {
    if ((flags & static_cast<std::uint32_t>(f)) == 0) continue;
    if (!out.empty()) out += '|';
    out += name;
  }
  return out;
}

std::optional<double> cusp_height_um(double radius, double ae, double curvature_across) {
  if (!(ae > 0) || !(ae < 2 * radius) || !std::isfinite(curvature_across)) return std::nullopt;
  try {
    if (std::abs(curvature_across) < kFlatCurvature) {
      return 1000 * geometry::flat_cusp_height(radius, ae);
    }
    const double rho = 1 / std::abs(curvature_across);
    const auto kind =
        curvature_across > 0 ? geometry::Curvature::convex : geometry::Curvature::concave;
    return 1000 * geometry::curved_cusp_height(radius, ae, rho, kind);
  } catch (const std::invalid_argument&) {
    // Outside the model's range (hollow tighter than the ball, no overlap).
    return std::nullopt;
  }
}

namespace {

std::uint32_t bit(PointFlag flag) { return static_cast<std::uint32_t>(flag); }

// The flag of the contact's status; none where the tool touches.
std::uint32_t contact_flag(geometry::BallStatus status) {
  switch (status) {
    case geometry::BallStatus::lifted:
    case geometry::BallStatus::missed:
      return bit(PointFlag::no_contact);
    case geometry::BallStatus::gouging:
      return bit(PointFlag::gouge);
    case geometry::BallStatus::touching:
      break;
  }
  return 0;
}

// The flag of each plan bound that decides a point's S.
constexpr std::array<std::pair<plan::Bound, PointFlag>, 8> kBoundFlags{{
    {plan::Bound::n_max, PointFlag::clamped_max},
    {plan::Bound::n_min, PointFlag::clamped_min},
    {plan::Bound::slew, PointFlag::slew},
    {plan::Bound::rate, PointFlag::rate},
    {plan::Bound::hysteresis, PointFlag::hysteresis},
    {plan::Bound::program, PointFlag::program_s},
    {plan::Bound::off, PointFlag::spindle_off},
    {plan::Bound::stretch, PointFlag::stretch},
}};

std::uint32_t bound_flag(plan::Bound bound) {
  for (const auto& [b, flag] : kBoundFlags) {
    if (b == bound) return bit(flag);
  }
  return 0;
}

// Every PointFlag of the point.
std::uint32_t point_flags(const pipeline::PointResult& result, const post::PointRecord& record,
                          const ReportInputs& inputs) {
  std::uint32_t flags = contact_flag(result.contact.status) | bound_flag(record.bound);
  if (inputs.n_max_rpm > 0 && record.s_before > inputs.n_max_rpm)
    flags |= bit(PointFlag::before_over_max);
  if (record.s_before > 0 && record.s_before < inputs.n_min_rpm)
    flags |= bit(PointFlag::before_under_min);
  if (result.engagement && result.ae_source == pipeline::AeSource::first_pass)
    flags |= bit(PointFlag::first_pass);
  if (result.contact.status == geometry::BallStatus::touching && !result.d_ref)
    flags |= bit(PointFlag::no_cut);
  return flags;
}

// The cutting speeds at d_ref before and after the post, and their
// deviations from nominal.
void add_speeds(PointRow& row, double d_ref, double vc_nominal) {
  row.vc_before = geometry::cutting_speed(d_ref, row.s_before);
  row.vc_after = geometry::cutting_speed(d_ref, row.s_after);
  row.dev_before = *row.vc_before / vc_nominal - 1;
  row.dev_after = *row.vc_after / vc_nominal - 1;
}

// Surface quality where the tool cuts: the transverse profile (the tool's
// outline across the feed every ae). No cusp where no earlier pass lies
// beside this one (first pass: a full groove) or where the tool is not on
// the surface. None without a model: the surface is only known where the
// path lies.
bool cusp_is_predicted(const pipeline::PointResult& result) {
  return !result.normal_source && result.engagement && result.contact.contact &&
         result.feed.squaredNorm() > 0 && result.contact.status == geometry::BallStatus::touching &&
         result.ae_source != pipeline::AeSource::first_pass;
}

// The surface's normal curvature across the feed at the contact, where the
// model knows it (exact faces); flat otherwise (meshes).
double normal_curvature_across(const geometry::BallContact& contact, const Eigen::Vector3d& feed) {
  const auto& curvature = contact.contact->curvature;
  if (!curvature) return 0;
  const Eigen::Vector3d across = contact.normal.cross(feed).normalized();
  const double c1 = curvature->d1.dot(across), c2 = curvature->d2.dot(across);
  return curvature->k1 * c1 * c1 + curvature->k2 * c2 * c2;  // Euler's formula
}

// A ball's cusp, Ra and Rz: its arcs in closed form.
void add_ball_quality(PointRow& row, double radius, double ae, double k_across) {
  row.cusp_um = cusp_height_um(radius, ae, k_across);
  if (ae > 0 && ae < 2 * radius) {
    const auto r = geometry::transverse_roughness(radius, ae);
    row.ra_um = 1000 * r.ra;
    row.rz_um = 1000 * r.rz;
  }
}

// Another tool's, by revolved_cusp.
void add_revolved_quality(PointRow& row, const geometry::Tool& tool,
                          const pipeline::PathSample& sample, const pipeline::PointResult& result,
                          const ReportInputs& inputs, double k_across) {
  const geometry::CutSetup setup{inputs.ap_mm, result.ae, result.contact.normal, result.feed,
                                 result.side};
  const Eigen::Vector3d origin = geometry::tool_origin(sample.point, tool, inputs.cl_kind);
  const geometry::RevolvedCusp cusp = geometry::revolved_cusp(
      tool, setup, k_across, Eigen::Vector3d(result.contact.contact->point - origin));
  const auto in_um = [](const std::optional<double>& mm) {
    return mm ? std::optional<double>(1000 * *mm) : std::nullopt;
  };
  row.cusp_um = in_um(cusp.height);
  row.ra_um = in_um(cusp.ra);
  row.rz_um = in_um(cusp.rz);
}

// The cusp, Ra and Rz with the point's own section's tool (a program's
// sections may differ).
void add_surface_quality(PointRow& row, const pipeline::PathSample& sample,
                         const pipeline::PointResult& result, const post::PointRecord& record,
                         const ReportInputs& inputs) {
  const double k_across = normal_curvature_across(result.contact, result.feed);
  const geometry::Tool tool = record.tool.value_or(inputs.tool_shape);
  if (tool.kind == geometry::ToolKind::ball) {
    add_ball_quality(row, tool.radius(), result.ae, k_across);
  } else {
    add_revolved_quality(row, tool, sample, result, inputs, k_across);
  }
}

}  // namespace

PointRow make_row(const pipeline::PathSample& sample, const pipeline::PointResult& result,
                  const post::PointRecord& record, const ReportInputs& inputs) {
  PointRow row;
  row.line = record.line;
  row.point = sample.point;
  row.status = result.contact.status;
  if (result.contact.contact) {
    row.cc = result.contact.contact->point;
    row.normal = result.contact.normal;
  }
  row.feed = result.feed;
  row.ae = result.ae;
  row.ae_source = result.ae_source;
  if (result.engagement || result.ap_source == pipeline::ApSource::air) {
    row.ap = result.ap;
    row.ap_source = result.ap_source;
  }
  row.s_before = record.s_before;
  row.s_after = record.s_after;
  row.time_s = record.time_s;
  row.weight_s = record.weight_s;
  row.bound = record.bound;
  row.normal_source = result.normal_source;
  row.flags = point_flags(result, record, inputs);
  if (result.engagement) {
    row.d_max = result.engagement->d_max;
    row.d_min = result.engagement->d_min;
    if (result.engagement->points) row.d_cut = result.engagement->points->cut.diameter;
  }
  row.d_ref = result.d_ref;
  if (result.d_ref) add_speeds(row, *result.d_ref, inputs.vc_nominal);
  if (cusp_is_predicted(result)) add_surface_quality(row, sample, result, record, inputs);
  return row;
}

}  // namespace vcpost::report
