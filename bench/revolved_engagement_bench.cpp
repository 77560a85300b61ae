// Time per evaluation of the bull-nose and flat end mills' D_max, D_min
// and cutting points, and of their area-weighted mean, over the same
// finishing-like set-ups as engagement_bench.cpp's ball (tilt up to 60 deg,
// ap 0.1..0.5, ae 0.2..1 mm, D = 10; bull-nose rc = 2).
#include <benchmark/benchmark.h>

#include <numbers>
#include <random>
#include <vector>

#include "geometry/engagement.h"

namespace {

using namespace vcpost::geometry;

std::vector<CutSetup> finishing_setups(int count) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<CutSetup> setups;
  for (int i = 0; i < count; ++i) {
    const auto n = normal_from_angles(60 * std::numbers::pi / 180 * unit(rng),
                                      2 * std::numbers::pi * unit(rng));
    setups.push_back({0.1 + 0.4 * unit(rng), 0.2 + 0.8 * unit(rng), n,
                      feed_from_angle(2 * std::numbers::pi * unit(rng), n),
                      unit(rng) < 0.5 ? Side::left : Side::right});
  }
  return setups;
}

Tool tool_of(int kind) { return kind == 0 ? Tool::bull_nose(10, 2) : Tool::flat(10); }

void BM_RevolvedEngagement(benchmark::State& state) {
  const auto setups = finishing_setups(1024);
  const Tool tool = tool_of(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(evaluate_engagement(tool, setups[i++ & 1023]));
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(to_string(tool));
}
BENCHMARK(BM_RevolvedEngagement)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_RevolvedMeanDiameter(benchmark::State& state) {
  const auto setups = finishing_setups(256);
  const Tool tool = tool_of(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(engaged_mean_diameter(tool, setups[i++ & 255]));
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(to_string(tool));
}
BENCHMARK(BM_RevolvedMeanDiameter)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
