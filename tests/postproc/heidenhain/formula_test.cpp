// Q parameter formulas as the TNC 640's FORMULA key writes them: each value
// worked out by hand in the comment beside it (degrees for the angle
// functions; ^ before * / % before + -, left to right). Tolerance 1e-9.
#include "postproc/heidenhain/formula.h"

#include <gtest/gtest.h>

#include <numbers>

#include "tests/postproc/heidenhain/klartext_support.h"

namespace vcpost::heidenhain {
namespace {

using testing::end_of;
using testing::error_of;
using testing::expect_point;
using testing::motions;
using testing::run;

TEST(KlartextFormula, ValuesAsTheControlComputesThem) {
  const auto events =
      run("BEGIN PGM T MM\n"
          "FN 0: Q2 = +4\n"
          "FN 0: Q4 = +30\n"
          "Q1 = Q2 * 3 + SIN Q4\n"                          // 12 + 0.5 = 12.5
          "Q5 = ( Q1 + 2 ) / 4 ; note\n"                    // 14.5 / 4 = 3.625
          "QL2 = SQ 10 - 3^3\n"                             // 100 - 27 = 73
          "QR3 = 5 * 3 + 2 * 10\n"                          // 35
          "Q6 = QL2\n"                                      // 73
          "Q7 = SQRT 16 + ABS -2 + INT 2.7 + FRAC -1.25\n"  // 4 + 2 + 2 - 0.25 = 7.75
          "Q8 = SGN -3 + NEG Q2 + PI\n"                     // -1 - 4 + pi
          "Q9 = ASIN 0.5 + ACOS 0.5 + ATAN 1\n"             // 30 + 60 + 45 = 135
          "Q10 = LN EXP 2 + LOG 1000\n"                     // 2 + 3 = 5
          "Q11 = COS 60 * TAN 45\n"                         // 0.5
          "Q12 = 400 % 360\n"                               // 40
          "Q13 = 2 ^ 3 ^ 2\n"                               // (2^3)^2 = 64
          "Q14 = -( Q2 - 6 )\n"                             // 2
          "Q15 = 10 - 4 - 3\n"                              // 3
          "Q16 = 12 / 3 / 2 + SGN 0\n"                      // 2 + 0
          "Q17 = -Q2 * -QR3\n"                              // 140
          "L X+Q1 Y+Q5 Z-QL2 FQR3\n"
          "L X+Q6 Y+Q7 Z+Q8\n"
          "L X+Q9 Y+Q10 Z+Q11\n"
          "L X+Q12 Y+Q13 Z+Q14\n"
          "L X+Q15 Y+Q16 Z+Q17\n"
          "END PGM T MM\n");
  const auto m = motions(events);
  ASSERT_EQ(m.size(), 5u);
  expect_point(end_of(m[0]), 12.5, 3.625, -73);
  expect_point(end_of(m[1]), 73, 7.75, -5 + std::numbers::pi);
  expect_point(end_of(m[2]), 135, 5, 0.5);
  expect_point(end_of(m[3]), 40, 64, 2);
  expect_point(end_of(m[4]), 3, 2, 140);
  bool fed = false;
  for (const auto& e : events)
    if (const auto* f = std::get_if<program::SetFeedRate>(&e)) fed = f->rate == 35.0;
  EXPECT_TRUE(fed);  // FQR3
}

TEST(KlartextFormula, RefusesWhatTheControlRefuses) {
  EXPECT_EQ(error_of("BEGIN PGM T MM\nFN 0: Q2 = +4\nQ1 = 1 / ( Q2 - 4 )\n"), Code::E3318);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nQ1 = SQRT -1\n"), Code::E3318);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nQ1 = LN 0\n"), Code::E3318);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nQ1 = ASIN 2\n"), Code::E3318);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nQ1 = 2 +\n"), Code::E3328);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nQ1 = FOO 2\n"), Code::E3328);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nQ1 = 2 )\n"), Code::E3328);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nQ1 = 2 3\n"), Code::E3328);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nQ1 = " + std::string(100, '(') + "1\n"), Code::E3328);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nQ2000 = 1\n"), Code::E3309);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nQ1 = QL500\n"), Code::E3309);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nQS1 = \"TEXT\"\n"), Code::E3319);
}

}  // namespace
}  // namespace vcpost::heidenhain
