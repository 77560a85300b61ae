// Parse + interpret speed of a plain 3-axis G1 program (lines/s), the
// figure of issue 3 (target 5 M lines/s). bench/gcode_parse.sh compares
// the whole `vcpost moves --count` run with rs274 on the same file.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>
#include <vector>

#include "postproc/gcode/interpreter.h"

namespace {

std::string plain_program(int lines) {
  std::string text = "G21 G90 G17\nS12000 M3\nG0 X0 Y0 Z5\nG1 Z0 F1500\n";
  char line[64];
  for (int i = 0; i < lines; ++i) {
    std::snprintf(line, sizeof line, "G1 X%.3f Y%.3f Z%.3f\n", (i % 1000) * 0.1, (i / 1000) * 0.25,
                  -0.001 * (i % 97));
    text += line;
  }
  text += "M30\n";
  return text;
}

void BM_ParseInterpretPlainG1(benchmark::State& state) {
  const std::string text = plain_program(static_cast<int>(state.range(0)));
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
BENCHMARK(BM_ParseInterpretPlainG1)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace
