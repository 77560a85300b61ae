// Motion events -> HEIDENHAIN Klartext: whole small programs written out by
// hand (block numbers, BLK FORM from the CL stock, TOOL CALL with and
// without a tool, L/CC/C/CP, M codes, END PGM) and the errors.
#include "postproc/output/klartext_writer.h"

#include <gtest/gtest.h>

#include <sstream>

#include "tests/postproc/cldata/cl_support.h"

namespace vcpost::output {
namespace {

using namespace vcpost::program;
using cldata::testing::read_events;

std::string write_program(const std::vector<Event>& events, const KlartextFormat& format = {}) {
  std::ostringstream out;
  KlartextWriter writer(out, format);
  for (const auto& e : events) writer.write(e);
  writer.finish();
  return out.str();
}

TEST(KlartextWriter, SmallClProgramWithItsStock) {
  const auto events = read_events(
      "PARTNO/BRACKET (A)\nLOADTL/3\nCOOLNT/FLOOD\nSPINDL/6556.4,RPM,CLW\n"
      "INSERT/Stock Size X40. Y30. Z20.\nRAPID\n"
      "GOTO/-4.360504,-10.464015,25.\nRAPID\nGOTO/-4.360504,-10.464015,2.5\n"
      "FEDRAT/183.202375,MMPM\nGOTO/-4.360504,-10.464015,-6.\nGOTO/5,-10.464015,-6.\n"
      "CIRCLE/5,-5,-6,0,0,1,5.464015\nGOTO/10.464015,-5,-6\nSPINDL/OFF\nFINI\n");
  // The stock's size only: the blank from X0 Y0 up, from Z0 down. The
  // coolant before the speed closes the TOOL CALL, so the speed follows
  // in a TOOL CALL S of its own; FMAX leaves the modal F alone.
  const std::string expected =
      "0 BEGIN PGM 1000 MM\n"
      "1 BLK FORM 0.1 Z X+0 Y+0 Z-20\n"
      "2 BLK FORM 0.2 X+40 Y+30 Z+0\n"
      "3 ; PARTNO BRACKET (A)\n"
      "4 TOOL CALL 3 Z\n"
      "5 M8\n"
      "6 TOOL CALL S6556\n"
      "7 M3\n"
      "8 ; INSERT Stock Size X40. Y30. Z20.\n"
      "9 L X-4.3605 Y-10.464 Z+25 R0 FMAX\n"
      "10 L Z+2.5 R0 FMAX\n"
      "11 L Z-6 F183\n"
      "12 L X+5\n"
      "13 CC X+5 Y-5\n"
      "14 C X+10.464 Y-5 DR+\n"
      "15 M5\n"
      "16 M30\n"
      "17 END PGM 1000 MM\n";
  EXPECT_EQ(write_program(events), expected);
}

TEST(KlartextWriter, HelixAndFullTurnsArePolarArcsAndSpeedGoesIntoTheToolCall) {
  const std::vector<Event> events = {
      ChangeTool{1, {}},
      SetSpindleSpeed{10000, {}},
      SpindleOn{SpindleDirection::clockwise, {}},
      StraightTraverse{{0, 0, 0}, {10, 0, 5}, {}},
      SetFeedRate{500, FeedMode::per_minute, {}, std::nullopt},
      StraightFeed{{10, 0, 5}, {10, 0, 0}, {}},
      // Two turns clockwise down by 2: 720 deg about the pole.
      ArcFeed{{10, 0, 0}, {10, 0, -2}, {0, 0, 0}, Plane::xy, -2, {}},
      // Clockwise from 0 deg to 90 deg: three quarters of a turn, level: C.
      ArcFeed{{10, 0, -2}, {0, 10, -2}, {0, 0, -2}, Plane::xy, -1, {}},
      // A quarter counterclockwise down by 1: a helix, CP.
      ArcFeed{{0, 10, -2}, {-10, 0, -3}, {0, 0, -2}, Plane::xy, 1, {}},
      SetSpindleSpeed{9000.6, {}},
      StraightFeed{{-10, 0, -3}, {-10, 0, 5}, {}},
  };
  const std::string expected =
      "0 BEGIN PGM 1000 MM\n"
      "1 TOOL CALL 1 Z S10000\n"
      "2 M3\n"
      "3 L X+10 Y+0 Z+5 R0 FMAX\n"
      "4 L Z+0 F500\n"
      "5 CC X+0 Y+0\n"
      "6 CP IPA-720 IZ-2 DR-\n"
      "7 CC X+0 Y+0\n"
      "8 C X+0 Y+10 DR-\n"
      "9 CC X+0 Y+0\n"
      "10 CP IPA+90 IZ-1 DR+\n"
      "11 TOOL CALL S9001\n"
      "12 L Z+5\n"
      "13 M30\n"
      "14 END PGM 1000 MM\n";
  EXPECT_EQ(write_program(events), expected);
}

TEST(KlartextWriter, StockSizeFromTheClMessage) {
  const auto size = stock_size("INSERT Stock Size X95. Y150. Z120.");
  ASSERT_TRUE(size);
  EXPECT_EQ(*size, Eigen::Vector3d(95, 150, 120));
  EXPECT_FALSE(stock_size("PPRINT Stock Size X95. Y150. Z120."));
  EXPECT_FALSE(stock_size("INSERT Stock Size X95. Y150."));
  EXPECT_FALSE(stock_size("INSERT Stock Size X95. Y-150. Z1"));
}

TEST(KlartextWriter, RefusesWhatATncDoesNotTake) {
  const auto code_of = [](const Event& event) {
    try {
      write_program({StraightFeed{{0, 0, 0}, {1, 0, 0}, {}}, event});
    } catch (const OutputError& e) {
      return std::string(e.id());
    }
    return std::string("none");
  };
  EXPECT_EQ(code_of(ArcFeed{{1, 0, 0}, {-1, 0, 0}, {0, 0, 0}, Plane::xz, 1, {3, 1, 0}}), "E3250");
  EXPECT_EQ(code_of(SetFeedRate{2, FeedMode::inverse_time, {}, std::nullopt}), "E3251");
  EXPECT_EQ(code_of(ArcFeed{{1, 0, 0}, {1, 0, -5}, {0, 0, 0}, Plane::xy, 16, {}}), "E3252");
  EXPECT_EQ(code_of(ArcFeed{{1, 0, 0}, {1, 0, -5}, {0, 0, 0}, Plane::xy, 15, {}}), "none");
}

}  // namespace
}  // namespace vcpost::output
