// PyCAM's settings block as a tool description, with the lines PyCAM 0.5.1
// wrote: ../shared/data/corpus/gcode/PyCAM_tiny_cat_outline.ngc (CAMotics'
// examples/cat/tiny_cat_outline.ngc), lines 14-41. The shape names
// SphericalCutter and ToroidalCutter are PyCAM's cutter classes (its
// pycam/Cutters and Toolpath/__init__.py ToolpathSettings.get_string, which
// writes "key = value" per line of each [section]).
#include "postproc/tools/pycam_settings.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "postproc/tools/program_tools.h"

namespace vcpost::tools {
namespace {

namespace fs = std::filesystem;

// The block of the corpus file, its ';' comments' text.
const std::vector<std::string> kCatBlock = {"PYCAM_TOOLPATH_SETTINGS: START",
                                            "[Bounds]",
                                            "maxz = 0.0",
                                            "maxx = 98.13376",
                                            "maxy = 117.703711",
                                            "minx = 9.25794",
                                            "miny = -6.918321",
                                            "minz = 0.0",
                                            "",
                                            "[Tool]",
                                            "torus_radius = 0.25",
                                            "speed = 1000.0",
                                            "shape = CylindricalCutter",
                                            "tool_radius = 0.79375",
                                            "feedrate = 200.0",
                                            "",
                                            "[Process]",
                                            "engrave_offset = 0.0",
                                            "step_down = 1.0",
                                            "generator = EngraveCutter",
                                            "postprocessor = SimpleCutter",
                                            "overlap_percent = 0",
                                            "milling_style = conventional",
                                            "material_allowance = 0.0",
                                            "pocketing_type = none",
                                            "path_direction = x",
                                            "",
                                            "PYCAM_TOOLPATH_SETTINGS: END"};

// Feeds `lines` to a ProgramTools as comments of lines 14.. of "p.ngc".
ProgramTools fed(const std::vector<std::string>& lines, bool inches = false) {
  ProgramTools p;
  int line = 14;
  for (const std::string& text : lines)
    p.on_comment(text, "p.ngc:" + std::to_string(line++), inches);
  return p;
}

std::vector<std::string> with_tool(const std::string& shape, const std::string& radius,
                                   const std::string& torus) {
  return {"PYCAM_TOOLPATH_SETTINGS: START",
          "[Tool]",
          "torus_radius = " + torus,
          "speed = 1000.0",
          "shape = " + shape,
          "tool_radius = " + radius,
          "PYCAM_TOOLPATH_SETTINGS: END"};
}

TEST(PycamSettings, CylindricalCutterOfTheCorpusIsAFlatMill) {
  ProgramTools p = fed(kCatBlock);
  EXPECT_TRUE(p.notes().empty());
  EXPECT_EQ(p.current(), nullptr);  // unnumbered: waits for the tool change
  p.on_tool_change(1);              // the file's "T1 M6", line 46
  p.on_motion();
  ASSERT_TRUE(p.current());
  EXPECT_EQ(p.current()->number, 1);
  EXPECT_EQ(p.current()->shape, ToolShape::flat);
  EXPECT_DOUBLE_EQ(p.current()->diameter, 1.5875);   // 2 x 0.79375 mm: a 1/16" end mill
  EXPECT_DOUBLE_EQ(*p.current()->corner_radius, 0);  // torus_radius is the toroidal's alone
  EXPECT_EQ(p.current()->origin, ToolOrigin::comment);
  EXPECT_EQ(p.current()->where, "p.ngc:26");  // its shape line
}

TEST(PycamSettings, SphericalAndToroidalCutters) {
  ProgramTools ball = fed(with_tool("SphericalCutter", "3.0", "0.25"));
  ball.on_tool_change(2);
  ASSERT_TRUE(ball.current());
  EXPECT_EQ(ball.current()->shape, ToolShape::ball);
  EXPECT_DOUBLE_EQ(ball.current()->diameter, 6);
  EXPECT_DOUBLE_EQ(*ball.current()->corner_radius, 3);

  ProgramTools bull = fed(with_tool("ToroidalCutter", "5.0", "1.0"));
  bull.on_tool_change(3);
  ASSERT_TRUE(bull.current());
  EXPECT_EQ(bull.current()->shape, ToolShape::bull_nose);
  EXPECT_DOUBLE_EQ(bull.current()->diameter, 10);  // tool_radius is the outer radius
  EXPECT_DOUBLE_EQ(*bull.current()->corner_radius, 1);

  // G20 in effect: inches.
  ProgramTools inch = fed(with_tool("SphericalCutter", "0.125", "0.25"), true);
  inch.on_tool_change(1);
  ASSERT_TRUE(inch.current());
  EXPECT_DOUBLE_EQ(inch.current()->diameter, 6.35);
}

TEST(PycamSettings, UnreadableBlocksLeaveNotesNotBalls) {
  const std::vector<std::vector<std::string>> bad = {
      with_tool("ConicalCutter", "3.0", "0.25"),       // no such PyCAM shape here
      with_tool("SphericalCutter", "-3", "0.25"),      // no radius
      with_tool("SphericalCutter", "three", "0.25"),   // no number
      with_tool("ToroidalCutter", "3.0", "3.0"),       // the corner is the whole radius
      with_tool("SphericalCutter", "1e300", "0.25")};  // beyond any tool
  for (const auto& block : bad) {
    ProgramTools p = fed(block);
    ASSERT_EQ(p.notes().size(), 1u) << block[4] << " " << block[5];
    EXPECT_NE(p.notes()[0].find("PyCAM tool comment not read"), std::string::npos) << p.notes()[0];
    p.on_tool_change(1);
    EXPECT_EQ(p.current(), nullptr);
  }
  // A block cut short by another comment: a note, and that comment is read
  // as what it is.
  ProgramTools cut = fed({"PYCAM_TOOLPATH_SETTINGS: START", "[Tool]", "shape = SphericalCutter",
                          "tool_radius = 3.0", "T2 D=10. CR=0. - ZMIN=-5. - flat end mill"});
  ASSERT_EQ(cut.notes().size(), 1u);
  EXPECT_NE(cut.notes()[0].find("without its END line"), std::string::npos) << cut.notes()[0];
  cut.on_tool_change(2);
  ASSERT_TRUE(cut.current());
  EXPECT_EQ(cut.current()->shape, ToolShape::flat);
  // A block without [Tool] says nothing of the tool.
  ProgramTools none = fed(
      {"PYCAM_TOOLPATH_SETTINGS: START", "[Bounds]", "minz = 0.0", "PYCAM_TOOLPATH_SETTINGS: END"});
  EXPECT_TRUE(none.notes().empty());
}

// The corpus file itself, its ';' lines in order: the same block.
TEST(PycamSettings, TheCorpusFileHoldsTheseLines) {
  const fs::path file =
      fs::path(VCPOST_SHARED_DATA_DIR) / "corpus" / "gcode" / "PyCAM_tiny_cat_outline.ngc";
  if (!fs::exists(file)) GTEST_SKIP() << "shared data absent: " << file;
  std::ifstream in(file);
  std::string line;
  std::vector<std::string> block;
  for (int n = 1; std::getline(in, line) && n <= 41; ++n) {
    if (n >= 14) block.push_back(line.substr(1));  // without its ';'
  }
  EXPECT_EQ(block, kCatBlock);
}

}  // namespace
}  // namespace vcpost::tools
