// The shared string helpers of core/text.h, on hand-written cases.
#include "core/text.h"

#include <gtest/gtest.h>

namespace vcpost {
namespace {

TEST(Text, TrimDropsOnlyTheGivenCharactersAtBothEnds) {
  EXPECT_EQ(trim(" \t a b \r\n"), "a b");
  EXPECT_EQ(trim(" \t a b \r\n", kBlanks), "a b \r\n");
  EXPECT_EQ(trim("  x  ", " "), "x");
  EXPECT_EQ(trim("\tx\t", " "), "\tx\t");
  EXPECT_EQ(trim(""), "");
  EXPECT_EQ(trim(" \t\v\f"), "");
}

TEST(Text, CaseChangesAsciiLettersOnly) {
  EXPECT_EQ(to_lower("STEP.Stp_9\xC3\x89"), "step.stp_9\xC3\x89");
  EXPECT_EQ(to_upper("cutter/ball\xC3\xA9"), "CUTTER/BALL\xC3\xA9");
}

TEST(Text, FiniteNumberTakesTheWholeTextOrNothing) {
  EXPECT_EQ(finite_number("0.25"), 0.25);
  EXPECT_EQ(finite_number("-19.8"), -19.8);
  EXPECT_EQ(finite_number("1e-05"), 1e-05);
  EXPECT_EQ(finite_number(".5"), 0.5);
  EXPECT_FALSE(finite_number(""));
  EXPECT_FALSE(finite_number(" 1"));
  EXPECT_FALSE(finite_number("+1"));
  EXPECT_FALSE(finite_number("1x"));
  EXPECT_FALSE(finite_number("inf"));
  EXPECT_FALSE(finite_number("nan"));
  EXPECT_FALSE(finite_number("1e999"));
}

}  // namespace
}  // namespace vcpost
