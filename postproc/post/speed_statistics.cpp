#include "postproc/post/speed_statistics.h"

#include "geometry/engagement.h"

namespace vcpost::post {

void SpeedStatistics::open_block(const plan::BlockPlan& block) {
  if (block.bound == plan::Bound::off) return;
  if (!placement_ || placement_->placement.run != block.run) {
    close_placement();
    placement_.emplace();
    placement_->placement.run = block.run;
    placement_->placement.start_s = block.start_s;
  }
  if (!block.s_word) return;
  ++placement_->placement.s_words;
  if (!block.stop_place) ++placement_->placement.in_feed;
  // Every S word stops the path on such a control (LinuxCNC stops even
  // on an unchanged one); at a stop place the path stopped anyway, but
  // the word still costs its stop time there.
  if (spindle_.stops_path_on_change) ++placement_->placement.stops;
}

void SpeedStatistics::add_sample(const HeldSample& sample, double program_rpm, double planned_rpm,
                                 double nominal, VcTally& section_before, VcTally& section_after) {
  if (std::isnan(sample.d_ref)) return;
  // Each speed once, into the program's, the section's and the run's tallies.
  const double before = geometry::cutting_speed(sample.d_ref, program_rpm);
  const double after = geometry::cutting_speed(sample.d_ref, planned_rpm);
  const double weight = sample.weight_s;
  before_.add(before, nominal, weight);
  after_.add(after, nominal, weight);
  section_before.add(before, nominal, weight);
  section_after.add(after, nominal, weight);
  if (placement_) {
    placement_->before.add(before, nominal, weight);
    placement_->after.add(after, nominal, weight);
    placement_->placement.cutting_time_s += weight;
  }
}

void SpeedStatistics::add_bound_time(const plan::BlockPlan& block) {
  const double duration = block.end_s - block.start_s;
  switch (block.bound) {
    case plan::Bound::n_max:
      summary_.time_clamped_max_s += duration;
      break;
    case plan::Bound::n_min:
      summary_.time_clamped_min_s += duration;
      break;
    case plan::Bound::slew:
      summary_.time_slew_s += duration;
      break;
    case plan::Bound::rate:
      summary_.time_rate_s += duration;
      break;
    default:
      break;
  }
}

void SpeedStatistics::close_placement() {
  if (!placement_) return;
  SectionPlacement& p = placement_->placement;
  p.time_cost_s = static_cast<double>(p.stops) * spindle_.stop_cost_s;
  p.before = placement_->before.statistics();
  p.after = placement_->after.statistics();
  summary_.s_placement.sections.push_back(p);
  placement_.reset();
}

void SpeedStatistics::finish() {
  summary_.before = before_.statistics();
  summary_.after = after_.statistics();
  close_placement();
  SPlacement& placement = summary_.s_placement;
  placement.at_stops = spindle_.stops_path_on_change;
  placement.priced = placement.at_stops && spindle_.s_in_feed == machines::SInFeed::priced;
  placement.stop_cost_s = spindle_.stop_cost_s;
  for (const auto& section : placement.sections) {
    placement.s_words += section.s_words;
    placement.in_feed += section.in_feed;
    placement.stops += section.stops;
    placement.time_cost_s += section.time_cost_s;
  }
}

}  // namespace vcpost::post
