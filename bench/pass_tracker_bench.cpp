// The pass tracker's cost per contact point (issue 7: the post job runs it
// sequentially for every point, so it must stay well under 0.2 us a point,
// whatever the point density). Same settings as the post job for a 10 mm
// ball: search radius D, path gap 4 D, memory 2^20 points.
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <numbers>
#include <vector>

#include "postproc/pipeline/pass_tracker.h"

namespace {

using Eigen::Vector3d;
using vcpost::pipeline::PassTracker;

struct Sample {
  Vector3d cc;
  Vector3d feed;
  bool new_pass = false;
  Vector3d normal = Vector3d::UnitZ();
};

// Zig-zag raster on z = 0: passes along x, `along` mm between points,
// `across` mm between passes, each pass `length` mm long.
std::vector<Sample> raster(double along, double across, double length, std::size_t points) {
  std::vector<Sample> out;
  const auto per_pass = static_cast<int>(std::lround(length / along)) + 1;
  for (int k = 0; out.size() < points; ++k) {
    const double sign = k % 2 == 0 ? 1 : -1;
    for (int i = 0; i < per_pass && out.size() < points; ++i) {
      const double x = sign > 0 ? along * i : length - along * i;
      out.push_back({Vector3d(x, across * k, 0), Vector3d(sign, 0, 0), i == 0});
    }
  }
  return out;
}

// Archimedean spiral on z = 0, `pitch` mm between turns, `along` mm between
// points; starts one turn out so the first turn is not a point.
std::vector<Sample> spiral(double along, double pitch, std::size_t points) {
  std::vector<Sample> out;
  const double b = pitch / (2 * std::numbers::pi);
  double theta = 2 * std::numbers::pi;
  while (out.size() < points) {
    const double r = b * theta;
    const Vector3d tangent = Vector3d(b * std::cos(theta) - r * std::sin(theta),
                                      b * std::sin(theta) + r * std::cos(theta), 0)
                                 .normalized();
    out.push_back({Vector3d(r * std::cos(theta), r * std::sin(theta), 0), tangent, out.empty()});
    theta += along / std::hypot(r, b);
  }
  return out;
}

// Zig-zag raster over z = 4 sin(2 pi x / 40) cos(2 pi y / 55) (waves of
// several mm, like the sample generator's wavy part): passes along x seen
// from above, `along` mm between points and `across` mm between passes,
// each `length` mm long; the true surface normal, the feed tangent to the
// surface.
std::vector<Sample> wavy_raster(double along, double across, double length, std::size_t points) {
  constexpr double kx = 2 * std::numbers::pi / 40, ky = 2 * std::numbers::pi / 55;
  std::vector<Sample> out;
  const auto per_pass = static_cast<int>(std::lround(length / along)) + 1;
  for (int k = 0; out.size() < points; ++k) {
    const double sign = k % 2 == 0 ? 1 : -1;
    const double y = across * k;
    for (int i = 0; i < per_pass && out.size() < points; ++i) {
      const double x = sign > 0 ? along * i : length - along * i;
      const double z = 4 * std::sin(kx * x) * std::cos(ky * y);
      const double zx = 4 * kx * std::cos(kx * x) * std::cos(ky * y);
      const double zy = -4 * ky * std::sin(kx * x) * std::sin(ky * y);
      const Vector3d normal = Vector3d(-zx, -zy, 1).normalized();
      const Vector3d feed = (sign * Vector3d(1, 0, zx)).normalized();  // normal . feed = 0
      out.push_back({Vector3d(x, y, z), feed, i == 0, normal});
    }
  }
  return out;
}

// One row of `points` points `along` mm apart on the wavy surface above
// (along x, at y = 20), run `times` times back and forth without a break
// but the turn: a repeated finishing pass. `jitter` mm moves each point
// across the row by a pseudo-random amount in [-jitter, jitter], as the
// contact points of a ball found again from another start do (about 0.03
// mm at the default contact tolerance); 0 retraces the row exactly, as the
// tool positions a bull-nose or flat mill is tracked by.
std::vector<Sample> retraced_row(double along, int points, int times, double jitter) {
  constexpr double kx = 2 * std::numbers::pi / 40, ky = 2 * std::numbers::pi / 55;
  const double y0 = 20;
  std::vector<Sample> out;
  std::uint64_t lcg = 99991;
  for (int k = 0; k < times; ++k) {
    const double sign = k % 2 == 0 ? 1 : -1;
    for (int i = 0; i < points; ++i) {
      const double x = sign > 0 ? along * i : along * (points - 1 - i);
      lcg = lcg * 6364136223846793005ULL + 1442695040888963407ULL;
      const double y = y0 + jitter * (static_cast<double>(lcg >> 11) * 0x1p-52 - 1);
      const double z = 4 * std::sin(kx * x) * std::cos(ky * y);
      const double zx = 4 * kx * std::cos(kx * x) * std::cos(ky * y);
      const double zy = -4 * ky * std::sin(kx * x) * std::sin(ky * y);
      const Vector3d normal = Vector3d(-zx, -zy, 1).normalized();
      const Vector3d feed = (sign * Vector3d(1, 0, zx)).normalized();
      out.push_back({Vector3d(x, y, z), feed, i == 0, normal});
    }
  }
  return out;
}

void run(benchmark::State& state, const std::vector<Sample>& path) {
  auto tracker = std::make_unique<PassTracker>(10.0, 40.0, std::size_t{1} << 20);
  std::size_t i = 0;
  std::size_t found = 0;
  for (auto _ : state) {
    if (i == path.size()) {
      state.PauseTiming();
      tracker = std::make_unique<PassTracker>(10.0, 40.0, std::size_t{1} << 20);
      i = 0;
      state.ResumeTiming();
    }
    const Sample& s = path[i++];
    if (s.new_pass) tracker->break_pass();
    const auto neighbour = tracker->step(s.cc, s.normal, s.feed);
    found += neighbour.has_value();
    benchmark::DoNotOptimize(neighbour);
  }
  state.counters["found"] =
      benchmark::Counter(static_cast<double>(found), benchmark::Counter::kAvgIterations);
}

// Dense finishing raster: 0.05 mm along, 0.3 mm across, 50 mm passes.
void BM_DenseRaster(benchmark::State& state) {
  static const auto path = raster(0.05, 0.3, 50, 200000);
  run(state, path);
}
BENCHMARK(BM_DenseRaster)->Iterations(200000);

// Fine raster like the sample generator's: 0.0775 mm along and across, 100 mm passes.
void BM_FineRaster(benchmark::State& state) {
  static const auto path = raster(0.0775, 0.0775, 100, 200000);
  run(state, path);
}
BENCHMARK(BM_FineRaster)->Iterations(200000);

// The fine raster over the wavy surface: what `vcpost post` meets on the
// sample generator's wavy part (curved passes: no run is flat).
void BM_WavyFineRaster(benchmark::State& state) {
  static const auto path = wavy_raster(0.0775, 0.0775, 100, 200000);
  run(state, path);
}
BENCHMARK(BM_WavyFineRaster)->Iterations(200000);

// Sparse raster: 0.5 mm along, 2 mm across, 50 mm passes.
void BM_SparseRaster(benchmark::State& state) {
  static const auto path = raster(0.5, 2, 50, 200000);
  run(state, path);
}
BENCHMARK(BM_SparseRaster)->Iterations(200000);

// Spiral: 0.05 mm along, 0.3 mm pitch (never breaks; the path gap decides).
void BM_Spiral(benchmark::State& state) {
  static const auto path = spiral(0.05, 0.3, 200000);
  run(state, path);
}
BENCHMARK(BM_Spiral)->Iterations(200000);

// Passes a hair apart or on top of each other (issue 42), each against an
// ordinary raster of the same number of points and spacing along the pass
// (BM_OrdinaryRaster): a 130-point row retraced 1000 times, its contact
// points jittered and exact; a raster at ae 0.005 mm.
void BM_OrdinaryRaster(benchmark::State& state) {
  static const auto path = wavy_raster(0.5, 0.5, 64.5, 130000);
  run(state, path);
}
BENCHMARK(BM_OrdinaryRaster)->Iterations(130000);

void BM_RetracedRowJittered(benchmark::State& state) {
  static const auto path = retraced_row(0.5, 130, 1000, 0.03);
  run(state, path);
}
BENCHMARK(BM_RetracedRowJittered)->Iterations(130000);

void BM_RetracedRowExact(benchmark::State& state) {
  static const auto path = retraced_row(0.5, 130, 1000, 0);
  run(state, path);
}
BENCHMARK(BM_RetracedRowExact)->Iterations(130000);

void BM_HairRaster(benchmark::State& state) {
  static const auto path = wavy_raster(0.5, 0.005, 64.5, 130000);
  run(state, path);
}
BENCHMARK(BM_HairRaster)->Iterations(130000);

}  // namespace
