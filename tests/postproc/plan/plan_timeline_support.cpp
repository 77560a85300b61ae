#include "tests/postproc/plan/plan_timeline_support.h"

#include <algorithm>

#include "machines/builtin.h"

namespace vcpost::plan::testing {

machines::SpindleSpec property_spec(int round, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto shipped = machines::builtin_profiles();
  if (round % 2 == 0) {
    auto spec = machines::builtin_profile(
                    shipped[static_cast<std::size_t>(round / 2) % shipped.size()].name)
                    .spindle();
    spec.stops_path_on_change = false;  // the per-block planner's figures
    return spec;
  }
  machines::SpindleSpec spec;
  spec.n_min_rpm = 10 + 2000 * u(rng);
  spec.n_max_rpm = spec.n_min_rpm + 100 + 20000 * u(rng);
  spec.acceleration_rpm_per_s = 50 + 8000 * u(rng);
  spec.deceleration_rpm_per_s = 50 + 8000 * u(rng);
  const double resolutions[] = {0.001, 0.5, 1, 5, 10, 50};
  spec.s_resolution_rpm = resolutions[static_cast<std::size_t>(u(rng) * 6) % 6];
  spec.min_change_rpm = 20 * u(rng);
  spec.min_change_percent = 3 * u(rng);
  spec.max_changes_per_s = 0.5 + 30 * u(rng);
  return spec;
}

std::vector<Sample> random_timeline(const machines::SpindleSpec& spec, std::mt19937& rng,
                                    double time_scale) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Sample> samples;
  double t = 0.0;
  double target = spec.n_min_rpm + (spec.n_max_rpm - spec.n_min_rpm) * u(rng);
  SpindleState state = SpindleState::cw;
  double program = 6000;
  const std::size_t blocks = 50 + static_cast<std::size_t>(u(rng) * 400);
  for (std::size_t k = 0; k < blocks; ++k) {
    const double len = time_scale * (u(rng) < 0.2 ? 0.5 * u(rng) : 0.05 * u(rng) * u(rng));
    const bool rapid = u(rng) < 0.05;
    const bool air = !rapid && u(rng) < 0.05;
    const bool tool_change = u(rng) < 0.01;
    if (u(rng) < 0.02) state = state == SpindleState::off ? SpindleState::cw : SpindleState::off;
    if (u(rng) < 0.01) state = SpindleState::ccw;
    if (u(rng) < 0.02) program = u(rng) < 0.3 ? 0.0 : 1000 + 9000 * u(rng);
    const int n = 1 + static_cast<int>(u(rng) * 4);
    for (int i = 0; i < n; ++i) {
      Sample s;
      s.time_s = t + len * i / n;
      s.block = k;
      s.rapid = rapid;
      s.tool_change = tool_change && i == 0;
      s.spindle = state;
      s.program_rpm = program;
      if (u(rng) < 0.03) target *= 0.5 + u(rng);  // a jump
      target *= 1.0 + 0.02 * (u(rng) - 0.5);
      target = std::clamp(target, 5.0, 40000.0);
      if (!rapid && !air) s.target_rpm = target;
      samples.push_back(s);
    }
    t += len;
  }
  return samples;
}

}  // namespace vcpost::plan::testing
