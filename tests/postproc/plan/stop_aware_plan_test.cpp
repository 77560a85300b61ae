// The stop-aware spindle plan (stop_aware_plan.h; issue 17): on a control
// whose path stops at every S word, S words only where the path stops or
// leaves the material anyway, one S per stretch between them. Checked on a
// timeline worked out by hand, and on random timelines against an
// independent whole-timeline computation (every stretch's best constant by
// brute force) and a simulation of the spindle following the S words.
#include "postproc/plan/stop_aware_plan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "machines/builtin.h"
#include "tests/postproc/plan/plan_timeline_support.h"

namespace vcpost::plan {
namespace {

using machines::SpindleSpec;

constexpr double kTol = 1e-6;
constexpr double kInf = std::numeric_limits<double>::infinity();

SpindleSpec stopping_spec() {
  SpindleSpec spec;
  spec.n_min_rpm = 100;
  spec.n_max_rpm = 8000;
  spec.acceleration_rpm_per_s = 1000;
  spec.deceleration_rpm_per_s = 1000;
  spec.s_resolution_rpm = 1;
  spec.min_change_rpm = 5;
  spec.min_change_percent = 1;
  spec.max_changes_per_s = 5;
  spec.stops_path_on_change = true;
  return spec;
}

Sample at(double t, std::size_t block, std::optional<double> target, bool rapid = false) {
  Sample s;
  s.time_s = t;
  s.block = block;
  s.target_rpm = target;
  s.rapid = rapid;
  s.program_rpm = 4000;
  return s;
}

// Three passes, each behind rapids (b0, b4-b5, b8), one sample per block:
//   b0 0.0 rapid | b1 1.0 5000.7 | b2 2.0 4000.2 | b3 3.0 4500
//   b4 4.0 rapid | b5 4.5 rapid  | b6 5.0 6000   | b7 6.0 6500
//   b8 7.0 rapid | b9 9.0 1500   | b10 9.5 1600
// Stretches start at b0, b4 (b5 joins: no feed since b4) and b8.
// Stretch 3 (from t = 7): own 1500; what the S before it may be so that
// the spindle, slowing at 1000 rpm/s from t = 7, is under its ceilings:
// min(1500 + 1000 * 2.0, 1600 + 1000 * 2.5) = 3500.
// Stretch 2 (from t = 4): min(own 6000, 3500) = 3500, lowered (slew).
// Its own slow-down bound: min(6000 + 1000, 6500 + 2000) = 7000; with
// stretch 3's: min(7000, 3500 + 1000 * 3) = 6500 at t = 4.
// Stretch 1: min(own 4000.2, 6500) = 4000.2 -> S4000 (the grid).
TEST(StopAwarePlan, ThreePassesWorkedByHand) {
  const std::vector<Sample> samples = {
      at(0.0, 0, {}, true), at(1.0, 1, 5000.7),   at(2.0, 2, 4000.2), at(3.0, 3, 4500),
      at(4.0, 4, {}, true), at(4.5, 5, {}, true), at(5.0, 6, 6000),   at(6.0, 7, 6500),
      at(7.0, 8, {}, true), at(9.0, 9, 1500),     at(9.5, 10, 1600)};
  const auto plan = plan_spindle(samples, stopping_spec());
  ASSERT_EQ(plan.blocks.size(), 11u);
  const double s[] = {4000, 4000, 4000, 4000, 3500, 3500, 3500, 3500, 1500, 1500, 1500};
  const bool word[] = {true, false, false, false, true, false, false, false, true, false, false};
  const Bound bound[] = {Bound::rapid, Bound::stretch, Bound::resolution, Bound::stretch,
                         Bound::rapid, Bound::rapid,   Bound::slew,       Bound::slew,
                         Bound::rapid, Bound::none,    Bound::stretch};
  for (std::size_t k = 0; k < 11; ++k) {
    SCOPED_TRACE(k);
    EXPECT_DOUBLE_EQ(plan.blocks[k].planned_rpm, s[k]);
    EXPECT_EQ(plan.blocks[k].s_word, word[k]);
    EXPECT_EQ(plan.blocks[k].bound, bound[k]) << to_string(plan.blocks[k].bound);
  }
  EXPECT_EQ(plan.s_words, 3u);
}

TEST(StopAwarePlan, ASmallRiseKeepsTheLowerSAndAFallIsAlwaysWritten) {
  // Threshold at 4000 rpm: max(5, 1 % of 4000) = 40 rpm.
  std::vector<Sample> samples = {at(0.0, 0, {}, true), at(1.0, 1, 4000),
                                 at(2.0, 2, {}, true), at(3.0, 3, 4030),   // +30: kept at 4000
                                 at(4.0, 4, {}, true), at(5.0, 5, 4100),   // +100: written
                                 at(6.0, 6, {}, true), at(7.0, 7, 4099)};  // -1: written
  const auto plan = plan_spindle(samples, stopping_spec());
  ASSERT_EQ(plan.blocks.size(), 8u);
  EXPECT_TRUE(plan.blocks[0].s_word);
  EXPECT_FALSE(plan.blocks[2].s_word);
  EXPECT_DOUBLE_EQ(plan.blocks[3].planned_rpm, 4000);
  EXPECT_EQ(plan.blocks[3].bound, Bound::hysteresis);
  EXPECT_TRUE(plan.blocks[4].s_word);
  EXPECT_DOUBLE_EQ(plan.blocks[5].planned_rpm, 4100);
  EXPECT_TRUE(plan.blocks[6].s_word);
  EXPECT_DOUBLE_EQ(plan.blocks[7].planned_rpm, 4099);
}

TEST(StopAwarePlan, AFeedStreamWithoutAStopHoldsOneSpeed) {
  // 400 blocks of feed after one rapid: one word, the lowest target.
  std::vector<Sample> samples = {at(0.0, 0, {}, true)};
  for (std::size_t k = 1; k <= 400; ++k)
    samples.push_back(at(0.05 * static_cast<double>(k), k,
                         5000 + 1000 * std::sin(0.05 * static_cast<double>(k))));
  const auto plan = plan_spindle(samples, stopping_spec());
  EXPECT_EQ(plan.s_words, 1u);
  double lowest = kInf;
  for (std::size_t k = 1; k <= 400; ++k) lowest = std::min(lowest, *samples[k].target_rpm);
  for (const auto& b : plan.blocks) EXPECT_DOUBLE_EQ(b.planned_rpm, std::floor(lowest));
}

TEST(StopAwarePlan, AReversalAndADwellAreStopsAndTheRateLimitMergesStretches) {
  // b2 starts after a reversal (path_stops): a new stretch. b3 too, but
  // only 0.1 s after b2 (rate 5/s: 0.2 s): it joins b2's stretch.
  std::vector<Sample> samples = {at(0.0, 0, {}, true), at(1.0, 1, 3000), at(2.0, 2, 5000),
                                 at(2.1, 3, 6000), at(3.0, 4, 7000)};
  samples[2].path_stops = true;
  samples[3].path_stops = true;
  const auto plan = plan_spindle(samples, stopping_spec());
  ASSERT_EQ(plan.blocks.size(), 5u);
  EXPECT_TRUE(plan.blocks[2].s_word);
  EXPECT_DOUBLE_EQ(plan.blocks[2].planned_rpm, 5000);
  EXPECT_FALSE(plan.blocks[3].s_word);
  EXPECT_FALSE(plan.blocks[4].s_word);  // no stop before it
  EXPECT_DOUBLE_EQ(plan.blocks[4].planned_rpm, 5000);
}

// Priced words (s_in_feed = "priced"): one rapid, then a feed stream of
// 20 one-second blocks, one sample each; the last block has no time of its
// own (its end is its start). A split at b11 gives each part its own
// ceiling; the gain is the cutting time brought to nominal vc, the change
// times the sum of dt / E over the higher part; the cost is the stop.
std::vector<Sample> two_levels(double first, double second) {
  std::vector<Sample> samples = {at(0.0, 0, {}, true)};
  for (std::size_t k = 1; k <= 20; ++k)
    samples.push_back(at(static_cast<double>(k), k, k <= 10 ? first : second));
  return samples;
}

TEST(StopAwarePlan, PricedWordRisesWhereTheGainOutweighsTheStop) {
  // 3000 then 6000 rpm: at b11 the gain is 3000 * 9 * (1 / 6000) = 4.5 s
  // (b11-b19 one second each, b20 none); a later block gains less, an
  // earlier one nothing (its second part still holds a 3000 ceiling).
  SpindleSpec spec = stopping_spec();
  spec.s_in_feed = machines::SInFeed::priced;
  spec.stop_cost_s = 0.1;
  auto plan = plan_spindle(two_levels(3000, 6000), spec);
  ASSERT_EQ(plan.blocks.size(), 21u);
  EXPECT_EQ(plan.s_words, 2u);
  for (std::size_t k = 0; k <= 20; ++k) {
    SCOPED_TRACE(k);
    EXPECT_DOUBLE_EQ(plan.blocks[k].planned_rpm, k <= 10 ? 3000 : 6000);
    EXPECT_EQ(plan.blocks[k].s_word, k == 0 || k == 11);
  }
  EXPECT_FALSE(plan.blocks[11].stop_place);  // a word in the feed stream: a paid stop
  // A stop of 4.6 s costs more than the 4.5 s won: one S for the stream.
  spec.stop_cost_s = 4.6;
  plan = plan_spindle(two_levels(3000, 6000), spec);
  EXPECT_EQ(plan.s_words, 1u);
  for (const auto& b : plan.blocks) EXPECT_DOUBLE_EQ(b.planned_rpm, 3000);
  // With a 10 % at-speed window the control also waits for the spindle to
  // reach 5400 from 3000: 2.4 s at 1000 rpm/s, 4.8 s at 500 rpm/s.
  spec.stop_cost_s = 0.1;
  spec.at_speed_window_percent = 10;
  EXPECT_EQ(plan_spindle(two_levels(3000, 6000), spec).s_words, 2u);  // 2.5 s < 4.5 s
  spec.acceleration_rpm_per_s = 500;
  EXPECT_EQ(plan_spindle(two_levels(3000, 6000), spec).s_words, 1u);  // 4.9 s > 4.5 s
  // Never (the default) keeps the stream whole whatever the gain.
  spec.s_in_feed = machines::SInFeed::never;
  spec.at_speed_window_percent = 0;
  EXPECT_EQ(plan_spindle(two_levels(3000, 6000), spec).s_words, 1u);
}

TEST(StopAwarePlan, PricedWordsFallEarlyEnoughForTheSpindle) {
  // 6000 then 3000 rpm from b11 (t = 11). The control does not wait for the
  // spindle, which slows at 1000 rpm/s: before a fall written at t_k the
  // first part holds at most 3000 + 1000 * (11 - t_k). Gains of a first
  // split: k = 11: 0; k = 10: 1000 * 9 / 6000 = 1.5 s; k = 9: 2000 * 8 / 6000
  // = 2.67 s; k = 8: 3000 * 7 / 6000 = 3.5 s (b1-b7); k = 7: 3000 * 6 / 6000
  // = 3 s. So b8. In b8-b20 then: k = 9: (5000 - 3000) / 6000 = 0.33 s, k =
  // 10: (4000 - 3000) * 2 / 6000 = 0.33 s (the first wins the tie), so b9;
  // in b9-b20: k = 10: 1000 / 6000 = 0.17 s > 0.1 s, so b10. The S steps
  // down with the spindle: 6000, 5000 (b8), 4000 (b9), 3000 (b10), each
  // second at 1000 rpm/s.
  SpindleSpec spec = stopping_spec();
  spec.s_in_feed = machines::SInFeed::priced;
  spec.stop_cost_s = 0.1;
  const auto plan = plan_spindle(two_levels(6000, 3000), spec);
  ASSERT_EQ(plan.blocks.size(), 21u);
  EXPECT_EQ(plan.s_words, 4u);
  for (std::size_t k = 0; k <= 20; ++k) {
    SCOPED_TRACE(k);
    const double s = k <= 7 ? 6000 : k == 8 ? 5000 : k == 9 ? 4000 : 3000;
    EXPECT_DOUBLE_EQ(plan.blocks[k].planned_rpm, s);
    EXPECT_EQ(plan.blocks[k].s_word, k == 0 || (k >= 8 && k <= 10));
  }
  // At a stop cost of 0.2 s the step at b10 (0.17 s) no longer pays: words
  // at b0, b8 and b9.
  spec.stop_cost_s = 0.2;
  EXPECT_EQ(plan_spindle(two_levels(6000, 3000), spec).s_words, 3u);
}

// ---- Random timelines against an independent computation.

double grid_floor(const SpindleSpec& spec, double x) {
  return std::floor(x / spec.s_resolution_rpm + 1e-9) * spec.s_resolution_rpm;
}
double grid_ceil(const SpindleSpec& spec, double x) {
  return std::ceil(x / spec.s_resolution_rpm - 1e-9) * spec.s_resolution_rpm;
}

struct BlockView {
  std::size_t first = 0, end = 0;  // its samples [first, end)
};

// Blocks as runs of samples with the same block index.
std::vector<BlockView> blocks_of(const std::vector<Sample>& samples) {
  std::vector<BlockView> out;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (out.empty() || samples[i].block != samples[out.back().first].block) out.push_back({i, i});
    out.back().end = i + 1;
  }
  return out;
}

bool on(const Sample& s) { return s.spindle != SpindleState::off && s.program_rpm > 0; }

// The plan of stop_aware_plan.h, computed from its text over the whole
// timeline by brute force: planned S per block.
std::vector<double> reference(const std::vector<Sample>& samples, const SpindleSpec& spec) {
  const double g_min = grid_ceil(spec, spec.n_min_rpm), g_max = grid_floor(spec, spec.n_max_rpm);
  const double hold = 1.0 / spec.max_changes_per_s - 1e-9;
  const auto blocks = blocks_of(samples);
  std::vector<double> out(blocks.size(), 0.0);
  // Run of each block (-1: off), stretch of each block.
  std::vector<long> run(blocks.size(), -1);
  std::vector<std::size_t> stretch(blocks.size(), 0);
  long r = -1;
  std::size_t st = 0;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const Sample& f = samples[blocks[k].first];
    bool tool_change = false;
    for (std::size_t i = blocks[k].first; i < blocks[k].end; ++i)
      tool_change = tool_change || samples[i].tool_change;
    if (!on(f)) continue;
    const bool fresh = k == 0 || run[k - 1] < 0 || tool_change ||
                       samples[blocks[k - 1].first].spindle != f.spindle;
    if (fresh) {
      run[k] = ++r;
      stretch[k] = ++st;
      continue;
    }
    run[k] = r;
    // A new stretch: an allowed block, a feed block since the stretch's
    // start, and the hold passed.
    std::size_t start = k;
    while (start > 0 && stretch[start - 1] == stretch[k - 1] && run[start - 1] == r) --start;
    bool feed = false;
    for (std::size_t j = start; j < k; ++j)
      feed = feed || !s_word_allowed(samples[blocks[j].first]);
    const bool allowed = f.rapid || f.path_stops || f.tool_change;
    const double since = f.time_s - samples[blocks[start].first].time_s;
    stretch[k] = allowed && feed && since >= hold ? ++st : stretch[k - 1];
  }
  // Per stretch: its samples' ceilings (cut ones if any, else far ones).
  auto ceilings = [&](std::size_t s) {
    std::vector<std::pair<double, double>> cut, far;  // (time, E)
    for (std::size_t k = 0; k < blocks.size(); ++k) {
      if (run[k] < 0 || stretch[k] != s) continue;
      for (std::size_t i = blocks[k].first; i < blocks[k].end; ++i) {
        const Sample& x = samples[i];
        if (x.rapid) continue;
        const double e = std::clamp(x.target_rpm ? *x.target_rpm : x.program_rpm, g_min, g_max);
        (x.target_rpm ? cut : far).push_back({x.time_s, e});
      }
    }
    return cut.empty() ? far : cut;
  };
  bool has_s = false;  // an S is in effect in the run
  double s_in_effect = 0;
  std::size_t last_stretch = 0;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    if (run[k] < 0) {
      out[k] = samples[blocks[k].first].program_rpm;
      continue;
    }
    if (stretch[k] == last_stretch) {
      out[k] = s_in_effect;
      continue;
    }
    last_stretch = stretch[k];
    const bool run_first = k == 0 || run[k - 1] != run[k];
    if (run_first) has_s = false;
    double need = kInf;
    for (const auto& [t, e] : ceilings(stretch[k])) need = std::min(need, e);
    // Every later stretch of the run, from the end of this one.
    std::optional<double> t_end;
    for (std::size_t j = k + 1; j < blocks.size() && run[j] == run[k]; ++j) {
      if (stretch[j] == stretch[k]) continue;
      if (!t_end) t_end = samples[blocks[j].first].time_s;
      if (stretch[j] == stretch[j - 1]) continue;
      for (const auto& [t, e] : ceilings(stretch[j]))
        need = std::min(need, e + spec.deceleration_rpm_per_s * (t - *t_end));
    }
    double v = s_in_effect;
    if (need < kInf)
      v = std::max(g_min, grid_floor(spec, std::min(need, g_max)));
    else if (!has_s)
      v = std::max(
          g_min, grid_floor(spec, std::clamp(samples[blocks[k].first].program_rpm, g_min, g_max)));
    const double threshold =
        std::max(spec.min_change_rpm, spec.min_change_percent / 100 * s_in_effect);
    const bool word = !has_s || v < s_in_effect - kTol || v - s_in_effect >= threshold - kTol;
    if (word) {
      s_in_effect = v;
      has_s = true;
    }
    out[k] = s_in_effect;
  }
  return out;
}

// A random timeline with reversals and dwells (path_stops) now and then.
std::vector<Sample> timeline(const SpindleSpec& spec, std::mt19937& rng, double scale) {
  auto samples = testing::random_timeline(spec, rng, scale);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if ((i == 0 || samples[i].block != samples[i - 1].block) && u(rng) < 0.05)
      samples[i].path_stops = true;
  }
  return samples;
}

TEST(StopAwarePlan, RandomTimelinesMatchTheBruteForceStretches) {
  std::mt19937 rng(1717);
  for (int round = 0; round < 120; ++round) {
    SCOPED_TRACE(round);
    auto spec = testing::property_spec(round, rng);
    spec.stops_path_on_change = true;
    spec.s_in_feed = machines::SInFeed::never;  // fanuc-3axis-sar prices words
    const auto samples = timeline(spec, rng, round % 3 == 0 ? 0.05 : 1.0);
    const auto plan = plan_spindle(samples, spec);
    const auto expected = reference(samples, spec);
    ASSERT_EQ(plan.blocks.size(), expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k)
      ASSERT_NEAR(plan.blocks[k].planned_rpm, expected[k], kTol) << "block " << k;
  }
}

TEST(StopAwarePlan, EverySWordIsAtAnAllowedPlaceAndNoneInsideAFeedStream) {
  std::mt19937 rng(4242);
  for (int round = 0; round < 120; ++round) {
    SCOPED_TRACE(round);
    auto spec = testing::property_spec(round, rng);
    spec.stops_path_on_change = true;
    spec.s_in_feed = machines::SInFeed::never;  // fanuc-3axis-sar prices words
    const auto samples = timeline(spec, rng, 1.0);
    const auto plan = plan_spindle(samples, spec);
    const auto blocks = blocks_of(samples);
    ASSERT_EQ(plan.blocks.size(), blocks.size());
    std::size_t words = 0;
    for (std::size_t k = 0; k < blocks.size(); ++k) {
      if (!plan.blocks[k].s_word) continue;
      ++words;
      const Sample& f = samples[blocks[k].first];
      const bool run_start = k == 0 || plan.blocks[k - 1].run != plan.blocks[k].run ||
                             plan.blocks[k - 1].bound == Bound::off;
      EXPECT_TRUE(run_start || s_word_allowed(f)) << "block " << k << " in a feed stream";
    }
    EXPECT_EQ(words, plan.s_words);
  }
}

// The spindle following the words: a rise at once (the worst case for
// overspeed), a fall at exactly the deceleration; at every sample with a
// target it is at or under the clamped target.
TEST(StopAwarePlan, TheSpindleNeverRunsAboveACeiling) {
  std::mt19937 rng(99);
  for (int round = 0; round < 120; ++round) {
    SCOPED_TRACE(round);
    auto spec = testing::property_spec(round, rng);
    spec.stops_path_on_change = true;
    if (round % 4 == 1) {  // priced words too: their parts keep the slew bounds
      spec.s_in_feed = machines::SInFeed::priced;
      spec.stop_cost_s = 0.01 * (round % 7);
    }
    const double g_min = grid_ceil(spec, spec.n_min_rpm), g_max = grid_floor(spec, spec.n_max_rpm);
    const auto samples = timeline(spec, rng, round % 2 ? 0.05 : 1.0);
    const auto plan = plan_spindle(samples, spec);
    std::size_t k = 0;
    double omega = 0, commanded = 0, t_last = 0;
    std::optional<std::size_t> run, block;
    bool off = false;
    for (const Sample& x : samples) {
      omega = std::max(commanded, omega - spec.deceleration_rpm_per_s * (x.time_s - t_last));
      t_last = x.time_s;
      if (!block || *block != x.block) {  // a new block: its word takes effect
        block = x.block;
        while (plan.blocks[k].block != x.block) ++k;
        const BlockPlan& b = plan.blocks[k];
        off = b.bound == Bound::off;
        if (off) {
          run.reset();
        } else if (!run || *run != b.run) {
          run = b.run;
          omega = commanded = b.planned_rpm;  // a run starts from rest; the control waits
        } else if (b.s_word) {
          commanded = b.planned_rpm;
          omega = std::max(omega, commanded);
        }
      }
      if (off || x.rapid || !x.target_rpm) continue;
      const double e = std::clamp(*x.target_rpm, g_min, g_max);
      EXPECT_LE(omega, e + 1e-6) << "sample at " << x.time_s << " block " << x.block;
    }
  }
}

TEST(StopAwarePlan, StreamingGivesBlocksBeforeTheEndAndTheSamePlan) {
  std::mt19937 rng(7);
  auto spec = testing::property_spec(1, rng);
  spec.stops_path_on_change = true;
  const auto samples = timeline(spec, rng, 1.0);
  StopAwarePlanner planner(spec);
  std::vector<BlockPlan> out;
  std::size_t before_end = 0;
  for (const auto& s : samples) {
    planner.push(s);
    planner.take_final(out);
    before_end = out.size();
  }
  planner.finish();
  planner.take_final(out);
  const auto whole = plan_spindle(samples, spec);
  ASSERT_EQ(out.size(), whole.blocks.size());
  for (std::size_t k = 0; k < out.size(); ++k) {
    EXPECT_EQ(out[k].planned_rpm, whole.blocks[k].planned_rpm);
    EXPECT_EQ(out[k].s_word, whole.blocks[k].s_word);
  }
  EXPECT_GT(before_end, 0u);
  EXPECT_THROW(planner.push(samples.front()), PlanError);
}

}  // namespace
}  // namespace vcpost::plan
