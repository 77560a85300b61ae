// Whole programs with several tools: a section per tool change, posted when
// its tool is a ball-end mill over the model, kept byte for byte otherwise.
// The dome raster of dome_program_support.h is cut twice, first by a flat
// end mill T1, then by a ball-end mill T2, the tools named only in Fusion
// 360's header comments (or on the command line).
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

#include "../dome_program_support.h"
#include "../rs274_support.h"
#include "../temp_folder.h"
#include "machines/builtin.h"
#include "postproc/post/post_job.h"

namespace vcpost::post {
namespace {

// The raster's moves without its header and footer.
std::string raster_body(int spindle) {
  const std::string raster = testing::dome_raster(2.0, 0.5, spindle);
  const std::size_t begin = raster.find("F2000\n") + 6;
  const std::size_t end = raster.find("G0 Z60\n");
  return raster.substr(begin, end - begin);
}

// T1 (flat) then T2 (ball) over the same dome; `header` holds the tool comments.
std::string two_tool_program(const std::string& header) {
  return "%\n" + header + "G21 G90 G17 G94\nT1 M6\nS5000 M3\nF2000\n" + raster_body(5000) +
         "G0 Z60\nM5\nT2 M6\nS8000 M3\nF2000\n" + raster_body(8000) + "G0 Z60\nM5\nM30\n%\n";
}

const char* fusion_header =
    "(T1 D=10. CR=0. - ZMIN=-5. - flat end mill)\n(T2 D=10. CR=5. - ZMIN=-5. - ball end mill)\n";

struct Posted {
  std::string text;
  PostSummary summary;
};

Posted post(const std::string& program, const tools::ToolChoices& choices) {
  PostSettings settings;
  settings.point.ap = 0.3;
  settings.tools = choices;
  Posted out;
  const auto model = testing::dome();
  out.summary = post_program(program, "two.ngc", model, machines::builtin_profile("generic"),
                             settings, [&](std::string_view bytes) { out.text.append(bytes); });
  return out;
}

tools::ToolChoices vc_only(double vc) {
  tools::ToolChoices choices;
  choices.vc = vc;
  return choices;
}

// The flat section is the input's bytes up to T2's tool change; the ball
// section is rewritten; the motion is the same.
void expect_flat_kept_ball_posted(const std::string& input, const Posted& out) {
  const std::size_t t2 = input.find("T2 M6");
  ASSERT_NE(t2, std::string::npos);
  EXPECT_EQ(out.text.substr(0, t2), input.substr(0, t2));
  EXPECT_NE(out.text.substr(t2), input.substr(t2));
  ASSERT_EQ(out.summary.sections.size(), 2u);
  const ToolSection& flat = out.summary.sections[0];
  const ToolSection& ball = out.summary.sections[1];
  EXPECT_EQ(flat.tool, 1);
  ASSERT_TRUE(flat.entry);
  EXPECT_EQ(flat.entry->shape, tools::ToolShape::flat);
  EXPECT_FALSE(flat.posted);
  EXPECT_EQ(flat.s_words, 0u);
  EXPECT_GT(flat.points, 1000u);  // the raster: 21 passes of 81 points, kept unevaluated
  EXPECT_EQ(ball.tool, 2);
  ASSERT_TRUE(ball.entry);
  EXPECT_EQ(ball.entry->shape, tools::ToolShape::ball);
  EXPECT_TRUE(ball.posted);
  EXPECT_GT(ball.s_words, 0u);
  EXPECT_EQ(ball.s_words, out.summary.s_words);
  EXPECT_EQ(ball.points, out.summary.samples);  // only the ball's points are evaluated
  // The ball section alone, as a program of its own, gives the same figures.
  tools::ToolChoices every_ball = vc_only(120);
  every_ball.table.add(tools::parse_tool_option("ball:10"));
  const Posted alone = post(testing::dome_raster(2.0, 0.5, 8000), every_ball);
  ASSERT_EQ(alone.summary.sections.size(), 1u);
  EXPECT_EQ(ball.touching, alone.summary.touching);
  EXPECT_EQ(ball.gouging, alone.summary.gouging);
  EXPECT_EQ(ball.lifted + ball.missed, alone.summary.lifted + alone.summary.missed);
  EXPECT_EQ(ball.s_words, alone.summary.s_words);
  ASSERT_TRUE(ball.before && ball.after);
  EXPECT_GT(ball.after->within_10_percent, ball.before->within_10_percent);
  EXPECT_LE(ball.after->max, 120 * (1 + 1e-9));
  EXPECT_LT(ball.start_s, ball.end_s);
  EXPECT_LE(flat.end_s, ball.start_s);

  if (std::system("command -v rs274 >/dev/null 2>&1") != 0) return;
  const testing::Folder dir;
  const std::string before = testing::rs274_motion(dir.path(), "in.ngc", input);
  const std::string after = testing::rs274_motion(dir.path(), "out.ngc", out.text);
  EXPECT_FALSE(before.empty());
  EXPECT_EQ(before, after);
}

TEST(ToolSections, FusionCommentsNameTheTools) {
  const std::string input = two_tool_program(fusion_header);
  const Posted out = post(input, vc_only(120));
  expect_flat_kept_ball_posted(input, out);
  EXPECT_EQ(out.summary.sections[0].entry->origin, tools::ToolOrigin::comment);
  EXPECT_EQ(out.summary.sections[0].entry->where, "two.ngc:2");
  EXPECT_EQ(out.summary.sections[1].entry->where, "two.ngc:3");
  EXPECT_DOUBLE_EQ(out.summary.sections[1].vc_nominal, 120);
}

TEST(ToolSections, ToolsGivenPerNumberOnTheCommandLine) {
  const std::string input = two_tool_program("");
  tools::ToolChoices choices = vc_only(120);
  choices.table.add(tools::parse_tool_option("T1=flat:10"));
  choices.table.add(tools::parse_tool_option("T2=ball:10"));
  const Posted out = post(input, choices);
  expect_flat_kept_ball_posted(input, out);
  EXPECT_EQ(out.summary.sections[1].entry->origin, tools::ToolOrigin::command_line);
}

TEST(ToolSections, CommandLineBeatsTheComments) {
  // The comments call both tools balls; the command line says T1 is flat.
  const std::string input = two_tool_program(
      "(T1 D=10. CR=5. - ZMIN=-5. - ball end mill)\n(T2 D=10. CR=5. - ZMIN=-5. - ball end mill)\n");
  tools::ToolChoices choices = vc_only(120);
  choices.table.add(tools::parse_tool_option("T1=flat:10"));
  expect_flat_kept_ball_posted(input, post(input, choices));
}

TEST(ToolSections, PostToolsChoosesTheSections) {
  const std::string input = two_tool_program(
      "(T1 D=10. CR=5. - ZMIN=-5. - ball end mill)\n(T2 D=10. CR=5. - ZMIN=-5. - ball end mill)\n");
  tools::ToolChoices choices = vc_only(120);
  choices.post_tools = std::vector<int>{2};
  const Posted out = post(input, choices);
  EXPECT_EQ(out.summary.sections[0].reason, "not in --post-tools");
  EXPECT_FALSE(out.summary.sections[0].posted);
  EXPECT_TRUE(out.summary.sections[1].posted);
  const std::size_t t2 = input.find("T2 M6");
  EXPECT_EQ(out.text.substr(0, t2), input.substr(0, t2));
}

TEST(ToolSections, VcPerTool) {
  const std::string input = two_tool_program(
      "(T1 D=10. CR=5. - ZMIN=-5. - ball end mill)\n(T2 D=10. CR=5. - ZMIN=-5. - ball end mill)\n");
  tools::ToolChoices choices;
  choices.vc = 120;
  choices.vc_by_tool[2] = 90;
  const Posted out = post(input, choices);
  ASSERT_EQ(out.summary.sections.size(), 2u);
  EXPECT_TRUE(out.summary.sections[0].posted);
  EXPECT_TRUE(out.summary.sections[1].posted);
  EXPECT_DOUBLE_EQ(out.summary.sections[0].vc_nominal, 120);
  EXPECT_DOUBLE_EQ(out.summary.sections[1].vc_nominal, 90);
  // The same surface at 3/4 of the speed: its mean vc after is 3/4 of T1's (within the band).
  ASSERT_TRUE(out.summary.sections[0].after && out.summary.sections[1].after);
  EXPECT_NEAR(out.summary.sections[1].after->mean / out.summary.sections[0].after->mean, 0.75,
              0.02);
  EXPECT_LE(out.summary.sections[1].after->max, 90 * (1 + 1e-9));
}

// Tool numbers the command line names but the program never selects are
// warned of, one line each; a tools file may list a shop's whole table.
TEST(ToolSections, ToolsNamedButNotInTheProgramAreWarnedOf) {
  tools::ToolChoices choices;
  choices.post_tools = std::vector<int>{2, 7};
  choices.vc_by_tool = {{2, 150.0}, {3, 150.0}};
  choices.table.add(tools::parse_tool_option("T8=ball:6"));
  tools::ToolEntry from_file = tools::parse_tool_option("T9=ball:6");
  from_file.origin = tools::ToolOrigin::tools_file;
  choices.table.add(from_file);
  std::vector<ToolSection> sections(3);
  sections[1].tool = 2;
  sections[2].tool = 1;
  const std::vector<std::string> expected = {
      "--post-tools names T7, which no tool change of the program selects (its tools: T1, T2)",
      "--vc names T3, which no tool change of the program selects (its tools: T1, T2)",
      "--tool names T8, which no tool change of the program selects (its tools: T1, T2)"};
  EXPECT_EQ(unused_tool_choices(choices, sections), expected);
  choices = {};
  choices.vc = 120;
  EXPECT_TRUE(unused_tool_choices(choices, sections).empty());
}

TEST(ToolSections, UnknownToolsAndSectionsInTheAirKeepTheirSpeed) {
  // T3 is named nowhere; T2 is a ball whose path runs 25 mm and more above the dome.
  std::string lifted;
  for (int i = 0; i <= 40; ++i) lifted += "G1 X" + std::to_string(i - 20) + " Y0 Z50\n";
  const std::string input =
      "%\n(T2 D=10. CR=5. - ZMIN=-5. - ball end mill)\nG21 G90 G17 G94\n"
      "T3 M6\nS5000 M3\nF2000\n" +
      raster_body(5000) + "G0 Z60\nT2 M6\nS8000 M3\nF2000\n" + lifted + "G0 Z60\nM5\nM30\n%\n";
  const Posted out = post(input, vc_only(120));
  EXPECT_EQ(out.text, input);
  ASSERT_EQ(out.summary.sections.size(), 2u);
  EXPECT_FALSE(out.summary.sections[0].entry);
  EXPECT_NE(out.summary.sections[0].reason.find("unknown tool"), std::string::npos);
  EXPECT_FALSE(out.summary.sections[1].posted);
  EXPECT_EQ(out.summary.sections[1].reason, "the path never touches the model: speed kept");
  EXPECT_EQ(out.summary.s_words, 0u);
}

// The dome raster as CL GOTOs (ball centre on the dome, 21 passes of 81 points).
std::string cl_raster() {
  std::ostringstream raster;
  raster.setf(std::ios::fixed);
  raster.precision(6);
  for (double y = -20; y <= 20 + 1e-9; y += 2) {
    for (int i = 0; i <= 80; ++i) {
      const double x = -20 + i * 0.5;
      const double z = -20 + std::sqrt(45.0 * 45.0 - x * x - y * y) - testing::dome_ball_radius;
      raster << "GOTO/" << x << "," << y << "," << z << "\n";
    }
  }
  return raster.str();
}

// CL data without LOAD/TOOL or LOADTL (CAMWorks writes a CUTTER per
// operation): TOOLNO names the first tool, and the second CUTTER, after the
// first section has moved, is the change to the tool SELECT/TOOL named: two
// sections, each with its own cutter's shape. Before, the second CUTTER was
// dropped and the ball's raster was kept as the flat mill's.
TEST(ToolSections, ClCutterWithoutLoadToolStartsASection) {
  const std::string input =
      "UNITS/MM\nCUTTER/10,0\nTOOLNO/1\nSPINDL/5000,RPM,CLW\n"
      "FEDRAT/2000,MMPM\n" +
      cl_raster() + "SELECT/TOOL,2\nCUTTER/10,5\nSPINDL/8000,RPM,CLW\n" + cl_raster() + "FINI\n";
  const Posted out = post(input, vc_only(120));
  ASSERT_EQ(out.summary.sections.size(), 2u);
  EXPECT_EQ(out.summary.sections[0].tool, 1);
  ASSERT_TRUE(out.summary.sections[0].entry);
  EXPECT_EQ(out.summary.sections[0].entry->shape, tools::ToolShape::flat);
  EXPECT_FALSE(out.summary.sections[0].posted);
  EXPECT_EQ(out.summary.sections[1].tool, 2);
  ASSERT_TRUE(out.summary.sections[1].entry);
  EXPECT_EQ(out.summary.sections[1].entry->shape, tools::ToolShape::ball);
  EXPECT_EQ(out.summary.sections[1].entry->where, "two.ngc:1708");
  EXPECT_TRUE(out.summary.sections[1].posted);
  EXPECT_NE(out.text.find("T1 M6\n"), std::string::npos);
  EXPECT_NE(out.text.find("T2 M6\n"), std::string::npos);
}

// CL data: CUTTER before LOADTL names each tool; the flat T1's SPINDL stays
// its S, the ball T2's section gets the planned S words.
TEST(ToolSections, ClCuttersNameTheTools) {
  const std::string raster = cl_raster();
  const std::string input =
      "PARTNO TWO\nUNITS/MM\nCUTTER/10,0\nLOADTL/1\nSPINDL/5000,RPM,CLW\n"
      "FEDRAT/2000,MMPM\n" +
      raster + "CUTTER/10,5\nLOADTL/2\nSPINDL/8000,RPM,CLW\n" + raster + "FINI\n";
  const Posted out = post(input, vc_only(120));
  ASSERT_EQ(out.summary.sections.size(), 2u);
  EXPECT_EQ(out.summary.sections[0].tool, 1);
  EXPECT_EQ(out.summary.sections[0].entry->shape, tools::ToolShape::flat);
  EXPECT_EQ(out.summary.sections[0].entry->origin, tools::ToolOrigin::cl_record);
  EXPECT_FALSE(out.summary.sections[0].posted);
  EXPECT_TRUE(out.summary.sections[1].posted);
  EXPECT_EQ(out.summary.sections[1].entry->shape, tools::ToolShape::ball);
  // Between T1 M6 and T2 M6 the only S is the CL's own 5000.
  const std::size_t t1 = out.text.find("T1 M6"), t2 = out.text.find("T2 M6");
  ASSERT_NE(t1, std::string::npos);
  ASSERT_NE(t2, std::string::npos);
  const std::string first = out.text.substr(t1, t2 - t1);
  EXPECT_NE(first.find("S5000"), std::string::npos) << first.substr(0, 300);
  std::size_t s_count = 0;
  for (std::size_t at = first.find('S'); at != std::string::npos; at = first.find('S', at + 1))
    s_count += std::isdigit(static_cast<unsigned char>(first[at + 1])) ? 1 : 0;
  EXPECT_EQ(s_count, 1u);
  EXPECT_GT(out.summary.sections[1].s_words, 1u);
  EXPECT_EQ(out.summary.sections[0].s_words, 0u);
}

}  // namespace
}  // namespace vcpost::post
