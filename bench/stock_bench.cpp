// The in-process stock at the size of issue 44's target: a 300 x 300 mm
// block at 0.1 mm (9 M cells), 1 M roughing points (Z-level trochoidal rows
// of a D16 bull-nose, rc 0.8, levels 2 mm apart, moves 0.35-0.85 mm), then
// 1 M ball D10 finishing points (a raster over a wavy surface, 0.3 mm
// along, 0.3 mm across), then depth_along at 1 M finishing points along
// the surface normal. Process CPU time (both cores) and wall time.
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "geometry/stock/height_field.h"

namespace {

using Eigen::Vector3d;
using vcpost::geometry::Tool;
using vcpost::geometry::stock::Cutter;
using vcpost::geometry::stock::HeightField;

constexpr std::size_t kPoints = 1'000'000;
constexpr std::size_t kMemoryLimit = std::size_t{1} << 30;

HeightField block() { return HeightField::block({0, 0, -30}, {300, 300, 0}, 0.1, kMemoryLimit); }

// Trochoidal rows along x, 12 mm apart: loops of radius 4 advancing 1.5 mm
// a turn, 0.15 rad a point; a plunge to each level.
std::vector<Vector3d> roughing(std::size_t points) {
  std::vector<Vector3d> tips;
  tips.reserve(points);
  constexpr double kLoop = 4, kAdvance = 1.5, kStep = 0.15;
  for (int level = 1; tips.size() < points; ++level) {
    const double z = -2.0 * level;
    tips.emplace_back(-8, 4, 5);
    for (double y = 4; y < 304 && tips.size() < points; y += 12) {
      for (double theta = 0; tips.size() < points; theta += kStep) {
        const double x = -8 + kAdvance * theta / (2 * std::numbers::pi) + kLoop * std::cos(theta);
        if (x > 308) break;
        tips.emplace_back(x, y + kLoop * std::sin(theta), z);
      }
    }
  }
  return tips;
}

double surface(double x, double y) { return -14 + 3 * std::sin(x / 20) * std::cos(y / 25); }

Vector3d surface_normal(double x, double y) {
  const double dx = 3 * std::cos(x / 20) / 20 * std::cos(y / 25);
  const double dy = -3 * std::sin(x / 20) * std::sin(y / 25) / 25;
  return Vector3d(-dx, -dy, 1).normalized();
}

// A zig-zag raster of a D10 ball's tips on the wavy surface (the tip on
// the surface point under it: close enough for a load).
std::vector<Vector3d> finishing(std::size_t points) {
  std::vector<Vector3d> tips;
  tips.reserve(points);
  for (int row = 0; tips.size() < points; ++row) {
    const double y = 0.15 + 0.3 * row;
    for (int i = 0; i < 1000 && tips.size() < points; ++i) {
      const double x = row % 2 == 0 ? 0.15 + 0.3 * i : 299.85 - 0.3 * i;
      tips.emplace_back(x, y, surface(x, y));
    }
  }
  return tips;
}

void BM_CutPathRoughing(benchmark::State& state) {
  const std::vector<Vector3d> tips = roughing(static_cast<std::size_t>(state.range(0)));
  const Cutter cutter{Tool::bull_nose(16, 0.8)};
  for (auto _ : state) {
    state.PauseTiming();
    HeightField field = block();
    state.ResumeTiming();
    field.cut_path(cutter, tips);
    benchmark::DoNotOptimize(field.top(1500, 1500));
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * tips.size()));
}
BENCHMARK(BM_CutPathRoughing)
    ->Arg(100'000)
    ->Arg(kPoints)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

const HeightField& roughed() {
  static const HeightField field = [] {
    HeightField f = block();
    f.cut_path(Cutter{Tool::bull_nose(16, 0.8)}, roughing(kPoints));
    return f;
  }();
  return field;
}

void BM_CutPathFinishing(benchmark::State& state) {
  const std::vector<Vector3d> tips = finishing(kPoints);
  const Cutter cutter{Tool::ball(10)};
  const HeightField& start = roughed();
  for (auto _ : state) {
    state.PauseTiming();
    HeightField field = start;
    state.ResumeTiming();
    field.cut_path(cutter, tips);
    benchmark::DoNotOptimize(field.top(1500, 1500));
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * tips.size()));
}
BENCHMARK(BM_CutPathFinishing)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

// ap at each finishing point: the material over the surface along its
// normal, up to 10 mm, on the roughed stock.
void BM_DepthAlong(benchmark::State& state) {
  const std::vector<Vector3d> tips = finishing(kPoints);
  std::vector<Vector3d> normals;
  normals.reserve(tips.size());
  for (const Vector3d& p : tips) normals.push_back(surface_normal(p.x(), p.y()));
  const HeightField& field = roughed();
  double total = 0;
  for (auto _ : state) {
    for (std::size_t i = 0; i < tips.size(); ++i)
      total += field.depth_along(tips[i], normals[i], 10);
  }
  benchmark::DoNotOptimize(total);
  state.counters["mean_depth_mm"] = total / static_cast<double>(state.iterations() * tips.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * tips.size()));
}
BENCHMARK(BM_DepthAlong)->Unit(benchmark::kMillisecond);

}  // namespace
