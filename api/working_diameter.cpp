#include "vcpost/working_diameter.h"

#include <stdexcept>

#include "api/translate.h"
#include "geometry/engagement.h"
#include "geometry/tool.h"

namespace vcpost::api {
namespace {

geometry::Tool internal_tool(const Tool& tool) {
  switch (tool.kind) {
    case ToolKind::ball:
      return geometry::Tool::ball(tool.diameter);
    case ToolKind::bull_nose:
      return geometry::Tool::bull_nose(tool.diameter, tool.corner_radius);
    case ToolKind::flat:
      return geometry::Tool::flat(tool.diameter);
  }
  // Inside the library: guarded() (api/translate.h) turns every exception
  // into vcpost::api::Error.
  throw std::invalid_argument("unknown tool kind");
}

// The tool as parse_tool would accept it (the engine's precondition).
geometry::Tool checked_tool(const Tool& tool) { return geometry::parse_tool(to_string(tool)); }

geometry::CutSetup internal_setup(const CutSetup& setup) {
  geometry::CutSetup out;
  out.ap = setup.ap;
  out.ae = setup.ae;
  out.normal = {setup.normal.x, setup.normal.y, setup.normal.z};
  out.feed = {setup.feed.x, setup.feed.y, setup.feed.z};
  out.side = setup.side == Side::left ? geometry::Side::left : geometry::Side::right;
  // Turned into vcpost::api::Error by guarded() (api/translate.h).
  if (!(out.normal.norm() > 0)) throw std::invalid_argument("the surface normal is zero");
  if (!(out.feed.norm() > 0)) throw std::invalid_argument("the feed direction is zero");
  return out;
}

}  // namespace

Tool parse_tool(std::string_view spec) {
  return guarded([&] {
    const geometry::Tool tool = geometry::parse_tool(spec);
    const ToolKind kind = tool.kind == geometry::ToolKind::ball        ? ToolKind::ball
                          : tool.kind == geometry::ToolKind::bull_nose ? ToolKind::bull_nose
                                                                       : ToolKind::flat;
    return Tool{kind, tool.diameter, tool.corner_radius};
  });
}

std::string to_string(const Tool& tool) {
  return guarded([&] { return geometry::to_string(internal_tool(tool)); });
}

WorkingDiameter working_diameter(const Tool& tool, const CutSetup& setup) {
  return guarded([&] {
    const geometry::Engagement e =
        geometry::evaluate_engagement(checked_tool(tool), internal_setup(setup));
    WorkingDiameter out;
    out.engaged = e.d_max.has_value();  // as `vcpost deff` decides it
    out.d_max = e.d_max;
    out.d_min = e.d_min;
    if (e.points) out.d_cut = e.points->cut.diameter;
    out.flags = geometry::flag_names(e.flags);
    return out;
  });
}

std::optional<double> mean_working_diameter(const Tool& tool, const CutSetup& setup) {
  return guarded(
      [&] { return geometry::engaged_mean_diameter(checked_tool(tool), internal_setup(setup)); });
}

double spindle_speed_for(double vc_m_per_min, double diameter_mm) {
  return geometry::spindle_speed_for(vc_m_per_min, diameter_mm);
}

}  // namespace vcpost::api
