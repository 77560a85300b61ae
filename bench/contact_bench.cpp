// Closest-point queries on a B-spline STEP face (geometry/occt): warm along
// a coherent toolpath (one and two threads), cold through the BVH, and in
// the same process on the same points OpenCASCADE's GeomAPI_ProjectPointOnSurf
// per point and a warm Extrema_GenLocateExtPS; the same surface cut into
// 10 x 10 sewn faces (occt::wavy_patches) written to STEP and loaded back
// (load time, warm and cold queries on the same path); after the Google
// Benchmark runs, a summary prints microseconds per point and the ratios.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <BRep_Tool.hxx>
#include <Extrema_GenLocateExtPS.hxx>
#include <Extrema_POnSurf.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom_Surface.hxx>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "geometry/occt/brep_model.h"
#include "geometry/occt/sample_shapes.h"
#include "geometry/occt/shape_model.h"

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using vcpost::geometry::ContactHint;
using vcpost::occt::BrepModel;

constexpr double kRadius = 5;  // ball of 10 mm

struct Setup {
  TopoDS_Face face = vcpost::occt::wavy_bspline_face();
  Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
  BrepModel model = vcpost::occt::model_from_shape(face);
  std::vector<Vector3d> path;  // ball centres, zig-zag raster, 0.02 mm apart along the pass
  std::vector<Vector2d> path_uv;
  std::vector<Vector3d> feet;       // the surface point under each centre: the exact CC
  std::vector<Vector3d> scattered;  // random centres for cold queries

  Setup() {
    // Zig-zag passes along u, 0.5 mm apart, each 0.02 mm between points
    // (u spans ~100 mm): centres R along the normal from the surface.
    for (int pass = 0; pass < 20; ++pass) {
      const double v = 0.05 + 0.9 * pass / 19.0;
      for (int i = 0; i <= 5000; ++i) {
        const double s = 0.02 + 0.96 * i / 5000.0;
        const double u = pass % 2 == 0 ? s : 1 - s;
        GeomLProp_SLProps props(surface, u, v, 1, 1e-9);
        const gp_Pnt p = props.Value();
        gp_Dir n = props.Normal();
        if (n.Z() < 0) n.Reverse();
        path.emplace_back(p.X() + kRadius * n.X(), p.Y() + kRadius * n.Y(),
                          p.Z() + kRadius * n.Z());
        path_uv.emplace_back(u, v);
        feet.emplace_back(p.X(), p.Y(), p.Z());
      }
    }
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> xy(0, 100), z(-5, 15);
    for (int i = 0; i < 20000; ++i) scattered.emplace_back(xy(rng), xy(rng), z(rng));
  }
};

const Setup& setup() {
  static const Setup s;
  return s;
}

// Warm queries over [begin, end) of the path with one hint; returns a sum
// so the work is kept.
double warm_run(const Setup& s, std::size_t begin, std::size_t end) {
  ContactHint hint;
  double sum = 0;
  for (std::size_t i = begin; i < end; ++i) {
    sum += s.model.closest_point(s.path[i], 2 * kRadius, &hint)->distance;
  }
  return sum;
}

// Warm queries of `model` over every `stride`-th point of the path (stride
// 1: 0.02 mm apart, 5: 0.1 mm, 25: 0.5 mm).
double strided_warm_run(const BrepModel& model, const std::vector<Vector3d>& path,
                        std::size_t stride) {
  ContactHint hint;
  double sum = 0;
  for (std::size_t i = 0; i < path.size(); i += stride) {
    sum += model.closest_point(path[i], 2 * kRadius, &hint)->distance;
  }
  return sum;
}

double cold_run(const BrepModel& model, const std::vector<Vector3d>& points) {
  double sum = 0;
  for (const Vector3d& p : points) sum += model.closest_point(p, 1e9, nullptr)->distance;
  return sum;
}

double cpu_seconds();

// The wavy surface as 10 x 10 sewn B-spline faces, through a STEP file: the
// 100-face model of issue 7 (load time measured here, in this process).
struct Patches {
  std::optional<BrepModel> model;
  double load_wall_s = 0, load_cpu_s = 0;

  Patches() {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("vcpost_contact_bench_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::filesystem::path file = dir / "patches.step";
    vcpost::occt::write_shape_step(file, vcpost::occt::wavy_patches(10, 10),
                                   "vcpost wavy patches 10 x 10");
    const double cpu0 = cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    model.emplace(BrepModel::load_step(file));
    load_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    load_cpu_s = cpu_seconds() - cpu0;
    std::filesystem::remove_all(dir);
  }
};

const Patches& patches() {
  static const Patches p;
  return p;
}

void BM_PatchesWarm(benchmark::State& state) {
  const Setup& s = setup();
  const Patches& p = patches();
  const auto stride = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(strided_warm_run(*p.model, s.path, stride));
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>((s.path.size() + stride - 1) / stride));
}
BENCHMARK(BM_PatchesWarm)->Arg(1)->Arg(5)->Arg(25)->Unit(benchmark::kMillisecond);

void BM_PatchesCold(benchmark::State& state) {
  const Setup& s = setup();
  const Patches& p = patches();
  for (auto _ : state) benchmark::DoNotOptimize(cold_run(*p.model, s.scattered));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(s.scattered.size()));
}
BENCHMARK(BM_PatchesCold)->Unit(benchmark::kMillisecond);

void BM_FaceWarmStrided(benchmark::State& state) {
  const Setup& s = setup();
  const auto stride = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(strided_warm_run(s.model, s.path, stride));
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>((s.path.size() + stride - 1) / stride));
}
BENCHMARK(BM_FaceWarmStrided)->Arg(5)->Arg(25)->Unit(benchmark::kMillisecond);

void BM_WarmQueries(benchmark::State& state) {
  const Setup& s = setup();
  // Each thread takes its own contiguous chunk of the path (own hint).
  const std::size_t chunk = s.path.size() / static_cast<std::size_t>(state.threads());
  const std::size_t begin = chunk * static_cast<std::size_t>(state.thread_index());
  for (auto _ : state) benchmark::DoNotOptimize(warm_run(s, begin, begin + chunk));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(chunk));
}
BENCHMARK(BM_WarmQueries)->Unit(benchmark::kMillisecond)->UseRealTime()->Threads(1)->Threads(2);

void BM_ColdQueries(benchmark::State& state) {
  const Setup& s = setup();
  for (auto _ : state) {
    double sum = 0;
    for (const Vector3d& p : s.scattered) {
      sum += s.model.closest_point(p, 1e9, nullptr)->distance;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(s.scattered.size()));
}
BENCHMARK(BM_ColdQueries)->Unit(benchmark::kMillisecond);

double geomapi_run(const Setup& s, std::size_t count, std::size_t stride) {
  double sum = 0;
  GeomAPI_ProjectPointOnSurf projector;
  for (std::size_t k = 0; k < count; ++k) {
    const Vector3d& p = s.path[k * stride];
    projector.Init(gp_Pnt(p.x(), p.y(), p.z()), s.surface);
    sum += projector.LowerDistance();
  }
  return sum;
}

void BM_GeomAPIProjectPointOnSurf(benchmark::State& state) {
  const Setup& s = setup();
  constexpr std::size_t kCount = 100;
  for (auto _ : state) benchmark::DoNotOptimize(geomapi_run(s, kCount, s.path.size() / kCount));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kCount));
}
BENCHMARK(BM_GeomAPIProjectPointOnSurf)->Unit(benchmark::kMillisecond);

// Extrema_GenLocateExtPS started from the previous point's answer (as our
// warm start), so it is compared like for like.
double locate_run(const Setup& s, std::size_t count) {
  const GeomAdaptor_Surface adaptor(s.surface);
  Extrema_GenLocateExtPS locate(adaptor);
  double u = s.path_uv[0].x(), v = s.path_uv[0].y(), sum = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const Vector3d& p = s.path[i];
    locate.Perform(gp_Pnt(p.x(), p.y(), p.z()), u, v, Standard_True);
    if (locate.IsDone()) {
      locate.Point().Parameter(u, v);
      sum += locate.SquareDistance();
    }
  }
  return sum;
}

void BM_ExtremaGenLocateExtPSWarm(benchmark::State& state) {
  const Setup& s = setup();
  constexpr std::size_t kCount = 20000;
  for (auto _ : state) benchmark::DoNotOptimize(locate_run(s, kCount));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kCount));
}
BENCHMARK(BM_ExtremaGenLocateExtPSWarm)->Unit(benchmark::kMillisecond);

// A real free-form part (shared data: 110 faces, 74 B-splines, trimmed):
// ball centres R off the surface along a zig-zag raster over its top.
struct RealPart {
  std::optional<BrepModel> model;
  std::vector<Vector3d> path;

  RealPart() {
    const std::filesystem::path file =
        std::filesystem::path(VCPOST_SHARED_DATA_DIR) / "step" / "bug27693_cornetta-step.stp";
    if (!std::filesystem::exists(file)) return;
    model.emplace(BrepModel::load_step(file));
    const Eigen::AlignedBox3d box = model->bounds();
    ContactHint hint;
    for (int pass = 0; pass < 40; ++pass) {
      const double y = box.min().y() + box.sizes().y() * (pass + 0.5) / 40;
      for (int i = 0; i <= 1000; ++i) {
        const double t = (pass % 2 == 0 ? i : 1000 - i) / 1000.0;
        const Vector3d above(box.min().x() + box.sizes().x() * t, y, box.max().z() + 20);
        const auto c = model->closest_point(above, 1e9, &hint);
        path.push_back(c->point + kRadius * (above - c->point).normalized());
      }
    }
  }
};

const RealPart& real_part() {
  static const RealPart part;
  return part;
}

double real_run(const RealPart& part, bool warm) {
  ContactHint hint;
  double sum = 0;
  for (const Vector3d& p : part.path) {
    sum += part.model->closest_point(p, 1e9, warm ? &hint : nullptr)->distance;
  }
  return sum;
}

void BM_RealPart(benchmark::State& state) {
  const RealPart& part = real_part();
  if (!part.model) {
    state.SkipWithError("shared data absent");
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(real_run(part, state.range(0) == 1));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(part.path.size()));
  state.SetLabel(state.range(0) == 1 ? "warm" : "cold");
}
BENCHMARK(BM_RealPart)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

struct Timing {
  double wall_us = 0, cpu_us = 0;  // per point; cpu is summed over the process' threads
};

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Best of `repeats` runs: the machine is shared, so the CPU time is the
// steadier figure when others are busy.
template <class F>
Timing per_point(F&& run, std::size_t points, int repeats) {
  Timing best{1e300, 1e300};
  for (int r = 0; r < repeats; ++r) {
    const double cpu0 = cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(run());
    const std::chrono::duration<double, std::micro> took = std::chrono::steady_clock::now() - start;
    const double n = static_cast<double>(points);
    best.wall_us = std::min(best.wall_us, took.count() / n);
    best.cpu_us = std::min(best.cpu_us, (cpu_seconds() - cpu0) * 1e6 / n);
  }
  return best;
}

void print_summary() {
  const Setup& s = setup();
  const std::size_t n = s.path.size();
  const Timing warm = per_point([&] { return warm_run(s, 0, n); }, n, 5);
  const Timing warm2 = per_point(
      [&] {
        double a = 0, b = 0;
        std::thread t([&] { a = warm_run(s, 0, n / 2); });
        b = warm_run(s, n / 2, n);
        t.join();
        return a + b;
      },
      n, 5);
  const Timing cold = per_point(
      [&] {
        double sum = 0;
        for (const Vector3d& p : s.scattered)
          sum += s.model.closest_point(p, 1e9, nullptr)->distance;
        return sum;
      },
      s.scattered.size(), 3);
  const Timing geomapi = per_point([&] { return geomapi_run(s, 100, n / 100); }, 100, 3);
  const Timing locate = per_point([&] { return locate_run(s, n); }, n, 3);
  // Exactness on the same run: CC against the construction's foot points.
  ContactHint hint;
  double worst = 0;
  for (std::size_t i = 0; i < n; ++i) {
    worst = std::max(
        worst, (s.model.closest_point(s.path[i], 2 * kRadius, &hint)->point - s.feet[i]).norm());
  }
  std::printf(
      "\ncontact on a bicubic B-spline face (%d triangles in the index), %zu path points,"
      " ball R %.0f mm; largest CC error against the construction %.2e mm\n",
      s.model.info().triangles, n, kRadius, worst);
  std::printf("  %-32s %10s %10s %12s\n", "per point", "wall us", "CPU us", "M points/s");
  const auto row = [](const char* name, const Timing& t) {
    std::printf("  %-32s %10.3f %10.3f %12.3f\n", name, t.wall_us, t.cpu_us, 1 / t.wall_us);
  };
  row("ours warm, 1 thread", warm);
  row("ours warm, 2 threads (total)", warm2);
  row("ours cold (BVH + Newton)", cold);
  row("GeomAPI_ProjectPointOnSurf", geomapi);
  row("Extrema_GenLocateExtPS warm", locate);
  std::printf(
      "  ratios (CPU): GeomAPI / ours warm %.0fx, GeomAPI / ours cold %.0fx, "
      "Extrema_GenLocateExtPS / ours warm %.1fx\n",
      geomapi.cpu_us / warm.cpu_us, geomapi.cpu_us / cold.cpu_us, locate.cpu_us / warm.cpu_us);
  std::printf(
      "  ratios (wall): GeomAPI / ours warm %.0fx, Extrema_GenLocateExtPS / ours warm %.1fx\n",
      geomapi.wall_us / warm.wall_us, locate.wall_us / warm.wall_us);
  const Patches& p = patches();
  std::printf(
      "  the same surface as 10 x 10 sewn faces (%d faces, %d triangles): STEP load %.3f s wall,"
      " %.3f s CPU (first load in this process)\n",
      p.model->face_count(), p.model->info().triangles, p.load_wall_s, p.load_cpu_s);
  for (const std::size_t stride : {std::size_t{1}, std::size_t{5}, std::size_t{25}}) {
    const std::size_t m = (n + stride - 1) / stride;
    const std::string face_name =
        "1 face warm, " + std::to_string(0.02 * static_cast<double>(stride)).substr(0, 4) + " mm";
    const std::string name = "100 faces warm, " +
                             std::to_string(0.02 * static_cast<double>(stride)).substr(0, 4) +
                             " mm";
    row(face_name.c_str(),
        per_point([&] { return strided_warm_run(s.model, s.path, stride); }, m, 3));
    row(name.c_str(), per_point([&] { return strided_warm_run(*p.model, s.path, stride); }, m, 3));
  }
  row("100 faces cold",
      per_point([&] { return cold_run(*p.model, s.scattered); }, s.scattered.size(), 2));
  {
    // Same surface, same points: the two models must give the same CC.
    ContactHint patch_hint;
    double worst_patch = 0;
    for (std::size_t i = 0; i < n; ++i) {
      worst_patch = std::max(
          worst_patch,
          (p.model->closest_point(s.path[i], 2 * kRadius, &patch_hint)->point - s.feet[i]).norm());
    }
    std::printf("  100 faces: largest CC error against the construction %.2e mm\n", worst_patch);
  }
  const RealPart& part = real_part();
  if (part.model) {
    const std::size_t m = part.path.size();
    std::printf("  real part (cornetta, %d faces, %d triangles), %zu points on a raster:\n",
                part.model->face_count(), part.model->info().triangles, m);
    row("ours warm, 1 thread", per_point([&] { return real_run(part, true); }, m, 3));
    row("ours cold", per_point([&] { return real_run(part, false); }, m, 2));
  }
}

}  // namespace

// --no_summary skips the summary (for profiling one benchmark, e.g. under
// valgrind --tool=callgrind).
int main(int argc, char** argv) {
  bool summary = true;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--no_summary") {
      summary = false;
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (summary) print_summary();
  return 0;
}
