// `vcpost verify` for Klartext: a program posted as the writer posts it
// holds (its changes counted), and forged changes are refused with their
// codes: an L coordinate changed, a TOOL CALL S before a block that does
// not move, a skipped block number, a block removed, a speed that is no
// number.
#include <gtest/gtest.h>

#include <string>

#include "postproc/verify/verify.h"
#include "tests/postproc/klartext_fixture.h"

namespace vcpost::verify {
namespace {

using testing::kKlartextInput;
using testing::kKlartextPosted;

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

bool has(const Result& r, Code code) {
  for (const auto& v : r.violations)
    if (v.code == code) return true;
  return false;
}

TEST(VerifyKlartext, APostedProgramHolds) {
  const Result r = verify_klartext(kKlartextInput, kKlartextPosted, Options{});
  ASSERT_TRUE(r.ok()) << format(r.violations.front(), "posted.h");
  EXPECT_EQ(r.s_changes, 3u);  // one TOOL CALL's S, two inserted
  EXPECT_EQ(r.f_changes, 1u);  // F200 -> F250
  EXPECT_EQ(r.inserted_blocks, 2u);
  ASSERT_EQ(r.changes.size(), 4u);
  EXPECT_EQ(describe(r.changes[0]), "S2500 -> S3000");
  EXPECT_EQ(r.changes[0].line, 4u);
  EXPECT_EQ(describe(r.changes[1]), "+ S3100");
  EXPECT_EQ(r.changes[1].line, 6u);
  EXPECT_EQ(describe(r.changes[2]), "F200 -> F250");
  EXPECT_EQ(r.motions, 4u);  // the L blocks (the cycle is defined, never called)
  EXPECT_TRUE(verify_klartext(kKlartextInput, kKlartextInput, Options{}).ok());
}

TEST(VerifyKlartext, ACoordinateChangedIsRefused) {
  const Result r =
      verify_klartext(kKlartextInput, replaced(kKlartextPosted, "8 L X+10", "8 L X+11"), Options{});
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(has(r, Code::E7136));
  EXPECT_TRUE(has(r, Code::E7141));
  EXPECT_EQ(r.violations.front().line, 8u);
}

TEST(VerifyKlartext, AToolCallSBeforeABlockThatDoesNotMoveIsRefused) {
  // Before the cycle's definition instead of before the move after it.
  std::string forged = replaced(kKlartextPosted, "10 TOOL CALL S3200\r\n", "");
  forged = replaced(forged, "9 CYCL DEF 200", "9 TOOL CALL S3200\r\n10 CYCL DEF 200");
  const Result r = verify_klartext(kKlartextInput, forged, Options{});
  EXPECT_TRUE(has(r, Code::E7138));
  EXPECT_EQ(r.violations.front().line, 9u);
}

TEST(VerifyKlartext, ASkippedNumberIsRefused) {
  const Result r = verify_klartext(kKlartextInput,
                                   replaced(kKlartextPosted, "11 L X+20", "12 L X+20"), Options{});
  EXPECT_TRUE(has(r, Code::E7137));
  EXPECT_EQ(r.violations.front().line, 19u);
  // Not renumbered after an insert: the move keeps the number of the new block.
  const Result same =
      verify_klartext(kKlartextInput, replaced(kKlartextPosted, "7 L Z-1", "6 L Z-1"), Options{});
  EXPECT_TRUE(has(same, Code::E7137));
}

TEST(VerifyKlartext, ARemovedBlockAndABadSpeedAreRefused) {
  EXPECT_TRUE(has(verify_klartext(kKlartextInput,
                                  replaced(kKlartextPosted, "3 FN 0: Q1=500\r\n", ""), Options{}),
                  Code::E7136));
  EXPECT_TRUE(has(verify_klartext(kKlartextInput,
                                  replaced(kKlartextPosted, "12 END PGM T MM\r\n", ""), Options{}),
                  Code::E7139));
  EXPECT_TRUE(
      has(verify_klartext(kKlartextInput, replaced(kKlartextPosted, "S3000", "S0"), Options{}),
          Code::E7140));
}

// An F of the posted block 11 (output line 19, "11 L X+20 F...") that is a
// plain positive number the reader refuses: over its 1e12 limit at the
// 13th digit (column 24). The blocks before it compare, the output does not
// read from there: named once, where the reader stops.
TEST(VerifyKlartext, AnOutputThatDoesNotReadIsNamedWhereItStops) {
  const Result r = verify_klartext(
      kKlartextInput, replaced(kKlartextPosted, "11 L X+20 F300", "11 L X+20 F3000000000000"),
      Options{});
  ASSERT_EQ(r.violation_count, 1u) << format(r.violations.front(), "posted.h");
  EXPECT_EQ(format(r.violations[0], "posted.h"),
            "posted.h:19:24: error[E7142]: the output does not read: number too large");
  // Refused by its meaning, not its syntax: F0 is no feed rate, so block 6
  // (line 6) feeds before any is given; its F digits are no plain positive
  // number either (E7140, at the digit, column 9).
  const Result no_feed = verify_klartext(
      kKlartextInput, replaced(kKlartextInput, "6 L Z-1 F200", "6 L Z-1 F0"), Options{});
  ASSERT_EQ(no_feed.violation_count, 2u);
  EXPECT_EQ(
      format(no_feed.violations[0], "out.h"),
      "out.h:6:3: error[E7142]: the output does not read: a feed move before any feed rate F");
  EXPECT_EQ(no_feed.violations[1].code, Code::E7140);
  EXPECT_EQ(no_feed.violations[1].line, 6u);
  EXPECT_EQ(no_feed.violations[1].column, 9u);
}

// An input that does not read is the reader's error, named with the
// input's file as the G-code and CL inputs are: its syntax (F over the
// reader's 1e12 limit at the 13th digit, column 22 of line 6) and its
// meaning (F0 is no feed rate: block 6 feeds before any, at its L, column 3).
TEST(VerifyKlartext, AnInputThatDoesNotReadIsNamedWithItsFile) {
  const auto refusal = [](const std::string& input) -> std::string {
    try {
      verify_klartext(input, kKlartextPosted, Options{}, "in.h");
    } catch (const vcpost::Error& e) {
      EXPECT_EQ(e.where().file, "in.h");
      EXPECT_EQ(e.where().line, 6u);
      return e.what();
    }
    return "read";
  };
  EXPECT_EQ(refusal(replaced(kKlartextInput, "6 L Z-1 F200", "6 L Z-1 F3000000000000")),
            "in.h:6:22: error[E3303]: number too large");
  EXPECT_EQ(refusal(replaced(kKlartextInput, "6 L Z-1 F200", "6 L Z-1 F0")),
            "in.h:6:3: error[E3325]: a feed move before any feed rate F");
}

}  // namespace
}  // namespace vcpost::verify
