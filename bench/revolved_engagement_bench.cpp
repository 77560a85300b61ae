// Time per evaluation of D_max, D_min and the cutting points
// (evaluate_engagement) and of the area-weighted mean
// (engaged_mean_diameter), for the ball, bull-nose and flat end mills side
// by side (issue 21's targets: <= 1 us for the extremes, <= 50 us for the
// mean, on every tool).
//
// Three sets of set-ups, the argument naming the tool (0 ball, 1 bull-nose,
// 2 flat):
// - finishing: D = 10 (bull-nose rc = 2), tilt up to 60 deg, ap 0.1..0.5,
//   ae 0.2..1 mm (engagement_bench.cpp's ball set-ups, same seed);
// - random: the tests' random cases (revolved_engagement_test.cpp), where
//   the issue's figures were taken: D 4..20, rc 0.1..0.9 R, ap up to half
//   of D, ae up to 1.12 D, tilt up to 80 deg, left and right;
// - level and nearly level: the random ones with feeds level (Z-level
//   passes) or nearly so (the mean only), either way and uphill only.
// And the issue's set-up on which the old mean did not finish in 300 s,
// and the report's cusp of the bull-nose and flat mill (revolved_cusp).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "geometry/engagement.h"
#include "geometry/revolved_engagement.h"

namespace {

using namespace vcpost::geometry;
constexpr double kPi = std::numbers::pi;

struct Case {
  Tool tool;
  CutSetup setup;
};

Tool finishing_tool(int kind) {
  return kind == 0 ? Tool::ball(10) : kind == 1 ? Tool::bull_nose(10, 2) : Tool::flat(10);
}

std::vector<Case> finishing_cases(int kind, int count) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Case> cases;
  for (int i = 0; i < count; ++i) {
    const auto n = normal_from_angles(60 * kPi / 180 * unit(rng), 2 * kPi * unit(rng));
    cases.push_back(
        {finishing_tool(kind),
         {0.1 + 0.4 * unit(rng), 0.2 + 0.8 * unit(rng), n, feed_from_angle(2 * kPi * unit(rng), n),
          unit(rng) < 0.5 ? Side::left : Side::right}});
  }
  return cases;
}

std::vector<Case> random_cases(int kind, int count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Case> cases;
  for (int i = 0; i < count; ++i) {
    const double diameter = 4 + 16 * unit(rng);
    const double corner = diameter / 2 * (0.1 + 0.8 * unit(rng));
    const double ap = diameter * (0.01 + 0.5 * unit(rng) * unit(rng));
    const double ae = diameter * (0.02 + 1.1 * unit(rng));
    const auto n = normal_from_angles(80 * kPi / 180 * unit(rng), 2 * kPi * unit(rng));
    const auto feed = feed_from_angle(2 * kPi * unit(rng), n);
    const Side side = unit(rng) < 0.5 ? Side::left : Side::right;
    const Tool tool = kind == 0   ? Tool::ball(diameter)
                      : kind == 1 ? Tool::bull_nose(diameter, corner)
                                  : Tool::flat(diameter);
    cases.push_back({tool, {ap, ae, n, feed, side}});
  }
  return cases;
}

// Nearly level feeds on the random set-ups' tools and widths: |F_z| log-
// uniform in 1e-6..1e-3, the end face nearly parallel to F, up and down
// the slope (`uphill`: F_z in 1e-5..1e-3 only). The bull-nose's mean goes
// round the boundary from |F_z| = 1e-5 and along the profile below, the
// feed turned level.
std::vector<Case> nearly_level_cases(int kind, int count, bool uphill = false) {
  std::vector<Case> cases = random_cases(kind, count);
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(0, 1);
  for (Case& c : cases) {
    const Eigen::Vector3d& n = c.setup.normal;
    const Eigen::Vector3d level = n.cross(Eigen::Vector3d::UnitZ()).normalized();
    const Eigen::Vector3d down = n.cross(level);  // down.z = -sin(tilt)
    const double size = std::pow(10.0, uphill ? -5 + 2 * unit(rng) : -6 + 3 * unit(rng));
    const double f_z = uphill || unit(rng) < 0.5 ? size : -size;
    const double s = std::clamp(f_z / down.z(), -1.0, 1.0);
    c.setup.feed = std::sqrt(1 - s * s) * level + s * down;
  }
  return cases;
}

// Level feeds (F_z = 0: Z-level passes) on the random set-ups, either way
// along the level line.
std::vector<Case> level_cases(int kind, int count) {
  std::vector<Case> cases = random_cases(kind, count);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Eigen::Vector3d level =
        cases[i].setup.normal.cross(Eigen::Vector3d::UnitZ()).normalized();
    cases[i].setup.feed = i % 2 == 0 ? level : Eigen::Vector3d(-level);
  }
  return cases;
}

void label(benchmark::State& state, const char* set) {
  const int kind = static_cast<int>(state.range(0));
  state.SetLabel(std::string(set) + " " + (kind == 0 ? "ball" : kind == 1 ? "bull-nose" : "flat"));
  state.SetItemsProcessed(state.iterations());
}

template <class Evaluate>
void run(benchmark::State& state, const std::vector<Case>& cases, const Evaluate& evaluate) {
  std::size_t i = 0;
  for (auto _ : state) {
    const Case& c = cases[i++ % cases.size()];
    benchmark::DoNotOptimize(evaluate(c.tool, c.setup));
  }
}

// With the cutting points, as a report asks for them.
Engagement extremes(const Tool& tool, const CutSetup& setup) {
  return evaluate_engagement(tool, setup, CuttingPointsWanted::yes);
}

// Without them, as `vcpost post` evaluates (the D_max policy).
Engagement extremes_only(const Tool& tool, const CutSetup& setup) {
  return evaluate_engagement(tool, setup, CuttingPointsWanted::no);
}

void BM_ExtremesFinishing(benchmark::State& state) {
  run(state, finishing_cases(static_cast<int>(state.range(0)), 1024), extremes);
  label(state, "finishing");
}
void BM_ExtremesRandom(benchmark::State& state) {
  run(state, random_cases(static_cast<int>(state.range(0)), 1024), extremes);
  label(state, "random");
}
void BM_ExtremesOnlyFinishing(benchmark::State& state) {
  run(state, finishing_cases(static_cast<int>(state.range(0)), 1024), extremes_only);
  label(state, "finishing, no cutting points");
}
void BM_MeanFinishing(benchmark::State& state) {
  run(state, finishing_cases(static_cast<int>(state.range(0)), 256), engaged_mean_diameter);
  label(state, "finishing");
}
void BM_MeanRandom(benchmark::State& state) {
  run(state, random_cases(static_cast<int>(state.range(0)), 256), engaged_mean_diameter);
  label(state, "random");
}
void BM_MeanNearlyLevel(benchmark::State& state) {
  run(state, nearly_level_cases(static_cast<int>(state.range(0)), 64), engaged_mean_diameter);
  label(state, "nearly level");
}
BENCHMARK(BM_ExtremesFinishing)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ExtremesRandom)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ExtremesOnlyFinishing)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MeanFinishing)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MeanRandom)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MeanNearlyLevel)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
// Z-level passes as `vcpost post` evaluates them (no cutting points).
void BM_ExtremesOnlyLevel(benchmark::State& state) {
  run(state, level_cases(static_cast<int>(state.range(0)), 1024), extremes_only);
  label(state, "level, no cutting points");
}
BENCHMARK(BM_ExtremesOnlyLevel)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
void BM_MeanLevel(benchmark::State& state) {
  run(state, level_cases(static_cast<int>(state.range(0)), 256), engaged_mean_diameter);
  label(state, "level");
}
BENCHMARK(BM_MeanLevel)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
void BM_MeanNearlyLevelUphill(benchmark::State& state) {
  run(state, nearly_level_cases(static_cast<int>(state.range(0)), 256, true),
      engaged_mean_diameter);
  label(state, "nearly level uphill");
}
BENCHMARK(BM_MeanNearlyLevelUphill)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

// The report's cusp, Ra and Rz of a bull-nose (1) or flat mill (2) on the
// finishing set-ups: the second argument the surface's curvature across
// the feed, 1/mm (0: the tangent plane; 0.02: a convex R50 crest).
void BM_Cusp(benchmark::State& state) {
  const double curvature = static_cast<double>(state.range(1)) / 100;
  run(state, finishing_cases(static_cast<int>(state.range(0)), 1024),
      [&](const Tool& tool, const CutSetup& setup) {
        return revolved_cusp(tool, setup, curvature);
      });
  label(state, curvature == 0 ? "finishing, plane" : "finishing, curved");
}
BENCHMARK(BM_Cusp)->ArgsProduct({{1, 2}, {0, 2}})->Unit(benchmark::kMicrosecond);

// The issue's set-up on which the old mean did not finish in 300 s.
void BM_MeanIssueHangCase(benchmark::State& state) {
  const Tool tool = Tool::bull_nose(14.221441, 1.301500345);
  const CutSetup setup{1.496298,
                       1.614521,
                       {-0.131600501421, -0.225882401184, 0.965224558774},
                       {0.803756669574, -0.594227560155, -0.029475801401},
                       Side::left};
  for (auto _ : state) benchmark::DoNotOptimize(engaged_mean_diameter(tool, setup));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MeanIssueHangCase)->Unit(benchmark::kMicrosecond);

}  // namespace
