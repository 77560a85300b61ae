// The spindle planner on hand-made timelines (figures worked out by hand in
// the comments) and on random ones (the invariants of spindle_plan.h,
// checked independently of the planner's own code: the clamped targets are
// recomputed here and the spindle is simulated following the S words at
// its acceleration limits).
#include "postproc/plan/spindle_plan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "machines/builtin.h"
#include "tests/postproc/plan/plan_timeline_support.h"

namespace vcpost::plan {
namespace {

using machines::SpindleSpec;

constexpr double kTol = 1e-6;  // rpm; the planner works on a grid of >= 0.001 rpm

SpindleSpec mazak() { return machines::builtin_profile("mazak-3axis").spindle(); }

using testing::uniform;

double grid_ceil(const SpindleSpec& spec, double x) {
  return std::ceil(x / spec.s_resolution_rpm - 1e-9) * spec.s_resolution_rpm;
}
double grid_floor(const SpindleSpec& spec, double x) {
  return std::floor(x / spec.s_resolution_rpm + 1e-9) * spec.s_resolution_rpm;
}

// The clamped target of a sample (no target: the program's S); nullopt for
// rapids, which carry no vc requirement.
std::optional<double> clamped(const SpindleSpec& spec, const Sample& s) {
  if (s.rapid) return std::nullopt;
  const double t = s.target_rpm ? *s.target_rpm : s.program_rpm;
  return std::clamp(t, grid_ceil(spec, spec.n_min_rpm), grid_floor(spec, spec.n_max_rpm));
}

// Checks every invariant of the plan's contract; returns the number of
// blocks checked against the band.
std::size_t check_invariants(const std::vector<Sample>& samples, const SpindlePlan& plan,
                             const SpindleSpec& spec) {
  const double g_min = grid_ceil(spec, spec.n_min_rpm);
  const double g_max = grid_floor(spec, spec.n_max_rpm);
  const double hold = 1.0 / spec.max_changes_per_s;
  // Block index in the plan of every sample.
  std::vector<std::size_t> of(samples.size());
  {
    std::size_t k = 0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      while (plan.blocks[k].block != samples[i].block) ++k;
      of[i] = k;
    }
  }
  std::size_t words = 0;
  std::size_t banded = 0;
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::size_t prev_word = kNone;  // plan index of the last S word of the run
  for (std::size_t k = 0; k < plan.blocks.size(); ++k) {
    const auto& b = plan.blocks[k];
    SCOPED_TRACE("block " + std::to_string(b.block) + " S " + std::to_string(b.planned_rpm) +
                 " bound " + std::string(to_string(b.bound)));
    words += b.s_word ? 1 : 0;
    if (b.bound == Bound::off) {
      EXPECT_FALSE(b.s_word);
      continue;
    }
    // On the grid, inside the range.
    EXPECT_NEAR(b.planned_rpm, grid_floor(spec, b.planned_rpm), kTol);
    EXPECT_GE(b.planned_rpm, g_min - kTol);
    EXPECT_LE(b.planned_rpm, g_max + kTol);
    // A run starts with a word.
    const bool run_start =
        k == 0 || plan.blocks[k - 1].bound == Bound::off || plan.blocks[k - 1].run != b.run;
    if (run_start) {
      EXPECT_TRUE(b.s_word);
      prev_word = kNone;
    }
    if (b.s_word) {
      if (prev_word != kNone) {
        const auto& p = plan.blocks[prev_word];
        const double dt = b.start_s - p.start_s;
        const double ds = b.planned_rpm - p.planned_rpm;
        EXPECT_GE(dt, hold - 1e-9) << "S words closer than 1/rate";
        if (ds > 0) {
          EXPECT_LE(ds, spec.acceleration_rpm_per_s * dt + kTol);
          EXPECT_GE(ds, change_threshold(spec, p.planned_rpm) - kTol) << "rise under threshold";
        } else {
          EXPECT_LE(-ds, spec.deceleration_rpm_per_s * dt + kTol);
        }
        EXPECT_GT(std::abs(ds), kTol) << "word repeats the S in effect";
      }
      prev_word = k;
    }
  }
  EXPECT_EQ(words, plan.s_words);

  // Block S under every clamped target of its samples; the band where no
  // limit binds.
  for (std::size_t k = 0; k < plan.blocks.size(); ++k) {
    const auto& b = plan.blocks[k];
    if (b.bound == Bound::off) continue;
    double ceiling = std::numeric_limits<double>::infinity();
    bool any_target = false;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (of[i] != k) continue;
      if (const auto c = clamped(spec, samples[i])) ceiling = std::min(ceiling, *c);
      any_target = any_target || samples[i].target_rpm.has_value();
    }
    EXPECT_LE(b.planned_rpm, ceiling + kTol) << "block " << b.block;
    if (any_target && (b.bound == Bound::none || b.bound == Bound::resolution ||
                       b.bound == Bound::hysteresis || b.bound == Bound::n_max)) {
      const double band = spec.s_resolution_rpm + change_threshold(spec, ceiling);
      EXPECT_GE(b.planned_rpm, ceiling - band - kTol) << "block " << b.block;
      ++banded;
    }
  }

  // The spindle following the words at its limits stays under the clamped
  // targets at every sample. The command during [t_i, t_i+1] is that of
  // sample i's block; a run starts with the spindle at its first S.
  double a = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& b = plan.blocks[of[i]];
    if (b.bound == Bound::off) continue;
    const bool run_start =
        i == 0 || plan.blocks[of[i - 1]].bound == Bound::off || plan.blocks[of[i - 1]].run != b.run;
    if (run_start) {
      a = b.planned_rpm;
    } else {
      const double cmd = plan.blocks[of[i - 1]].planned_rpm;
      const double dt = samples[i].time_s - samples[i - 1].time_s;
      a = a < cmd ? std::min(cmd, a + spec.acceleration_rpm_per_s * dt)
                  : std::max(cmd, a - spec.deceleration_rpm_per_s * dt);
    }
    if (const auto c = clamped(spec, samples[i])) {
      EXPECT_LE(a, *c + kTol) << "spindle over the target at sample " << i << " t "
                              << samples[i].time_s;
    }
  }
  return banded;
}

std::vector<double> planned(const SpindlePlan& plan) {
  std::vector<double> out;
  for (const auto& b : plan.blocks) out.push_back(b.planned_rpm);
  return out;
}

TEST(SpindlePlan, StepDownIsMetAtItsTimeTheSlewStartsEarly) {
  // 8000 rpm until t = 1 s, then 6000; mazak: 4000 rpm/s, one word per 0.1 s.
  // The 2000 rpm drop needs 0.5 s: the slow-down starts at t = 0.5 s and
  // goes in steps of 400 rpm per 0.1 s (each word the lowest target of the
  // next 0.1 s): 7600, 7200, 6800, 6400, 6000 at t = 0.5 ... 0.9 s.
  const auto spec = mazak();
  const auto samples =
      uniform(200, 0.01, [](double t) { return t < 1.0 - 1e-9 ? 8000.0 : 6000.0; });
  const auto plan = plan_spindle(samples, spec);
  check_invariants(samples, plan, spec);
  const auto s = planned(plan);
  for (std::size_t k = 0; k < 50; ++k) EXPECT_DOUBLE_EQ(s[k], 8000.0) << k;
  const double steps[] = {7600, 7200, 6800, 6400, 6000};
  for (std::size_t j = 0; j < 5; ++j)
    for (std::size_t k = 50 + 10 * j; k < 60 + 10 * j; ++k) EXPECT_DOUBLE_EQ(s[k], steps[j]) << k;
  for (std::size_t k = 100; k < 200; ++k) EXPECT_DOUBLE_EQ(s[k], 6000.0) << k;
  EXPECT_EQ(plan.s_words, 6u);
  // Block 50: the curve allows 7960 over its span, the word holds 7600 for
  // 0.1 s: mostly the rate's doing. Block 95: the curve allows 6160, S 6000:
  // the slow-down's.
  EXPECT_EQ(plan.blocks[50].bound, Bound::rate);
  EXPECT_EQ(plan.blocks[95].bound, Bound::slew);
  EXPECT_EQ(plan.blocks[100].bound, Bound::none);
}

TEST(SpindlePlan, StepUpIsFollowedAtTheAccelerationLimit) {
  // 6000 rpm on the samples until t = 0.99 s, 8000 from t = 1 s: the speed
  // may rise at 4000 rpm/s from the last 6000 sample, never ahead of
  // 6000 + 4000 (t - 0.99); words every 0.1 s, the first once the gain
  // reaches the threshold (60 rpm at 6000): t = 1.01 s, 6080.
  const auto spec = mazak();
  const auto samples =
      uniform(300, 0.01, [](double t) { return t < 1.0 - 1e-9 ? 6000.0 : 8000.0; });
  const auto plan = plan_spindle(samples, spec);
  check_invariants(samples, plan, spec);
  const auto s = planned(plan);
  for (std::size_t k = 0; k < 101; ++k) EXPECT_DOUBLE_EQ(s[k], 6000.0) << k;
  const double steps[] = {6080, 6480, 6880, 7280, 7680};
  for (std::size_t j = 0; j < 5; ++j)
    for (std::size_t k = 101 + 10 * j; k < 111 + 10 * j; ++k) EXPECT_DOUBLE_EQ(s[k], steps[j]) << k;
  for (std::size_t k = 151; k < 300; ++k) EXPECT_DOUBLE_EQ(s[k], 8000.0) << k;
  for (std::size_t k = 100; k < 300; ++k) {
    const double line = 6000.0 + 4000.0 * (plan.blocks[k].start_s - 0.99);
    EXPECT_LE(s[k], line + kTol) << k;                                  // never ahead of the limit
    EXPECT_GE(s[k], std::min(8000.0, line) - 400.0 - 60.0 - 1.0) << k;  // one hold behind at most
    // Beyond the band, the larger share of the shortfall: the ramp (8000 -
    // line) or the staircase under it (line - S).
    if (s[k] < 8000.0 - 81.0) {
      const double ramp = 8000.0 - std::min(8000.0, line);
      EXPECT_EQ(plan.blocks[k].bound,
                ramp >= std::min(8000.0, line) - s[k] ? Bound::slew : Bound::rate)
          << k;
    }
  }
  EXPECT_EQ(plan.blocks[110].bound, Bound::slew);  // line 6440, S 6080
  EXPECT_EQ(plan.blocks[150].bound, Bound::rate);  // line 8000, S 7680
}

TEST(SpindlePlan, ClampsToTheSpindleRange) {
  // mazak: 35 .. 12000 rpm. Above: n_max (vc under nominal); below: n_min
  // (vc over nominal, reported).
  const auto spec = mazak();
  auto high = uniform(20, 0.05, [](double) { return 15000.0; });
  auto plan = plan_spindle(high, spec);
  check_invariants(high, plan, spec);
  for (const auto& b : plan.blocks) {
    EXPECT_DOUBLE_EQ(b.planned_rpm, 12000.0);
    EXPECT_EQ(b.bound, Bound::n_max);
  }
  auto low = uniform(20, 0.05, [](double) { return 20.0; });
  plan = plan_spindle(low, spec);
  check_invariants(low, plan, spec);
  for (const auto& b : plan.blocks) {
    EXPECT_DOUBLE_EQ(b.planned_rpm, 35.0);
    EXPECT_EQ(b.bound, Bound::n_min);
  }
}

TEST(SpindlePlan, RoundsDownToTheResolution) {
  auto spec = mazak();
  auto samples = uniform(10, 0.05, [](double) { return 7345.9; });
  auto plan = plan_spindle(samples, spec);
  EXPECT_DOUBLE_EQ(plan.blocks[3].planned_rpm, 7345.0);
  EXPECT_EQ(plan.blocks[3].bound, Bound::resolution);
  spec.s_resolution_rpm = 10.0;
  plan = plan_spindle(samples, spec);
  check_invariants(samples, plan, spec);
  EXPECT_DOUBLE_EQ(plan.blocks[3].planned_rpm, 7340.0);
}

TEST(SpindlePlan, HysteresisKeepsTheLowerSpeedNeverTheHigher) {
  // 8000, then +0.5 % (8040: under the 80 rpm threshold at 8000): no word,
  // 8000 kept; then 7990, 10 rpm under the S in effect: a word is forced on
  // the last 8040 block (its span ends at the 7990 sample) and goes a
  // threshold under that block's need: 8040 - 80.4 -> 7959 (also within the
  // band of 7990 after it: 31 rpm under).
  const auto spec = mazak();
  const auto samples = uniform(90, 0.05, [](double t) {
    return t < 1.5 - 1e-9 ? 8000.0 : t < 3.0 - 1e-9 ? 8040.0 : 7990.0;
  });
  const auto plan = plan_spindle(samples, spec);
  check_invariants(samples, plan, spec);
  EXPECT_EQ(plan.s_words, 2u);
  EXPECT_DOUBLE_EQ(plan.blocks[40].planned_rpm, 8000.0);
  EXPECT_EQ(plan.blocks[40].bound, Bound::hysteresis);
  EXPECT_FALSE(plan.blocks[30].s_word);
  // The drop is commanded one block before the target drops (its span ends there).
  EXPECT_TRUE(plan.blocks[59].s_word);
  EXPECT_DOUBLE_EQ(plan.blocks[59].planned_rpm, 7959.0);
  EXPECT_EQ(plan.blocks[59].bound, Bound::hysteresis);
  EXPECT_DOUBLE_EQ(plan.blocks[80].planned_rpm, 7959.0);
  EXPECT_EQ(plan.blocks[80].bound, Bound::hysteresis);
}

TEST(SpindlePlan, RateLimitHoldsTheLowestTargetOfTheWindow) {
  // The target alternates 8000/7000 every 0.03 s; with a fast spindle only
  // the one-word-per-0.1-s limit binds: the S stays at 7000 and the 8000
  // blocks are reported as held by the rate limit (51 of them, 34 inside
  // an 8000 stretch), except the 17 whose span ends on a 7000 sample: the
  // speed must be down there, and the slow-down is the slew's share.
  auto spec = mazak();
  spec.acceleration_rpm_per_s = spec.deceleration_rpm_per_s = 1e6;
  const auto samples = uniform(100, 0.01, [](double t) {
    return static_cast<int>(std::floor(t / 0.03 + 1e-9)) % 2 == 0 ? 8000.0 : 7000.0;
  });
  const auto plan = plan_spindle(samples, spec);
  check_invariants(samples, plan, spec);
  std::size_t rate = 0, slew = 0;
  for (const auto& b : plan.blocks) {
    EXPECT_DOUBLE_EQ(b.planned_rpm, 7000.0);
    rate += b.bound == Bound::rate ? 1 : 0;
    slew += b.bound == Bound::slew ? 1 : 0;
  }
  EXPECT_EQ(plan.s_words, 1u);
  EXPECT_EQ(rate, 34u);
  EXPECT_EQ(slew, 17u);
}

// Cut blocks 0..49 (0.02 s each) at `before`, one rapid block of 0.5 s
// (samples at its start and end), cut blocks at `after`.
std::vector<Sample> with_rapid(double before, double after) {
  std::vector<Sample> out;
  auto add = [&](double t, std::size_t block, std::optional<double> target, bool rapid) {
    Sample s;
    s.time_s = t;
    s.block = block;
    s.target_rpm = target;
    s.rapid = rapid;
    s.program_rpm = 8000;
    out.push_back(s);
  };
  for (std::size_t k = 0; k < 50; ++k) add(0.02 * static_cast<double>(k), k, before, false);
  add(1.0, 50, std::nullopt, true);
  add(1.5, 50, std::nullopt, true);
  for (std::size_t k = 51; k < 100; ++k)
    add(1.5 + 0.02 * static_cast<double>(k - 51), k, after, false);
  return out;
}

TEST(SpindlePlan, RapidCarriesTheSlowDownToTheNextCut) {
  // 9000 -> rapid 0.5 s -> 7000: the 2000 rpm drop takes exactly the rapid
  // (4000 rpm/s), so the cut before keeps its 9000 and the rapid's block
  // commands 7000.
  const auto spec = mazak();
  const auto samples = with_rapid(9000, 7000);
  const auto plan = plan_spindle(samples, spec);
  check_invariants(samples, plan, spec);
  EXPECT_DOUBLE_EQ(plan.blocks[49].planned_rpm, 9000.0);
  EXPECT_EQ(plan.blocks[49].bound, Bound::none);
  EXPECT_TRUE(plan.blocks[50].s_word);
  EXPECT_DOUBLE_EQ(plan.blocks[50].planned_rpm, 7000.0);
  EXPECT_EQ(plan.blocks[50].bound, Bound::rapid);
  EXPECT_DOUBLE_EQ(plan.blocks[51].planned_rpm, 7000.0);
  EXPECT_EQ(plan.s_words, 2u);
}

TEST(SpindlePlan, RapidMovesToTheNextCutsSpeedEarly) {
  // 7000 -> rapid 0.5 s -> 9000: the rise starts with the rapid, and the
  // next cut starts at its full speed.
  const auto spec = mazak();
  const auto samples = with_rapid(7000, 9000);
  const auto plan = plan_spindle(samples, spec);
  check_invariants(samples, plan, spec);
  EXPECT_DOUBLE_EQ(plan.blocks[49].planned_rpm, 7000.0);
  EXPECT_TRUE(plan.blocks[50].s_word);
  EXPECT_DOUBLE_EQ(plan.blocks[50].planned_rpm, 9000.0);
  EXPECT_DOUBLE_EQ(plan.blocks[51].planned_rpm, 9000.0);
  EXPECT_EQ(plan.blocks[51].bound, Bound::none);
}

TEST(SpindlePlan, ShortRapidKeepsThePreviousSpeedWhereTheLimitsSaySo) {
  // A 0.05 s rapid (t = 1.0 .. 1.05) between 7000 and 9000: the rise may
  // start when the last 7000 block starts being left (t = 0.98), so by the
  // rapid's end 4000 * 0.07 = 280 rpm more: 7280 is written on the rapid
  // (>= the 70 rpm threshold); the cut then climbs at the limit.
  const auto spec = mazak();
  auto samples = with_rapid(7000, 9000);
  for (auto& s : samples)
    if (s.block > 50 || (s.block == 50 && s.time_s > 1.2)) s.time_s -= 0.45;
  const auto plan = plan_spindle(samples, spec);
  check_invariants(samples, plan, spec);
  EXPECT_DOUBLE_EQ(plan.blocks[50].planned_rpm, 7280.0);
  EXPECT_EQ(plan.blocks[51].bound, Bound::slew);
}

TEST(SpindlePlan, ToolChangeRestartsThePlan) {
  // Run 1 at 9000, a tool change, run 2 at 3000 at once: no slow-down in run
  // 1 (the spindle stops for the change), a word on run 2's first block.
  const auto spec = mazak();
  auto samples = uniform(40, 0.05, [](double t) { return t < 1.0 - 1e-9 ? 9000.0 : 3000.0; });
  samples[20].tool_change = true;
  const auto plan = plan_spindle(samples, spec);
  check_invariants(samples, plan, spec);
  EXPECT_DOUBLE_EQ(plan.blocks[19].planned_rpm, 9000.0);
  EXPECT_EQ(plan.blocks[19].run, 0u);
  EXPECT_EQ(plan.blocks[20].run, 1u);
  EXPECT_TRUE(plan.blocks[20].s_word);
  EXPECT_DOUBLE_EQ(plan.blocks[20].planned_rpm, 3000.0);
  EXPECT_EQ(plan.s_words, 2u);
}

TEST(SpindlePlan, SpindleOffAndS0AreLeftAlone) {
  const auto spec = mazak();
  auto samples = uniform(60, 0.05, [](double) { return 9000.0; });
  for (std::size_t k = 20; k < 30; ++k) samples[k].spindle = SpindleState::off;  // M5
  for (std::size_t k = 40; k < 45; ++k) samples[k].program_rpm = 0.0;            // S0
  const auto plan = plan_spindle(samples, spec);
  check_invariants(samples, plan, spec);
  for (std::size_t k = 20; k < 30; ++k) {
    EXPECT_EQ(plan.blocks[k].bound, Bound::off);
    EXPECT_DOUBLE_EQ(plan.blocks[k].planned_rpm, 8000.0);  // the program's S, untouched
    EXPECT_FALSE(plan.blocks[k].s_word);
  }
  for (std::size_t k = 40; k < 45; ++k) {
    EXPECT_EQ(plan.blocks[k].bound, Bound::off);
    EXPECT_DOUBLE_EQ(plan.blocks[k].planned_rpm, 0.0);
  }
  EXPECT_TRUE(plan.blocks[30].s_word);  // the spindle restarts: a new run
  EXPECT_TRUE(plan.blocks[45].s_word);
  EXPECT_EQ(plan.blocks[45].run, 2u);
  EXPECT_EQ(plan.s_words, 3u);
}

TEST(SpindlePlan, DirectionChangeStartsANewRun) {
  const auto spec = mazak();
  auto samples = uniform(20, 0.05, [](double) { return 9000.0; });
  for (std::size_t k = 10; k < 20; ++k) samples[k].spindle = SpindleState::ccw;
  const auto plan = plan_spindle(samples, spec);
  EXPECT_EQ(plan.blocks[10].run, 1u);
  EXPECT_TRUE(plan.blocks[10].s_word);
}

TEST(SpindlePlan, WithoutContactTheProgramsSpeedIsTheCeiling) {
  // Contact at 9000 for 1 s, then 1 s in the air (program S 8000), then
  // contact again: in the air the S comes back down to 8000, not lower.
  const auto spec = mazak();
  auto samples = uniform(60, 0.05, [](double) { return 9000.0; });
  for (std::size_t k = 20; k < 40; ++k) samples[k].target_rpm.reset();
  const auto plan = plan_spindle(samples, spec);
  check_invariants(samples, plan, spec);
  // The 1000 rpm drop takes 0.25 s: 9000 until about t = 0.75 s.
  EXPECT_DOUBLE_EQ(plan.blocks[10].planned_rpm, 9000.0);
  EXPECT_DOUBLE_EQ(plan.blocks[30].planned_rpm, 8000.0);
  EXPECT_EQ(plan.blocks[30].bound, Bound::program);
  EXPECT_DOUBLE_EQ(plan.blocks[50].planned_rpm, 9000.0);
}

TEST(SpindlePlan, WithinTwoPercentWhereNoLimitBindsOnEveryShippedProfile) {
  // A slow sinusoid between 3000 and 5000 rpm (at most 50 rpm/s: 12.5 rpm in
  // the longest word hold, 0.25 s, well under every profile's 30 rpm
  // threshold there): every block in the band, and at most 2 % under.
  for (const auto& bp : machines::builtin_profiles()) {
    SCOPED_TRACE(std::string(bp.name));
    const auto spec = machines::builtin_profile(bp.name).spindle();
    if (spec.stops_path_on_change) continue;  // one S per stretch: stop_aware_plan_test.cpp
    const auto samples =
        uniform(2000, 0.1, [](double t) { return 4000.0 + 1000.0 * std::sin(0.05 * t); });
    const auto plan = plan_spindle(samples, spec);
    EXPECT_EQ(check_invariants(samples, plan, spec), plan.blocks.size());
    for (const auto& b : plan.blocks) {
      EXPECT_GE(b.planned_rpm, 0.98 * *b.target_rpm) << b.block;
      EXPECT_LE(b.planned_rpm, *b.target_rpm + kTol) << b.block;
    }
  }
}

TEST(SpindlePlan, RejectsABrokenTimeline) {
  const auto spec = mazak();
  auto samples = uniform(3, 0.1, [](double) { return 5000.0; });
  samples[2].time_s = 0.05;
  EXPECT_THROW(plan_spindle(samples, spec), PlanError);
  samples = uniform(3, 0.1, [](double) { return 5000.0; });
  samples[1].target_rpm = -1.0;
  EXPECT_THROW(plan_spindle(samples, spec), PlanError);
  samples = uniform(3, 0.1, [](double) { return 5000.0; });
  samples[2].block = 0;
  EXPECT_THROW(plan_spindle(samples, spec), PlanError);
  EXPECT_TRUE(plan_spindle({}, spec).blocks.empty());
}

// Random timelines (plan_timeline_support.h) on the shipped profiles and on
// random specs.
TEST(SpindlePlanProperty, RandomTimelinesKeepEveryInvariant) {
  std::mt19937 rng(20240605);
  std::size_t checked_blocks = 0;
  for (int round = 0; round < 300; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    const SpindleSpec spec = testing::property_spec(round, rng);
    const auto samples = testing::random_timeline(spec, rng);
    const auto plan = plan_spindle(samples, spec);
    checked_blocks += plan.blocks.size();
    check_invariants(samples, plan, spec);
    if (::testing::Test::HasFailure()) break;  // one round's report is enough
  }
  EXPECT_GT(checked_blocks, 30000u);
}

TEST(FeedCoupling, KeepsTheFeedPerToothWithinTheLimits) {
  machines::FeedSpec feed{10.0, 5000.0, 20000.0};
  // 0.05 mm/tooth * 2 teeth * 8000 rpm = 800 mm/min.
  auto c = coupled_feed(0.05, 2, 8000, feed);
  EXPECT_DOUBLE_EQ(c.f_mm_per_min, 800.0);
  EXPECT_EQ(c.bound, FeedBound::none);
  c = coupled_feed(0.2, 4, 12000, feed);  // 9600 > 5000
  EXPECT_DOUBLE_EQ(c.f_mm_per_min, 5000.0);
  EXPECT_EQ(c.bound, FeedBound::f_max);
  c = coupled_feed(0.001, 1, 100, feed);  // 0.1 < 10
  EXPECT_DOUBLE_EQ(c.f_mm_per_min, 10.0);
  EXPECT_EQ(c.bound, FeedBound::f_min);
  EXPECT_DOUBLE_EQ(feed_per_tooth(1200, 6000, 2), 0.1);
  EXPECT_THROW(coupled_feed(0.0, 2, 8000, feed), PlanError);
  EXPECT_THROW(feed_per_tooth(1200, 0, 2), PlanError);
}

TEST(FeedCoupling, FeedWordsOnlyWhereTheFeedChanges) {
  // The step-down timeline; program F 1200 at S 8000 (fz = 0.075 with 2
  // teeth): F follows S as 0.15 * S, rounded down to 0.1 mm/min.
  const auto spec = mazak();
  const auto samples =
      uniform(200, 0.01, [](double t) { return t < 1.0 - 1e-9 ? 8000.0 : 6000.0; });
  const auto plan = plan_spindle(samples, spec);
  std::vector<BlockFeedInput> inputs(plan.blocks.size(), BlockFeedInput{1200.0, 8000.0});
  const machines::FeedSpec feed{1.0, 20000.0, 42000.0};
  const auto feeds = plan_feeds(plan, inputs, std::nullopt, 2, feed, 0.1);
  std::size_t words = 0;
  for (std::size_t k = 0; k < feeds.size(); ++k) {
    EXPECT_NEAR(feeds[k].f_mm_per_min, 0.15 * plan.blocks[k].planned_rpm, 1e-9) << k;
    EXPECT_EQ(feeds[k].f_word, plan.blocks[k].s_word) << k;
    words += feeds[k].f_word ? 1 : 0;
  }
  EXPECT_EQ(words, 6u);
  // A given fz; rounding down to whole mm/min: 0.0333 * 2 * 8000 = 532.8 -> 532.
  const auto given = plan_feeds(plan, inputs, 0.0333, 2, feed, 1.0);
  EXPECT_DOUBLE_EQ(given[0].f_mm_per_min, 532.0);
  EXPECT_THROW(plan_feeds(plan, std::span(inputs).first(3), std::nullopt, 2, feed, 0.1), PlanError);
}

TEST(FeedCoupling, RapidsAndAirKeepTheProgramsFeed) {
  const auto spec = mazak();
  auto samples = uniform(10, 0.1, [](double) { return 9000.0; });
  samples[5].target_rpm.reset();
  const auto plan = plan_spindle(samples, spec);
  std::vector<BlockFeedInput> inputs(plan.blocks.size(), BlockFeedInput{1000.0, 8000.0});
  // fz 0.05 mm, 2 teeth: F = 0.1 * S on the cut blocks.
  const auto feeds = plan_feeds(plan, inputs, 0.05, 2, machines::FeedSpec{}, 0.1);
  EXPECT_DOUBLE_EQ(plan.blocks[4].planned_rpm, 8000.0);  // down to the air's 8000 in time
  EXPECT_NEAR(feeds[4].f_mm_per_min, 800.0, 1e-9);
  EXPECT_DOUBLE_EQ(feeds[5].f_mm_per_min, 1000.0);  // no contact: the program's F
  EXPECT_TRUE(feeds[5].f_word);
  EXPECT_NEAR(feeds[0].f_mm_per_min, 900.0, 1e-9);
}

}  // namespace
}  // namespace vcpost::plan
