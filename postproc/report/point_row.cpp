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

  auto set = [&](PointFlag f) { row.flags |= static_cast<std::uint32_t>(f); };
  switch (result.contact.status) {
    case geometry::BallStatus::lifted:
    case geometry::BallStatus::missed:
      set(PointFlag::no_contact);
      break;
    case geometry::BallStatus::gouging:
      set(PointFlag::gouge);
      break;
    case geometry::BallStatus::touching:
      break;
  }
  switch (record.bound) {
    case plan::Bound::n_max:
      set(PointFlag::clamped_max);
      break;
    case plan::Bound::n_min:
      set(PointFlag::clamped_min);
      break;
    case plan::Bound::slew:
      set(PointFlag::slew);
      break;
    case plan::Bound::rate:
      set(PointFlag::rate);
      break;
    case plan::Bound::hysteresis:
      set(PointFlag::hysteresis);
      break;
    case plan::Bound::program:
      set(PointFlag::program_s);
      break;
    case plan::Bound::off:
      set(PointFlag::spindle_off);
      break;
    case plan::Bound::stretch:
      set(PointFlag::stretch);
      break;
    default:
      break;
  }
  if (inputs.n_max_rpm > 0 && record.s_before > inputs.n_max_rpm) set(PointFlag::before_over_max);
  if (record.s_before > 0 && record.s_before < inputs.n_min_rpm) set(PointFlag::before_under_min);

  if (result.engagement) {
    row.d_max = result.engagement->d_max;
    row.d_min = result.engagement->d_min;
    if (result.engagement->points) row.d_cut = result.engagement->points->cut.diameter;
    if (result.ae_source == pipeline::AeSource::first_pass) set(PointFlag::first_pass);
  }
  row.d_ref = result.d_ref;
  if (result.contact.status == geometry::BallStatus::touching && !result.d_ref)
    set(PointFlag::no_cut);
  if (result.d_ref) {
    row.vc_before = geometry::cutting_speed(*result.d_ref, record.s_before);
    row.vc_after = geometry::cutting_speed(*result.d_ref, record.s_after);
    row.dev_before = *row.vc_before / inputs.vc_nominal - 1;
    row.dev_after = *row.vc_after / inputs.vc_nominal - 1;
  }

  // Surface quality where the tool cuts: the transverse profile (the
  // tool's outline across the feed every ae: a ball's arcs in closed form,
  // other tools' by revolved_cusp); the cusp with the surface's curvature
  // across the feed where the model knows it (exact faces), flat otherwise
  // (meshes). No cusp where no earlier pass lies beside this one (first
  // pass: a full groove) or where the tool is not on the surface. None
  // without a model: the surface is only known where the path lies.
  if (!result.normal_source && result.engagement && result.contact.contact &&
      result.feed.squaredNorm() > 0 && result.contact.status == geometry::BallStatus::touching &&
      result.ae_source != pipeline::AeSource::first_pass) {
    double k_across = 0;
    if (const auto& curvature = result.contact.contact->curvature) {
      const Eigen::Vector3d across = result.contact.normal.cross(result.feed).normalized();
      const double c1 = curvature->d1.dot(across), c2 = curvature->d2.dot(across);
      k_across = curvature->k1 * c1 * c1 + curvature->k2 * c2 * c2;  // Euler's formula
    }
    // The point's own section's tool (a program's sections may differ).
    const geometry::Tool tool = record.tool.value_or(inputs.tool_shape);
    if (tool.kind == geometry::ToolKind::ball) {
      const double radius = tool.radius();
      row.cusp_um = cusp_height_um(radius, result.ae, k_across);
      if (result.ae > 0 && result.ae < 2 * radius) {
        const auto r = geometry::transverse_roughness(radius, result.ae);
        row.ra_um = 1000 * r.ra;
        row.rz_um = 1000 * r.rz;
      }
    } else {
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
  }
  return row;
}

}  // namespace vcpost::report
