// APPR and DEP: the moves a TNC makes to approach and leave a contour,
// worked out by hand from the TNC user's manual's descriptions (its
// examples: PS (40, 10), APPR ... X+20 Y+20 or X+10 Y+20, Z-10). Points of
// the programmed contour (the tool radius is not applied). Tolerances:
// 1e-9 mm for exact values, 1e-4 mm for values rounded in the comments.
#include "postproc/heidenhain/approach.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/postproc/heidenhain/klartext_support.h"

namespace vcpost::heidenhain {
namespace {

using program::Event;
using testing::end_of;
using testing::error_of;
using testing::expect_point;
using testing::motions;
using testing::run;

const double r2 = std::sqrt(0.5);

template <class T>
const T& as(const Event& e) {
  return std::get<T>(e);
}

std::vector<double> feeds(const std::vector<Event>& events) {
  std::vector<double> out;
  for (const Event& e : events)
    if (const auto* f = std::get_if<program::SetFeedRate>(&e)) out.push_back(f->rate);
  return out;
}

// LT: PH = PA - LEN t, t the first element's direction (1,1)/sqrt2:
// (20,20) - 15 (0.70711, 0.70711) = (9.39340, 9.39340). PS -> PH at the
// feed before (F300, in the plane at Z 0), then PH -> PA at F100 down to
// Z-10 (the manual: Z is reached on the way to PA).
TEST(KlartextApproach, LineTangent) {
  const auto events =
      run("BEGIN PGM T MM\n"
          "L X+40 Y+10 Z+0 R0 F300 M3\n"
          "APPR LT X+20 Y+20 Z-10 LEN15 RR F100\n"
          "L X+35 Y+35\n"
          "END PGM T MM\n");
  const auto m = motions(events);
  ASSERT_EQ(m.size(), 4u);
  const auto& to_aux = as<program::StraightFeed>(m[1]);
  expect_point(to_aux.start, 40, 10, 0);
  expect_point(to_aux.end, 20 - 15 * r2, 20 - 15 * r2, 0);
  const auto& to_first = as<program::StraightFeed>(m[2]);
  expect_point(to_first.end, 20, 20, -10);
  expect_point(end_of(m[3]), 35, 35, -10);
  EXPECT_EQ(feeds(events), (std::vector<double>{300, 100}));
  bool right = false;
  for (const Event& e : events)
    if (const auto* c = std::get_if<program::CutterCompensation>(&e))
      right = c->side == program::CompensationSide::right;
  EXPECT_TRUE(right);
}

// LN: PH on the normal, on the compensation's side (RR: right of (1,1)/sqrt2,
// (1,-1)/sqrt2): (20,20) + 15 (0.70711, -0.70711) = (30.60660, 9.39340).
// After an FMAX block PS -> PH is at rapid.
TEST(KlartextApproach, LineNormalAfterARapid) {
  const auto events =
      run("BEGIN PGM T MM\n"
          "L X+40 Y+10 Z+0 R0 FMAX\n"
          "APPR LN X+20 Y+20 LEN+15 RR F100\n"
          "L X+35 Y+35\n"
          "END PGM T MM\n");
  const auto m = motions(events);
  ASSERT_EQ(m.size(), 4u);
  EXPECT_TRUE(std::holds_alternative<program::StraightTraverse>(m[1]));
  expect_point(end_of(m[1]), 20 + 15 * r2, 20 - 15 * r2, 0);
  EXPECT_TRUE(std::holds_alternative<program::StraightFeed>(m[2]));
  expect_point(end_of(m[2]), 20, 20, 0);
}

// CT (the manual's example): PA (10,20), first element to (20,35): t =
// (10,15)/18.02776 = (0.55470, 0.83205). RR with R+10: clockwise about the
// centre right of t: C = PA + 10 (0.83205, -0.55470) = (18.32050, 14.45300);
// CCA180: PH = 2C - PA = (26.64101, 8.90599).
TEST(KlartextApproach, CircleTangent) {
  const auto events =
      run("BEGIN PGM T MM\n"
          "L X+40 Y+10 Z+0 R0 FMAX M3\n"
          "APPR CT X+10 Y+20 Z-10 CCA180 R+10 RR F100\n"
          "L X+20 Y+35\n"
          "END PGM T MM\n");
  const auto m = motions(events);
  ASSERT_EQ(m.size(), 4u);
  expect_point(end_of(m[1]), 26.64101, 8.90599, 0, 1e-4);
  const auto& arc = as<program::ArcFeed>(m[2]);
  EXPECT_EQ(arc.rotation, -1);
  expect_point(arc.centre, 18.32050, 14.45300, 0, 1e-4);
  expect_point(arc.end, 10, 20, -10);  // a half helix down to Z-10
  // The arc ends tangent to the first element: its radius at PA is
  // perpendicular to t, and 10 long.
  const Eigen::Vector2d radial = Eigen::Vector2d(10, 20) - arc.centre.head<2>();
  EXPECT_NEAR(radial.norm(), 10, 1e-9);
  EXPECT_NEAR(radial.dot(Eigen::Vector2d(10, 15)), 0, 1e-9);
}

// LCT: the same circle (C (18.32050, 14.45300), R10, clockwise); the line
// from PS (40,10) touches it at T: PS - C = (21.67950, -4.45300), d =
// 22.13210, angle -11.60719 deg, alpha = acos(10/d) = 63.13869 deg;
// clockwise arriving: -11.60719 - 63.13869 = -74.74588 deg: T = C + 10
// (0.26310, -0.96477) = (20.95151, 4.80531). PS -> T at APPR's F100, then the arc to PA.
TEST(KlartextApproach, LineThenCircleTangent) {
  const auto events =
      run("BEGIN PGM T MM\n"
          "L X+40 Y+10 Z+0 R0 F300\n"
          "APPR LCT X+10 Y+20 Z-10 R10 RR F100\n"
          "L X+20 Y+35\n"
          "END PGM T MM\n");
  const auto m = motions(events);
  ASSERT_EQ(m.size(), 4u);
  const auto& line = as<program::StraightFeed>(m[1]);
  expect_point(line.end, 20.95151, 4.80531, 0, 1e-4);
  const auto& arc = as<program::ArcFeed>(m[2]);
  EXPECT_EQ(arc.rotation, -1);
  // Tangent at T: the line is perpendicular to the radius there.
  const Eigen::Vector2d radial = line.end.head<2>() - arc.centre.head<2>();
  EXPECT_NEAR(radial.norm(), 10, 1e-9);
  EXPECT_NEAR(radial.dot((line.end - line.start).head<2>()), 0, 1e-9);
  EXPECT_EQ(feeds(events), (std::vector<double>{300, 100}));  // F100 before the line
}

// DEP along the contour (1,0), RL (the tool left of it), PE (30,0):
// LT LEN12.5: PN (42.5, 0); LN LEN20: on the left normal (0,1): (30, 20);
// CT CCA90 R+8: counterclockwise about C = (30, 8): PN = (38, 8);
// LCT X+50 Y+20 R8: C (30, 8), PN - C = (20, 12), d = 23.32381, angle
// 30.96376 deg, alpha = acos(8/d) = 69.94042 deg; counterclockwise leaving:
// 30.96376 - 69.94042 = -38.97666 deg: T = (30 + 6.21922, 8 - 5.03203).
std::vector<Event> departed(const std::string& dep) {
  return run("BEGIN PGM T MM\nL X+0 Y+0 Z-5 RL F100\nL X+30\n" + dep + "\nEND PGM T MM\n");
}

TEST(KlartextDeparture, EveryForm) {
  auto m = motions(departed("DEP LT LEN12.5 F200"));
  ASSERT_EQ(m.size(), 3u);
  expect_point(end_of(m[2]), 42.5, 0, -5);
  m = motions(departed("DEP LN LEN+20 Z+50"));
  ASSERT_EQ(m.size(), 3u);
  expect_point(end_of(m[2]), 30, 20, 50);  // Z reached on the way to PN
  m = motions(departed("DEP CT CCA90 R+8"));
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(as<program::ArcFeed>(m[2]).rotation, 1);
  expect_point(as<program::ArcFeed>(m[2]).centre, 30, 8, -5);
  expect_point(end_of(m[2]), 38, 8, -5);
  const auto events = departed("DEP LCT X+50 Y+20 Z+10 R8");
  m = motions(events);
  ASSERT_EQ(m.size(), 4u);
  const auto& arc = as<program::ArcFeed>(m[2]);
  EXPECT_EQ(arc.rotation, 1);
  expect_point(arc.end, 36.21922, 2.96797, -5, 1e-4);
  const auto& line = as<program::StraightFeed>(m[3]);
  expect_point(line.end, 50, 20, 10);
  const Eigen::Vector2d radial = arc.end.head<2>() - Eigen::Vector2d(30, 8);
  EXPECT_NEAR(radial.dot((line.end - line.start).head<2>()), 0, 1e-9);
  // DEP ends the radius compensation.
  EXPECT_EQ(std::get<program::CutterCompensation>(events[events.size() - 2]).side,
            program::CompensationSide::off);
}

TEST(KlartextApproach, RefusedWhereTheControlRefuses) {
  // No contour element after APPR, CT without RL/RR, LCT from inside its circle,
  // DEP with nothing to leave.
  EXPECT_EQ(error_of("BEGIN PGM T MM\nL X+40 Y+10 F100\nAPPR LT X+20 Y+20 LEN15 RL\n"
                     "TOOL CALL 1 Z S1000\n"),
            Code::E3329);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nL X+40 Y+10 F100\nAPPR CT X+20 Y+20 CCA90 R5\nL X+30\n"),
            Code::E3329);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nL X+21 Y+22 F100\nAPPR LCT X+20 Y+20 R5 RL\nL X+30\n"),
            Code::E3329);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nDEP LT LEN5 F100\n"), Code::E3329);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nL X+1 F100\nAPPR LT X+20 Y+20 LEN15 RL\n"),
            Code::E3329);  // the program ends
  EXPECT_EQ(error_of("BEGIN PGM T MM\nL X+1 F100\nAPPR XY X+20\nL X+2\n"), Code::E3307);
}

}  // namespace
}  // namespace vcpost::heidenhain
