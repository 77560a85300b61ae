#include "postproc/plan/streaming_plan.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "postproc/plan/plan_rules.h"
#include "postproc/plan/stop_aware_plan.h"

namespace vcpost::plan {

using detail::Grid;
using detail::kEps;
using detail::kInf;

double StreamingPlanner::horizon_s(const machines::SpindleSpec& spec) {
  const Grid grid{spec.s_resolution_rpm};
  const double range = std::max(0.0, grid.floor(spec.n_max_rpm) - grid.ceil(spec.n_min_rpm));
  return range / spec.deceleration_rpm_per_s + 1e-3;
}

StreamingPlanner::StreamingPlanner(const machines::SpindleSpec& spec)
    : spec_(spec),
      res_(spec.s_resolution_rpm),
      g_min_(Grid{spec.s_resolution_rpm}.ceil(spec.n_min_rpm)),
      g_max_(Grid{spec.s_resolution_rpm}.floor(spec.n_max_rpm)),
      // Times a nanosecond short of the hold count as the hold, as in plan_spindle.
      hold_(1.0 / spec.max_changes_per_s - 1e-9),
      horizon_(horizon_s(spec)) {}

double StreamingPlanner::clamp(double x) const { return std::clamp(x, g_min_, g_max_); }

std::size_t StreamingPlanner::held_samples() const { return open_.size() + points_.size(); }

// The open block is complete: it ends at `end_s`, the first time of the
// block after it (its own last time at the end of the timeline). It joins
// the current run, starts a new one, or is an off block.
void StreamingPlanner::close_block(double end_s) {
  const Sample& first = open_.front();
  double target = kInf;  // the smallest (targets are finite)
  bool tool_change = false;
  for (const auto& s : open_) {
    if (s.target_rpm) target = std::min(target, *s.target_rpm);
    tool_change = tool_change || s.tool_change;
  }
  const std::size_t index = blocks_base_ + blocks_.size();
  const bool on = detail::spindle_on(first);
  if (!on || !in_run_ || first.spindle != direction_ || tool_change) {
    if (in_run_) end_run();
    if (on) start_run(first.spindle, index);
  }
  // Filled in place: the block is large, and it comes once per block.
  Block& b = blocks_.emplace_back();
  b.plan.block = first.block;
  b.plan.run = run_;
  b.plan.start_s = first.time_s;
  b.plan.end_s = end_s;
  b.plan.stop_place = index == run_first_ || s_word_allowed(first);
  if (target < kInf) b.plan.target_rpm = target;
  if (!on) {
    b.off = true;
    b.done = true;
    b.plan.planned_rpm = first.program_rpm;
    b.plan.bound = Bound::off;
    assign();
  } else {
    b.own_min = b.span_min = b.ceiling_min = kInf;
    open_time_ = b.plan.end_s;
    for (std::size_t i = 0; i < open_.size(); ++i) add_point(open_[i], index, i == 0);
    if (settle_curve(false)) {
      greedy(false);
      settle_words(false);
      assign();
    }
  }
  open_.clear();
}

void StreamingPlanner::start_run(SpindleState direction, std::size_t first_block) {
  in_run_ = true;
  direction_ = direction;
  run_first_ = first_block;
  points_.clear();
  known_ = 0;
  curved_ = 0;
  last_cut_ceiling_.reset();
  last_forward_.reset();
  next_decide_ = first_block;
  window_.clear();
  window_next_ = first_block;
  last_forward_word_.reset();
  pending_.clear();
  kept_s_.reset();
  kept_.clear();
}

void StreamingPlanner::end_run() {
  settle_ceilings_at_run_end();
  settle_curve(true);
  // The run's last block: its span ends at its own last sample.
  Block& last = blocks_.back();
  last.end_curve = last.last_curve;
  complete(last);
  greedy(true);
  settle_words(true);
  assign();
  ++run_;
  in_run_ = false;
}

// ---- Samples: ceiling E and the curve n.

void StreamingPlanner::add_point(const Sample& s, std::size_t block, bool first) {
  Point& p = points_.emplace_back();
  p.time_s = s.time_s;
  p.program_rpm = s.program_rpm;
  p.block = block;
  p.rapid = s.rapid;
  p.has_target = s.target_rpm.has_value();
  p.first = first;
  if (s.rapid) return;  // its E waits for the next cut
  const double e = clamp(s.target_rpm ? *s.target_rpm : s.program_rpm);
  // The rapids since the last cut take the larger neighbouring ceiling.
  for (std::size_t i = known_; i + 1 < points_.size(); ++i) {
    points_[i].ceiling = std::max(last_cut_ceiling_.value_or(0.0), e);
    step_forward(points_[i]);
  }
  points_.back().ceiling = e;
  step_forward(points_.back());
  last_cut_ceiling_ = e;
  known_ = points_.size();
}

// The forward pass at one more point: the curve rises at most at the
// spindle's acceleration from the last point, and stays under the ceiling.
void StreamingPlanner::step_forward(Point& q) {
  q.forward = last_forward_
                  ? std::min(q.ceiling, *last_forward_ + spec_.acceleration_rpm_per_s *
                                                             (q.time_s - last_forward_time_))
                  : q.ceiling;
  last_forward_ = q.forward;
  last_forward_time_ = q.time_s;
}

void StreamingPlanner::settle_ceilings_at_run_end() {
  for (std::size_t i = known_; i < points_.size(); ++i) {
    auto& q = points_[i];
    q.ceiling = last_cut_ceiling_ ? *last_cut_ceiling_ : clamp(q.program_rpm);
    step_forward(q);
  }
  known_ = points_.size();
}

// The backward pass from the latest known point, once the window spans 2 H;
// the points more than H before that point are final (see the header).
// Returns whether any point became final.
bool StreamingPlanner::settle_curve(bool run_end) {
  if (known_ == 0) return false;
  const double t_last = points_[known_ - 1].time_s;
  if (!run_end && t_last - points_.front().time_s < 2 * horizon_) return false;
  points_[known_ - 1].curve = points_[known_ - 1].forward;
  for (std::size_t i = known_ - 1; i-- > 0;) {
    const double dt = points_[i + 1].time_s - points_[i].time_s;
    const double curve =
        std::min(points_[i].forward, points_[i + 1].curve + spec_.deceleration_rpm_per_s * dt);
    // Where the pass meets the last one's value, it would give the last
    // one's values all the way down (same sums of the same numbers): the
    // points before this one keep them. Halves the work of the pass.
    if (i < curved_ && curve == points_[i].curve) break;
    points_[i].curve = curve;
  }
  std::size_t n = 0;
  while (n < known_ && (run_end || t_last - points_[n].time_s >= horizon_)) fold(points_[n++]);
  points_.pop_front(n);
  known_ -= n;
  curved_ = known_;
  return n > 0;
}

// A point's final curve into its block's figures (and the block before,
// whose span ends at this block's first sample).
void StreamingPlanner::fold(const Point& p) {
  if (p.first && p.block != run_first_) {
    Block& prev = block_at(p.block - 1);
    prev.span_min = std::min(prev.span_min, p.curve);
    prev.end_curve = p.curve;
    complete(prev);
  }
  Block& b = block_at(p.block);
  b.own_min = std::min(b.own_min, p.curve);
  b.span_min = std::min(b.span_min, p.curve);
  b.ceiling_min = std::min(b.ceiling_min, p.ceiling);
  b.any_target = b.any_target || p.has_target;
  b.all_rapid = b.all_rapid && p.rapid;
  b.last_curve = p.curve;
}

// U: the highest S a block may command: the curve's lowest point over the
// block's span (its samples and the next block's first sample), on the grid.
// Commanding it, the spindle stays under the curve: it is already under at
// the block's start and moves towards U at least as fast as the curve. A
// rapid needs the curve only at its end (no vc requirement on the way; its
// ceiling is the same at all its samples, so the curve has no dip in it):
// it commands the curve's end value and so already moves towards the next
// cut's speed, up or down.
void StreamingPlanner::complete(Block& b) const {
  b.u = std::max(g_min_, Grid{res_}.floor(b.all_rapid ? b.end_curve : b.span_min));
  b.u_done = true;
}

// ---- Blocks: the greedy S words, one block at a time once its look-ahead
// window is known. A word at block k holds at least 1/rate, so it takes the
// lowest U of the blocks starting within that time. A word is forced when U
// drops under the S in effect; it then goes a threshold under the block's
// own need (so that a slow decline writes one word per threshold, not one
// per block, and the block stays in the band). A word is written by choice
// when the gain reaches the threshold.

void StreamingPlanner::greedy(bool run_end) {
  const std::size_t end = blocks_base_ + blocks_.size();
  while (next_decide_ < end && window_ready(next_decide_, run_end)) decide(next_decide_++);
}

// Fills the window of block k: k and the blocks starting within the hold
// after it. False while a block of it has no U yet or more blocks may join.
bool StreamingPlanner::window_ready(std::size_t k, bool run_end) {
  while (!window_.empty() && window_.front() < k) window_.pop_front();
  const std::size_t end = blocks_base_ + blocks_.size();
  const double start_k = block_at(k).plan.start_s;
  while (window_next_ < end &&
         (window_next_ <= k || block_at(window_next_).plan.start_s - start_k < hold_)) {
    const Block& b = block_at(window_next_);
    if (!b.u_done) return false;
    while (!window_.empty() && block_at(window_.back()).u >= b.u) window_.pop_back();
    window_.push_back(window_next_++);
  }
  return window_next_ < end || run_end;
}

void StreamingPlanner::decide(std::size_t k) {
  const Grid grid{res_};
  const Block& b = block_at(k);
  const double wm = block_at(window_.front()).u;
  const double start = b.plan.start_s;
  double v = wm;
  if (k != run_first_) {
    const double thr = change_threshold(spec_, s_);
    const bool may_write = start - last_word_time_ >= hold_;
    if (s_ > b.u + kEps) {
      // Cannot happen before the hold has passed: the last word covered it.
      // (A rapid has no need of its own: it goes to the next cut's speed.)
      const double own = b.own_min;
      v = b.all_rapid
              ? wm
              : std::min(wm, std::max(g_min_, grid.floor(own - change_threshold(spec_, own))));
    } else if (!(may_write && wm - s_ >= thr - kEps)) {
      return;
    }
  }
  s_ = v;
  last_word_time_ = start;
  // The forward slew pass: a rise capped at the acceleration from the last word.
  Word w{k, start, v, false};
  if (last_forward_word_) {
    const Word& p = *last_forward_word_;
    const double cap = grid.floor(p.s + spec_.acceleration_rpm_per_s * (w.time_s - p.time_s));
    if (w.s > cap + kEps) {
      w.s = std::max(cap, p.s);
      w.lowered = true;
    }
  }
  last_forward_word_ = w;
  pending_.push_back(w);
}

// ---- Words: the backward slew pass, dropping, and the blocks' S. The slew
// passes lower only: every ceiling still holds, and on the grid one pass
// each way suffices.

void StreamingPlanner::backward_slew(std::vector<Word>& words, const Word* next) const {
  const Grid grid{res_};
  for (std::size_t j = words.size(); j-- > 0;) {
    const Word* later = j + 1 < words.size() ? &words[j + 1] : next;
    if (!later) continue;
    const double dt = later->time_s - words[j].time_s;
    const double cap = grid.floor(later->s + spec_.deceleration_rpm_per_s * dt);
    if (words[j].s > cap + kEps) {
      words[j].s = std::max(cap, later->s);
      words[j].lowered = true;
    }
  }
}

// A pending word is final when the backward pass gives it the same S with
// no later word and with the lowest later word possible (g_min at the
// earliest time a word can still come): the pass is monotone in the later
// word's S and time, so every later word gives that S too. A final word
// makes every earlier one final.
void StreamingPlanner::settle_words(bool run_end) {
  if (pending_.empty()) return;
  optimistic_ = pending_;
  backward_slew(optimistic_, nullptr);
  std::size_t n_final = pending_.size();
  if (!run_end) {
    const std::size_t end = blocks_base_ + blocks_.size();
    const double t_next = next_decide_ < end ? block_at(next_decide_).plan.start_s : open_time_;
    const Word lowest{0, t_next, g_min_, false};
    pessimistic_ = pending_;
    backward_slew(pessimistic_, &lowest);
    n_final = 0;
    for (std::size_t i = pending_.size(); i-- > 0;) {
      if (optimistic_[i].s == pessimistic_[i].s &&
          optimistic_[i].lowered == pessimistic_[i].lowered) {
        n_final = i + 1;
        break;
      }
    }
  }
  for (std::size_t i = 0; i < n_final; ++i) keep(optimistic_[i]);
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(n_final));
}

// After lowering, a word that repeats the S in effect or raises it by less
// than the threshold is dropped (keeping the lower S is always safe, and the
// slew between the remaining words still holds by the triangle inequality).
void StreamingPlanner::keep(const Word& w) {
  if (kept_s_) {
    const double prev = *kept_s_;
    if (std::abs(w.s - prev) <= kEps) return;
    if (w.s > prev && w.s - prev < change_threshold(spec_, prev) - kEps) return;
  }
  kept_.push_back(w);
  kept_s_ = w.s;
}

// Blocks whose every word up to them is final get their S and bound.
void StreamingPlanner::assign() {
  const std::size_t end = blocks_base_ + blocks_.size();
  for (; assign_next_ < end; ++assign_next_) {
    Block& b = block_at(assign_next_);
    if (b.off) continue;
    if (assign_next_ >= next_decide_ ||
        (!pending_.empty() && pending_.front().block <= assign_next_))
      break;
    if (!kept_.empty() && kept_.front().block == assign_next_) {
      in_effect_ = kept_.front().s;
      in_effect_lowered_ = kept_.front().lowered;
      kept_.pop_front();
      b.plan.s_word = true;
    }
    b.plan.planned_rpm = in_effect_;
    const detail::BlockFacts facts{b.any_target, b.all_rapid, b.ceiling_min, b.span_min};
    b.plan.bound = detail::classify_bound(spec_, g_min_, g_max_, facts, b.plan.target_rpm,
                                          in_effect_, in_effect_lowered_);
    b.done = true;
  }
}

// ---- Feeds.

StreamingFeedPlanner::StreamingFeedPlanner(std::optional<double> fz_mm, int teeth,
                                           const machines::FeedSpec& feed, double step_mm_per_min)
    : fz_mm_(fz_mm), teeth_(teeth), feed_(feed), step_(step_mm_per_min) {
  if (!(step_mm_per_min > 0)) throw PlanError("plan_feeds: the F step must be > 0");
}

BlockFeed StreamingFeedPlanner::next(const BlockPlan& block, const BlockFeedInput& input) {
  BlockFeed o;
  o.f_mm_per_min = input.program_f_mm_per_min;
  const bool coupled = block.target_rpm && block.bound != Bound::off &&
                       block.bound != Bound::rapid && block.bound != Bound::program &&
                       input.program_f_mm_per_min > 0;
  if (coupled) {
    const Grid grid{step_};
    const int teeth = input.teeth > 0 ? input.teeth : teeth_;
    const double fz =
        fz_mm_ ? *fz_mm_ : feed_per_tooth(input.program_f_mm_per_min, input.program_s_rpm, teeth);
    const auto c = coupled_feed(fz, teeth, block.planned_rpm, feed_);
    o.bound = c.bound;
    // Down to the output's step, but never under f_min.
    o.f_mm_per_min = std::max(grid.floor(c.f_mm_per_min), grid.ceil(feed_.f_min_mm_per_min));
  }
  if (o.f_mm_per_min > 0) {
    o.f_word = !in_effect_ || std::abs(*in_effect_ - o.f_mm_per_min) > step_ * 1e-6;
    in_effect_ = o.f_mm_per_min;
  }
  return o;
}

}  // namespace vcpost::plan
