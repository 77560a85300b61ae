// Random spindle specs and timelines for the planner's property tests
// (spindle_plan_test.cpp, streaming_plan_test.cpp).
#pragma once

#include <random>
#include <vector>

#include "machines/profile.h"
#include "postproc/plan/spindle_plan.h"

namespace vcpost::plan::testing {

// Round `round`'s spec: a shipped profile on even rounds, a random one
// (coarse resolutions, slow spindles, tight rates) on odd ones; always with
// stops_path_on_change false (the per-block planner of streaming_plan.h).
machines::SpindleSpec property_spec(int round, std::mt19937& rng);

// Blocks of random length with 1..4 samples, targets as a random walk with
// jumps, beyond the range now and then, rapids, air moves, tool changes,
// M5 and S0 stretches, direction changes. `time_scale` stretches every
// block (0.01: dense samples, 20: sparse ones).
std::vector<Sample> random_timeline(const machines::SpindleSpec& spec, std::mt19937& rng,
                                    double time_scale = 1.0);

// One sample per block at its start, blocks of `dt` seconds, targets
// target(t) in rpm.
template <class F>
std::vector<Sample> uniform(std::size_t blocks, double dt, F target, double program_rpm = 8000) {
  std::vector<Sample> out;
  out.reserve(blocks);
  for (std::size_t k = 0; k < blocks; ++k) {
    Sample s;
    s.time_s = static_cast<double>(k) * dt;
    s.block = k;
    s.target_rpm = target(s.time_s);
    s.program_rpm = program_rpm;
    out.push_back(s);
  }
  return out;
}

}  // namespace vcpost::plan::testing
