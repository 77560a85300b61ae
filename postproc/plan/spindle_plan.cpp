#include "postproc/plan/spindle_plan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "postproc/plan/plan_rules.h"
#include "postproc/plan/stop_aware_plan.h"
#include "postproc/plan/streaming_plan.h"

namespace vcpost::plan {

std::string_view to_string(Bound b) {
  switch (b) {
    case Bound::none:
      return "none";
    case Bound::resolution:
      return "resolution";
    case Bound::hysteresis:
      return "hysteresis";
    case Bound::n_max:
      return "n_max";
    case Bound::n_min:
      return "n_min";
    case Bound::slew:
      return "slew";
    case Bound::rate:
      return "rate";
    case Bound::stretch:
      return "stretch";
    case Bound::program:
      return "program";
    case Bound::rapid:
      return "rapid";
    case Bound::off:
      return "off";
  }
  return "?";
}

double change_threshold(const machines::SpindleSpec& spec, double s_rpm) {
  return std::max(spec.min_change_rpm, spec.min_change_percent / 100.0 * s_rpm);
}

namespace detail {

void check_sample(std::size_t index, const Sample& s, const Sample* prev) {
  auto fail = [index](const char* what) {
    throw PlanError("sample " + std::to_string(index) + ": " + what);
  };
  if (!std::isfinite(s.time_s)) fail("time is not finite");
  if (!std::isfinite(s.program_rpm) || s.program_rpm < 0) fail("program S must be finite and >= 0");
  if (s.target_rpm && (!std::isfinite(*s.target_rpm) || *s.target_rpm <= 0))
    fail("target speed must be finite and > 0");
  if (prev) {
    if (s.time_s < prev->time_s) fail("time goes backwards");
    if (s.block < prev->block) fail("block index goes backwards");
  }
}

Bound classify_bound(const machines::SpindleSpec& spec, double g_min, double g_max,
                     const BlockFacts& facts, std::optional<double> target_rpm, double s,
                     bool lowered) {
  if (!facts.any_target) return facts.all_rapid ? Bound::rapid : Bound::program;
  const Grid grid{spec.s_resolution_rpm};
  const double target = *target_rpm;
  const double ceiling = facts.ceiling;
  if (target < g_min - kEps) return Bound::n_min;
  const bool clamped_max = target > g_max + kEps;
  const double deficit = ceiling - s;
  const double band = change_threshold(spec, ceiling) + spec.s_resolution_rpm;
  if (deficit <= kEps) return clamped_max ? Bound::n_max : Bound::none;
  if (s >= grid.floor(ceiling) - kEps) return clamped_max ? Bound::n_max : Bound::resolution;
  if (deficit <= band + kEps) return clamped_max ? Bound::n_max : Bound::hysteresis;
  if (lowered) return Bound::slew;
  // The larger share of the deficit names the limit: the curve under the
  // ceiling over the block's span (acceleration, or the slow-down before a
  // lower target), or the staircase under the curve (the word rate).
  const double slew_part = ceiling - facts.curve_min;
  const double rate_part = facts.curve_min - s;
  return slew_part >= rate_part ? Bound::slew : Bound::rate;
}

}  // namespace detail

namespace {
template <class Planner>
SpindlePlan run_planner(Planner planner, std::span<const Sample> samples) {
  for (const auto& s : samples) planner.push(s);
  planner.finish();
  SpindlePlan plan;
  planner.take_final(plan.blocks);
  plan.s_words = planner.s_words();
  return plan;
}
}  // namespace

// A streaming planner fed the whole timeline (streaming_plan.cpp and
// stop_aware_plan.cpp hold the passes).
SpindlePlan plan_spindle(std::span<const Sample> samples, const machines::SpindleSpec& spec) {
  if (spec.stops_path_on_change) return run_planner(StopAwarePlanner(spec), samples);
  return run_planner(StreamingPlanner(spec), samples);
}

CoupledFeed coupled_feed(double fz_mm, int teeth, double n_rpm, const machines::FeedSpec& feed) {
  if (!(fz_mm > 0) || !std::isfinite(fz_mm)) throw PlanError("feed per tooth must be > 0");
  if (teeth < 1) throw PlanError("number of teeth must be >= 1");
  if (!(n_rpm > 0) || !std::isfinite(n_rpm)) throw PlanError("spindle speed must be > 0");
  const double f = fz_mm * teeth * n_rpm;
  if (f < feed.f_min_mm_per_min) return {feed.f_min_mm_per_min, FeedBound::f_min};
  if (f > feed.f_max_mm_per_min) return {feed.f_max_mm_per_min, FeedBound::f_max};
  return {f, FeedBound::none};
}

double feed_per_tooth(double program_f_mm_per_min, double program_s_rpm, int teeth) {
  if (!(program_f_mm_per_min > 0) || !(program_s_rpm > 0) || teeth < 1)
    throw PlanError("feed per tooth needs the program's F > 0, S > 0 and teeth >= 1");
  return program_f_mm_per_min / (teeth * program_s_rpm);
}

std::vector<BlockFeed> plan_feeds(const SpindlePlan& plan, std::span<const BlockFeedInput> inputs,
                                  std::optional<double> fz_mm, int teeth,
                                  const machines::FeedSpec& feed, double step_mm_per_min) {
  if (inputs.size() != plan.blocks.size())
    throw PlanError("plan_feeds: one feed input per plan block is needed");
  StreamingFeedPlanner planner(fz_mm, teeth, feed, step_mm_per_min);
  std::vector<BlockFeed> out;
  out.reserve(inputs.size());
  for (std::size_t k = 0; k < inputs.size(); ++k)
    out.push_back(planner.next(plan.blocks[k], inputs[k]));
  return out;
}

}  // namespace vcpost::plan
