// Rules shared by the planner (streaming_plan.cpp) and its whole-timeline
// reference in the tests (tests/postproc/plan/plan_reference_support.cpp), so
// that both give the same plan to the bit. Internal to the plan module.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>

#include "machines/profile.h"
#include "postproc/plan/spindle_plan.h"

namespace vcpost::plan::detail {

// Values on the S grid (multiples of the resolution). The small allowance
// keeps a value computed as 7345 - 1e-12 on 7345 instead of 7344.
struct Grid {
  double res;
  double floor(double x) const { return std::floor(x / res + 1e-9) * res; }
  double ceil(double x) const { return std::ceil(x / res - 1e-9) * res; }
};

// Comparisons of speeds on the grid: well under any resolution.
constexpr double kEps = 1e-6;

// No bound (yet): the start of a running minimum.
constexpr double kInf = std::numeric_limits<double>::infinity();

// Throws PlanError when sample `index` breaks the contract of spindle_plan.h;
// `prev` is the sample before it (nullptr for the first).
void check_sample(std::size_t index, const Sample& s, const Sample* prev);

inline bool spindle_on(const Sample& s) {
  return s.spindle != SpindleState::off && s.program_rpm > 0;
}

// What the bound of a planned block is decided from.
struct BlockFacts {
  bool any_target = false;  // a sample of the block has a target
  bool all_rapid = true;    // every sample of the block is a rapid
  double ceiling = 0.0;     // lowest ceiling E over the block's samples
  double curve_min = 0.0;   // lowest curve n over the block's span
};

// The limit that decided planned S `s` of a block whose smallest target is
// `target`; `lowered`: the S word in effect was lowered by the slew passes.
Bound classify_bound(const machines::SpindleSpec& spec, double g_min, double g_max,
                     const BlockFacts& facts, std::optional<double> target, double s, bool lowered);

}  // namespace vcpost::plan::detail
