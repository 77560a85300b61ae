// One working-diameter evaluation of the bull-nose and the flat end mill
// (extremes and cutting points), and one area-weighted mean, on a tilted
// surface with a general feed direction.
#include <benchmark/benchmark.h>

#include <numbers>

#include "geometry/revolved_engagement.h"

namespace {

using vcpost::geometry::CutSetup;
using vcpost::geometry::Tool;

CutSetup tilted_setup() {
  CutSetup s;
  s.ap = 0.4;
  s.ae = 0.8;
  s.normal = vcpost::geometry::normal_from_angles(35 * std::numbers::pi / 180, 0.6);
  s.feed = vcpost::geometry::feed_from_angle(1.9, s.normal);
  s.side = vcpost::geometry::Side::left;
  return s;
}

void BM_BullNoseEvaluation(benchmark::State& state) {
  const Tool tool = Tool::bull_nose(10, 2);
  const CutSetup s = tilted_setup();
  for (auto _ : state) benchmark::DoNotOptimize(vcpost::geometry::evaluate_revolved_engagement(tool, s));
}
BENCHMARK(BM_BullNoseEvaluation)->Unit(benchmark::kMicrosecond);

void BM_FlatEvaluation(benchmark::State& state) {
  const Tool tool = Tool::flat(10);
  const CutSetup s = tilted_setup();
  for (auto _ : state) benchmark::DoNotOptimize(vcpost::geometry::evaluate_revolved_engagement(tool, s));
}
BENCHMARK(BM_FlatEvaluation)->Unit(benchmark::kMicrosecond);

void BM_BullNoseMean(benchmark::State& state) {
  const Tool tool = Tool::bull_nose(10, 2);
  const CutSetup s = tilted_setup();
  for (auto _ : state) benchmark::DoNotOptimize(vcpost::geometry::revolved_mean_diameter(tool, s));
}
BENCHMARK(BM_BullNoseMean)->Unit(benchmark::kMillisecond);

void BM_FlatMean(benchmark::State& state) {
  const Tool tool = Tool::flat(10);
  const CutSetup s = tilted_setup();
  for (auto _ : state) benchmark::DoNotOptimize(vcpost::geometry::revolved_mean_diameter(tool, s));
}
BENCHMARK(BM_FlatMean)->Unit(benchmark::kMillisecond);

}  // namespace
