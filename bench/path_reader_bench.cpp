// The post job's first, serial stage: G-code text -> timeline slots and path
// samples (PathReader), on a program shaped like vcpost-samplegen's wavy
// raster (the 1 M-point post of bench/scale.sh): modal "X.. Z.." G1 lines
// 0.077 mm apart, 6 decimals, zigzag rows with a Y step. Every other stage
// of the post runs in parallel behind this one, so its lines/s bound the
// post's points/s.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "machines/builtin.h"
#include "postproc/post/path_reader.h"

namespace {

std::string raster_program(int lines) {
  std::string text =
      "%\n(wavy raster)\nG21 G90 G17 G94 G40\nT1 M6\nS4000 M3\nG0 Z50.000000\n"
      "G0 X10.000000 Y10.000000\nG1 Z3.718361 F800\n";
  constexpr int kRow = 1292;
  constexpr double kStep = 0.0774594;
  char line[64];
  double y = 10.0;
  for (int i = 0; i < lines; ++i) {
    const int row = i / kRow;
    const int k = i % kRow;
    if (k == 0 && i > 0) {
      y += kStep;
      std::snprintf(line, sizeof line, "Y%.6f Z%.6f\n", y, 6.0 + 2.5 * std::sin(y));
    } else {
      const double x = 10.0 + kStep * (row % 2 == 0 ? k : kRow - k);
      std::snprintf(line, sizeof line, "X%.6f Z%.6f\n", x,
                    6.0 + 2.5 * std::sin(x * 0.3) * std::cos(y * 0.2));
    }
    text += line;
  }
  text += "G0 Z50.000000\nM5\nM30\n%\n";
  return text;
}

void BM_PathReaderRaster(benchmark::State& state) {
  const std::string text = raster_program(static_cast<int>(state.range(0)));
  const auto profile = vcpost::machines::builtin_profile("mazak-3axis");
  const auto dialect = vcpost::post::dialect_of(profile);
  vcpost::post::Chunk chunk;         // reused, as the post reuses its chunks
  vcpost::tools::ToolChoices tools;  // every tool a D10 ball, as `--tool ball:10`
  tools.table.add(vcpost::tools::parse_tool_option("ball:10"));
  tools.vc = 120;
  std::uint64_t blocks = 0;
  for (auto _ : state) {
    vcpost::post::PathReader reader(text, "raster.nc", vcpost::post::ProgramKind::gcode, dialect,
                                    profile, 0.5, false, tools, 0.3);
    // The post's chunk size and default sample spacing (0.5 mm).
    while (reader.read(chunk, 2048)) benchmark::DoNotOptimize(chunk.slots.data());
    blocks += reader.totals().blocks;
  }
  state.counters["blocks/s"] =
      benchmark::Counter(static_cast<double>(blocks), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PathReaderRaster)->Arg(200000)->Unit(benchmark::kMillisecond);

}  // namespace
