// Which section a program's tool description belongs to.
#include "postproc/tools/program_tools.h"

#include <gtest/gtest.h>

namespace vcpost::tools {
namespace {

ToolEntry unnumbered(ToolShape shape, double d) {
  ToolEntry e;
  e.shape = shape;
  e.diameter = d;
  e.origin = ToolOrigin::cl_record;
  return e;
}

TEST(ProgramTools, NumberedCommentsBelongToTheirNumberAnywhere) {
  ProgramTools p;
  p.on_comment("T1 D=10. CR=0. - ZMIN=-5. - flat end mill", "a.nc:2", false);
  p.on_comment("T2 D=0.25 CR=0.125 - ZMIN=-5. - ball end mill", "a.nc:3", true);  // inches
  EXPECT_EQ(p.current(), nullptr);  // no tool change yet
  p.on_tool_change(2);
  p.on_motion();
  ASSERT_TRUE(p.current());
  EXPECT_EQ(p.current()->shape, ToolShape::ball);
  EXPECT_DOUBLE_EQ(p.current()->diameter, 6.35);  // 0.25 in
  EXPECT_DOUBLE_EQ(*p.current()->corner_radius, 3.175);
  EXPECT_EQ(p.current()->where, "a.nc:3");
  p.on_tool_change(1);
  EXPECT_EQ(p.current()->shape, ToolShape::flat);
  p.on_tool_change(3);
  EXPECT_EQ(p.current(), nullptr);
}

TEST(ProgramTools, UnnumberedBelongsToTheNextToolChangeOrTheSectionUnderWay) {
  ProgramTools p;
  // SolidWorks CAM: CUTTER, then LOAD/TOOL.
  p.on_entry(unnumbered(ToolShape::drill, 4));
  p.on_tool_change(14);
  p.on_motion();
  EXPECT_EQ(p.current()->shape, ToolShape::drill);
  EXPECT_EQ(p.current()->number, 14);
  // NX: LOAD/TOOL, then TLDATA before the first motion.
  p.on_tool_change(2);
  EXPECT_EQ(p.current(), nullptr);
  p.on_entry(unnumbered(ToolShape::ball, 30));
  p.on_motion();
  EXPECT_EQ(p.current()->shape, ToolShape::ball);
  EXPECT_EQ(p.current()->number, 2);
  // No tool change at all: the first section's own.
  ProgramTools q;
  q.on_entry(unnumbered(ToolShape::flat, 8));
  EXPECT_EQ(q.current(), nullptr);
  q.on_motion();
  ASSERT_TRUE(q.current());
  EXPECT_EQ(q.current()->shape, ToolShape::flat);
  EXPECT_FALSE(q.number());
}

TEST(ProgramTools, UnreadableCommentsLeaveNotes) {
  ProgramTools p;
  p.on_comment("T5 D=6. CR=3. - ZMIN=-1. - mystery cutter", "b.nc:7", false);
  p.on_comment("Pocket1", "b.nc:8", false);
  ASSERT_EQ(p.notes().size(), 1u);
  EXPECT_EQ(p.notes()[0].rfind("b.nc:7: Fusion 360/HSM tool comment not read", 0), 0u)
      << p.notes()[0];
  p.on_tool_change(5);
  EXPECT_EQ(p.current(), nullptr);  // unknown, not a ball
}

}  // namespace
}  // namespace vcpost::tools
