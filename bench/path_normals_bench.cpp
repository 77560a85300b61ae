// Normals from the toolpath (issue 39: posting without a model must be no
// slower than with one): estimate_path_normals on the generator's wavy
// rasters, the tips of a 6 mm ball, per point, beside the pass tracker
// alone on the same points (what the post with a model runs too, for ae),
// so the difference is what the normals cost on top of it; the model's
// contact queries per point are contact_bench's BM_WarmQueries. Arg: the
// stepover in hundredths of a mm.
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "postproc/pipeline/pass_tracker.h"
#include "postproc/pipeline/path_normals.h"
#include "postproc/samplegen/parts.h"
#include "postproc/samplegen/toolpath.h"

namespace {

using Eigen::Vector3d;
using vcpost::pipeline::PathNormalSettings;

struct Path {
  std::vector<Vector3d> tips;
  std::vector<Vector3d> feeds;  // unit, along the path
  std::vector<std::uint8_t> starts;
  double diameter = 0;
};

const Path& wavy_raster(std::int64_t stepover_hundredths) {
  static std::map<std::int64_t, Path> paths;
  auto [it, fresh] = paths.try_emplace(stepover_hundredths);
  if (!fresh) return it->second;
  const auto part = vcpost::samplegen::make_part("wavy");
  vcpost::samplegen::PathSpec spec;
  spec.pattern = vcpost::samplegen::Pattern::raster;
  spec.stepover = static_cast<double>(stepover_hundredths) / 100;
  spec.step = 0.5;
  spec.chord_tolerance = vcpost::samplegen::kSampleChordTolerance;
  spec.tool_radius = part->tool_diameter / 2;
  spec.window = part->raster_window;
  spec.window_radius = part->raster_radius;
  Path& path = it->second;
  path.diameter = part->tool_diameter;
  vcpost::samplegen::generate(*part->surface, spec, 6, [&](const vcpost::samplegen::PathPoint& p) {
    path.tips.push_back(p.tip);
    path.starts.push_back(path.tips.size() == 1 ? 1 : 0);
  });
  for (std::size_t i = 0; i < path.tips.size(); ++i) {
    const std::size_t j = i + 1 < path.tips.size() ? i + 1 : i;
    const std::size_t k = j == i ? i - 1 : i;
    const Vector3d d = path.tips[j] - path.tips[k];
    path.feeds.push_back(d.norm() > 0 ? Vector3d(d.normalized()) : Vector3d::UnitX());
  }
  return path;
}

PathNormalSettings settings_for(const Path& path) {
  PathNormalSettings settings;
  settings.search_radius = path.diameter;
  settings.min_path_gap = 4 * path.diameter;  // as the post's pass tracker
  return settings;
}

void BM_PathNormals(benchmark::State& state) {
  const Path& path = wavy_raster(state.range(0));
  std::vector<vcpost::pipeline::EarlierPass> earlier;
  for (auto _ : state) {
    benchmark::DoNotOptimize(vcpost::pipeline::estimate_path_normals(path.tips, path.starts,
                                                                     settings_for(path), &earlier));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(path.tips.size()));
}
BENCHMARK(BM_PathNormals)->Arg(10)->Arg(50)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PassTrackerOnTheSamePoints(benchmark::State& state) {
  const Path& path = wavy_raster(state.range(0));
  const PathNormalSettings settings = settings_for(path);
  for (auto _ : state) {
    vcpost::pipeline::PassTracker tracker(settings.search_radius, settings.min_path_gap,
                                          vcpost::pipeline::PassTracker::kPostMemory);
    std::size_t found = 0;
    for (std::size_t i = 0; i < path.tips.size(); ++i) {
      const Vector3d up = (Vector3d::UnitZ() - path.feeds[i].z() * path.feeds[i]).normalized();
      found += tracker.step(path.tips[i], up, path.feeds[i]) ? 1 : 0;
    }
    benchmark::DoNotOptimize(found);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(path.tips.size()));
}
BENCHMARK(BM_PassTrackerOnTheSamePoints)->Arg(10)->Arg(50)->Unit(benchmark::kMillisecond);

}  // namespace
