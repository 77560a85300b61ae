// The comment text both writers add: printable ASCII kept, the rest
// dropped; parentheses turned to brackets only inside G-code's ( ).
#include "postproc/output/comment_text.h"

#include <gtest/gtest.h>

namespace vcpost::output {
namespace {

TEST(CommentText, ParenthesesBecomeBracketsOnlyInsideParentheses) {
  EXPECT_EQ(clean_comment("T1 (D10) R0.5", CommentEnd::parenthesis), "T1 [D10] R0.5");
  EXPECT_EQ(clean_comment("T1 (D10) R0.5", CommentEnd::line_end), "T1 (D10) R0.5");
}

TEST(CommentText, ControlBytesAndNonAsciiAreDropped) {
  // Tab, CR, DEL and the two bytes of UTF-8 "°" go; ' ' and '~' (0x20,
  // 0x7E, the ends of the printable range) stay.
  const std::string text = std::string("a\tb\rc\x7f") + "d\xc2\xb0 ~";
  EXPECT_EQ(clean_comment(text, CommentEnd::parenthesis), "abcd ~");
  EXPECT_EQ(clean_comment(text, CommentEnd::line_end), "abcd ~");
  EXPECT_EQ(clean_comment("", CommentEnd::line_end), "");
}

}  // namespace
}  // namespace vcpost::output
