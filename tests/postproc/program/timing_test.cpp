// Time along the path against durations computed by hand: lines, rapids,
// arcs and helices in G94, G93 and G95, dwells, block processing time, and
// a whole G-code program through the interpreter.
#include "postproc/program/timing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "postproc/gcode/interpreter.h"

namespace vcpost::program {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTol = 1e-9;  // seconds; all figures below are exact to rounding

TEST(PathClock, LineAtFeedPerMinute) {
  PathClock clock;
  clock.advance(SetFeedRate{600.0, FeedMode::per_minute, {}});
  // (0,0,0) -> (30,40,0): 50 mm at 600 mm/min = 1/12 min = 5 s.
  const EventTime t = clock.advance(StraightFeed{{0, 0, 0}, {30, 40, 0}, {}});
  EXPECT_NEAR(t.start, 0.0, kTol);
  EXPECT_NEAR(t.duration, 5.0, kTol);
  // Then 12 mm along Z: 1.2 s, starting at 5 s.
  const EventTime u = clock.advance(StraightFeed{{30, 40, 0}, {30, 40, -12}, {}});
  EXPECT_NEAR(u.start, 5.0, kTol);
  EXPECT_NEAR(u.duration, 1.2, kTol);
  EXPECT_NEAR(clock.elapsed(), 6.2, kTol);
}

TEST(PathClock, RapidsAtTheSettingsRate) {
  // Default 10,000 mm/min: 100 mm take 0.6 s.
  PathClock clock;
  EXPECT_NEAR(clock.advance(StraightTraverse{{0, 0, 0}, {0, 0, 100}, {}}).duration, 0.6, kTol);
  // A profile's 5,000 mm/min: 3-4-12 diagonal = 13 mm -> 0.156 s.
  PathClock slow(TimingSettings{5000.0, 0.0});
  EXPECT_NEAR(slow.advance(StraightTraverse{{0, 0, 0}, {3, 4, 12}, {}}).duration, 0.156, kTol);
  // Rapids need no feed rate.
  EXPECT_NEAR(slow.elapsed(), 0.156, kTol);
}

TEST(PathClock, ArcsAndHelices) {
  PathClock clock;
  clock.advance(SetFeedRate{300.0, FeedMode::per_minute, {}});
  // G3 quarter circle of radius 10: 5 pi mm at 300 mm/min = pi s.
  EXPECT_NEAR(clock.advance(ArcFeed{{10, 0, 0}, {0, 10, 0}, {0, 0, 0}, Plane::xy, 1, {}}).duration,
              kPi, kTol);
  // G2 with the same end points: three quarters, 15 pi mm = 3 pi s.
  EXPECT_NEAR(clock.advance(ArcFeed{{10, 0, 0}, {0, 10, 0}, {0, 0, 0}, Plane::xy, -1, {}}).duration,
              3 * kPi, kTol);
  // Full helical turn of radius 5 in XY falling 3 mm: hypot(10 pi, 3) mm.
  clock.advance(SetFeedRate{600.0, FeedMode::per_minute, {}});
  const double one_turn = std::sqrt(100 * kPi * kPi + 9) / 600 * 60;
  EXPECT_NEAR(clock.advance(ArcFeed{{5, 0, 0}, {5, 0, -3}, {0, 0, 0}, Plane::xy, 1, {}}).duration,
              one_turn, kTol);
  // The same with P2 (two turns): hypot(20 pi, 3) mm.
  const double two_turns = std::sqrt(400 * kPi * kPi + 9) / 600 * 60;
  EXPECT_NEAR(clock.advance(ArcFeed{{5, 0, 0}, {5, 0, -3}, {0, 0, 0}, Plane::xy, 2, {}}).duration,
              two_turns, kTol);
  // G18 half circle of radius 5 rising 4 along Y: hypot(5 pi, 4) mm.
  const double half = std::sqrt(25 * kPi * kPi + 16) / 600 * 60;
  EXPECT_NEAR(clock.advance(ArcFeed{{0, 0, 0}, {10, 4, 0}, {5, 0, 0}, Plane::xz, -1, {}}).duration,
              half, kTol);
}

TEST(PathClock, InverseTimeIgnoresTheLength) {
  PathClock clock;
  // G93 F2: every move takes 1/2 min, whatever its length.
  clock.advance(SetFeedRate{2.0, FeedMode::inverse_time, {}, 20.0});
  EXPECT_NEAR(clock.advance(StraightFeed{{0, 0, 0}, {10, 0, 0}, {}}).duration, 30.0, kTol);
  clock.advance(SetFeedRate{3.0, FeedMode::inverse_time, {}, 141.0});
  EXPECT_NEAR(
      clock.advance(ArcFeed{{20, 10, 0}, {30, 0, 0}, {30, 10, 0}, Plane::xy, -1, {}}).duration,
      20.0, kTol);
  // Rapids in G93 still run at the rapid rate: 50 mm -> 0.3 s.
  EXPECT_NEAR(clock.advance(StraightTraverse{{0, 0, 0}, {0, 0, 50}, {}}).duration, 0.3, kTol);
}

TEST(PathClock, FeedPerRevolutionUsesTheCurrentSpeed) {
  PathClock clock;
  clock.advance(SetSpindleSpeed{1000.0, {}});
  clock.advance(SpindleOn{SpindleDirection::clockwise, {}});
  clock.advance(SetFeedRate{0.1, FeedMode::per_revolution, {}});
  // 0.1 mm/rev * 1000 rpm = 100 mm/min: 10 mm take 6 s.
  EXPECT_NEAR(clock.advance(StraightFeed{{0, 0, 0}, {10, 0, 0}, {}}).duration, 6.0, kTol);
  // S2500 changes the speed, not the feed per revolution: 250 mm/min, 10 mm -> 2.4 s.
  clock.advance(SetSpindleSpeed{2500.0, {}});
  EXPECT_NEAR(clock.advance(StraightFeed{{10, 0, 0}, {20, 0, 0}, {}}).duration, 2.4, kTol);
  // Spindle stopped: the move never ends on a machine; refused with its source.
  clock.advance(SpindleOff{{}});
  try {
    clock.advance(StraightFeed{{20, 0, 0}, {30, 0, 0}, {9, 1, 120}});
    FAIL() << "no TimingError";
  } catch (const TimingError& e) {
    EXPECT_EQ(e.where().line, 9u);
    EXPECT_EQ(e.where().column, 1u);
    EXPECT_NE(std::string(e.what()).find("spindle stopped"), std::string::npos);
  }
}

TEST(PathClock, DwellAndZeroLengthAndUndefinedFeed) {
  PathClock clock;
  EXPECT_NEAR(clock.advance(Dwell{2.5, {}}).duration, 2.5, kTol);
  // Zero length takes no time, even without a feed rate.
  EXPECT_NEAR(clock.advance(StraightFeed{{1, 1, 1}, {1, 1, 1}, {}}).duration, 0.0, kTol);
  EXPECT_THROW(clock.advance(StraightFeed{{0, 0, 0}, {1, 0, 0}, {}}), TimingError);
  // Non-motion events take no time.
  EXPECT_NEAR(clock.advance(SetSpindleSpeed{1000.0, {}}).duration, 0.0, kTol);
  EXPECT_NEAR(clock.elapsed(), 2.5, kTol);
}

TEST(PathClock, BlockLastsTheLongerOfItsMoveAndTheBlockTime) {
  // MODELS.md 4: a block lasts max(L / F, block time), not L / F + block time.
  // Three 50 mm moves at 600 mm/min (5 s each) with 10 ms per block: 15 s,
  // not 15.03 s (the control reads ahead while it moves).
  PathClock look_ahead(TimingSettings{10'000.0, 0.01});
  look_ahead.advance(SetFeedRate{600.0, FeedMode::per_minute, {}});
  for (int i = 0; i < 3; ++i) look_ahead.advance(StraightFeed{{0, 0, 0}, {50, 0, 0}, {}});
  EXPECT_NEAR(look_ahead.elapsed(), 15.0, kTol);
  // 0.01 mm at 600 mm/min is 1 ms of feed, but the control needs 4 ms a
  // block: 4 ms. A 1 mm move (0.1 s) is not slowed. 0.04 mm is exactly 4 ms.
  PathClock clock(TimingSettings{10'000.0, 0.004});
  clock.advance(SetFeedRate{600.0, FeedMode::per_minute, {}});
  EXPECT_NEAR(clock.advance(StraightFeed{{0, 0, 0}, {0.01, 0, 0}, {}}).duration, 0.004, kTol);
  EXPECT_NEAR(clock.advance(StraightFeed{{0, 0, 0}, {1, 0, 0}, {}}).duration, 0.1, kTol);
  EXPECT_NEAR(clock.advance(StraightFeed{{0, 0, 0}, {0.04, 0, 0}, {}}).duration, 0.004, kTol);
  // Rapids too: 0.5 mm at 10,000 mm/min = 3 ms -> 4 ms; 1 mm = 6 ms stays.
  EXPECT_NEAR(clock.advance(StraightTraverse{{0, 0, 0}, {0.5, 0, 0}, {}}).duration, 0.004, kTol);
  EXPECT_NEAR(clock.advance(StraightTraverse{{0, 0, 0}, {1, 0, 0}, {}}).duration, 0.006, kTol);
  // The block time applies to motions only, not to dwells or settings.
  EXPECT_NEAR(clock.advance(Dwell{0.001, {}}).duration, 0.001, kTol);
  EXPECT_NEAR(clock.advance(SetSpindleSpeed{1000.0, {}}).duration, 0.0, kTol);
  // 200 moves of 0.5 mm at F1500 (20 ms each) with 1 ms per block: 4.0 s
  // (the stream of the LinuxCNC measurement, ../shared/tools/linuxcnc-sim).
  PathClock stream(TimingSettings{10'000.0, 0.001});
  stream.advance(SetFeedRate{1500.0, FeedMode::per_minute, {}});
  for (int i = 0; i < 200; ++i) stream.advance(StraightFeed{{0, 0, 0}, {0.5, 0, 0}, {}});
  EXPECT_NEAR(stream.elapsed(), 4.0, kTol);
}

TEST(PathClock, RefusesBadSettings) {
  EXPECT_THROW(PathClock(TimingSettings{0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(PathClock(TimingSettings{-5.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(PathClock(TimingSettings{1000.0, -1.0}), std::invalid_argument);
  EXPECT_THROW(PathClock(TimingSettings{std::nan(""), 0.0}), std::invalid_argument);
}

// A G-code program through the interpreter and the clock; every duration by hand.
TEST(PathClock, WholeProgramFromTheInterpreter) {
  const std::string text =
      "G21 G90 G17 G94\n"
      "S1000 M3\n"
      "G0 X0 Y0 Z10\n"        // 10 mm rapid at 10,000 mm/min: 0.06 s
      "G1 Z0 F600\n"          // 10 mm at 600: 1 s
      "G1 X30 Y40\n"          // 50 mm: 5 s
      "G3 X20 Y50 I-10 J0\n"  // quarter circle r 10 about (20,40): 5 pi mm = pi/2 s
      "G4 P1.5\n"             // 1.5 s
      "G93 G1 X20 Y0 F4\n"    // 1/4 min: 15 s
      "G95 G1 X0 F0.2\n"      // 0.2 mm/rev * 1000 rpm = 200 mm/min, 20 mm: 6 s
      "G20 G94 G1 X1 F10\n"   // 25.4 mm at 254 mm/min: 6 s
      "M2\n";
  gcode::Interpreter interpreter(text, gcode::rs274ngc_dialect());
  PathClock clock;
  std::vector<Event> events;
  std::vector<double> moves;
  while (interpreter.next(events)) {
    for (const auto& e : events) {
      const EventTime t = clock.advance(e);
      if (is_motion(e) || std::holds_alternative<Dwell>(e)) moves.push_back(t.duration);
    }
    events.clear();
  }
  const std::vector<double> expected{0.06, 1.0, 5.0, kPi / 2, 1.5, 15.0, 6.0, 6.0};
  ASSERT_EQ(moves.size(), expected.size());
  for (std::size_t i = 0; i < moves.size(); ++i) EXPECT_NEAR(moves[i], expected[i], 1e-9) << i;
  EXPECT_NEAR(clock.elapsed(), 34.56 + kPi / 2, 1e-9);
}

}  // namespace
}  // namespace vcpost::program
