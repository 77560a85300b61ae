// The spindle planner over a whole timeline at once, as plan_spindle() was
// before it ran on the streaming planner: every pass over the whole run, in
// the plain order of spindle_plan.h's contract. The streaming planner must
// give the same plan bit for bit (streaming_plan_test.cpp).
#include "tests/postproc/plan/plan_reference_support.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include "postproc/plan/plan_rules.h"

namespace vcpost::plan::testing {

namespace {

using detail::Grid;
using detail::kEps;
using detail::spindle_on;

struct BlockSpan {
  std::size_t first = 0;  // first sample
  std::size_t last = 0;   // last sample (inclusive)
  bool on = false;
};

struct Word {
  std::size_t block = 0;  // index into the run's blocks (absolute plan index)
  double s = 0.0;
  bool lowered = false;  // lowered by the slew passes over the words
};

void validate(std::span<const Sample> samples) {
  for (std::size_t i = 0; i < samples.size(); ++i)
    detail::check_sample(i, samples[i], i > 0 ? &samples[i - 1] : nullptr);
}

// Plans one run: blocks [kb, ke] of `blocks`, writing into plan.blocks.
class RunPlanner {
 public:
  RunPlanner(std::span<const Sample> samples, std::span<const BlockSpan> blocks,
             const machines::SpindleSpec& spec, std::vector<BlockPlan>& out)
      : samples_(samples),
        blocks_(blocks),
        spec_(spec),
        out_(out),
        grid_{spec.s_resolution_rpm},
        g_min_(grid_.ceil(spec.n_min_rpm)),
        g_max_(grid_.floor(spec.n_max_rpm)) {}

  void plan(std::size_t kb, std::size_t ke) {
    kb_ = kb;
    ke_ = ke;
    ia_ = blocks_[kb].first;
    ie_ = blocks_[ke].last;
    ceilings();
    curve();
    block_ceilings();
    choose_words();
    slew_passes();
    drop_small_rises();
    assign();
  }

 private:
  double clamp(double x) const { return std::clamp(x, g_min_, g_max_); }

  // E: the ceiling at every sample: the clamped target, the program's S
  // where there is none, the larger neighbouring ceiling on rapids.
  void ceilings() {
    const std::size_t n = ie_ - ia_ + 1;
    ceiling_.assign(n, 0.0);
    std::vector<std::optional<double>> prev(n), next(n);
    std::optional<double> last;
    for (std::size_t i = 0; i < n; ++i) {
      const auto& s = samples_[ia_ + i];
      if (!s.rapid) last = clamp(s.target_rpm ? *s.target_rpm : s.program_rpm);
      prev[i] = last;
    }
    last.reset();
    for (std::size_t i = n; i-- > 0;) {
      const auto& s = samples_[ia_ + i];
      if (!s.rapid) last = clamp(s.target_rpm ? *s.target_rpm : s.program_rpm);
      next[i] = last;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const auto& s = samples_[ia_ + i];
      if (!s.rapid) {
        ceiling_[i] = *prev[i];
      } else if (prev[i] || next[i]) {
        ceiling_[i] = std::max(prev[i].value_or(0.0), next[i].value_or(0.0));
      } else {
        ceiling_[i] = clamp(s.program_rpm);
      }
    }
  }

  // n: the largest curve under the ceilings whose slope stays within
  // [-deceleration, acceleration] (forward pass, then backward pass).
  void curve() {
    const std::size_t n = ceiling_.size();
    curve_ = ceiling_;
    for (std::size_t i = 1; i < n; ++i) {
      const double dt = samples_[ia_ + i].time_s - samples_[ia_ + i - 1].time_s;
      curve_[i] = std::min(curve_[i], curve_[i - 1] + spec_.acceleration_rpm_per_s * dt);
    }
    for (std::size_t i = n - 1; i-- > 0;) {
      const double dt = samples_[ia_ + i + 1].time_s - samples_[ia_ + i].time_s;
      curve_[i] = std::min(curve_[i], curve_[i + 1] + spec_.deceleration_rpm_per_s * dt);
    }
  }

  // U: the highest S a block may command: the curve's lowest point over the
  // block's span (its samples and the next block's first sample), on the grid.
  // Commanding it, the spindle stays under the curve: it is already under
  // at the block's start and moves towards U at least as fast as the curve.
  // A rapid needs the curve only at its end (no vc requirement on the way;
  // its ceiling is the same at all its samples, so the curve has no dip in
  // it): it commands the curve's end value and so already moves towards the
  // next cut's speed, up or down.
  void block_ceilings() {
    const std::size_t nb = ke_ - kb_ + 1;
    ceil_.assign(nb, 0.0);
    curve_min_.assign(nb, 0.0);
    curve_own_.assign(nb, 0.0);
    rapid_.assign(nb, false);
    for (std::size_t k = 0; k < nb; ++k) {
      const auto& b = blocks_[kb_ + k];
      const std::size_t end = (kb_ + k < ke_) ? blocks_[kb_ + k + 1].first : b.last;
      double m = std::numeric_limits<double>::infinity();
      bool all_rapid = true;
      for (std::size_t i = b.first; i <= end; ++i) m = std::min(m, curve_[i - ia_]);
      double own = std::numeric_limits<double>::infinity();
      for (std::size_t i = b.first; i <= b.last; ++i) {
        all_rapid = all_rapid && samples_[i].rapid;
        own = std::min(own, curve_[i - ia_]);
      }
      curve_min_[k] = m;
      curve_own_[k] = own;
      rapid_[k] = all_rapid;
      ceil_[k] = std::max(g_min_, grid_.floor(all_rapid ? curve_[end - ia_] : m));
    }
  }

  double start(std::size_t k) const { return samples_[blocks_[kb_ + k].first].time_s; }

  // Greedy over the blocks: a word at block k holds at least 1/rate, so it
  // takes the lowest U of the blocks starting within that time. A word is
  // forced when U drops under the S in effect; it then goes a threshold
  // under the block's own need (so that a slow decline writes one word per
  // threshold, not one per block, and the block stays in the band). A word
  // is written by choice when the gain reaches the threshold.
  void choose_words() {
    const std::size_t nb = ceil_.size();
    // Times a nanosecond short of the hold count as the hold (0.6 - 0.5 is
    // 0.0999... in binary); the window and the permission use the same test.
    const double hold = 1.0 / spec_.max_changes_per_s - 1e-9;
    words_.clear();
    std::deque<std::size_t> window;  // block indices with increasing U
    std::size_t next = 0;            // first block not yet in the window
    auto window_min = [&](std::size_t k) {
      while (!window.empty() && window.front() < k) window.pop_front();
      while (next < nb && (next <= k || start(next) - start(k) < hold)) {
        while (!window.empty() && ceil_[window.back()] >= ceil_[next]) window.pop_back();
        window.push_back(next++);
      }
      return ceil_[window.front()];
    };
    double s = window_min(0);
    words_.push_back({kb_, s, false});
    double last_time = start(0);
    for (std::size_t k = 1; k < nb; ++k) {
      const double wm = window_min(k);
      const double thr = change_threshold(spec_, s);
      const bool may_write = start(k) - last_time >= hold;
      double v = s;
      if (s > ceil_[k] + kEps) {
        // Cannot happen before `hold` has passed: the last word covered it.
        // (A rapid has no need of its own: it goes to the next cut's speed.)
        const double own = curve_own_[k];
        v = rapid_[k]
                ? wm
                : std::min(wm, std::max(g_min_, grid_.floor(own - change_threshold(spec_, own))));
      } else if (may_write && wm - s >= thr - kEps) {
        v = wm;
      } else {
        continue;
      }
      words_.push_back({kb_ + k, v, false});
      s = v;
      last_time = start(k);
    }
  }

  double word_time(const Word& w) const { return samples_[blocks_[w.block].first].time_s; }

  // Slew between consecutive words: rises capped forward, drops made
  // feasible backward by lowering the earlier word. Lowering only: every
  // ceiling still holds, and on the grid one pass each way suffices.
  void slew_passes() {
    for (std::size_t j = 1; j < words_.size(); ++j) {
      const double dt = word_time(words_[j]) - word_time(words_[j - 1]);
      const double cap = grid_.floor(words_[j - 1].s + spec_.acceleration_rpm_per_s * dt);
      if (words_[j].s > cap + kEps) {
        words_[j].s = std::max(cap, words_[j - 1].s);
        words_[j].lowered = true;
      }
    }
    for (std::size_t j = words_.size(); j-- > 1;) {
      const double dt = word_time(words_[j]) - word_time(words_[j - 1]);
      const double cap = grid_.floor(words_[j].s + spec_.deceleration_rpm_per_s * dt);
      if (words_[j - 1].s > cap + kEps) {
        words_[j - 1].s = std::max(cap, words_[j].s);
        words_[j - 1].lowered = true;
      }
    }
  }

  // After lowering, a word may repeat the S in effect or raise it by less
  // than the threshold: drop it (keeping the lower S is always safe, and the
  // slew between the remaining words still holds by the triangle inequality).
  void drop_small_rises() {
    std::vector<Word> kept;
    kept.reserve(words_.size());
    for (const auto& w : words_) {
      if (!kept.empty()) {
        const double prev = kept.back().s;
        if (std::abs(w.s - prev) <= kEps) continue;
        if (w.s > prev && w.s - prev < change_threshold(spec_, prev) - kEps) continue;
      }
      kept.push_back(w);
    }
    words_ = std::move(kept);
  }

  void assign() {
    std::size_t j = 0;
    bool lowered = false;
    for (std::size_t k = kb_; k <= ke_; ++k) {
      auto& bp = out_[k];
      bp.s_word = false;
      if (j < words_.size() && words_[j].block == k) {
        bp.s_word = true;
        lowered = words_[j].lowered;
        ++j;
      }
      bp.planned_rpm = words_[j - 1].s;
      bp.bound = bound(k - kb_, bp, lowered);
    }
  }

  Bound bound(std::size_t k, const BlockPlan& bp, bool lowered) const {
    const auto& b = blocks_[kb_ + k];
    detail::BlockFacts facts;
    facts.ceiling = std::numeric_limits<double>::infinity();
    for (std::size_t i = b.first; i <= b.last; ++i) {
      facts.any_target = facts.any_target || samples_[i].target_rpm.has_value();
      facts.all_rapid = facts.all_rapid && samples_[i].rapid;
      facts.ceiling = std::min(facts.ceiling, ceiling_[i - ia_]);
    }
    facts.curve_min = curve_min_[k];
    return detail::classify_bound(spec_, g_min_, g_max_, facts, bp.target_rpm, bp.planned_rpm,
                                  lowered);
  }

  std::span<const Sample> samples_;
  std::span<const BlockSpan> blocks_;
  const machines::SpindleSpec& spec_;
  std::vector<BlockPlan>& out_;
  Grid grid_;
  double g_min_;
  double g_max_;
  std::size_t kb_ = 0, ke_ = 0, ia_ = 0, ie_ = 0;
  std::vector<double> ceiling_;    // E per sample of the run
  std::vector<double> curve_;      // n per sample of the run
  std::vector<double> ceil_;       // U per block of the run
  std::vector<double> curve_min_;  // lowest n over each block's span
  std::vector<double> curve_own_;  // lowest n over each block's own samples
  std::vector<bool> rapid_;        // the block is a rapid (all its samples)
  std::vector<Word> words_;
};

}  // namespace

SpindlePlan reference_plan_spindle(std::span<const Sample> samples,
                                   const machines::SpindleSpec& spec) {
  validate(samples);
  SpindlePlan plan;
  if (samples.empty()) return plan;

  // Blocks and their spans.
  std::vector<BlockSpan> blocks;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (i == 0 || samples[i].block != samples[i - 1].block) {
      blocks.push_back({i, i, spindle_on(samples[i])});
      BlockPlan bp;
      bp.block = samples[i].block;
      bp.start_s = samples[i].time_s;
      plan.blocks.push_back(bp);
    }
    blocks.back().last = i;
    auto& bp = plan.blocks.back();
    if (samples[i].target_rpm)
      bp.target_rpm =
          std::min(bp.target_rpm.value_or(*samples[i].target_rpm), *samples[i].target_rpm);
  }
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    plan.blocks[k].end_s = k + 1 < blocks.size() ? samples[blocks[k + 1].first].time_s
                                                 : samples[blocks[k].last].time_s;
  }

  // Runs: the spindle on in one direction, no tool change.
  RunPlanner planner(samples, blocks, spec, plan.blocks);
  std::size_t run = 0;
  std::size_t k = 0;
  while (k < blocks.size()) {
    if (!blocks[k].on) {
      auto& bp = plan.blocks[k];
      bp.planned_rpm = samples[blocks[k].first].program_rpm;
      bp.bound = Bound::off;
      bp.run = run;
      ++k;
      continue;
    }
    const std::size_t kb = k;
    const auto direction = samples[blocks[kb].first].spindle;
    ++k;
    while (k < blocks.size() && blocks[k].on && samples[blocks[k].first].spindle == direction) {
      bool tool_change = false;
      for (std::size_t i = blocks[k].first; i <= blocks[k].last; ++i)
        tool_change = tool_change || samples[i].tool_change;
      if (tool_change) break;
      ++k;
    }
    planner.plan(kb, k - 1);
    for (std::size_t j = kb; j < k; ++j) plan.blocks[j].run = run;
    ++run;
  }
  for (const auto& bp : plan.blocks) plan.s_words += bp.s_word ? 1 : 0;
  return plan;
}

}  // namespace vcpost::plan::testing
