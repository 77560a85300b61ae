// The intake and output that the streamed spindle planners share
// (StreamingPlanner, StopAwarePlanner): samples checked and gathered into
// the open block, which closes when the first sample of the next block comes
// (or at finish()), and the queue of planned blocks taken out in order once
// final. A CRTP base: the planner (Derived) gives
// - void close_block(double end_s): the open block (open_) is complete; it
//   ends at end_s, the first time of the next block (its own last time at
//   the end of the timeline); it clears open_;
// - void end_timeline(): after the last block closed (end the open run);
// - void taken(std::size_t n): n blocks were popped from the front of
//   blocks_ (to shift its indices);
// and Block (with BlockPlan plan and bool done) and the Queue that holds
// them (front, pop_front, empty).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "postproc/plan/plan_rules.h"
#include "postproc/plan/spindle_plan.h"

namespace vcpost::plan::detail {

template <class Derived, class Block, class Queue>
class BlockStream {
 public:
  // Throws PlanError like plan_spindle (the sample is then not taken), or
  // after finish().
  void push(const Sample& sample) {
    if (finished_)
      throw PlanError("sample " + std::to_string(pushed_) +
                      ": pushed after the end of the timeline");
    check_sample(pushed_, sample, open_.empty() ? nullptr : &open_.back());
    if (!open_.empty() && sample.block != open_.back().block) self().close_block(sample.time_s);
    open_.push_back(sample);
    ++pushed_;
  }

  void finish() {
    if (finished_) return;
    finished_ = true;
    if (!open_.empty()) self().close_block(open_.back().time_s);
    self().end_timeline();
  }

  // Appends the final blocks to `out` (does not clear it); returns how many.
  std::size_t take_final(std::vector<BlockPlan>& out) {
    std::size_t n = 0;
    while (!blocks_.empty() && blocks_.front().done) {
      const BlockPlan& plan = blocks_.front().plan;
      out.push_back(plan);
      taken_s_words_ += plan.s_word ? 1 : 0;
      blocks_.pop_front();
      ++n;
    }
    self().taken(n);
    return n;
  }

  std::size_t s_words() const { return taken_s_words_; }  // among the blocks taken

 protected:
  BlockStream() = default;

  std::size_t pushed_ = 0;
  std::vector<Sample> open_;  // samples of the open block
  bool finished_ = false;
  Queue blocks_;  // planned blocks not taken yet, in order
  std::size_t taken_s_words_ = 0;

 private:
  Derived& self() { return static_cast<Derived&>(*this); }
};

}  // namespace vcpost::plan::detail
