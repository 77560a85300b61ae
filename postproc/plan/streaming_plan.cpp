#include "postproc/plan/streaming_plan.h"

#include <algorithm>
#include <cmath>
#include <span>

namespace vcpost::plan {

StreamingPlanner::StreamingPlanner(const machines::SpindleSpec& spec) : spec_(spec) {}

void StreamingPlanner::push(const Sample& sample) {
  if (finished_) throw PlanError("push after finish");
  samples_.push_back(sample);
  try {
    (void)plan_spindle(std::span(samples_).last(std::min<std::size_t>(2, samples_.size())), spec_);
  } catch (const PlanError&) {
    samples_.pop_back();
    throw;
  }
}

void StreamingPlanner::finish() {
  if (finished_) return;
  finished_ = true;
  final_ = plan_spindle(samples_, spec_).blocks;
  samples_.clear();
}

std::size_t StreamingPlanner::take_final(std::vector<BlockPlan>& out) {
  const std::size_t n = final_.size() - taken_;
  for (std::size_t k = taken_; k < final_.size(); ++k) {
    out.push_back(final_[k]);
    s_words_ += final_[k].s_word ? 1 : 0;
  }
  taken_ = final_.size();
  return n;
}

std::size_t StreamingPlanner::held_samples() const { return samples_.size(); }
std::size_t StreamingPlanner::s_words() const { return s_words_; }

StreamingFeedPlanner::StreamingFeedPlanner(std::optional<double> fz_mm, int teeth,
                                           const machines::FeedSpec& feed, double step_mm_per_min)
    : fz_mm_(fz_mm), teeth_(teeth), feed_(feed), step_(step_mm_per_min) {}

BlockFeed StreamingFeedPlanner::next(const BlockPlan& block, const BlockFeedInput& input) {
  SpindlePlan one;
  one.blocks.push_back(block);
  auto f = plan_feeds(one, std::span(&input, 1), fz_mm_, teeth_, feed_, step_)[0];
  if (f.f_mm_per_min > 0) {
    f.f_word = !in_effect_ || std::abs(*in_effect_ - f.f_mm_per_min) > step_ * 1e-6;
    in_effect_ = f.f_mm_per_min;
  }
  return f;
}

}  // namespace vcpost::plan
