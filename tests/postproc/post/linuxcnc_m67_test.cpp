// The linuxcnc-3axis-m67 profile (issue 41): the speed changes on LinuxCNC's
// analog output 0 (M67 E0 Q), placed in motion. On the dome raster: the
// only S word left is the spindle's start, LinuxCNC's rs274 reads the
// output with the input's moves and the same speeds vcpost planned, verify
// holds, and a program posted so reads back with its speeds (posted again,
// it is the same program). CL input written for the profile does the same.
#include <gtest/gtest.h>

#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../dome_program_support.h"
#include "../rs274_support.h"
#include "../temp_folder.h"
#include "machines/builtin.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/post/post_job.h"
#include "postproc/verify/verify.h"

namespace vcpost::post {
namespace {

using testing::dome;
using testing::dome_raster;

PostSettings settings() {
  PostSettings s;
  s.point.tool = geometry::Tool::ball(2 * testing::dome_ball_radius);
  s.point.ap = 0.3;
  s.point.vc = 120;
  return s;
}

std::string run_post(const std::string& program, const std::string& name,
                     const std::string& machine, PostSummary& summary) {
  const auto model = dome();
  std::string out;
  summary = post_program(program, name, model, machines::builtin_profile(machine), settings(),
                         [&](std::string_view bytes) { out.append(bytes); });
  return out;
}

// The lines of `text` that match `pattern`.
std::vector<std::string> lines_matching(const std::string& text, const std::regex& pattern) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (std::regex_search(line, pattern)) out.push_back(line);
  return out;
}

// rs274's transcript split into the motion and the values it gave analog output 0.
struct Rs274Reading {
  std::string motion;
  std::vector<double> output_0;
};
Rs274Reading rs274_reading(const std::string& transcript) {
  Rs274Reading r;
  static const std::regex output(R"(SET_(MOTION|AUX)_OUTPUT_VALUE\(0,\s*([-0-9.]+)\))");
  std::istringstream in(transcript);
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_search(line, m, output))
      r.output_0.push_back(std::stod(m[2].str()));
    else
      r.motion += line + "\n";
  }
  return r;
}

// The spindle speeds vcpost reads from a program with the speed on output 0.
std::vector<double> speeds_read(const std::string& text) {
  gcode::Dialect dialect = gcode::rs274ngc_dialect();
  dialect.speed_output = 0;
  gcode::Interpreter interpreter(text, dialect);
  std::vector<program::Event> events;
  while (interpreter.next(events)) {
  }
  std::vector<double> out;
  for (const auto& e : events)
    if (const auto* s = std::get_if<program::SetSpindleSpeed>(&e)) out.push_back(s->rpm);
  return out;
}

verify::Options m67_verify() {
  verify::Options options;
  options.dialect = dialect_of(machines::builtin_profile("linuxcnc-3axis-m67"));
  options.speed_output = options.dialect.speed_output;
  return options;
}

TEST(LinuxCncM67, SpeedsChangeInMotionOnOutput0AndReadBack) {
  const std::string input = dome_raster(1.0, 0.5, 8000);
  PostSummary with_s{}, with_m67{};
  run_post(input, "dome.ngc", "linuxcnc-3axis", with_s);
  const std::string output = run_post(input, "dome.ngc", "linuxcnc-3axis-m67", with_m67);

  // One S word: the spindle's start, with M68 beside it; every change is an M67.
  const auto s_lines = lines_matching(output, std::regex(R"((^|\s)S[0-9])"));
  ASSERT_EQ(s_lines.size(), 1u);
  EXPECT_TRUE(std::regex_match(s_lines[0], std::regex(R"(S([0-9]+) M3 M68 E0 Q\1)"))) << s_lines[0];
  const auto m67_lines = lines_matching(output, std::regex(R"(^G1 .* M67 E0 Q[0-9]+$)"));
  EXPECT_GT(m67_lines.size(), 50u);
  EXPECT_EQ(m67_lines.size() + 1, with_m67.s_words);
  // Planned as in motion: no word stops the path; the S-word profile's
  // words stop it, and reach no more of the cut near vc.
  EXPECT_EQ(with_m67.s_placement.stops, 0u);
  EXPECT_FALSE(with_m67.s_placement.at_stops);
  EXPECT_TRUE(with_s.s_placement.at_stops);
  ASSERT_TRUE(with_m67.after && with_s.after);
  EXPECT_GE(with_m67.after->within_10_percent, with_s.after->within_10_percent);

  // LinuxCNC's rs274: the input's moves, and on output 0 the speeds vcpost
  // reads (its start's M68 and each M67).
  if (std::system("command -v rs274 >/dev/null 2>&1") == 0) {
    const testing::Folder dir;
    const auto in = rs274_reading(testing::rs274_motion(dir.path(), "in.ngc", input));
    const auto out = rs274_reading(testing::rs274_motion(dir.path(), "out.ngc", output));
    EXPECT_GT(std::count(in.motion.begin(), in.motion.end(), '\n'), 400);
    EXPECT_EQ(in.motion, out.motion);
    EXPECT_TRUE(in.output_0.empty());
    auto read = speeds_read(output);
    ASSERT_FALSE(read.empty());
    read.erase(read.begin());  // the S word of the start (its M68 follows with the same value)
    EXPECT_EQ(out.output_0, read);
  }

  // verify: the M67/M68 words are speed words, nothing else changed.
  const verify::Result r = verify::verify_gcode(input, output, m67_verify());
  EXPECT_TRUE(r.ok()) << (r.violations.empty() ? "" : verify::format(r.violations[0], "out"));
  EXPECT_EQ(r.s_changes, with_m67.s_words + 1);  // the start's S word and its M68

  // Read back: the posted speeds are the program's; posted again, the same program.
  PostSummary again{};
  EXPECT_EQ(run_post(output, "dome.m67.ngc", "linuxcnc-3axis-m67", again), output);
  ASSERT_TRUE(again.before);
  EXPECT_DOUBLE_EQ(again.before->within_10_percent, with_m67.after->within_10_percent);
  EXPECT_DOUBLE_EQ(again.before->mean, with_m67.after->mean);
}

// The dome raster as APT CL data (tool-tip points, the same moves).
std::string dome_cl() {
  std::ostringstream cl;
  cl << "PARTNO/dome raster\nUNITS/MM\nLOADTL/1\nCUTTER/10.000000,5.000000\n"
        "SPINDL/8000.000000,RPM,CLW\n";
  std::istringstream in(dome_raster(1.0, 0.5, 8000));
  static const std::regex move(R"(^G([01]) (?:X(\S+) Y(\S+) )?Z(\S+)$)");
  double x = 0, y = 0;
  bool feed = false;
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (!std::regex_match(line, m, move)) continue;
    if (m[2].matched) {
      x = std::stod(m[2].str());
      y = std::stod(m[3].str());
    }
    if (m[1] == "0") {
      cl << "RAPID\n";
    } else if (!feed) {
      cl << "FEDRAT/2000.000000,MMPM\n";
      feed = true;
    }
    cl << "GOTO/" << x << "," << y << "," << m[4].str() << "\n";
  }
  cl << "SPINDL/OFF\nFINI\n";
  return cl.str();
}

TEST(LinuxCncM67, ClInputIsWrittenWithM67SpeedChanges) {
  const std::string cl = dome_cl();
  PostSummary summary{};
  const std::string output = run_post(cl, "dome.cls", "linuxcnc-3axis-m67", summary);
  const auto starts = lines_matching(output, std::regex(R"(^S([0-9]+) M68 E0 Q\1 M3$)"));
  EXPECT_EQ(starts.size(), 1u) << output.substr(0, 400);
  const auto changes = lines_matching(output, std::regex(R"(^(G1 )?X.* M67 E0 Q[0-9]+$)"));
  EXPECT_GT(changes.size(), 50u);
  EXPECT_TRUE(lines_matching(output, std::regex(R"((^|\s)S[0-9])")).size() == 1u);
  const verify::Result r = verify::verify_cl(
      cl, output, cl_output_verify_options(machines::builtin_profile("linuxcnc-3axis-m67")));
  EXPECT_TRUE(r.ok()) << (r.violations.empty() ? "" : verify::format(r.violations[0], "out"));
  EXPECT_GT(r.motions, 3000u);
  if (std::system("command -v rs274 >/dev/null 2>&1") == 0) {
    const testing::Folder dir;
    const auto read = rs274_reading(testing::rs274_motion(dir.path(), "out.ngc", output));
    // Each feed GOTO is one straight feed of rs274's.
    const auto count = [](const std::string& text, const std::string& what) {
      std::size_t n = 0;
      for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
      return n;
    };
    EXPECT_EQ(count(read.motion, "STRAIGHT_FEED"), count(cl, "GOTO/") - count(cl, "RAPID"));
    EXPECT_EQ(read.output_0.size(), changes.size() + 1);  // each change and the start's M68
  }
}

}  // namespace
}  // namespace vcpost::post
