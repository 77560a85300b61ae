// The cutting-speed statistics of a post, fed block by block in the order
// the blocks become final: vc before and after over the posted sections
// (the whole program's, each section's and each placement run's), the S
// words of each run and what their stops cost, and the time each planner
// bound held the speed. The post job's last stage owns one.
#pragma once

#include <cmath>
#include <cstddef>
#include <optional>

#include "machines/profile.h"
#include "postproc/plan/spindle_plan.h"
#include "postproc/post/post_job.h"
#include "postproc/post/tallies.h"

namespace vcpost::post {

// What the last stage keeps of an evaluated sample until its block is final.
struct HeldSample {
  float d_ref = NAN;  // mm; NaN where the tool does not cut
  float weight_s = 0;
  std::size_t block = 0;
  double time_s = 0;
};

class SpeedStatistics {
 public:
  // Writes into `summary` (its bound times as blocks come, the rest at finish).
  SpeedStatistics(const machines::SpindleSpec& spindle, PostSummary& summary)
      : spindle_(spindle), summary_(summary) {}

  // A final block, before its samples: opens or continues the placement
  // run it belongs to (off blocks belong to none) and counts its S word.
  void open_block(const plan::BlockPlan& block);

  // A sample of a posted section's block: vc at the program's speed (before)
  // and at the planned one (after), into the program's, the section's
  // (`section_before`, `section_after`) and the run's tallies. One that
  // does not cut counts nothing.
  void add_sample(const HeldSample& sample, double program_rpm, double planned_rpm, double nominal,
                  VcTally& section_before, VcTally& section_after);

  // A posted section's block: its time under the bound that decided its S.
  void add_bound_time(const plan::BlockPlan& block);

  // Closes the last run; the program's before/after and the placement totals.
  void finish();

 private:
  void close_placement();

  struct Placement {
    SectionPlacement placement;
    VcTally before, after;
  };

  machines::SpindleSpec spindle_;
  PostSummary& summary_;
  VcTally before_, after_;
  std::optional<Placement> placement_;
};

}  // namespace vcpost::post
