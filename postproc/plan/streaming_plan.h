// The spindle planner for a streamed timeline: the plan of spindle_plan.h
// (which states the contract), computed while the samples come in, in
// memory bounded by the spindle's figures, not by the program's length.
// plan_spindle() is this planner fed the whole timeline; the tests hold it
// against a reference that runs every pass over the whole timeline at once
// (tests/postproc/plan/plan_reference_support.cpp).
//
// Why a window suffices, pass by pass (within one run; a run's end settles
// everything before it):
// - ceilings E: per sample, except a rapid's, which waits for the end of
//   its rapid stretch (the next cut's ceiling);
// - forward curve (rise at most `acceleration`): sequential, one value
//   carried;
// - backward curve (fall at most `deceleration`): every curve value lies in
//   [g_min, g_max] (the clamped range on the S grid), so a sample later by
//   more than H = (g_max - g_min) / deceleration + 1 ms cannot pull a
//   curve value down: the chain from it has risen past g_max on the way.
//   The 1 ms covers the rounding of the chain's sums (under 1e-11 rpm per
//   sample for speeds under 65536 rpm, against the >= 0.05 rpm that 1 ms
//   adds at 50 rpm/s: billions of samples in a window).
//   The pass is recomputed from the latest known sample once the window
//   spans 2 H, and the samples more than H before it are final;
// - per-block ceiling U: the curve over the block and the next block's
//   first sample;
// - greedy S words: sequential, its state (the S in effect, the last word's
//   time) carried; a block's decision looks ahead to the blocks starting
//   within 1 / max_changes_per_s;
// - slew pass over the words, forward: sequential;
// - slew pass over the words, backward (a word lowered so the next one can
//   be reached at the deceleration): monotone in the next word's value and
//   time, so a word is final once it comes out the same with no later word
//   at all and with the lowest possible one (g_min, as early as the next
//   undecided block). With the shipped profiles that is about H after it;
//   with a resolution coarser than deceleration / max_changes_per_s a
//   rounded-down chain can reach further, and the words (not the samples)
//   wait longer;
// - dropping repeated or too small rises, and giving each block its S:
//   sequential.
// Nothing is approximated: the plan equals the whole-timeline passes' bit
// for bit (same operations in the same order where it matters).
//
// Memory and delay: held_samples() <= the samples of the open block (the
// one the last sample belongs to) plus those pushed at or after t_c - 2 H,
// where t_c is the time of the last non-rapid sample before the open block
// (rapids after it wait for the next cut). A block comes out about
// 3 H + 1 / max_changes_per_s after its end (2 H for the curve, the word
// look-ahead, H for its word to settle), plus the length of the next block
// and of a rapid stretch after it: with mazak-3axis (H = 2.99 s) under
// 9.2 s of program time. Until then a block waits as a few numbers, not
// samples.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "machines/profile.h"
#include "postproc/plan/block_stream.h"
#include "postproc/plan/ring_queue.h"
#include "postproc/plan/spindle_plan.h"

namespace vcpost::plan {

// A block of StreamingPlanner waiting for its plan.
struct StreamingBlock {
  BlockPlan plan;
  bool off = false;   // spindle off: planned already
  bool done = false;  // final, ready for take_final
  // From the final curve of its samples (run blocks only):
  double own_min = 0.0;    // lowest curve over its own samples
  double span_min = 0.0;   // ... and the next block's first sample
  double end_curve = 0.0;  // curve at the span's end
  double last_curve = 0.0;
  double ceiling_min = 0.0;
  bool any_target = false;
  bool all_rapid = true;
  double u = 0.0;  // the highest S it may command
  bool u_done = false;
};

// Plans the spindle while the timeline streams in, with bounded memory:
// feed samples in order with push(); take the blocks whose plan can no
// longer change with take_final(); call finish() after the last sample,
// then take_final() returns the rest. The blocks come out in order and
// equal plan_spindle() over the whole timeline, field for field.
class StreamingPlanner : public detail::BlockStream<StreamingPlanner, StreamingBlock,
                                                    detail::RingQueue<StreamingBlock>> {
 public:
  // The spec must be valid (as a loaded profile's is).
  explicit StreamingPlanner(const machines::SpindleSpec& spec);
  // push(), finish(), take_final(), s_words(): see block_stream.h.
  std::size_t held_samples() const;  // samples kept now (for tests of the bound)

  // The horizon H above (s).
  static double horizon_s(const machines::SpindleSpec& spec);

 private:
  friend class detail::BlockStream<StreamingPlanner, StreamingBlock,
                                   detail::RingQueue<StreamingBlock>>;
  using Block = StreamingBlock;
  // A sample of the current run whose curve is not final yet.
  struct Point {
    double time_s = 0.0;
    double program_rpm = 0.0;
    double ceiling = 0.0;   // E (known once the rapid stretch it is in ends)
    double forward = 0.0;   // the forward curve
    double curve = 0.0;     // the curve n (final once the point leaves)
    std::size_t block = 0;  // absolute plan index of its block
    bool rapid = false;
    bool has_target = false;
    bool first = false;  // first sample of its block
  };
  struct Word {
    std::size_t block = 0;  // absolute plan index
    double time_s = 0.0;    // its block's start
    double s = 0.0;
    bool lowered = false;
  };

  void close_block(double end_s);
  void end_timeline() {
    if (in_run_) end_run();
  }
  void taken(std::size_t n) { blocks_base_ += n; }
  void start_run(SpindleState direction, std::size_t first_block);
  void end_run();
  void add_point(const Sample& s, std::size_t block, bool first);
  void step_forward(Point& q);
  void settle_ceilings_at_run_end();
  bool settle_curve(bool run_end);
  void fold(const Point& p);
  void complete(Block& b) const;
  void greedy(bool run_end);
  bool window_ready(std::size_t k, bool run_end);
  void decide(std::size_t k);
  void settle_words(bool run_end);
  void backward_slew(std::vector<Word>& words, const Word* next) const;
  void keep(const Word& w);
  void assign();
  Block& block_at(std::size_t k) { return blocks_[k - blocks_base_]; }
  const Block& block_at(std::size_t k) const { return blocks_[k - blocks_base_]; }
  double clamp(double x) const;

  machines::SpindleSpec spec_;
  double res_;
  double g_min_;
  double g_max_;
  double hold_;     // shortest time between S words, less a nanosecond
  double horizon_;  // H

  // blocks_base_ is the plan index of blocks_.front().
  std::size_t blocks_base_ = 0;
  std::size_t assign_next_ = 0;  // first block not final

  // The current run.
  bool in_run_ = false;
  SpindleState direction_ = SpindleState::cw;
  std::size_t run_ = 0;                     // index of the current (or next) run
  std::size_t run_first_ = 0;               // plan index of its first block
  detail::RingQueue<Point> points_;         // samples whose curve is not final
  std::size_t known_ = 0;                   // points_ with E and the forward curve known
  std::size_t curved_ = 0;                  // points_ with a curve from the last backward pass
  std::optional<double> last_cut_ceiling_;  // E of the last non-rapid sample
  std::optional<double> last_forward_;
  double last_forward_time_ = 0.0;
  double open_time_ = 0.0;  // first time of the block after the accepted ones

  // Greedy word choice.
  std::size_t next_decide_ = 0;            // plan index of the next block to decide
  detail::RingQueue<std::size_t> window_;  // blocks with increasing U
  std::size_t window_next_ = 0;            // first block not yet in the window
  double s_ = 0.0;                         // S in effect (as chosen)
  double last_word_time_ = 0.0;
  std::optional<Word> last_forward_word_;       // last word after the forward slew pass
  std::vector<Word> pending_;                   // words whose backward slew may change
  std::vector<Word> optimistic_, pessimistic_;  // scratch
  std::optional<double> kept_s_;                // S of the last word kept
  detail::RingQueue<Word> kept_;                // kept words not yet given to blocks
  double in_effect_ = 0.0;
  bool in_effect_lowered_ = false;
};

// Feed coupling block by block, in plan order (what plan_feeds() does over a
// whole plan; plan_feeds() runs on it). Throws PlanError when the step is
// not > 0, and from next() on bad input as plan_feeds().
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
