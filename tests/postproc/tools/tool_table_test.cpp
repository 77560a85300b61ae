// The tool table and its command-line and file sources.
#include "postproc/tools/tool_table.h"

#include <gtest/gtest.h>

#include "postproc/tools/tools_file.h"

namespace vcpost::tools {
namespace {

TEST(ToolOption, PlainSpecMeansEveryTool) {
  const ToolEntry e = parse_tool_option("ball:10");
  EXPECT_FALSE(e.number);
  EXPECT_EQ(e.shape, ToolShape::ball);
  EXPECT_DOUBLE_EQ(e.diameter, 10);
  EXPECT_DOUBLE_EQ(*e.corner_radius, 5);
  EXPECT_EQ(e.origin, ToolOrigin::command_line);
}

TEST(ToolOption, NumberedSpecs) {
  const ToolEntry a = parse_tool_option("T8=ball:14");
  EXPECT_EQ(a.number, 8);
  EXPECT_DOUBLE_EQ(a.diameter, 14);
  const ToolEntry b = parse_tool_option("2=bull:12:2");
  EXPECT_EQ(b.number, 2);
  EXPECT_EQ(b.shape, ToolShape::bull_nose);
  EXPECT_DOUBLE_EQ(*b.corner_radius, 2);
  const ToolEntry c = parse_tool_option("T1=flat:10");
  EXPECT_EQ(c.shape, ToolShape::flat);
  EXPECT_DOUBLE_EQ(*c.corner_radius, 0);
  const ToolEntry d = parse_tool_option("T3=drill:4.2");
  EXPECT_EQ(d.shape, ToolShape::drill);
  EXPECT_DOUBLE_EQ(d.diameter, 4.2);
  EXPECT_FALSE(d.geometry());
  const ToolEntry o = parse_tool_option("T4=other");
  EXPECT_EQ(o.shape, ToolShape::other);
  EXPECT_FALSE(o.geometry());
  // A corner radius of D/2 is the ball (issue 21): posted as one.
  const auto full = parse_tool_option("T5=bull:10:5").geometry();
  ASSERT_TRUE(full);
  EXPECT_EQ(full->kind, geometry::ToolKind::ball);
  EXPECT_DOUBLE_EQ(full->corner_radius, 5);
}

TEST(ToolOption, BadSpecsNameTheOption) {
  for (const char* bad : {"sphere:10", "T=ball:10", "Tx=ball:10", "T-1=ball:10", "ball:0",
                          "ball:ten", "bull:10:6", "drill", "drill:-1", "T2=other:x"}) {
    try {
      parse_tool_option(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const ToolTableError& e) {
      EXPECT_NE(std::string(e.what()).find("--tool"), std::string::npos) << e.what();
    }
  }
}

TEST(ToolTable, ResolveFollowsTheSourceOrder) {
  ToolTable table;
  ToolEntry program = parse_tool_option("T2=flat:10");
  program.origin = ToolOrigin::comment;
  // Nothing given: the program decides; nothing at all: null.
  EXPECT_EQ(table.resolve(2, &program), &program);
  EXPECT_EQ(table.resolve(2, nullptr), nullptr);
  // A plain --tool beats the program...
  table.add(parse_tool_option("ball:10"));
  EXPECT_EQ(table.resolve(2, &program)->shape, ToolShape::ball);
  EXPECT_FALSE(table.resolve(2, &program)->number);
  EXPECT_EQ(table.resolve(std::nullopt, nullptr)->shape, ToolShape::ball);
  // ... a tools-file entry beats the plain --tool ...
  ToolEntry file = parse_tool_option("T2=bull:10:1");
  file.origin = ToolOrigin::tools_file;
  table.add(file);
  EXPECT_EQ(table.resolve(2, &program)->shape, ToolShape::bull_nose);
  EXPECT_EQ(table.resolve(3, &program)->shape, ToolShape::ball);  // not tool 2's
  // ... and the command line's own entry beats the file.
  table.add(parse_tool_option("T2=drill:3"));
  EXPECT_EQ(table.resolve(2, &program)->shape, ToolShape::drill);
  // A weaker source does not replace a stronger one.
  table.add(file);
  EXPECT_EQ(table.resolve(2, &program)->shape, ToolShape::drill);
  EXPECT_THROW(table.add(parse_tool_option("T2=ball:4")), ToolTableError);
}

TEST(ToolChoices, VcPerTool) {
  ToolChoices choices;
  add_vc_option("120", choices);
  add_vc_option("T2=150", choices);
  add_vc_option("3=90.5", choices);
  EXPECT_DOUBLE_EQ(*choices.vc_of(2), 150);
  EXPECT_DOUBLE_EQ(*choices.vc_of(3), 90.5);
  EXPECT_DOUBLE_EQ(*choices.vc_of(7), 120);
  EXPECT_DOUBLE_EQ(*choices.vc_of(std::nullopt), 120);
  EXPECT_THROW(add_vc_option("T2=100", choices), ToolTableError);
  EXPECT_THROW(add_vc_option("100", choices), ToolTableError);
  EXPECT_THROW(add_vc_option("T4=0", choices), ToolTableError);
  EXPECT_THROW(add_vc_option("T4=fast", choices), ToolTableError);
  ToolChoices only_one;
  add_vc_option("T2=150", only_one);
  EXPECT_FALSE(only_one.vc_of(3));
}

TEST(ToolChoices, PostToolsList) {
  EXPECT_EQ(parse_tool_list("T2,T8"), (std::vector<int>{2, 8}));
  EXPECT_EQ(parse_tool_list("5"), (std::vector<int>{5}));
  EXPECT_THROW(parse_tool_list("T2,,T8"), ToolTableError);
  EXPECT_THROW(parse_tool_list("ball"), ToolTableError);
}

TEST(ToolsFile, ReadsEveryKey) {
  ToolTable table;
  load_tools_file(R"(# the shop's tools
[[tool]]
number = 2
shape = "ball"
diameter = 10
teeth = 2
name = "D10 ball, carbide"

[[tool]]
number = 8
shape = "bull"
diameter = 12.0
corner_radius = 1.5

[[tool]]
number = 9
shape = "drill"
diameter = 6.8
)",
                  "shop.toml", table);
  ASSERT_EQ(table.numbered().size(), 3u);
  const ToolEntry* t2 = table.resolve(2, nullptr);
  ASSERT_TRUE(t2);
  EXPECT_EQ(t2->origin, ToolOrigin::tools_file);
  EXPECT_EQ(t2->where, "shop.toml:2");
  EXPECT_EQ(t2->teeth, 2);
  EXPECT_EQ(t2->name, "D10 ball, carbide");
  ASSERT_TRUE(t2->geometry());
  EXPECT_DOUBLE_EQ(t2->geometry()->corner_radius, 5);
  const ToolEntry* t8 = table.resolve(8, nullptr);
  EXPECT_EQ(t8->geometry()->kind, geometry::ToolKind::bull_nose);
  EXPECT_DOUBLE_EQ(t8->geometry()->corner_radius, 1.5);
  EXPECT_EQ(table.resolve(9, nullptr)->shape, ToolShape::drill);
}

TEST(ToolsFile, ErrorsNameFileLineAndColumn) {
  struct Case {
    const char* text;
    const char* expected;
  };
  const Case cases[] = {
      {"[[tool]]\nnumber = 1\nshape = \"ball\"\ndiameter = 6\nflutes = 2\n",
       "t.toml:5:1: error[E1604]: unknown key 'flutes'"},
      {"[[tool]]\nnumber = 1\nshape = \"cone\"\ndiameter = 6\n", "t.toml:3:9: error[E1605]"},
      {"[[tool]]\nnumber = 1\nshape = \"ball\"\n",
       "t.toml:1:1: error[E1604]: [[tool]] needs diameter"},
      {"[[tool]]\nnumber = 1\nshape = \"bull\"\ndiameter = 6\ncorner_radius = 3\n",
       "t.toml:5:17: error[E1605]"},
      {"[[tool]]\nnumber = 1\nshape = \"ball\"\ndiameter = 6\ncorner_radius = 2\n",
       "t.toml:5:17: error[E1605]: corner_radius of a ball mill must be diameter/2"},
      {"[[tool]]\nnumber = 1\nshape = \"ball\"\ndiameter = \"6\"\n", "t.toml:4:12: error[E1604]"},
      {"[[tool]]\nnumber = 1\nshape = \"ball\"\ndiameter = 6\n[[tool]]\nnumber = 1\n"
       "shape = \"flat\"\ndiameter = 6\n",
       "t.toml:5:1: error[E1605]: tool T1 is given twice"},
      {"tool = 3\n", "t.toml:1:1: error[E1604]"},
      {"[[tool]\n", "t.toml:1:"},
  };
  for (const Case& c : cases) {
    ToolTable table;
    try {
      load_tools_file(c.text, "t.toml", table);
      ADD_FAILURE() << c.text << " was accepted";
    } catch (const ToolTableError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(c.expected, 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace vcpost::tools
