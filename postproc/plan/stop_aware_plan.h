// The spindle plan for a control whose path stops at every S word in motion
// (profile key spindle.stops_path_on_change; issue 17, MODELS.md section 4):
// LinuxCNC (canon flushes the segment queue at SET_SPINDLE_SPEED), grbl
// (its planner is emptied on a changed S), Fanuc with the speed arrival
// check, Sinumerik with the S function acknowledged before motion. An S
// word in a feed stream would leave a dwell mark where vcpost is meant to
// improve the surface, so S words go only where the path stops or leaves
// the material anyway, and one S holds each stretch between two such places.
//
// Where an S word may go (s_word_allowed): a block whose first sample is a
// rapid or in the air (G0, an approach, a link or a plunge that starts off
// the material: the path stops with the tool clear of the surface), a block
// before which the path stops anyway (Sample::path_stops: a sharp reversal,
// a dwell, a program stop), and the first block of a run (a tool change, the
// spindle started or reversed).
//
// Stretches: a stretch starts at an allowed block that follows a feed
// stream (a block where no S word may go), and at least 1 / max_changes_per_s
// after the start of the stretch before it; it holds every block up to the
// next stretch. A run of allowed blocks (retract, rapids, plunge) thus starts
// one stretch, at its first block: the spindle has the whole run of rapids
// to reach the next cut's speed.
//
// The S of stretch j, which starts at t_j and ends at t_{j+1}: the largest
// value on the S grid in [n_min, n_max] that is
// - at or under the ceiling E_i of every cutting sample of the stretch
//   (E: the target clamped to [n_min, n_max]; rapids and samples in the air
//   have none): with the policy `max` no engaged edge runs above vc. Samples
//   far from the model (no contact: the per-block plan keeps the program's
//   S there) bound a stretch by the program's S only when it has no target
//   at all: one S must serve the cut the model describes, and a plunge from
//   the clearance height is far from the model for most of its length;
// - at or under E_i + deceleration * (t_i - t_{j+1}) for every cutting
//   sample i of the run after t_{j+1}: the spindle, slowing at its
//   deceleration from this S once the next word comes, is at or under every
//   later ceiling (it never relies on the control waiting for the spindle).
// A rise needs no such bound: the spindle lags under the new S, vc under
// nominal, never over. The word is written when the S falls, when it rises
// by at least the hysteresis threshold, and at the first stretch of a run;
// otherwise the lower S in effect holds (still at or under every ceiling).
//
// Priced words (spindle.s_in_feed = "priced"): a closed stretch is also
// split inside its feed stream where a word is worth its stop. The gain of
// a split at block k, with each part at its own ceiling (own_A, own_B), is
// the cutting time it brings to nominal vc: (own_high - own_low) times the
// sum of dt_i / E_i over the samples of the part with the higher ceiling
// (a second of cutting at 10 % under vc raised to nominal counts 0.1 s);
// before a fall the first part counts only up to what the spindle, slowing
// from the split on, brings under the second part's ceilings (the control
// does not wait for it: the fall must come early).
// Its cost is the stop: stop_cost_s, plus, with an at-speed window w, the
// wait for the spindle to come within w of the new speed (|change| less w
// of the new S, at the acceleration or deceleration). The best split whose
// gain exceeds its cost is made, each part then the same way; parts are at
// least 1 / max_changes_per_s long. The parts become stretches as above
// (their S then under the slew bounds, which the gain leaves out).
//
// Bounds per block: none / resolution / hysteresis / n_max / n_min as in
// spindle_plan.h; beyond the band, `stretch` (a lower need elsewhere in the
// stretch holds S down) or `slew` (the deceleration bound above did).
//
// Memory: a stretch is decided once the next stretch starts more than
// H = (g_max - g_min) / deceleration after its end (or its run ends), so the
// blocks of the longest stretch between two stops are held (a few numbers
// per block), not a window of the spindle's figures as in streaming_plan.h.
#pragma once

#include <algorithm>
#include <cstddef>
#include <deque>
#include <limits>
#include <optional>
#include <vector>

#include "machines/profile.h"
#include "postproc/plan/block_stream.h"
#include "postproc/plan/spindle_plan.h"

namespace vcpost::plan {

// Whether an S word may start the block whose first sample is `first`
// (within a run; the first block of a run always may).
bool s_word_allowed(const Sample& first);

// A block of StopAwarePlanner waiting for its plan.
struct StopAwareBlock {
  BlockPlan plan;
  bool off = false;
  bool done = false;
  bool any_target = false;
  bool all_rapid = true;
  double ceiling_min = 0.0;  // lowest ceiling E of its cutting samples
  std::size_t stretch = 0;   // absolute stretch index
  // What a priced split needs to rebuild its parts' needs and gains.
  double cut_fall = 0.0;     // lowest E_i + deceleration * t_i of its cutting samples
  double far_own = 0.0;      // lowest E of its samples far from the model
  double far_fall = 0.0;     // lowest E_i + deceleration * t_i of those
  double weight = 0.0;       // sum of dt_i / E_i over its cutting samples, s/rpm
  double program_rpm = 0.0;  // the program's S at its start
};

// The stop-aware plan while the timeline streams in: the same interface as
// StreamingPlanner (push, finish, take_final), the blocks out in order.
class StopAwarePlanner
    : public detail::BlockStream<StopAwarePlanner, StopAwareBlock, std::deque<StopAwareBlock>> {
 public:
  // The spec must be valid (as a loaded profile's is).
  explicit StopAwarePlanner(const machines::SpindleSpec& spec);
  // push(), finish(), take_final(), s_words(): see block_stream.h.
  std::size_t stretches() const { return stretches_; }  // stretches decided so far
  std::size_t held_blocks() const { return blocks_.size(); }

 private:
  friend class detail::BlockStream<StopAwarePlanner, StopAwareBlock, std::deque<StopAwareBlock>>;
  using Block = StopAwareBlock;
  // What a set of samples asks of a stretch's S (infinity: no sample).
  struct Need {
    double own = std::numeric_limits<double>::infinity();   // lowest E
    double fall = std::numeric_limits<double>::infinity();  // lowest E_i + dec * (t_i - start)
  };
  struct Stretch {
    double start_s = 0.0;
    double end_s = 0.0;  // the next stretch's start (valid once closed, unless run_last)
    Need cut;            // its samples with a target
    Need far;            // its samples far from the model (no target, not in the air)
    const Need& need() const {
      return cut.own < std::numeric_limits<double>::infinity() ? cut : far;
    }
    double program_rpm = 0.0;  // the program's S at its start
    bool run_first = false;
    bool run_last = false;
    bool closed = false;
    bool has_stream = false;  // holds a block where no S word may go
  };

  void close_block(double end_s);
  void end_timeline() {
    if (in_run_) end_run();
  }
  void taken(std::size_t n) { assign_from_ -= std::min(assign_from_, n); }
  void start_run(SpindleState direction);
  void end_run();
  void open_stretch(double start_s, double program_rpm, bool run_first);
  void decide(bool run_end);
  void assign();
  // Priced words: the closed stretch at the back of stretches_q_, whose
  // blocks end before blocks_[to], split where words are worth their stops.
  void split_priced(std::size_t to);
  std::vector<std::size_t> priced_splits(std::size_t from, std::size_t to, double start_s,
                                         double end_s) const;
  double stop_cost(double s_from, double s_to) const;

  machines::SpindleSpec spec_;
  double g_min_, g_max_;
  double hold_;     // shortest time between S words, less a nanosecond
  double horizon_;  // H

  bool in_run_ = false;
  SpindleState direction_ = SpindleState::cw;
  std::size_t run_ = 0;
  std::deque<Stretch> stretches_q_;  // the current run's stretches not decided yet
  std::size_t stretch_base_ = 0;     // absolute index of stretches_q_.front()
  std::size_t stretches_ = 0;        // stretches decided
  std::optional<double> s_;          // S in effect in the run (as written)

  // Decided stretches waiting for their blocks: absolute index -> S, word, lowered.
  struct Decision {
    std::size_t stretch = 0;
    double s = 0.0;
    bool word = false;
    bool lowered = false;
  };
  std::deque<Decision> decisions_;
  std::size_t assign_from_ = 0;               // blocks_[assign_from_] is the first not assigned
  std::optional<std::size_t> last_assigned_;  // stretch of the last block assigned
  std::vector<double> reach_;                 // scratch of decide()
};

}  // namespace vcpost::plan
