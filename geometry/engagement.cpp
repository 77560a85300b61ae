#include "geometry/engagement.h"

#include <array>
#include <cmath>
#include <numbers>
#include <utility>

#include "geometry/ball_engagement.h"
#include "geometry/cut_frame.h"
#include "geometry/revolved_engagement.h"

namespace vcpost::geometry {

std::vector<std::string> flag_names(EngagementFlags flags) {
  static constexpr std::array<std::pair<EngagementFlag, const char*>, 7> kNames = {{
      {EngagementFlag::nothing_engaged, "nothing_engaged"},
      {EngagementFlag::shank_engaged, "shank_engaged"},
      {EngagementFlag::zero_ae, "zero_ae"},
      {EngagementFlag::zero_ap, "zero_ap"},
      {EngagementFlag::ap_exceeds_d, "ap_exceeds_d"},
      {EngagementFlag::undercut, "undercut"},
      {EngagementFlag::feed_along_normal, "feed_along_normal"},
  }};
  std::vector<std::string> names;
  for (const auto& [flag, name] : kNames) {
    if (flags.has(flag)) names.emplace_back(name);
  }
  return names;
}

CutCheck check_cut(const Tool& tool, const CutSetup& setup) {
  CutCheck check;
  if (!(setup.ap > 0)) check.flags.set(EngagementFlag::zero_ap);
  if (!(setup.ae > 0)) check.flags.set(EngagementFlag::zero_ae);
  if (setup.ap >= tool.diameter) check.flags.set(EngagementFlag::ap_exceeds_d);

  const double n_length = setup.normal.norm();
  if (!(n_length > 0) || !(setup.normal.z() / n_length > 0)) {
    check.flags.set(EngagementFlag::undercut);
    return check;
  }
  const Eigen::Vector3d normal = setup.normal / n_length;
  const Eigen::Vector3d tangent = setup.feed - setup.feed.dot(normal) * normal;
  // Relative to |feed| so a tiny tilt of a long vector is still a direction.
  if (!(tangent.norm() > 1e-9 * setup.feed.norm())) {
    check.flags.set(EngagementFlag::feed_along_normal);
    return check;
  }
  const Eigen::Vector3d feed = tangent.normalized();
  check.frame = CutFrame{feed, normal.cross(feed), normal, setup.side == Side::left ? 1.0 : -1.0};
  check.rim_exists = setup.ap > 0 && setup.ap < tool.diameter;
  check.can_engage = check.rim_exists && setup.ae > 0;
  return check;
}

namespace {
// A bull-nose whose corner fills the radius is a ball: the ball's engine.
Tool as_engine_sees(const Tool& tool) {
  const bool ball = tool.kind == ToolKind::bull_nose && tool.corner_radius >= tool.radius();
  return ball ? Tool::ball(tool.diameter) : tool;
}
}  // namespace

Engagement evaluate_engagement(const Tool& given, const CutSetup& setup,
                               CuttingPointsWanted points) {
  const Tool tool = as_engine_sees(given);
  if (tool.kind != ToolKind::ball) {
    return evaluate_revolved_engagement(tool, setup, points);
  }
  const CutCheck check = check_cut(tool, setup);
  Engagement out;
  out.flags = check.flags;
  if (!check.frame) {
    out.flags.set(EngagementFlag::nothing_engaged);
    return out;
  }
  out.feed_dir = check.frame->feed;
  out.side_dir = check.frame->side;
  out.normal = check.frame->normal;
  evaluate_ball(tool.radius(), setup, check, points, out);
  return out;
}

std::optional<double> engaged_mean_diameter(const Tool& given, const CutSetup& setup) {
  const Tool tool = as_engine_sees(given);
  if (tool.kind != ToolKind::ball) return revolved_mean_diameter(tool, setup);
  const CutCheck check = check_cut(tool, setup);
  if (!check.can_engage) return std::nullopt;
  return ball_mean_diameter(tool.radius(), setup, *check.frame);
}

MillingMode milling_mode(Side previous_pass, SpindleDirection spindle) {
  // M3 turns clockwise seen from the spindle: the edges on the tool's right
  // move against the feed, so uncut material on the right is climb milling.
  const bool uncut_on_right = previous_pass == Side::left;
  const bool clockwise = spindle == SpindleDirection::clockwise;
  return uncut_on_right == clockwise ? MillingMode::down : MillingMode::up;
}

Eigen::Vector3d feed_from_angle(double feed_angle_rad, const Eigen::Vector3d& normal) {
  const Eigen::Vector3d level(std::cos(feed_angle_rad), std::sin(feed_angle_rad), 0);
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d projected = level - level.dot(n) * n;
  const double length = projected.norm();
  return length > 0 ? Eigen::Vector3d(projected / length) : projected;
}

Eigen::Vector3d normal_from_angles(double tilt_rad, double azimuth_rad) {
  return {std::sin(tilt_rad) * std::cos(azimuth_rad), std::sin(tilt_rad) * std::sin(azimuth_rad),
          std::cos(tilt_rad)};
}

double spindle_speed_for(double vc_m_per_min, double diameter_mm) {
  return 1000 * vc_m_per_min / (std::numbers::pi * diameter_mm);
}

double cutting_speed(double diameter_mm, double rpm) {
  return std::numbers::pi * diameter_mm * rpm / 1000;
}

}  // namespace vcpost::geometry
