// Gouge and lift depths and the diagnosis of a path off the model, on
// distances whose statistics are known by hand.
#include "postproc/post/offset_diagnosis.h"

#include <gtest/gtest.h>

namespace vcpost::post {
namespace {

TEST(OffsetHistogram, DepthsOfGougesAndLifts) {
  OffsetHistogram h(0.01, 5);
  for (const double e : {-0.02, -0.04, -0.06, 0.0, 0.005, -0.005, 0.5, 1.5}) h.add(e);
  const DepthStatistics gouge = h.gouge();
  EXPECT_EQ(gouge.points, 3u);
  EXPECT_DOUBLE_EQ(gouge.min, 0.02);
  EXPECT_DOUBLE_EQ(gouge.max, 0.06);
  EXPECT_NEAR(gouge.median, 0.04, 0.001);  // 1 um bins
  const DepthStatistics lift = h.lift();
  EXPECT_EQ(lift.points, 2u);
  EXPECT_DOUBLE_EQ(lift.min, 0.5);
  EXPECT_DOUBLE_EQ(lift.max, 1.5);
  EXPECT_NEAR(lift.median, 0.5, 0.001);  // the lower of two
  EXPECT_FALSE(h.diagnosis());           // no offset holds half the points
}

TEST(OffsetHistogram, DepthsJustBeyondTheToleranceCountInTheMedian) {
  // Tolerance 0.01 mm: 0.0102 rounds to the 0.010 bin, which also holds
  // points within the tolerance. Lifts sorted: 600 at 0.0102, 400 at 0.05,
  // 600 at 0.2; the 800th of 1600 is 0.05 (the walk that skipped the 0.010
  // bin said 0.2). Gouges the same way round; 0.0098 is within the tolerance.
  OffsetHistogram h(0.01, 5);
  for (const double e : {0.0102, -0.0102}) {
    for (int i = 0; i < 600; ++i) h.add(e);
  }
  for (const double e : {0.05, -0.05}) {
    for (int i = 0; i < 400; ++i) h.add(e);
  }
  for (const double e : {0.2, -0.2}) {
    for (int i = 0; i < 600; ++i) h.add(e);
  }
  for (int i = 0; i < 5000; ++i) h.add(i % 2 ? 0.0098 : -0.0098);
  for (const DepthStatistics& d : {h.lift(), h.gouge()}) {
    EXPECT_EQ(d.points, 1600u);
    EXPECT_DOUBLE_EQ(d.min, 0.0102);
    EXPECT_NEAR(d.median, 0.05, 1e-9);
    EXPECT_DOUBLE_EQ(d.max, 0.2);
  }
  // More than half of them in the tolerance's bin: the median is there.
  OffsetHistogram most(0.01, 5);
  for (int i = 0; i < 3; ++i) most.add(0.0102 + 0.0001 * i);
  most.add(0.3);
  EXPECT_NEAR(most.lift().median, 0.0103, 0.0005);  // the 2nd of 4, within the bin
}

TEST(OffsetHistogram, StockLeftIsNamed) {
  OffsetHistogram h(0.01, 5);
  for (int i = 0; i < 900; ++i) h.add(0.3 + 0.01 * ((i % 5) - 2) / 2);  // 0.29 .. 0.31
  for (int i = 0; i < 100; ++i) h.add(0.0);
  const auto d = h.diagnosis();
  ASSERT_TRUE(d);
  EXPECT_NEAR(d->offset_mm, 0.3, 1e-3);
  EXPECT_NEAR(d->share, 0.9, 1e-9);
  EXPECT_NE(d->causes.find("stock to leave in the CAM (0.300 mm)"), std::string::npos) << d->causes;
}

TEST(OffsetHistogram, TheToolRadiusPointsAtTheClPoint) {
  OffsetHistogram above(0.01, 5), below(0.01, 5);
  for (int i = 0; i < 10; ++i) {
    above.add(5.0);
    below.add(-5.0);
  }
  ASSERT_TRUE(above.diagnosis());
  EXPECT_NE(above.diagnosis()->causes.find("--cl-point center"), std::string::npos);
  ASSERT_TRUE(below.diagnosis());
  EXPECT_NE(below.diagnosis()->causes.find("--cl-point tip"), std::string::npos);
}

TEST(OffsetHistogram, ChordErrorsAreNotAnOffset) {
  // A coarse path over a convex surface: gouges spread from 0 to 0.04 mm.
  OffsetHistogram h(0.01, 5);
  for (int i = 0; i <= 400; ++i) h.add(-0.0001 * i);
  EXPECT_FALSE(h.diagnosis());
  EXPECT_EQ(h.gouge().points, 300u);  // deeper than 0.01 mm: i = 101 .. 400
}

TEST(OffsetHistogram, APathThatNeverTouchesNamesASmallLift) {
  // Every point 0.03 to 0.04 mm above the model (a ball 0.07 mm smaller
  // than the program's): no chord error explains a path that never
  // touches, so an offset below 0.05 mm but beyond the tolerance is named.
  OffsetHistogram above(0.01, 5);
  for (int i = 0; i <= 100; ++i) above.add(0.03 + 0.0001 * i);
  const auto d = above.diagnosis();
  ASSERT_TRUE(d);
  EXPECT_NEAR(d->offset_mm, 0.035, 1e-3);
  EXPECT_NEAR(d->share, 1.0, 1e-9);
  EXPECT_EQ(above.lift().points, 101u);
  // The same with points that touch: the 0.05 mm floor holds.
  OffsetHistogram touching(0.01, 5);
  for (int i = 0; i <= 100; ++i) touching.add(0.03 + 0.0001 * i);
  for (int i = 0; i < 10; ++i) touching.add(0.0);
  EXPECT_FALSE(touching.diagnosis());
}

}  // namespace
}  // namespace vcpost::post
