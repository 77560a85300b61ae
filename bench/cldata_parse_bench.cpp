// APT CL parse speed on a generated 1 M-point GOTO file (NX CLSF style,
// 4 decimals): records/s of the record reader alone and of the full reader
// to motion events, and the peak-RSS growth while reading (streaming: it
// must stay at the reader's buffers, not the file size).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "postproc/cldata/cl_reader.h"
#include "postproc/cldata/record_reader.h"

namespace {

constexpr long points = 1'000'000;

const std::string& generated_file() {
  static const std::string path = [] {
    const auto p = std::filesystem::temp_directory_path() /
                   ("vcpost_cldata_bench_" + std::to_string(points) + ".cls");
    if (!std::filesystem::exists(p)) {
      std::ofstream out(p, std::ios::binary);
      out << "TOOL PATH/FIXED_CONTOUR,TOOL,BALL_MILL\n"
             "TLDATA/MILL,10.0000,5.0000,75.0000,0.0000,0.0000\n"
             "FEDRAT/MMPM,2000.0000\nSPINDL/RPM,12000,CLW\n";
      char line[128];
      for (long i = 0; i < points; ++i) {
        const double t = static_cast<double>(i) * 1e-3;
        std::snprintf(line, sizeof line, "GOTO/%.4f,%.4f,%.4f\n", 100.0 * std::cos(t),
                      100.0 * std::sin(t), -0.001 * static_cast<double>(i % 5000));
        out << line;
      }
      out << "END-OF-PATH\n";
    }
    return p.string();
  }();
  return path;
}

long max_rss_kb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

void BM_ClRecordReader(benchmark::State& state) {
  const std::string& path = generated_file();
  std::uint64_t records = 0;
  for (auto _ : state) {
    std::ifstream in(path, std::ios::binary);
    vcpost::cldata::ClRecordReader reader(in, path);
    vcpost::cldata::ClRecord r;
    while (reader.next(r)) {
      ++records;
      benchmark::DoNotOptimize(r.params.data());
    }
  }
  state.counters["records/s"] =
      benchmark::Counter(static_cast<double>(records), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ClRecordReader)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_ClReaderEvents(benchmark::State& state) {
  const std::string& path = generated_file();
  std::uint64_t records = 0;
  std::uint64_t events = 0;
  const long rss_before = max_rss_kb();
  for (auto _ : state) {
    std::ifstream in(path, std::ios::binary);
    vcpost::cldata::ClReader reader(in, path);
    while (auto e = reader.next()) {
      ++events;
      benchmark::DoNotOptimize(e);
    }
    records += reader.record_count();
  }
  state.counters["records/s"] =
      benchmark::Counter(static_cast<double>(records), benchmark::Counter::kIsRate);
  state.counters["events/s"] =
      benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsRate);
  state.counters["file_MB"] =
      static_cast<double>(std::filesystem::file_size(path)) / (1024.0 * 1024.0);
  state.counters["peak_rss_growth_kB"] = static_cast<double>(max_rss_kb() - rss_before);
}
BENCHMARK(BM_ClReaderEvents)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
