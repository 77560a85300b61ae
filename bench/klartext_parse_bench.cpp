// Read speed of the Klartext reader against the G-code reader (lines/s),
// issue 38's figure: on the same 1 M-block path (a raster of straight feed
// moves with three coordinates, as hyperMILL writes its finishing
// programs), Klartext within 20 % of G-code.
//   build/release/bench/klartext_parse_bench --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>
#include <vector>

#include "postproc/gcode/interpreter.h"
#include "postproc/heidenhain/interpreter.h"

namespace {

// The i-th point of the path, as both programs write it.
void point(int i, double& x, double& y, double& z) {
  x = (i % 1000) * 0.1;
  y = (i / 1000) * 0.25;
  z = -0.001 * (i % 97);
}

std::string gcode_program(int blocks) {
  std::string text = "G21 G90 G17\nS12000 M3\nG0 X0 Y0 Z5\nG1 Z0 F1500\n";
  char line[80];
  double x, y, z;
  for (int i = 0; i < blocks; ++i) {
    point(i, x, y, z);
    std::snprintf(line, sizeof line, "G1 X%.4f Y%.4f Z%.4f\n", x, y, z);
    text += line;
  }
  return text + "M30\n";
}

// hyperMILL's form: block numbers, L with all three axes.
std::string klartext_program(int blocks) {
  std::string text =
      "0 BEGIN PGM BENCH MM\n1 TOOL CALL 1 Z S12000\n2 L X+0 Y+0 Z+5 R0 FMAX M3\n"
      "3 L Z+0 F1500\n";
  char line[96];
  double x, y, z;
  for (int i = 0; i < blocks; ++i) {
    point(i, x, y, z);
    std::snprintf(line, sizeof line, "%d L X%.4f Y%.4f Z%.4f\n", i + 4, x, y, z);
    text += line;
  }
  return text + std::to_string(blocks + 4) + " M30\n" + std::to_string(blocks + 5) +
         " END PGM BENCH MM\n";
}

void BM_ReadGcode(benchmark::State& state) {
  const std::string text = gcode_program(static_cast<int>(state.range(0)));
  std::vector<vcpost::program::Event> events;
  std::uint64_t lines = 0;
  for (auto _ : state) {
    vcpost::gcode::Interpreter interpreter(text, vcpost::gcode::rs274ngc_dialect());
    while (interpreter.next(events)) events.clear();
    lines += interpreter.lines_read();
  }
  state.counters["lines/s"] =
      benchmark::Counter(static_cast<double>(lines), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ReadGcode)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

void BM_ReadKlartext(benchmark::State& state) {
  const std::string text = klartext_program(static_cast<int>(state.range(0)));
  std::vector<vcpost::program::Event> events;
  std::uint64_t lines = 0;
  for (auto _ : state) {
    vcpost::heidenhain::Interpreter interpreter(text);
    while (interpreter.next(events)) events.clear();
    lines += interpreter.lines_read();
  }
  state.counters["lines/s"] =
      benchmark::Counter(static_cast<double>(lines), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ReadKlartext)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

}  // namespace
