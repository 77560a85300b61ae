#include "postproc/deff/evaluation.h"

#include <Eigen/Geometry>
#include <cmath>

#include "postproc/deff/setup_input.h"

namespace vcpost::deff {

Description describe(const SetupRequest& request) {
  Description description;
  description.tool = request.tool;
  description.spindle = request.spindle;
  geometry::CutSetup setup;
  setup.ap = request.ap;
  setup.ae = request.ae;
  setup.side = request.side;
  if (request.normal) {
    setup.normal = *request.normal;
  } else {
    check_tilt(request.tilt_deg);
    setup.normal = geometry::normal_from_angles(degrees_to_radians(request.tilt_deg),
                                                degrees_to_radians(request.azimuth_deg));
  }
  if (request.feed) {
    setup.feed = *request.feed;
  } else {
    // Check the normal with a stand-in feed across it before projecting.
    geometry::CutSetup probe = setup;
    probe.feed = setup.normal.unitOrthogonal();
    setup.normal = checked_setup(request.tool, probe).normal;
    setup.feed =
        geometry::feed_from_angle(degrees_to_radians(request.feed_angle_deg), setup.normal);
    description.feed_angle_deg = request.feed_angle_deg;
  }
  description.setup = checked_setup(request.tool, setup);
  return description;
}

Evaluation evaluate(const geometry::Tool& tool, const geometry::CutSetup& setup) {
  return {geometry::evaluate_engagement(tool, setup), geometry::engaged_mean_diameter(tool, setup)};
}

std::optional<double> Speed::vc_at(std::optional<double> diameter) const {
  if (!diameter || !rpm) return std::nullopt;
  return geometry::cutting_speed(*diameter, *rpm);
}

Speed plan_speed(const Evaluation& evaluation, const SpeedRequest& request) {
  Speed speed;
  speed.policy = request.policy;
  speed.vc_nominal = request.vc;
  speed.d_ref = geometry::reference_diameter(request.policy, evaluation.engagement,
                                             [&] { return evaluation.d_mean; });
  if (request.rpm) {
    speed.rpm = request.rpm;
  } else if (request.vc && speed.d_ref) {
    const double rpm = geometry::target_rpm(*request.vc, *speed.d_ref);
    if (std::isfinite(rpm)) speed.rpm = rpm;  // unbounded at d_ref = 0: none to give
  }
  return speed;
}

}  // namespace vcpost::deff
