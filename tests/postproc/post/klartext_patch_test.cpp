// Posting Klartext: a TOOL CALL's S changed in place, TOOL CALL S blocks
// inserted before the moves that start a new speed, every later block
// renumbered (END PGM included), plain F digits changed and every other byte
// kept (CRLF, a comment byte that is not UTF-8, a `~` continued cycle).
// Expected texts written out by hand.
#include "postproc/post/klartext_patch.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace vcpost::post {
namespace {

const std::string kProgram =
    "1 BEGIN PGM T MM\r\n"
    "2 ; K\xf6rivek\r\n"
    "3 FN 0: Q1=500\r\n"
    "4 TOOL CALL 5 Z S2500 DL+0\r\n"
    "5 L X+0 Y+0 Z+5 R0 FMAX M3\r\n"
    "6 L Z-1 F200\r\n"
    "7 L X+10 FQ1\r\n"
    "8 CYCL DEF 200 DRILLING ~\r\n"
    "    Q200=2 ;SET-UP CLEARANCE ~\r\n"
    "    Q201=-5 ;DEPTH ~\r\n"
    "    Q206=150 ;FEED RATE FOR PLUNGING ~\r\n"
    "    Q202=5 ;PLUNGING DEPTH ~\r\n"
    "    Q210=0 ;DWELL TIME AT TOP ~\r\n"
    "    Q203=0 ;SURFACE COORDINATE ~\r\n"
    "    Q204=50 ;2ND SET-UP CLEARANCE ~\r\n"
    "    Q211=0 ;DWELL TIME AT BOTTOM\r\n"
    "9 L X+20 F300\r\n"
    "10 END PGM T MM\r\n";

std::uint64_t offset_of(const std::string& text, const std::string& block_start) {
  return text.find(block_start);
}

std::string patched(const std::string& text, const std::vector<gcode::WordPatch>& patches,
                    std::uint64_t split = 0) {
  KlartextPatcher patcher(text);
  std::string out;
  const auto sink = [&out](std::string_view piece) { out += piece; };
  std::vector<gcode::WordPatch> first, second;
  for (const auto& p : patches) (split && p.block_offset >= split ? second : first).push_back(p);
  if (split) {
    patcher.write(0, split, first, sink);
    patcher.write(split, text.size(), second, sink);
  } else {
    patcher.write(0, text.size(), first, sink);
  }
  return out;
}

std::vector<gcode::WordPatch> patches_of(const std::string& text) {
  return {{offset_of(text, "4 TOOL"), 'S', "3000"},
          {offset_of(text, "6 L"), 'S', "3100"},
          {offset_of(text, "6 L"), 'F', "250"},
          {offset_of(text, "7 L"), 'F', "400"},  // FQ1 stays
          {offset_of(text, "9 L"), 'S', "3200"}};
}

const std::string kExpected =
    "1 BEGIN PGM T MM\r\n"
    "2 ; K\xf6rivek\r\n"
    "3 FN 0: Q1=500\r\n"
    "4 TOOL CALL 5 Z S3000 DL+0\r\n"
    "5 L X+0 Y+0 Z+5 R0 FMAX M3\r\n"
    "6 TOOL CALL S3100\r\n"
    "7 L Z-1 F250\r\n"
    "8 L X+10 FQ1\r\n"
    "9 CYCL DEF 200 DRILLING ~\r\n"
    "    Q200=2 ;SET-UP CLEARANCE ~\r\n"
    "    Q201=-5 ;DEPTH ~\r\n"
    "    Q206=150 ;FEED RATE FOR PLUNGING ~\r\n"
    "    Q202=5 ;PLUNGING DEPTH ~\r\n"
    "    Q210=0 ;DWELL TIME AT TOP ~\r\n"
    "    Q203=0 ;SURFACE COORDINATE ~\r\n"
    "    Q204=50 ;2ND SET-UP CLEARANCE ~\r\n"
    "    Q211=0 ;DWELL TIME AT BOTTOM\r\n"
    "10 TOOL CALL S3200\r\n"
    "11 L X+20 F300\r\n"
    "12 END PGM T MM\r\n";

TEST(KlartextPatch, InsertsToolCallSAndRenumbersKeepingEveryOtherByte) {
  EXPECT_EQ(patched(kProgram, patches_of(kProgram)), kExpected);
  // Written in two pieces, the numbering carries on.
  EXPECT_EQ(patched(kProgram, patches_of(kProgram), offset_of(kProgram, "8 CYCL")), kExpected);
  // No patch: the program as it was, byte for byte.
  EXPECT_EQ(patched(kProgram, {}), kProgram);
}

TEST(KlartextPatch, TakesFOnlyInAPlainFWord) {
  KlartextPatcher patcher(kProgram);
  EXPECT_TRUE(patcher.takes_f(offset_of(kProgram, "6 L")));     // F200
  EXPECT_FALSE(patcher.takes_f(offset_of(kProgram, "7 L")));    // FQ1
  EXPECT_FALSE(patcher.takes_f(offset_of(kProgram, "5 L")));    // FMAX
  EXPECT_FALSE(patcher.takes_f(offset_of(kProgram, "4 TOO")));  // no F
}

TEST(KlartextPatch, NumbersGrowADigitAndUnnumberedProgramsStayUnnumbered) {
  const std::string numbered = "998 L X+1 F100\n999 L X+2\n1000 END PGM T MM\n";
  EXPECT_EQ(patched(numbered, {{offset_of(numbered, "999"), 'S', "4000"}}),
            "998 L X+1 F100\n999 TOOL CALL S4000\n1000 L X+2\n1001 END PGM T MM\n");
  const std::string bare = "BEGIN PGM T MM\nL X+1 F100\nEND PGM T MM";  // no final line end
  EXPECT_EQ(patched(bare, {{offset_of(bare, "L X"), 'S', "4000"}}),
            "BEGIN PGM T MM\nTOOL CALL S4000\nL X+1 F100\nEND PGM T MM");
}

}  // namespace
}  // namespace vcpost::post
