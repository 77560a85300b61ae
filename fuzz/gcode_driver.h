// The G-code driver (see fuzz/finding.h for the contract of drivers).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz/event_checks.h"
#include "postproc/gcode/diagnostics.h"
#include "postproc/gcode/dialect.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/gcode/writer.h"
#include "postproc/program/timing.h"

namespace vcpost::fuzz {

// Interpreter limits for fuzzing: loops, calls and recursion end long before
// the run's -timeout, so a slow input is a real finding, not a legal long
// loop (100,000 iterations of a loop that calls arcs took over 5 s in three
// dialects under the sanitizers).
inline gcode::InterpreterLimits fuzz_interpreter_limits() {
  gcode::InterpreterLimits limits;
  limits.max_loop_iterations = 100'000;
  limits.max_blocks = 50'000;
  limits.max_cycle_moves = 200'000;
  return limits;
}

// Interprets `text` in one dialect, times every event, then checks that the
// S/F writer is lossless (no patches: the same bytes) and accepts a patch
// on every block the interpreter read (up to 64 of them).
// Events per dialect past which a run stops ("budget"): a legal program
// can ask for millions (a Fanuc G83 with L320 repeats and Q2, 0.002 mm
// pecks, makes 3.5 M), more than the run's -timeout allows under the
// sanitizers.
inline constexpr std::uint64_t kFuzzMaxEvents = 500'000;

inline std::string run_gcode(std::string_view text, const gcode::Dialect& dialect) {
  gcode::Interpreter interpreter(text, dialect, fuzz_interpreter_limits());
  program::PathClock clock;
  std::vector<program::Event> events;
  std::vector<std::uint64_t> offsets;
  std::string outcome = "ok";
  std::uint64_t seen = 0;
  try {
    while (interpreter.next(events)) {
      for (const auto& e : events) {
        check_finite(e);
        clock.advance(e);
      }
      seen += events.size();
      events.clear();
      if (seen > kFuzzMaxEvents) {
        outcome = "budget";
        break;
      }
      if (offsets.size() < 64) offsets.push_back(interpreter.block().offset);
    }
  } catch (const gcode::GcodeError& e) {
    outcome = std::string(to_string(e.diagnostic().code));
  } catch (const program::TimingError&) {
    outcome = "timing";
  }
  if (gcode::patched(text, {}) != text) throw FuzzFinding("writer without patches changed bytes");
  std::sort(offsets.begin(), offsets.end());
  offsets.erase(std::unique(offsets.begin(), offsets.end()), offsets.end());
  std::vector<gcode::WordPatch> patches;
  for (auto offset : offsets) patches.push_back({offset, 'S', "1234"});
  (void)gcode::patched(text, patches);
  return outcome;
}

// The same text in the three dialects: "rs274ngc:<outcome> fanuc:<outcome>
// mazak:<outcome>".
inline std::string run_gcode_all_dialects(std::string_view text) {
  return "rs274ngc:" + run_gcode(text, gcode::rs274ngc_dialect()) +
         " fanuc:" + run_gcode(text, gcode::fanuc_dialect()) +
         " mazak:" + run_gcode(text, gcode::mazak_dialect());
}

}  // namespace vcpost::fuzz
