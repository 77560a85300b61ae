#include "postproc/plan/stop_aware_plan.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "postproc/plan/plan_rules.h"
#include "postproc/plan/streaming_plan.h"

namespace vcpost::plan {

using detail::Grid;
using detail::kEps;
using detail::kInf;

bool s_word_allowed(const Sample& first) {
  return first.rapid || first.path_stops || first.tool_change;
}

StopAwarePlanner::StopAwarePlanner(const machines::SpindleSpec& spec)
    : spec_(spec),
      g_min_(Grid{spec.s_resolution_rpm}.ceil(spec.n_min_rpm)),
      g_max_(Grid{spec.s_resolution_rpm}.floor(spec.n_max_rpm)),
      hold_(1.0 / spec.max_changes_per_s - 1e-9),
      horizon_(StreamingPlanner::horizon_s(spec)) {}

void StopAwarePlanner::start_run(SpindleState direction) {
  in_run_ = true;
  direction_ = direction;
  s_.reset();
}

void StopAwarePlanner::end_run() {
  Stretch& last = stretches_q_.back();
  last.run_last = true;
  last.closed = true;
  split_priced(blocks_.size());
  decide(true);
  assign();
  ++run_;
  in_run_ = false;
}

void StopAwarePlanner::open_stretch(double start_s, double program_rpm, bool run_first) {
  Stretch& st = stretches_q_.emplace_back();
  st.start_s = start_s;
  st.program_rpm = program_rpm;
  st.run_first = run_first;
}

void StopAwarePlanner::close_block(double end_s) {
  const Sample& first = open_.front();
  double target = kInf;
  bool tool_change = false;
  for (const auto& s : open_) {
    if (s.target_rpm) target = std::min(target, *s.target_rpm);
    tool_change = tool_change || s.tool_change;
  }
  const bool on = detail::spindle_on(first);
  if (!on || !in_run_ || first.spindle != direction_ || tool_change) {
    if (in_run_) end_run();
    if (on) start_run(first.spindle);
  }
  Block& b = blocks_.emplace_back();
  b.plan.block = first.block;
  b.plan.run = run_;
  b.plan.start_s = first.time_s;
  b.plan.end_s = end_s;
  if (target < kInf) b.plan.target_rpm = target;
  if (!on) {
    b.off = b.done = true;
    b.plan.planned_rpm = first.program_rpm;
    b.plan.bound = Bound::off;
    open_.clear();
    return;
  }
  const bool allowed = s_word_allowed(first);
  b.plan.stop_place = allowed || stretches_q_.empty();
  if (stretches_q_.empty()) {
    open_stretch(first.time_s, first.program_rpm, true);
  } else {
    Stretch& current = stretches_q_.back();
    if (allowed && current.has_stream && first.time_s - current.start_s >= hold_) {
      current.end_s = first.time_s;
      current.closed = true;
      split_priced(blocks_.size() - 1);  // b is the next stretch's
      open_stretch(first.time_s, first.program_rpm, false);
    }
  }
  Stretch& st = stretches_q_.back();
  b.stretch = stretch_base_ + stretches_q_.size() - 1;
  if (!allowed) st.has_stream = true;
  b.ceiling_min = b.cut_fall = b.far_own = b.far_fall = kInf;
  b.program_rpm = first.program_rpm;
  const double dec = spec_.deceleration_rpm_per_s;
  for (std::size_t i = 0; i < open_.size(); ++i) {
    const Sample& s = open_[i];
    b.any_target = b.any_target || s.target_rpm.has_value();
    b.all_rapid = b.all_rapid && s.rapid;
    if (s.rapid) continue;  // no vc to keep: no ceiling
    const double e = std::clamp(s.target_rpm ? *s.target_rpm : s.program_rpm, g_min_, g_max_);
    Need& need = s.target_rpm ? st.cut : st.far;
    need.own = std::min(need.own, e);
    need.fall = std::min(need.fall, e + dec * (s.time_s - st.start_s));
    if (s.target_rpm) {
      b.ceiling_min = std::min(b.ceiling_min, e);
      b.cut_fall = std::min(b.cut_fall, e + dec * s.time_s);
      const double next = i + 1 < open_.size() ? open_[i + 1].time_s : end_s;
      b.weight += (next - s.time_s) / e;
    } else {
      b.far_own = std::min(b.far_own, e);
      b.far_fall = std::min(b.far_fall, e + dec * s.time_s);
    }
  }
  open_.clear();
  decide(false);
  assign();
}

// Decides the stretches whose S no later sample can change: those whose end
// lies more than H before the start of the open stretch (a ceiling that
// late is out of the spindle's reach: E + deceleration * H >= g_max), and
// all of them at the run's end.
void StopAwarePlanner::decide(bool run_end) {
  const std::size_t n = stretches_q_.size();
  if (n == 0) return;
  const double t_open = stretches_q_.back().start_s;
  if (!run_end && (n < 2 || t_open - stretches_q_.front().end_s <= horizon_)) return;
  // reach[m]: the highest S that may be in effect at stretch m's start, so
  // that the spindle slowing from it stays under every ceiling from there on.
  reach_.assign(n, kInf);
  reach_[n - 1] = stretches_q_[n - 1].need().fall;
  for (std::size_t m = n - 1; m-- > 0;) {
    const double dt = stretches_q_[m + 1].start_s - stretches_q_[m].start_s;
    reach_[m] =
        std::min(stretches_q_[m].need().fall, reach_[m + 1] + spec_.deceleration_rpm_per_s * dt);
  }
  const Grid grid{spec_.s_resolution_rpm};
  std::size_t k = 0;
  for (; k < n; ++k) {
    const Stretch& st = stretches_q_[k];
    const bool last = k + 1 == n;
    if (!run_end && (last || t_open - st.end_s <= horizon_)) break;
    double need = st.need().own;
    bool lowered = false;
    if (!last && reach_[k + 1] < need) {
      need = reach_[k + 1];
      lowered = true;
    }
    Decision d;
    d.stretch = stretch_base_ + k;
    double v = 0.0;
    if (need < kInf) {
      v = std::max(g_min_, grid.floor(std::min(need, g_max_)));
    } else if (st.run_first || !s_) {
      v = std::max(g_min_, grid.floor(std::clamp(st.program_rpm, g_min_, g_max_)));
    } else {
      v = *s_;  // no ceiling anywhere ahead in the run: keep the S in effect
    }
    // Forced: the first word of a run, a lower ceiling or the slow-down for one.
    if (!s_ || st.run_first || v < *s_ - kEps) {
      d.word = true;
    } else {
      d.word = v - *s_ >= change_threshold(spec_, *s_) - kEps;
    }
    if (d.word) s_ = v;
    d.s = *s_;
    d.lowered = d.word && lowered;
    decisions_.push_back(d);
    ++stretches_;
  }
  stretches_q_.erase(stretches_q_.begin(), stretches_q_.begin() + static_cast<std::ptrdiff_t>(k));
  stretch_base_ += k;
}

double StopAwarePlanner::stop_cost(double s_from, double s_to) const {
  double cost = spec_.stop_cost_s;
  const double window = spec_.at_speed_window_percent / 100;
  if (window > 0) {  // the control waits until the spindle is within the window
    cost += s_to > s_from
                ? std::max(0.0, s_to * (1 - window) - s_from) / spec_.acceleration_rpm_per_s
                : std::max(0.0, s_from - s_to * (1 + window)) / spec_.deceleration_rpm_per_s;
  }
  return cost;
}

// The blocks blocks_[from, to) of one closed stretch from start_s to end_s:
// where priced words split it (block indices, ascending; see the header).
// The blocks are grouped into at most kMaxCells cells, each at least the
// shortest time between S words long; the best split into parts at cell
// starts is found by dynamic programming over the cells, O(cells^2).
std::vector<std::size_t> StopAwarePlanner::priced_splits(std::size_t from, std::size_t to,
                                                         double start_s, double end_s) const {
  constexpr std::size_t kMaxCells = 400;
  struct Cell {
    std::size_t block;  // its first block
    double start_s;
    double own = kInf, fall = kInf, weight = 0.0;
  };
  const double length = std::max(hold_, (end_s - start_s) / static_cast<double>(kMaxCells));
  std::vector<Cell> cells;
  for (std::size_t k = from; k < to; ++k) {
    const StopAwareBlock& b = blocks_[k];
    if (cells.empty() ||
        (b.plan.start_s - cells.back().start_s >= length && end_s - b.plan.start_s >= hold_))
      cells.push_back({k, cells.empty() ? start_s : b.plan.start_s});
    Cell& c = cells.back();
    c.own = std::min(c.own, b.ceiling_min);
    c.fall = std::min(c.fall, b.cut_fall);
    c.weight += b.weight;
  }
  const std::size_t n = cells.size();
  if (n < 2) return {};
  // suffix_fall[j]: the lowest E_i + deceleration * t_i from cell j on; a
  // part ending at cell j holds at most suffix_fall[j] - deceleration * t_j.
  std::vector<double> suffix_fall(n + 1, kInf);
  for (std::size_t j = n; j-- > 0;) suffix_fall[j] = std::min(suffix_fall[j + 1], cells[j].fall);
  // best[j]: the most cutting time at nominal vc, less the stops, over the
  // cells before j; s_of[j] the S of its last part, parent[j] that part's start.
  std::vector<double> best(n + 1, -kInf), s_of(n + 1, 0.0);
  std::vector<std::size_t> parent(n + 1, 0);
  best[0] = 0.0;
  for (std::size_t j = 1; j <= n; ++j) {
    const double slew =
        j < n ? suffix_fall[j] - spec_.deceleration_rpm_per_s * cells[j].start_s : kInf;
    double own = kInf, weight = 0.0;
    for (std::size_t i = j; i-- > 0;) {
      own = std::min(own, cells[i].own);
      weight += cells[i].weight;
      if (best[i] == -kInf || own == kInf) continue;  // a part needs a cutting sample
      const double s = std::min(own, slew);
      const double value = best[i] + s * weight - (i > 0 ? stop_cost(s_of[i], s) : 0.0);
      if (value > best[j]) {
        best[j] = value;
        s_of[j] = s;
        parent[j] = i;
      }
    }
  }
  std::vector<std::size_t> splits;
  if (best[n] == -kInf) return splits;
  for (std::size_t j = parent[n]; j > 0; j = parent[j]) splits.push_back(cells[j].block);
  std::reverse(splits.begin(), splits.end());
  return splits;
}

// The closed stretch at the back of stretches_q_ holds the blocks from the
// first of its index up to blocks_[to): split into parts where priced
// words pay, each part a stretch with the needs of its blocks.
void StopAwarePlanner::split_priced(std::size_t to) {
  if (spec_.s_in_feed != machines::SInFeed::priced) return;
  const std::size_t index = stretch_base_ + stretches_q_.size() - 1;
  std::size_t from = to;
  while (from > 0 && !blocks_[from - 1].done && blocks_[from - 1].stretch == index) --from;
  const Stretch whole = stretches_q_.back();
  if (to - from < 2) return;
  const double end_s = whole.run_last ? blocks_[to - 1].plan.end_s : whole.end_s;
  std::vector<std::size_t> cuts = priced_splits(from, to, whole.start_s, end_s);
  if (cuts.empty()) return;
  stretches_q_.pop_back();
  cuts.push_back(to);
  const double dec = spec_.deceleration_rpm_per_s;
  std::size_t begin = from;
  for (std::size_t part = 0; part < cuts.size(); ++part) {
    const bool first = part == 0, last = part + 1 == cuts.size();
    Stretch& st = stretches_q_.emplace_back();
    st.start_s = first ? whole.start_s : blocks_[begin].plan.start_s;
    st.end_s = last ? whole.end_s : blocks_[cuts[part]].plan.start_s;
    st.program_rpm = first ? whole.program_rpm : blocks_[begin].program_rpm;
    st.run_first = first && whole.run_first;
    st.run_last = last && whole.run_last;
    st.closed = st.has_stream = true;
    for (std::size_t k = begin; k < cuts[part]; ++k) {
      Block& b = blocks_[k];
      b.stretch = index + part;
      st.cut.own = std::min(st.cut.own, b.ceiling_min);
      st.cut.fall = std::min(st.cut.fall, b.cut_fall - dec * st.start_s);
      st.far.own = std::min(st.far.own, b.far_own);
      st.far.fall = std::min(st.far.fall, b.far_fall - dec * st.start_s);
    }
    begin = cuts[part];
  }
}

// Blocks of decided stretches get their S and bound; the first block of a
// stretch carries its word.
void StopAwarePlanner::assign() {
  for (; assign_from_ < blocks_.size(); ++assign_from_) {
    Block& b = blocks_[assign_from_];
    if (b.done) continue;  // off
    while (!decisions_.empty() && decisions_.front().stretch < b.stretch) decisions_.pop_front();
    if (decisions_.empty() || decisions_.front().stretch != b.stretch) break;
    const Decision& d = decisions_.front();
    b.plan.s_word = d.word && last_assigned_ != b.stretch;
    last_assigned_ = b.stretch;
    b.plan.planned_rpm = d.s;
    const detail::BlockFacts facts{b.any_target, b.all_rapid, b.ceiling_min, b.ceiling_min};
    Bound bound =
        detail::classify_bound(spec_, g_min_, g_max_, facts, b.plan.target_rpm, d.s, false);
    if (bound == Bound::rate) bound = d.lowered ? Bound::slew : Bound::stretch;
    b.plan.bound = bound;
    b.done = true;
  }
}

}  // namespace vcpost::plan
