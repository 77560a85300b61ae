// The streaming spindle planner's throughput: samples per second through
// push() and take_final() on a long finishing-like timeline, and
// plan_spindle() (the same planner fed a whole timeline held in memory). Target (issue 7): at least
// 5 M samples/s, so the planner is never the bottleneck of a 1 M points/s post.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "machines/builtin.h"
#include "postproc/plan/streaming_plan.h"

namespace {

using vcpost::plan::Sample;

// Finishing-like: blocks of 1..4 samples about 1 ms apart (a 2 mm/s ...
// 6 m/min path sampled every 0.1 mm), the target wandering between 3000
// and 11000 rpm over the part with fast ripples and jumps between passes,
// a 40 ms rapid every 2 s and a second of air now and then.
std::vector<Sample> timeline(std::size_t samples) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Sample> out;
  out.reserve(samples);
  double t = 0.0;
  std::size_t block = 0;
  while (out.size() < samples) {
    const bool rapid = block % 1000 == 999;
    const bool air = block % 20000 > 19500;
    const int n = 1 + static_cast<int>(u(rng) * 4);
    const double len = rapid ? 0.04 : 0.0005 + 0.002 * u(rng);
    for (int i = 0; i < n && out.size() < samples; ++i) {
      Sample s;
      s.time_s = t + len * i / n;
      s.block = block;
      s.rapid = rapid;
      s.program_rpm = 8000;
      if (!rapid && !air)
        s.target_rpm = 7000.0 + 3000.0 * std::sin(0.3 * s.time_s) +
                       800.0 * std::sin(9.0 * s.time_s) + 50.0 * u(rng);
      out.push_back(s);
    }
    t += len;
    ++block;
  }
  return out;
}

// What the post feeds the planner on a raster finishing program such as
// p1m.nc (1 M blocks of 0.077 mm at F800): one sample per block, 5.8 ms
// apart, one run with no rapid, the target following the waves of the part.
std::vector<Sample> raster_timeline(std::size_t samples) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Sample> out(samples);
  for (std::size_t i = 0; i < samples; ++i) {
    Sample& s = out[i];
    s.time_s = 0.0058 * static_cast<double>(i);
    s.block = i;
    s.program_rpm = 4000;
    s.target_rpm = 7000.0 + 3000.0 * std::sin(0.3 * s.time_s) + 800.0 * std::sin(9.0 * s.time_s) +
                   50.0 * u(rng);
  }
  return out;
}

void run_streaming_planner(benchmark::State& state, const std::vector<Sample>& samples) {
  const auto spec = vcpost::machines::builtin_profile("mazak-3axis").spindle();
  std::vector<vcpost::plan::BlockPlan> out;
  std::size_t held = 0;
  for (auto _ : state) {
    vcpost::plan::StreamingPlanner planner(spec);
    out.clear();
    for (const auto& s : samples) {
      planner.push(s);
      planner.take_final(out);
      if (out.size() > 4096) out.clear();  // the caller writes them out
    }
    held = std::max(held, planner.held_samples());
    planner.finish();
    planner.take_final(out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["held_before_finish"] = static_cast<double>(held);
}

void BM_StreamingPlanner(benchmark::State& state) {
  run_streaming_planner(state, timeline(static_cast<std::size_t>(state.range(0))));
}
BENCHMARK(BM_StreamingPlanner)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

void BM_StreamingPlannerRaster(benchmark::State& state) {
  run_streaming_planner(state, raster_timeline(static_cast<std::size_t>(state.range(0))));
}
BENCHMARK(BM_StreamingPlannerRaster)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

void BM_PlanSpindleWhole(benchmark::State& state) {
  const auto samples = timeline(static_cast<std::size_t>(state.range(0)));
  const auto spec = vcpost::machines::builtin_profile("mazak-3axis").spindle();
  for (auto _ : state) {
    auto plan = vcpost::plan::plan_spindle(samples, spec);
    benchmark::DoNotOptimize(plan.blocks.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_PlanSpindleWhole)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

}  // namespace
