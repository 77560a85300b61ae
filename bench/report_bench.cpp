// The report's own cost, without the post job: collecting N points (rows,
// statistics, decimation, grids, regions), streaming them as CSV, and
// rendering the HTML page, with the page's size as a counter. The points
// follow a zig-zag raster over 120 x 80 mm with a working diameter and a
// planned S that vary along it, so every plot and table has content.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>

#include "postproc/report/chart_library.h"
#include "postproc/report/csv_writer.h"
#include "postproc/report/report.h"

namespace {

using namespace vcpost;

report::ReportInputs inputs() {
  report::ReportInputs in;
  in.program = "bench.nc";
  in.vc_nominal = 120;
  in.n_min_rpm = 35;
  in.n_max_rpm = 12000;
  in.plan_min = {-6, -6};
  in.plan_max = {126, 86};
  return in;
}

struct Point {
  pipeline::PathSample sample;
  pipeline::PointResult result;
  post::PointRecord record;
};

// Point k of n on the raster.
Point point(std::size_t k, std::size_t n) {
  const double passes = 40, per_pass = static_cast<double>(n) / passes;
  const double pass = std::floor(static_cast<double>(k) / per_pass);
  const double u = (static_cast<double>(k) - pass * per_pass) / per_pass;
  Point p;
  const double x = static_cast<int>(pass) % 2 == 0 ? 120 * u : 120 * (1 - u), y = 2 * pass;
  p.sample.point = {x, y, 6 * std::sin(2 * std::numbers::pi * x / 60)};
  p.result.contact.status = geometry::BallStatus::touching;
  geometry::ModelContact c;
  c.point = p.sample.point;
  p.result.contact.contact = c;
  p.result.feed = Eigen::Vector3d::UnitX();
  p.result.ae = 2;
  p.result.ae_source = pipeline::AeSource::measured;
  const double d = 3.4 + 2.5 * std::abs(std::sin(2 * std::numbers::pi * x / 60));
  geometry::Engagement e;
  e.d_max = d;
  e.d_min = 0.5;
  p.result.engagement = e;
  p.result.d_ref = d;
  const double target = 1000 * 120 / (std::numbers::pi * d);
  p.record = {static_cast<std::uint32_t>(10 + k / 4),
              0.001 * static_cast<double>(k),
              0.001,
              4800,
              std::min(target, 12000.0),
              target > 12000 ? plan::Bound::n_max : plan::Bound::none};
  return p;
}

std::string chart_library() {
  std::ifstream in(std::string(report::chart_library_path()), std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void BM_CollectAndCsv(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::uint64_t bytes = 0;
  for (auto _ : state) {
    report::ReportCollector collector(inputs());
    report::CsvWriter csv([&](std::string_view chunk) { bytes += chunk.size(); });
    for (std::size_t k = 0; k < n; ++k) {
      const Point p = point(k, n);
      csv.write(collector.add(p.sample, p.result, p.record));
    }
    csv.finish();
    benchmark::DoNotOptimize(collector.finish({}, 0));
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
  state.counters["csv_MB"] =
      static_cast<double>(bytes) / static_cast<double>(state.iterations()) / 1e6;
}
BENCHMARK(BM_CollectAndCsv)->Arg(1000000)->Unit(benchmark::kMillisecond);

void BM_RenderHtml(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  report::ReportCollector collector(inputs());
  for (std::size_t k = 0; k < n; ++k) {
    const Point p = point(k, n);
    collector.add(p.sample, p.result, p.record);
  }
  const report::ReportData data = collector.finish({}, 0);
  const std::string library = chart_library();
  std::size_t size = 0;
  for (auto _ : state) {
    const std::string page = report::render_html(data, library);
    size = page.size();
    benchmark::DoNotOptimize(page.data());
  }
  state.counters["page_MB"] = static_cast<double>(size) / 1e6;
  // To time a browser on the page: VCPOST_REPORT_BENCH_PAGE=/tmp/p.html
  // writes the last page rendered.
  if (const char* path = std::getenv("VCPOST_REPORT_BENCH_PAGE")) {
    std::ofstream(path, std::ios::binary) << report::render_html(data, library);
  }
  state.counters["library_MB"] = static_cast<double>(library.size()) / 1e6;
}
BENCHMARK(BM_RenderHtml)->Arg(1000000)->Arg(10000000)->Unit(benchmark::kMillisecond);

}  // namespace
