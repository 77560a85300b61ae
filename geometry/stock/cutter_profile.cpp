#include "geometry/stock/cutter_profile.h"

#include <numbers>
#include <sstream>

#include "core/error.h"

namespace vcpost::geometry::stock {

namespace {

[[noreturn]] void bad_cutter(const std::string& what) {
  throw Error(Code::E4706, "stock: " + what);
}

}  // namespace

CutterProfile CutterProfile::of(const Cutter& cutter) {
  const Tool& tool = cutter.tool;
  if (!(tool.diameter > 0) || !std::isfinite(tool.diameter)) {
    std::ostringstream text;
    text << "cutter diameter " << tool.diameter << " mm is not a positive length";
    bad_cutter(text.str());
  }
  CutterProfile profile;
  profile.radius = tool.radius();
  if (cutter.point_angle_deg != 0) {
    if (!(cutter.point_angle_deg > 0 && cutter.point_angle_deg < 180)) {
      std::ostringstream text;
      text << "drill point angle " << cutter.point_angle_deg << " degrees is not between 0 and 180";
      bad_cutter(text.str());
    }
    profile.kind = ProfileKind::cone;
    profile.cone_slope = 1 / std::tan(cutter.point_angle_deg * std::numbers::pi / 360);
    return profile;
  }
  switch (tool.kind) {
    case ToolKind::flat:
      profile.kind = ProfileKind::flat;
      return profile;
    case ToolKind::ball:
      profile.kind = ProfileKind::ball;
      profile.corner_radius = profile.radius;
      return profile;
    case ToolKind::bull_nose:
      break;
  }
  if (!(tool.corner_radius > 0 && tool.corner_radius <= profile.radius)) {
    std::ostringstream text;
    text << "bull-nose corner radius " << tool.corner_radius << " mm is not in (0, "
         << profile.radius << "]";
    bad_cutter(text.str());
  }
  profile.kind = ProfileKind::torus;
  profile.corner_radius = tool.corner_radius;
  profile.flat_radius = profile.radius - tool.corner_radius;
  return profile;
}

}  // namespace vcpost::geometry::stock
