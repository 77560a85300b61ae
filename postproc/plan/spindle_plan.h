// The spindle planner: from the target spindle speed at every sample of the
// toolpath to the S word of every block, within what the machine can do
// (MODELS.md section 4, issue 5 "Planning"). A pure function of a timeline
// and a machine's SpindleSpec; no I/O.
//
// Units: time in s from program start, speeds in rpm.
//
// Timing model. The S in effect on a block holds from the time of its first
// sample to the time of the next block's first sample (give each move's
// start point as the first sample of its block). The spindle follows a
// commanded S at its acceleration/deceleration limit (the profile's figures
// are what it achieves at least).
//
// What the plan guarantees within each run (a stretch of samples with the
// spindle on in one direction and no tool change):
// - every planned S lies on the resolution grid inside [n_min, n_max];
// - planned S <= the target of every sample of its block clamped to
//   [n_min, n_max] (vc <= vc_nom wherever n_min does not bind), and the
//   spindle, following the S words at its limits, stays at or under the
//   clamped targets at every sample: a decrease is commanded early enough
//   (the slow-down starts before a drop in the target, never after);
// - between two consecutive S words j-1, j of a run:
//   S_j - S_{j-1} <= acceleration * (t_j - t_{j-1}) and
//   S_{j-1} - S_j <= deceleration * (t_j - t_{j-1});
// - consecutive S words are at least 1 / max_changes_per_s apart;
// - an S word that raises the speed raises it by at least the hysteresis
//   threshold max(min_change_rpm, min_change_percent % of the current S);
//   a smaller gain is never written (the lower speed is kept);
// - where no limit binds (Bound::none, resolution, hysteresis, n_max) the
//   planned S is within s_resolution + threshold(target) under the block's
//   clamped target (the band; <= 2 % with the shipped profiles from 300 rpm).
//
// Spindle semantics: S0 or M5 means off; off stretches are left untouched
// (no S word, the program's S reported). A tool change or a change of
// direction starts a new run: the plan restarts there (the spindle starts
// from rest and the control waits for it), and the first block of a run
// always gets an S word. Samples without a target keep the program's own S
// as their ceiling (no contact: vc means nothing there). Rapids have no
// ceiling of their own: they take the larger of the neighbouring cuts'
// ceilings, so the speed moves towards the next cut's S during the rapid as
// far as the limits allow.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "machines/profile.h"

namespace vcpost::plan {

enum class SpindleState { off, cw, ccw };  // M5 (or S0), M3, M4

struct Sample {
  double time_s = 0.0;    // from program start, non-decreasing
  std::size_t block = 0;  // block index in the program, non-decreasing
  // Spindle speed that keeps vc at vc_nom here (rpm, > 0); nullopt where
  // there is no contact or no cutting.
  std::optional<double> target_rpm;
  bool rapid = false;        // G0 move
  bool tool_change = false;  // a tool change precedes this sample: the plan restarts
  // The path stops here anyway (a sharp reversal, a dwell or a program stop
  // before it): on a control whose path stops at an S word, an S word here
  // costs no stop of its own (stop_aware_plan.h). Set on a block's first sample.
  bool path_stops = false;
  SpindleState spindle = SpindleState::cw;
  double program_rpm = 0.0;  // the program's own S in effect here (0 = off)
};

// What decided the planned S of a block.
enum class Bound {
  none,        // S equals the block's target
  resolution,  // S is the target rounded down to the S resolution
  hysteresis,  // S kept under the target by less than the change threshold
  n_max,       // target above n_max: clamped (vc under nominal)
  n_min,       // target below n_min: clamped (vc OVER nominal)
  // Beyond the band, the larger share of the shortfall names the limit:
  slew,     // acceleration/deceleration: S starts changing early or follows late
  rate,     // the S-word rate (one S per block, words 1/rate apart) held S lower
  stretch,  // one S holds the stretch between two stops (stop_aware_plan.h): a lower need elsewhere
            // in it
  program,  // no target (no contact): the program's S is the ceiling
  rapid,    // rapid move: no vc requirement
  off,      // spindle off (M5/S0): untouched
};

std::string_view to_string(Bound b);

struct BlockPlan {
  std::size_t block = 0;  // block index in the program
  std::size_t run = 0;    // index of its run (0, 1, ...); off blocks: the next run's
  double start_s = 0.0;   // time of the block's first sample
  double end_s = 0.0;     // time of the next block's first sample (or its own last)
  // Smallest target over the block's samples (unclamped); nullopt when none.
  std::optional<double> target_rpm;
  double planned_rpm = 0.0;  // S in effect on the block (the program's S when off)
  bool s_word = false;       // a new S word starts on this block
  Bound bound = Bound::none;
  // An S word here costs no stop of its own where S stops the path: the
  // path stops or leaves the material anyway (s_word_allowed() of
  // stop_aware_plan.h), or a run starts.
  bool stop_place = false;
};

struct SpindlePlan {
  std::vector<BlockPlan> blocks;  // one per block that has samples, in order
  std::size_t s_words = 0;        // number of blocks with s_word
};

// Thrown for a timeline that breaks the contract above (time or block going
// backwards, a non-finite or non-positive target, negative program S): a
// caller's bug, not the user's input (E9001, exit 3).
class PlanError : public vcpost::Error {
 public:
  explicit PlanError(const std::string& message) : vcpost::Error(Code::E9001, message) {}
};

// Plans the spindle over the whole timeline. The spec must be valid (as a
// loaded profile's is). Throws PlanError. (It feeds StreamingPlanner of
// streaming_plan.h, which gives the same blocks with bounded memory, or,
// when spec.stops_path_on_change, StopAwarePlanner of stop_aware_plan.h,
// whose contract replaces the S-word placement above: S words only where
// the path stops anyway.)
SpindlePlan plan_spindle(std::span<const Sample> samples, const machines::SpindleSpec& spec);

// The hysteresis threshold at the current speed s (rpm).
double change_threshold(const machines::SpindleSpec& spec, double s_rpm);

// ---- Feed coupling: F = fz * z * n, clamped to the profile's feed limits.

enum class FeedBound { none, f_min, f_max };

struct CoupledFeed {
  double f_mm_per_min = 0.0;
  FeedBound bound = FeedBound::none;
};

// fz in mm per tooth, teeth >= 1, n in rpm (> 0). Throws PlanError on bad input.
CoupledFeed coupled_feed(double fz_mm, int teeth, double n_rpm, const machines::FeedSpec& feed);

// fz that the program's F gives at its S: F / (z * S). Throws PlanError
// when S or F is not positive.
double feed_per_tooth(double program_f_mm_per_min, double program_s_rpm, int teeth);

// One block's feed for plan_feeds().
struct BlockFeedInput {
  double program_f_mm_per_min = 0.0;  // F in effect on the block (0: none, e.g. a rapid)
  double program_s_rpm = 0.0;         // the program's S on the block
  int teeth = 0;  // the teeth of the block's tool where known (0: the planner's own)
};

struct BlockFeed {
  double f_mm_per_min = 0.0;  // the F to have in effect (the program's where not coupled)
  bool f_word = false;        // a new F word starts on this block
  FeedBound bound = FeedBound::none;
};

// Couples the feed of every planned cutting block (not rapids, not off or
// program-kept blocks) to its planned S. fz: the given value, or else each
// block's program F at the program S. F is rounded down to `step_mm_per_min`
// (> 0, the output's F resolution) so the feed per tooth never exceeds fz,
// and an F word is marked only where the rounded F changes.
// `inputs` has one entry per plan block. Throws PlanError on a size mismatch.
std::vector<BlockFeed> plan_feeds(const SpindlePlan& plan, std::span<const BlockFeedInput> inputs,
                                  std::optional<double> fz_mm, int teeth,
                                  const machines::FeedSpec& feed, double step_mm_per_min);

}  // namespace vcpost::plan
