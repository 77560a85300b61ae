// Time per evaluation of the ball's D_max, D_min and cutting points
// (target: <= 0.5 us on the 2-core CI machine), and of the mean diameter.
#include <benchmark/benchmark.h>

#include <numbers>
#include <random>
#include <vector>

#include "geometry/engagement.h"

namespace {

using namespace vcpost::geometry;

// Finishing-like set-ups: tilt up to 60 deg, ap 0.1..0.5, ae 0.2..1 mm, D = 10.
std::vector<CutSetup> finishing_setups(int count, double max_tilt_deg) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<CutSetup> setups;
  for (int i = 0; i < count; ++i) {
    const auto n = normal_from_angles(max_tilt_deg * std::numbers::pi / 180 * unit(rng),
                                      2 * std::numbers::pi * unit(rng));
    setups.push_back({0.1 + 0.4 * unit(rng), 0.2 + 0.8 * unit(rng), n,
                      feed_from_angle(2 * std::numbers::pi * unit(rng), n),
                      unit(rng) < 0.5 ? Side::left : Side::right});
  }
  return setups;
}

void BM_BallEngagement(benchmark::State& state) {
  const auto setups = finishing_setups(4096, static_cast<double>(state.range(0)));
  const Tool tool = Tool::ball(10);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(evaluate_engagement(tool, setups[i++ & 4095]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BallEngagement)->Arg(60)->Arg(85);

void BM_BallMeanDiameter(benchmark::State& state) {
  const auto setups = finishing_setups(256, 60);
  const Tool tool = Tool::ball(10);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(engaged_mean_diameter(tool, setups[i++ & 255]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BallMeanDiameter);

}  // namespace
