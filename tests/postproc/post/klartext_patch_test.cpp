// Posting Klartext: a TOOL CALL's S changed in place, TOOL CALL S blocks
// inserted before the moves that start a new speed, every later block
// renumbered (END PGM included), plain F digits changed and every other byte
// kept (CRLF, a comment byte that is not UTF-8, a `~` continued cycle).
// Expected texts written out by hand.
#include "postproc/post/klartext_patch.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/postproc/klartext_fixture.h"

namespace vcpost::post {
namespace {

using testing::kKlartextInput;
using testing::kKlartextPosted;

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

TEST(KlartextPatch, InsertsToolCallSAndRenumbersKeepingEveryOtherByte) {
  EXPECT_EQ(patched(kKlartextInput, patches_of(kKlartextInput)), kKlartextPosted);
  // Written in two pieces, the numbering carries on.
  EXPECT_EQ(
      patched(kKlartextInput, patches_of(kKlartextInput), offset_of(kKlartextInput, "8 CYCL")),
      kKlartextPosted);
  // No patch: the program as it was, byte for byte.
  EXPECT_EQ(patched(kKlartextInput, {}), kKlartextInput);
}

TEST(KlartextPatch, TakesFOnlyInAPlainFWord) {
  KlartextPatcher patcher(kKlartextInput);
  EXPECT_TRUE(patcher.takes_f(offset_of(kKlartextInput, "6 L")));     // F200
  EXPECT_FALSE(patcher.takes_f(offset_of(kKlartextInput, "7 L")));    // FQ1
  EXPECT_FALSE(patcher.takes_f(offset_of(kKlartextInput, "5 L")));    // FMAX
  EXPECT_FALSE(patcher.takes_f(offset_of(kKlartextInput, "4 TOO")));  // no F
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
