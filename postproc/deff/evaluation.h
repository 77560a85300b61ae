// The working-diameter evaluation of one cutting set-up: the set-up built
// from what the user gives (a normal as a vector or as tilt and azimuth, a
// feed as a vector or as an angle), the engine's engagement and mean
// diameter, and the spindle speed for a nominal cutting speed. No I/O.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "geometry/diameter_policy.h"
#include "geometry/engagement.h"
#include "geometry/tool.h"

namespace vcpost::deff {

// The set-up as given, before it is checked.
struct SetupRequest {
  geometry::Tool tool;
  double ap = 0, ae = 0;  // mm
  geometry::Side side = geometry::Side::left;
  geometry::SpindleDirection spindle = geometry::SpindleDirection::clockwise;
  std::optional<Eigen::Vector3d> normal;  // else from tilt and azimuth
  double tilt_deg = 0, azimuth_deg = 0;
  std::optional<Eigen::Vector3d> feed;  // else from feed_angle_deg
  double feed_angle_deg = 0;
};

// A checked set-up with what the user asked for, to echo with the results.
struct Description {
  geometry::Tool tool;
  geometry::CutSetup setup;
  geometry::SpindleDirection spindle = geometry::SpindleDirection::clockwise;
  std::optional<double> feed_angle_deg;  // when the feed was given as an angle
};

// Builds and checks one set-up (checked_setup, setup_input.h). A feed angle
// is projected onto the tangent plane, so the normal is checked first.
// Throws SetupError naming the field at fault (a tilt outside (-90, 90) is
// the normal's).
Description describe(const SetupRequest& request);

struct Evaluation {
  geometry::Engagement engagement;
  std::optional<double> d_mean;  // mm; empty when nothing is engaged
};

// Runs the engine. REQUIRES: setup passed checked_setup (setup_input.h).
// Throws what the engine throws (std::logic_error for a tool kind it does
// not handle yet).
Evaluation evaluate(const geometry::Tool& tool, const geometry::CutSetup& setup);

using geometry::DiameterPolicy;  // which diameter sets the spindle speed

struct SpeedRequest {
  DiameterPolicy policy = DiameterPolicy::max;
  std::optional<double> vc;   // nominal cutting speed, m/min, > 0
  std::optional<double> rpm;  // given spindle speed, 1/min, > 0
};

struct Speed {
  DiameterPolicy policy = DiameterPolicy::max;
  std::optional<double> d_ref;       // mm; empty when the policy's point does not exist
  std::optional<double> vc_nominal;  // m/min, as requested
  // The spindle speed the cutting speeds are given at: the request's rpm, or
  // the one that gives vc_nominal at d_ref; empty when d_ref is missing or 0
  // (n unbounded).
  std::optional<double> rpm;
  std::optional<double> vc_at(std::optional<double> diameter) const;
};

Speed plan_speed(const Evaluation& evaluation, const SpeedRequest& request);

}  // namespace vcpost::deff
