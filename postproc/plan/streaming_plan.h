// The spindle planner for a streamed timeline: the same plan as
// plan_spindle() (spindle_plan.h holds the contract), computed while the
// samples come in, with bounded memory.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "machines/profile.h"
#include "postproc/plan/spindle_plan.h"

namespace vcpost::plan {

// Plans the spindle while the timeline streams in, with bounded memory:
// feed samples in order with push(); take the blocks whose plan can no
// longer change with take_final(); call finish() after the last sample,
// then take_final() returns the rest. The blocks come out in order and
// equal plan_spindle() over the whole timeline, field for field.
class StreamingPlanner {
 public:
  explicit StreamingPlanner(const machines::SpindleSpec& spec);
  void push(const Sample& sample);  // throws PlanError like plan_spindle
  void finish();
  // Appends the final blocks to `out` (does not clear it); returns how many.
  std::size_t take_final(std::vector<BlockPlan>& out);
  std::size_t held_samples() const;  // samples kept now (for tests of the bound)
  std::size_t s_words() const;       // S words among the blocks taken so far

 private:
  machines::SpindleSpec spec_;
  std::vector<Sample> samples_;
  std::vector<BlockPlan> final_;
  std::size_t taken_ = 0;
  std::size_t s_words_ = 0;
  bool finished_ = false;
};

// Feed coupling block by block, in plan order (what plan_feeds() does over a whole plan).
class StreamingFeedPlanner {
 public:
  StreamingFeedPlanner(std::optional<double> fz_mm, int teeth, const machines::FeedSpec& feed,
                       double step_mm_per_min);
  BlockFeed next(const BlockPlan& block, const BlockFeedInput& input);

 private:
  std::optional<double> fz_mm_;
  int teeth_;
  machines::FeedSpec feed_;
  double step_;
  std::optional<double> in_effect_;
};

}  // namespace vcpost::plan
