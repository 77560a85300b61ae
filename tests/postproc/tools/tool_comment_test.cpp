// G-code tool comments, each format with lines as CAM posts wrote them.
#include "postproc/tools/tool_comment.h"

#include <gtest/gtest.h>

namespace vcpost::tools {
namespace {

// Reads `comment` (the text inside the parentheses) and expects an entry.
ToolEntry read(std::string_view comment, CommentFormat format) {
  const auto found = read_tool_comment(comment);
  EXPECT_TRUE(found) << comment;
  if (!found) return {};
  EXPECT_EQ(found->format, format) << comment;
  EXPECT_TRUE(found->entry) << comment << ": " << found->note;
  return found->entry.value_or(ToolEntry{});
}

// Fusion 360 personal-use grbl post, line 2 of
// ../shared/data/corpus/gcode/F360_grbl_SheepTile-v2.nc (Sienci-Labs/gsender).
TEST(FusionComment, FlatEndMillOfTheCorpus) {
  const ToolEntry e = read("T1  D=6.35 CR=0 - ZMIN=-19.8 - flat end mill", CommentFormat::fusion);
  EXPECT_EQ(e.number, 1);
  EXPECT_EQ(e.shape, ToolShape::flat);
  EXPECT_DOUBLE_EQ(e.diameter, 6.35);
  EXPECT_DOUBLE_EQ(*e.corner_radius, 0);
  EXPECT_EQ(e.origin, ToolOrigin::comment);
}

// Inventor HSM's fanuc.cps output, Autodesk/cam-posteditor public/test.nc:
// upper-case type words.
TEST(FusionComment, UpperCaseTypesOfInventorHsm) {
  const ToolEntry face = read("T1 D=50.8 CR=0. - ZMIN=0. - FACE MILL", CommentFormat::fusion);
  EXPECT_EQ(face.shape, ToolShape::other);  // a face mill is not posted as a flat end mill
  EXPECT_DOUBLE_EQ(face.diameter, 50.8);
  const ToolEntry flat =
      read("T2 D=9.525 CR=0. - ZMIN=-10. - FLAT END MILL", CommentFormat::fusion);
  EXPECT_EQ(flat.number, 2);
  EXPECT_EQ(flat.shape, ToolShape::flat);
  EXPECT_DOUBLE_EQ(flat.diameter, 9.525);
}

// Fusion header lines found in the public code index: an inch NC Viewer demo
// (O32123) and a Hurco WinMax .hnc header (T7..T23), and the Makera Carvera
// post's lines with tool names before D=.
TEST(FusionComment, BallBullChamferAndNamedTools) {
  const ToolEntry ball =
      read("T3 D=0.125 CR=0.0625 - ZMIN=0.5 - ball end mill", CommentFormat::fusion);
  EXPECT_EQ(ball.number, 3);
  EXPECT_EQ(ball.shape, ToolShape::ball);
  EXPECT_DOUBLE_EQ(ball.diameter, 0.125);  // program units: the caller converts
  ASSERT_TRUE(ball.geometry());
  EXPECT_DOUBLE_EQ(ball.geometry()->corner_radius, 0.0625);

  const ToolEntry bull =
      read("T20 D=2. CR=0.181 - ZMIN=1.008 - bullnose end mill", CommentFormat::fusion);
  EXPECT_EQ(bull.number, 20);
  EXPECT_EQ(bull.shape, ToolShape::bull_nose);
  EXPECT_DOUBLE_EQ(*bull.corner_radius, 0.181);
  EXPECT_EQ(bull.geometry()->kind, geometry::ToolKind::bull_nose);

  const ToolEntry chamfer =
      read("T16 D=0.25 CR=0. TAPER=45deg - ZMIN=0.948 - chamfer mill", CommentFormat::fusion);
  EXPECT_EQ(chamfer.shape, ToolShape::other);

  const ToolEntry named =
      read("T2  6mm ball  D=6 CR=3 - ZMIN=-4 - ball end mill", CommentFormat::fusion);
  EXPECT_EQ(named.number, 2);
  EXPECT_EQ(named.shape, ToolShape::ball);
  EXPECT_DOUBLE_EQ(named.diameter, 6);
  EXPECT_EQ(named.name, "6mm ball");
  const ToolEntry makera = read(
      "T1  3.175 flat  Makera  M1  D=3.175 CR=0 - ZMIN=-6 - flat end mill", CommentFormat::fusion);
  EXPECT_DOUBLE_EQ(makera.diameter, 3.175);
  EXPECT_EQ(makera.name, "3.175 flat  Makera  M1");

  const ToolEntry drill = read("T4 D=0.2 TAPER=118deg - drill", CommentFormat::fusion);
  EXPECT_EQ(drill.shape, ToolShape::drill);
}

TEST(FusionComment, UnreadableLinesGiveNotesNotBalls) {
  for (const char* text : {"T5 D=6. CR=3. - ZMIN=-1. - mystery cutter",  // unknown type
                           "T5 D=6. CR=3.", "T5 D=x CR=3. - ball end mill",
                           "T5 D=6. CR=1. - ZMIN=0 - ball end mill"}) {  // a ball with CR != D/2
    const auto found = read_tool_comment(text);
    ASSERT_TRUE(found) << text;
    EXPECT_FALSE(found->entry) << text;
    EXPECT_FALSE(found->note.empty()) << text;
  }
  // Not tool descriptions at all.
  for (const char* text : {"Pocket1", "T1", "ZMIN=-6", "2D Adaptive1", "Tool change T1 D=6"}) {
    EXPECT_FALSE(read_tool_comment(text)) << text;
  }
}

// Mastercam's default post: the tool name, then number, offsets and
// diameter. The line from Mastercam's HELLOWORLD example program, as
// quoted in G-code tutorials of the public code index.
TEST(MastercamComment, HelloWorldLine) {
  const ToolEntry e = read(" 1/16 FLAT ENDMILL TOOL - 1 DIA. OFF. - 1 LEN. - 1 DIA. - .0625",
                           CommentFormat::mastercam);
  EXPECT_EQ(e.number, 1);
  EXPECT_EQ(e.shape, ToolShape::flat);
  EXPECT_DOUBLE_EQ(e.diameter, 0.0625);
  EXPECT_EQ(e.name, "1/16 FLAT ENDMILL");
}

TEST(MastercamComment, TypeWordsOfTheName) {
  EXPECT_EQ(
      read("1/4 BALL ENDMILL TOOL - 3 DIA. OFF. - 3 LEN. - 3 DIA. - .25", CommentFormat::mastercam)
          .shape,
      ToolShape::ball);
  EXPECT_EQ(
      read("1/2 BULL ENDMILL TOOL - 4 DIA. OFF. - 4 LEN. - 4 DIA. - .5", CommentFormat::mastercam)
          .shape,
      ToolShape::bull_nose);
  EXPECT_FALSE(read("1/2 BULL ENDMILL TOOL - 4 DIA. OFF. - 4 LEN. - 4 DIA. - .5",
                    CommentFormat::mastercam)
                   .geometry());  // no corner radius in the line
  EXPECT_EQ(
      read("1/4 SPOT DRILL TOOL - 5 DIA. OFF. - 5 LEN. - 5 DIA. - .25", CommentFormat::mastercam)
          .shape,
      ToolShape::drill);
  const auto unnamed = read_tool_comment("TOOL - 6 DIA. OFF. - 6 LEN. - 6 DIA. - .25");
  ASSERT_TRUE(unnamed);
  EXPECT_FALSE(unnamed->entry);  // no type word: unknown, not a ball
}

// Carbide Create's post (TOOL/MILL,d,r,length,taper half-angle), lines as
// the Carbide Create-compatible generators of the public code index write
// them for its tools 201 (1/4 flat), 202 (1/4 ball) and 102 (1/8 flat).
TEST(CarbideComment, MillLines) {
  const ToolEntry flat = read("TOOL/MILL,6.35, 0.00, 0.00, 0.00", CommentFormat::carbide);
  EXPECT_FALSE(flat.number);  // belongs to the next tool change (M6T201)
  EXPECT_EQ(flat.shape, ToolShape::flat);
  EXPECT_DOUBLE_EQ(flat.diameter, 6.35);
  const ToolEntry ball = read("TOOL/MILL,6.35, 3.17, 0.00, 0.00", CommentFormat::carbide);
  EXPECT_EQ(ball.shape, ToolShape::ball);  // 3.17 is 6.35/2 at two decimals
  EXPECT_DOUBLE_EQ(*ball.corner_radius, 3.175);
  const ToolEntry small = read("TOOL/MILL,3.17, 0.00, 0.00, 0.00", CommentFormat::carbide);
  EXPECT_DOUBLE_EQ(small.diameter, 3.17);
  const ToolEntry vbit = read("TOOL/MILL,0.03, 0.00, 10.00, 45.00", CommentFormat::carbide);
  EXPECT_EQ(vbit.shape, ToolShape::other);
  const ToolEntry bull = read("TOOL/MILL,6.35, 1.00, 0.00, 0.00", CommentFormat::carbide);
  EXPECT_EQ(bull.shape, ToolShape::bull_nose);
  EXPECT_DOUBLE_EQ(*bull.corner_radius, 1.0);
  const auto bad = read_tool_comment("TOOL/MILL,abc");
  ASSERT_TRUE(bad);
  EXPECT_FALSE(bad->entry);
}

TEST(TypeNames, Shapes) {
  EXPECT_EQ(shape_from_type_name("ball end mill"), ToolShape::ball);
  EXPECT_EQ(shape_from_type_name("BALL ENDMILL"), ToolShape::ball);
  EXPECT_EQ(shape_from_type_name("bull nose end mill"), ToolShape::bull_nose);
  EXPECT_EQ(shape_from_type_name("flat end mill"), ToolShape::flat);
  EXPECT_EQ(shape_from_type_name("center drill"), ToolShape::drill);
  EXPECT_EQ(shape_from_type_name("tap right hand"), ToolShape::other);
  EXPECT_EQ(shape_from_type_name("counter sink"), ToolShape::other);
  EXPECT_EQ(shape_from_type_name("tapered mill"), ToolShape::other);
  EXPECT_EQ(shape_from_type_name("boring bar"), ToolShape::other);
  EXPECT_EQ(shape_from_type_name("holder"), std::nullopt);
}

// hyperMILL 2025's lines before a TOOL CALL (Heidenhain output, the shared
// programs W5246NS01007A8.h, A1.h and B13.h): the text after '*'.
TEST(HypermillComment, BullNoseFlatAndBall) {
  const ToolEntry bull = read(" - T626960718 | JJ-T4R0.5-N-ES_H63ZM6L120X / DM=4.01 CR=0.5 TL=145",
                              CommentFormat::hypermill);
  EXPECT_FALSE(bull.number.has_value());  // hyperMILL's id, not the TOOL CALL's number
  EXPECT_EQ(bull.shape, ToolShape::bull_nose);
  EXPECT_DOUBLE_EQ(bull.diameter, 4.01);
  EXPECT_DOUBLE_EQ(*bull.corner_radius, 0.5);
  EXPECT_EQ(bull.name, "JJ-T4R0.5-N-ES_H63ZM6L120X");
  const ToolEntry flat =
      read(" - TOOL: T61804393 | FRA-P8400-S7.7R0_H63WM8L65X / DM=7.7 CR=0 TL=91",
           CommentFormat::hypermill);
  EXPECT_EQ(flat.shape, ToolShape::flat);
  EXPECT_DOUBLE_EQ(*flat.corner_radius, 0);
  const ToolEntry ball = read(" - T7 | BALL-6_H63 / DM=6 CR=3 TL=80", CommentFormat::hypermill);
  EXPECT_EQ(ball.shape, ToolShape::ball);
  EXPECT_DOUBLE_EQ(*ball.corner_radius, 3);
  // The tool list header names no TOOL CALL: not read.
  EXPECT_FALSE(
      read_tool_comment(" T626960718 | JJ-T4R0.5-N-ES_H63ZM6L120X / DM=4.01 CR=0.5 TL=145"));
  const auto bad = read_tool_comment(" - T7 | X / DM=6 CR=4 TL=80");
  ASSERT_TRUE(bad);
  EXPECT_FALSE(bad->entry);  // CR above DM/2: a note, never a guess
}

}  // namespace
}  // namespace vcpost::tools
