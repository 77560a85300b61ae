// STL mesh model: reading a 100 k-triangle binary STL, building the index
// (on one and on two of oneTBB's threads), and closest-point queries along a coherent finishing
// path (warm: the hint of the previous point; cold: no hint; two threads with a hint each).
//
// The mesh is the sample wavy mould (postproc/samplegen) tessellated on a
// 224 x 224 grid (100,352 triangles, about 0.54 x 0.36 mm cells); the query
// points are the ball centres (R = 5) of a drop-cutter raster over it,
// 0.1 mm apart along the feed, 1 mm between passes.
#include <benchmark/benchmark.h>
#include <oneapi/tbb/global_control.h>

#include <thread>

#include "geometry/mesh/mesh_model.h"
#include "geometry/mesh/stl_reader.h"
#include "postproc/samplegen/parts.h"

namespace {

using namespace vcpost;

const std::string& stl_bytes() {
  static const std::string bytes = [] {
    const auto part = samplegen::make_part("wavy");
    mesh::StlMesh m;
    const int n = 224;
    const auto box = part->surface->domain();
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j)
        m.vertices.push_back(part->surface->point(
            box.min() +
            (box.max() - box.min()).cwiseProduct(Eigen::Vector2d(double(i) / n, double(j) / n))));
    const auto at = [&](int i, int j) { return std::uint32_t(i * (n + 1) + j); };
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
    return mesh::to_binary_stl(m, "vcpost mesh_bench wavy mould");
  }();
  return bytes;
}

const mesh::MeshModel& model() {
  static const mesh::MeshModel m(mesh::parse_stl(stl_bytes(), "bench.stl"));
  return m;
}

const std::vector<Eigen::Vector3d>& path() {
  static const std::vector<Eigen::Vector3d> points = [] {
    const auto part = samplegen::make_part("wavy");
    samplegen::PathSpec spec;
    spec.tool_radius = 5;
    spec.window = part->raster_window;
    spec.stepover = 1;
    spec.step = 0.1;
    std::vector<Eigen::Vector3d> out;
    samplegen::generate(*part->surface, spec, 6,
                        [&](const samplegen::PathPoint& p) { out.push_back(p.center); });
    return out;
  }();
  return points;
}

void BM_StlParseBinary(benchmark::State& state) {
  const std::string& bytes = stl_bytes();
  for (auto _ : state) benchmark::DoNotOptimize(mesh::parse_stl(bytes, "bench.stl"));
  state.SetItemsProcessed(state.iterations() * 100352);
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(bytes.size()));
}
BENCHMARK(BM_StlParseBinary)->Unit(benchmark::kMillisecond);

// Argument: the threads oneTBB may use (the index is the same for any).
// Real time: the build runs on oneTBB's workers too.
void BM_MeshIndexBuild(benchmark::State& state) {
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(state.range(0)));
  const mesh::StlMesh m = mesh::parse_stl(stl_bytes(), "bench.stl");
  for (auto _ : state) benchmark::DoNotOptimize(mesh::MeshModel(m));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(m.triangles.size()));
}
BENCHMARK(BM_MeshIndexBuild)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Each thread walks its own contiguous chunk of the path with its own hint.
void query(benchmark::State& state, bool warm) {
  const auto& m = model();
  const auto& pts = path();
  const std::size_t chunk = pts.size() / static_cast<std::size_t>(state.threads());
  const std::size_t begin = chunk * static_cast<std::size_t>(state.thread_index());
  geometry::ContactHint hint;
  std::size_t i = begin;
  for (auto _ : state) {
    auto c = m.closest_point(pts[i], 5 + 1, warm ? &hint : nullptr);
    benchmark::DoNotOptimize(c);
    if (++i == begin + chunk) i = begin;
  }
  state.SetItemsProcessed(state.iterations());
  if (warm) {
    state.counters["warm_share"] = benchmark::Counter(
        double(hint.warm_queries) /
            double(std::max<std::uint64_t>(1, hint.warm_queries + hint.cold_queries)),
        benchmark::Counter::kAvgThreads);
  }
}

void BM_MeshWarmQuery(benchmark::State& state) { query(state, true); }
void BM_MeshColdQuery(benchmark::State& state) { query(state, false); }
BENCHMARK(BM_MeshWarmQuery)->Threads(1)->Threads(2)->UseRealTime();
BENCHMARK(BM_MeshColdQuery)->Threads(1)->Threads(2)->UseRealTime();

}  // namespace
