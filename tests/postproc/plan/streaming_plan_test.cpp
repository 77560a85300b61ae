// The streaming planner against the reference planner that runs every pass
// over the whole timeline at once (plan_reference_support.cpp, formerly
// plan_spindle()): field for field and bit for bit (both apply the same
// rules in the same floating-point order; a window that cuts a dependency
// shows up as a difference), with the held samples within the bound of
// streaming_plan.h. plan_spindle() itself now runs on the streaming planner.
#include "postproc/plan/streaming_plan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "machines/builtin.h"
#include "tests/postproc/plan/plan_reference_support.h"
#include "tests/postproc/plan/plan_timeline_support.h"

namespace vcpost::plan {
namespace {

using machines::SpindleSpec;

SpindleSpec mazak() { return machines::builtin_profile("mazak-3axis").spindle(); }

// H of streaming_plan.h, from the spec: the clamped range on the S grid
// over the deceleration, plus 1 ms.
double horizon(const SpindleSpec& spec) {
  const double res = spec.s_resolution_rpm;
  const double g_min = std::ceil(spec.n_min_rpm / res - 1e-9) * res;
  const double g_max = std::floor(spec.n_max_rpm / res + 1e-9) * res;
  return (g_max - g_min) / spec.deceleration_rpm_per_s + 1e-3;
}

// Streams `samples` with take_final() every `take_every` pushes (1: after
// every push), checking after each push that the held samples are within
// the bound: the open block's samples and those at or after t_c - 2 H,
// t_c the time of the last non-rapid sample before the open block.
// Returns the streamed plan; `peak` gets the most samples held, `lag` the
// longest time from a taken block's end to the last sample pushed.
SpindlePlan stream(const std::vector<Sample>& samples, const SpindleSpec& spec,
                   std::size_t take_every = 1, std::size_t* peak = nullptr, double* lag = nullptr) {
  StreamingPlanner planner(spec);
  SpindlePlan plan;
  const double window = 2 * horizon(spec);
  double t_c = -std::numeric_limits<double>::infinity();
  double t_block_cut = t_c;  // last non-rapid time in the open block
  std::size_t lo = 0;        // first sample at or after t_c - 2 H
  std::size_t most = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& s = samples[i];
    if (i > 0 && s.block != samples[i - 1].block) t_c = std::max(t_c, t_block_cut);
    if (!s.rapid) t_block_cut = s.time_s;
    planner.push(s);
    while (lo < i && samples[lo].time_s < t_c - window - 1e-9) ++lo;
    const std::size_t bound = i + 1 - lo;
    EXPECT_LE(planner.held_samples(), bound) << "after sample " << i;
    most = std::max(most, planner.held_samples());
    if ((i + 1) % take_every == 0) planner.take_final(plan.blocks);
    if (lag)
      *lag = std::max(*lag, s.time_s - (plan.blocks.empty() ? samples.front().time_s
                                                            : plan.blocks.back().end_s));
  }
  planner.finish();
  planner.take_final(plan.blocks);
  EXPECT_EQ(planner.held_samples(), 0u);
  plan.s_words = planner.s_words();
  if (peak) *peak = most;
  return plan;
}

// Field for field; doubles exactly.
void expect_same(const SpindlePlan& streamed, const SpindlePlan& whole) {
  ASSERT_EQ(streamed.blocks.size(), whole.blocks.size());
  EXPECT_EQ(streamed.s_words, whole.s_words);
  for (std::size_t k = 0; k < whole.blocks.size(); ++k) {
    const auto& a = streamed.blocks[k];
    const auto& b = whole.blocks[k];
    SCOPED_TRACE("plan block " + std::to_string(k) + " (block " + std::to_string(b.block) + ")");
    EXPECT_EQ(a.block, b.block);
    EXPECT_EQ(a.run, b.run);
    EXPECT_EQ(a.start_s, b.start_s);
    EXPECT_EQ(a.end_s, b.end_s);
    EXPECT_EQ(a.target_rpm, b.target_rpm);
    EXPECT_EQ(a.planned_rpm, b.planned_rpm);
    EXPECT_EQ(a.s_word, b.s_word);
    EXPECT_EQ(a.bound, b.bound);
    if (::testing::Test::HasFailure()) return;  // the first difference is enough
  }
}

using testing::uniform;

// 360 random timelines: the property test's generator (tool changes, M5/S0,
// direction changes, rapids, air moves, targets out of range) on shipped
// and random specs, at three sample spacings: as generated (blocks up to
// 0.5 s), 100 times denser (the windows span many blocks) and 20 times
// sparser (most blocks longer than the horizon).
TEST(StreamingPlan, EqualsThePlanOfTheWholeTimelineOnRandomTimelines) {
  std::mt19937 rng(7007);
  const double scales[] = {1.0, 0.01, 20.0};
  std::size_t blocks = 0;
  std::size_t words = 0;
  for (int round = 0; round < 360; ++round) {
    const double scale = scales[round % 3];
    SCOPED_TRACE("round " + std::to_string(round) + " scale " + std::to_string(scale));
    const SpindleSpec spec = testing::property_spec(round / 3, rng);
    const auto samples = testing::random_timeline(spec, rng, scale);
    const auto whole = testing::reference_plan_spindle(samples, spec);
    expect_same(stream(samples, spec), whole);
    expect_same(plan_spindle(samples, spec), whole);
    blocks += whole.blocks.size();
    words += whole.s_words;
    if (::testing::Test::HasFailure()) break;  // one round's report is enough
  }
  EXPECT_GT(blocks, 70000u);
  EXPECT_GT(words, 8000u);
}

TEST(StreamingPlan, TakingFinalBlocksRarelyOrOnlyAtTheEndChangesNothing) {
  std::mt19937 rng(77);
  for (int round = 0; round < 40; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    const SpindleSpec spec = testing::property_spec(round, rng);
    const auto samples = testing::random_timeline(spec, rng);
    const auto whole = testing::reference_plan_spindle(samples, spec);
    expect_same(stream(samples, spec, 97), whole);
    expect_same(stream(samples, spec, samples.size() + 1), whole);
    if (::testing::Test::HasFailure()) break;
  }
}

TEST(StreamingPlan, BlocksComeOutWhileTheTimelineStreams) {
  // The step-down timeline of spindle_plan_test (8000 -> 6000 at t = 1 s,
  // 10 ms blocks), 60 s long: with mazak, H = (12000 - 35) / 4000 + 0.001
  // = 2.99225 s; a block's S is final within about two H and the word look
  // ahead (0.1 s), so after t = 30 s at least the blocks up to t = 20 s are
  // out.
  const auto spec = mazak();
  const auto samples =
      uniform(6000, 0.01, [](double t) { return t < 1.0 - 1e-9 ? 8000.0 : 6000.0; });
  StreamingPlanner planner(spec);
  std::vector<BlockPlan> out;
  for (std::size_t i = 0; i <= 3000; ++i) {
    planner.push(samples[i]);
    planner.take_final(out);
  }
  EXPECT_GE(out.size(), 2000u);
  EXPECT_LT(out.size(), 3001u);
  ASSERT_GE(out.size(), 101u);
  EXPECT_DOUBLE_EQ(out[0].planned_rpm, 8000.0);
  EXPECT_DOUBLE_EQ(out[100].planned_rpm, 6000.0);
  EXPECT_EQ(planner.s_words(), 6u);  // as spindle_plan_test's hand-checked figure
}

// Hand-made runs: each case against the reference, field for field.
TEST(StreamingPlan, ToolChangesSpindleOffRapidsAndAirAsTheWholePlan) {
  const auto spec = mazak();
  const double h = horizon(spec);
  auto base = [](std::size_t n) {
    return uniform(n, 0.05, [](double t) { return 6000.0 + 2500.0 * std::sin(1.3 * t); });
  };
  struct Case {
    std::string name;
    std::vector<Sample> samples;
  };
  std::vector<Case> cases;
  {
    auto s = base(400);
    s[150].tool_change = true;
    s[300].tool_change = true;
    cases.push_back({"tool changes", s});
  }
  {
    // A tool change on a block's second sample starts the run at the block.
    std::vector<Sample> s;
    for (const auto& one : base(200)) {
      s.push_back(one);
      Sample second = one;
      second.time_s += 0.025;
      second.tool_change = one.block == 120;
      s.push_back(second);
    }
    cases.push_back({"tool change inside a block", s});
  }
  {
    auto s = base(400);
    for (std::size_t k = 100; k < 180; ++k) s[k].spindle = SpindleState::off;
    for (std::size_t k = 250; k < 260; ++k) s[k].program_rpm = 0.0;
    for (std::size_t k = 330; k < 400; ++k) s[k].spindle = SpindleState::ccw;
    cases.push_back({"M5, S0, M4", s});
  }
  {
    // A rapid stretch longer than the window (its samples wait for the cut
    // after it), at the start, inside, and at the end of the timeline.
    auto s = base(600);
    const std::size_t stretch = static_cast<std::size_t>(3 * h / 0.05);
    for (std::size_t k = 0; k < 10; ++k) s[k].rapid = true;
    for (std::size_t k = 200; k < 200 + stretch; ++k) s[k].rapid = true;
    for (std::size_t k = 580; k < 600; ++k) s[k].rapid = true;
    for (auto& x : s)
      if (x.rapid) x.target_rpm.reset();
    cases.push_back({"rapids", s});
  }
  {
    auto s = base(400);
    for (std::size_t k = 50; k < 300; ++k) s[k].target_rpm.reset();
    cases.push_back({"no target (air)", s});
  }
  {
    auto s = base(300);
    for (auto& x : s) x.target_rpm.reset();
    cases.push_back({"no target anywhere", s});
  }
  {
    auto s = base(300);
    for (auto& x : s) x.rapid = true, x.target_rpm.reset();
    cases.push_back({"rapids only", s});
  }
  {
    auto s = base(300);
    for (auto& x : s) x.spindle = SpindleState::off;
    cases.push_back({"spindle off throughout", s});
  }
  {
    // Every sample at the same time (a zero-length program).
    auto s = base(50);
    for (auto& x : s) x.time_s = 3.0;
    cases.push_back({"zero duration", s});
  }
  cases.push_back({"one sample", base(1)});
  cases.push_back({"empty", {}});
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    expect_same(stream(c.samples, spec), testing::reference_plan_spindle(c.samples, spec));
  }
}

TEST(StreamingPlan, OneMillionSamplesInBoundedMemory) {
  // 1 M samples, 1 ms apart, one block each: a target wandering between
  // 3000 and 9000 rpm with a 40 ms rapid every 2 s. mazak: H = 2.99225 s,
  // so at most 2 H / 1 ms + 1 held points (5985), plus the open block's
  // sample and a rapid stretch (40) waiting for its cut: 6026.
  const auto spec = mazak();
  std::vector<Sample> samples = uniform(1'000'000, 0.001, [](double t) {
    return 6000.0 + 2500.0 * std::sin(0.7 * t) + 500.0 * std::sin(11.0 * t);
  });
  for (std::size_t k = 0; k < samples.size(); ++k)
    if (k % 2000 >= 1960) samples[k].rapid = true, samples[k].target_rpm.reset();
  std::size_t peak = 0;
  double lag = 0.0;
  const auto streamed = stream(samples, spec, 1, &peak, &lag);
  const double bound = 2 * horizon(spec) / 0.001 + 1 + 1 + 40;
  EXPECT_LE(static_cast<double>(peak), bound);
  EXPECT_GT(static_cast<double>(peak), 0.5 * bound);  // the bound is not loose by orders
  // Blocks come out at most 3 H + 1 / rate (+ the rapid, 40 ms, and two
  // 1 ms blocks) behind the last sample: 2 H for the curve, the word
  // look-ahead, and H for the backward slew pass to settle a word (8.26 s
  // measured).
  EXPECT_LE(lag, 3 * horizon(spec) + 1.0 / spec.max_changes_per_s + 0.04 + 0.002);
  expect_same(streamed, testing::reference_plan_spindle(samples, spec));
}

TEST(StreamingPlan, RejectsABrokenSampleAndGoesOn) {
  const auto spec = mazak();
  const auto samples = uniform(300, 0.05, [](double t) { return 5000.0 + 1000.0 * std::sin(t); });
  StreamingPlanner planner(spec);
  SpindlePlan plan;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (i == 100) {
      Sample back = samples[i];
      back.time_s = 1.0;  // before sample 99's 4.95 s
      EXPECT_THROW(planner.push(back), PlanError);
      Sample bad = samples[i];
      bad.target_rpm = -1.0;
      EXPECT_THROW(planner.push(bad), PlanError);
      bad = samples[i];
      bad.block = 3;
      EXPECT_THROW(planner.push(bad), PlanError);
    }
    planner.push(samples[i]);
    planner.take_final(plan.blocks);
  }
  planner.finish();
  planner.take_final(plan.blocks);
  plan.s_words = planner.s_words();
  expect_same(plan, testing::reference_plan_spindle(samples, spec));
  EXPECT_THROW(planner.push(samples.back()), PlanError);  // after finish()
}

// A block's own tool teeth (a section whose tools-file entry gives them)
// replace the planner's (--teeth or the profile's): F = fz * z * n with
// that z; without them (0) the planner's. fz 0.05 mm, n 8000 rpm: 4 teeth
// 1600 mm/min, 2 teeth 800. With fz from the program's F and S, z cancels:
// F = F_prog * n / S_prog whatever the teeth.
TEST(StreamingFeedPlanner, TakesTheBlocksToolTeethWhereKnown) {
  const machines::FeedSpec feed{5.0, 6000.0, 30000.0};
  BlockPlan block;
  block.target_rpm = 8000.0;
  block.planned_rpm = 8000.0;
  block.bound = Bound::none;
  StreamingFeedPlanner given(0.05, 2, feed, 1.0);
  EXPECT_DOUBLE_EQ(given.next(block, {1000.0, 4000.0, 4}).f_mm_per_min, 1600.0);
  EXPECT_DOUBLE_EQ(given.next(block, {1000.0, 4000.0, 0}).f_mm_per_min, 800.0);
  StreamingFeedPlanner from_program(std::nullopt, 2, feed, 1.0);
  EXPECT_DOUBLE_EQ(from_program.next(block, {1000.0, 4000.0, 4}).f_mm_per_min, 2000.0);
  EXPECT_DOUBLE_EQ(from_program.next(block, {1000.0, 4000.0, 0}).f_mm_per_min, 2000.0);
}

TEST(StreamingFeedPlanner, EqualsPlanFeedsOnTheSamePlans) {
  // On streamed random plans: the same F as plan_feeds() over the whole
  // plan, and on coupled blocks F = fz * z * S rounded down to the step
  // (never more than fz per tooth) unless a feed limit binds.
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const machines::FeedSpec feed{5.0, 6000.0, 30000.0};
  std::size_t coupled = 0;
  for (int round = 0; round < 60; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    const SpindleSpec spec = testing::property_spec(round, rng);
    const auto samples = testing::random_timeline(spec, rng);
    const auto plan = stream(samples, spec);
    std::vector<BlockFeedInput> inputs;
    for (std::size_t k = 0; k < plan.blocks.size(); ++k)
      inputs.push_back({u(rng) < 0.1 ? 0.0 : 200.0 + 2000.0 * u(rng), 1000.0 + 9000.0 * u(rng)});
    const std::optional<double> fz =
        round % 2 ? std::optional<double>(0.01 + 0.1 * u(rng)) : std::nullopt;
    const int teeth = 1 + round % 4;
    const double step = round % 3 == 0 ? 1.0 : 0.1;
    const auto whole = plan_feeds(plan, inputs, fz, teeth, feed, step);
    StreamingFeedPlanner feeds(fz, teeth, feed, step);
    for (std::size_t k = 0; k < plan.blocks.size(); ++k) {
      const auto f = feeds.next(plan.blocks[k], inputs[k]);
      EXPECT_EQ(f.f_mm_per_min, whole[k].f_mm_per_min) << k;
      EXPECT_EQ(f.f_word, whole[k].f_word) << k;
      EXPECT_EQ(f.bound, whole[k].bound) << k;
      const auto& b = plan.blocks[k];
      const bool is_coupled = b.target_rpm && b.bound != Bound::off && b.bound != Bound::rapid &&
                              b.bound != Bound::program && inputs[k].program_f_mm_per_min > 0;
      if (is_coupled && f.bound == FeedBound::none) {
        const double z =
            fz ? *fz : inputs[k].program_f_mm_per_min / (teeth * inputs[k].program_s_rpm);
        const double exact = z * teeth * b.planned_rpm;
        EXPECT_LE(f.f_mm_per_min, std::max(exact, feed.f_min_mm_per_min) + 1e-9) << k;
        EXPECT_GT(f.f_mm_per_min, exact - step - 1e-9) << k;
        ++coupled;
      } else if (!is_coupled) {
        EXPECT_EQ(f.f_mm_per_min, inputs[k].program_f_mm_per_min) << k;
      }
    }
    if (::testing::Test::HasFailure()) break;
  }
  EXPECT_GT(coupled, 5000u);
  EXPECT_THROW(StreamingFeedPlanner(0.05, 2, feed, 0.0), PlanError);
}

}  // namespace
}  // namespace vcpost::plan
