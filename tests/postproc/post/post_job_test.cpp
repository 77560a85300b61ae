// The post job end to end on an analytic dome with an exact drop-cutter
// raster written in the test: only S words change, every S is one the
// machine can take at the rate it can change, vc never exceeds nominal,
// and the share of cutting time near nominal rises. When LinuxCNC's rs274
// is installed, it must read the same motion from input and output.
#include "postproc/post/post_job.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>

#include "../dome_program_support.h"
#include "../rs274_support.h"
#include "../temp_folder.h"
#include "geometry/analytic_surfaces.h"
#include "machines/builtin.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/program/timing.h"
#include "postproc/program/transcript.h"

namespace vcpost::post {
namespace {

using Eigen::Vector3d;
constexpr double ball_radius = testing::dome_ball_radius;

using testing::dome;
using testing::dome_raster;

PostSettings settings_for(double vc) {
  PostSettings s;
  s.point.tool = geometry::Tool::ball(2 * ball_radius);
  s.point.ap = 0.3;
  s.point.vc = vc;
  return s;
}

std::string run_post(const std::string& program, const machines::MachineProfile& profile,
                     const PostSettings& settings, PostSummary* summary = nullptr) {
  const auto model = dome();
  std::string out;
  const auto s = post_program(program, "dome.ngc", model, profile, settings,
                              [&](std::string_view bytes) { out.append(bytes); });
  if (summary) *summary = s;
  return out;
}

// Every event of a program, in order.
std::vector<program::Event> events_of(const std::string& text) {
  gcode::Interpreter interpreter(text, gcode::rs274ngc_dialect());
  std::vector<program::Event> events;
  while (interpreter.next(events)) {
  }
  return events;
}

TEST(PostJob, OnlySWordsChangeAndTheMotionIsTheSame) {
  const std::string input = dome_raster(1.0, 0.5, 8000);
  const auto profile = machines::builtin_profile("mazak-3axis");
  const std::string output = run_post(input, profile, settings_for(120));
  ASSERT_NE(input, output);
  // Line by line: equal once the S words are taken out.
  std::istringstream a(input), b(output);
  std::string la, lb;
  const std::regex s_word(R"( ?S[0-9.]+)");
  int lines = 0;
  while (std::getline(a, la)) {
    ASSERT_TRUE(std::getline(b, lb));
    EXPECT_EQ(std::regex_replace(la, s_word, ""), std::regex_replace(lb, s_word, "")) << la;
    ++lines;
  }
  EXPECT_FALSE(std::getline(b, lb));
  // And as interpreted motion.
  const auto before = events_of(input), after = events_of(output);
  std::vector<Vector3d> ends_before, ends_after;
  for (const auto& e : before) {
    if (const auto* f = std::get_if<program::StraightFeed>(&e)) ends_before.push_back(f->end);
  }
  for (const auto& e : after) {
    if (const auto* f = std::get_if<program::StraightFeed>(&e)) ends_after.push_back(f->end);
  }
  EXPECT_EQ(ends_before, ends_after);
  EXPECT_GT(lines, 3000);
}

struct SWord {
  double time_s;
  double rpm;
};

// The S words of a program with the time each takes effect.
std::vector<SWord> s_words(const std::string& text, const machines::MachineProfile& profile) {
  program::PathClock clock({profile.feed().rapid_mm_per_min, profile.control().block_time_s});
  std::vector<SWord> words;
  for (const auto& e : events_of(text)) {
    const auto t = clock.advance(e);
    if (const auto* s = std::get_if<program::SetSpindleSpeed>(&e))
      words.push_back({t.start, s->rpm});
  }
  return words;
}

TEST(PostJob, EverySpindleSpeedIsWithinTheMachinesRangeAndSlewLimit) {
  for (const char* name : {"mazak-3axis", "generic", "fanuc-3axis", "linuxcnc-3axis"}) {
    SCOPED_TRACE(name);
    const auto profile = machines::builtin_profile(name);
    const std::string output = run_post(dome_raster(1.0, 0.5, 8000), profile, settings_for(120));
    const auto words = s_words(output, profile);
    const auto& spindle = profile.spindle();
    // The raster has no rapid between its passes: where the path stops at
    // an S word, the header S (rewritten to the run's first) is all there is.
    ASSERT_GT(words.size(), spindle.stops_path_on_change ? 0u : 1u);
    if (words.size() > 1) {
      EXPECT_NE(words[1].rpm, words[0].rpm) << "a word repeating the S";
    }
    for (std::size_t i = 0; i < words.size(); ++i) {
      EXPECT_GE(words[i].rpm, spindle.n_min_rpm);
      EXPECT_LE(words[i].rpm, spindle.n_max_rpm);
      EXPECT_NEAR(std::fmod(words[i].rpm, spindle.s_resolution_rpm), 0, 1e-6);
      if (i < 1) continue;  // the header S stands before the cut
      // One S per stretch between stops (linuxcnc-3axis): a rise lags, and
      // the slow-down is planned against the samples, not word to word
      // (stop_aware_plan_test.cpp simulates the spindle).
      if (spindle.stops_path_on_change) continue;
      const double dt = words[i].time_s - words[i - 1].time_s, ds = words[i].rpm - words[i - 1].rpm;
      EXPECT_LE(ds, spindle.acceleration_rpm_per_s * dt + 1e-6) << i;
      EXPECT_LE(-ds, spindle.deceleration_rpm_per_s * dt + 1e-6) << i;
    }
  }
}

TEST(PostJob, CuttingSpeedStaysAtOrUnderNominalAndMoreTimeIsNearIt) {
  const auto profile = machines::builtin_profile("mazak-3axis");
  PostSummary summary;
  run_post(dome_raster(1.0, 0.5, 8000), profile, settings_for(120), &summary);
  ASSERT_TRUE(summary.before && summary.after);
  EXPECT_EQ(summary.touching, summary.samples - summary.lifted);
  EXPECT_LE(summary.after->max, 120 * (1 + 1e-9));
  EXPECT_GT(summary.after->within_10_percent, summary.before->within_10_percent);
  EXPECT_GT(summary.after->within_10_percent, summary.before->within_10_percent + 0.2);
  std::printf("dome raster, mazak-3axis: within +-10 %% of vc: %.1f %% before, %.1f %% after\n",
              100 * summary.before->within_10_percent, 100 * summary.after->within_10_percent);
}

TEST(PostJob, LevelCutNeedsOneSpeedAndTheFormulaGivesIt) {
  // A level plane: D_max is the rim diameter 2 sqrt(ap (D - ap)) everywhere,
  // so the whole cut runs at floor(1000 vc / (pi D_max)).
  geometry::PlanePatch plane;
  plane.u_min = plane.v_min = -100;
  plane.u_max = plane.v_max = 100;
  const geometry::AnalyticModel model({plane});
  std::string program = "G21 G90\nS6000 M3\nF1000\nG0 X0 Y0 Z1\nG1 Z0\n";
  for (int k = 0; k < 5; ++k) {
    program += k % 2 ? "G1 X0\n" : "G1 X30\n";
    program += "G1 Y" + std::to_string(0.5 * (k + 1)) + "\n";
  }
  program += "M30\n";
  std::string out;
  const auto profile = machines::builtin_profile("mazak-3axis");  // 12,000 rpm: no clamp
  const auto summary = post_program(program, "level.ngc", model, profile, settings_for(100),
                                    [&](std::string_view bytes) { out.append(bytes); });
  const double n = std::floor(100000 / (std::numbers::pi * 2 * std::sqrt(0.3 * 9.7)));  // 9330
  // The header S and the approach (in the air, like a rapid) take the cut's speed.
  EXPECT_NE(out.find("S" + std::to_string(static_cast<int>(n)) + " M3"), std::string::npos) << out;
  const std::regex s_word(R"(S([0-9]+))");
  int words = 0;
  for (auto it = std::sregex_iterator(out.begin(), out.end(), s_word); it != std::sregex_iterator();
       ++it) {
    EXPECT_EQ(std::stod((*it)[1]), n) << out;
    ++words;
  }
  EXPECT_LE(words, 2) << out;
  EXPECT_EQ(summary.s_words, static_cast<std::uint64_t>(words));
}

TEST(PostJob, AdjustFeedKeepsTheFeedPerTooth) {
  // Level plane, one speed n = 9329 rpm: with fz = 0.05 mm and 2 teeth the
  // cut runs at F = 0.05 * 2 * 9329 = 932.9 mm/min, written as F932 (the
  // profile writes whole mm/min, rounding down so fz is never exceeded).
  geometry::PlanePatch plane;
  plane.u_min = plane.v_min = -100;
  plane.u_max = plane.v_max = 100;
  const geometry::AnalyticModel model({plane});
  const std::string program =
      "G21 G90\nS6000 M3\nF1000\nG0 X0 Y0 Z1\nG1 Z0\nG1 X30\nG1 Y0.5\nG1 X0\nM30\n";
  PostSettings settings = settings_for(100);
  settings.adjust_feed = true;
  settings.fz_mm = 0.05;
  settings.teeth = 2;
  std::string out;
  const auto summary =
      post_program(program, "level.ngc", model, machines::builtin_profile("mazak-3axis"), settings,
                   [&](std::string_view bytes) { out.append(bytes); });
  EXPECT_NE(out.find("G1 X30 F932\n"), std::string::npos) << out;
  EXPECT_EQ(out.find("G0 X0 Y0 Z1 S9329 F"), std::string::npos) << out;  // no F on rapids
  EXPECT_GE(summary.f_words, 1u);
}

TEST(PostJob, ToolComesFromTheClCutterWhenNoneIsGiven) {
  PostSettings settings;
  settings.tools.emplace();
  settings.tools->vc = 120;
  const auto profile = machines::builtin_profile("generic");
  const auto section = first_postable_section(
      "PARTNO T\nUNITS/MM\nCUTTER/12.0,6.0\nGOTO/0,0,0\nFINI\n", "t.cls", profile, settings);
  ASSERT_TRUE(section);
  ASSERT_TRUE(section->entry);
  EXPECT_EQ(section->entry->shape, tools::ToolShape::ball);
  EXPECT_DOUBLE_EQ(section->entry->diameter, 12);
  EXPECT_EQ(section->entry->origin, tools::ToolOrigin::cl_record);
  EXPECT_EQ(section->entry->where, "t.cls:3");
  EXPECT_FALSE(first_postable_section("G0 X0\nM30\n", "t.ngc", profile, settings));
}

TEST(PostJob, Rs274ReadsTheSameMotionFromInputAndOutput) {
  if (std::system("command -v rs274 >/dev/null 2>&1") != 0) GTEST_SKIP() << "rs274 not installed";
  const std::string input = dome_raster(2.0, 0.5, 8000);
  const auto output =
      run_post(input, machines::builtin_profile("linuxcnc-3axis"), settings_for(120));
  const testing::Folder dir;
  auto transcript = [&](const std::string& name, const std::string& text) {
    return testing::rs274_motion(dir.path(), name, text);
  };
  const std::string a = transcript("in.ngc", input), b = transcript("out.ngc", output);
  EXPECT_GT(std::count(a.begin(), a.end(), '\n'), 400);
  EXPECT_EQ(a, b);
}

// One raster pass over the dome at `y` (x from -20 to 20, 1 mm apart):
// down onto the surface, along it, and up again.
std::string dome_pass(double y) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(6);
  auto z_at = [y](double x) { return -20 + std::sqrt(45.0 * 45.0 - x * x - y * y) - ball_radius; };
  out << "G0 X-20.000000 Y" << y << " Z" << z_at(-20) + 5 << "\nG1 Z" << z_at(-20) << "\n";
  for (int i = 1; i <= 40; ++i) out << "G1 X" << -20.0 + i << " Z" << z_at(-20.0 + i) << "\n";
  out << "G0 Z30.\n";
  return out.str();
}

// The S value of each line of `text` ("" when it has none).
std::vector<std::string> s_per_line(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  static const std::regex s_word(R"(S([0-9.]+))");
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    out.push_back(std::regex_search(line, m, s_word) ? m[1].str() : "");
  }
  return out;
}

TEST(PostJob, LinesRunTwiceGetTheLowestSOfTheirRuns) {
  // The pass at y = 0 as a subroutine, called at once and again at y = 0.4
  // after the pass at y = 15 (used to end in "internal error:
  // write_patched: patch offset 18446744073709551456"). The oracle is the
  // same program unrolled: its events are the same, so each run of a body
  // line gets the S the unrolled copy of that line gets. The called
  // program, run line by line (each S word in effect until the next), must
  // never turn faster than the unrolled one: a body line's one S is the
  // lowest S the unrolled program has in effect at either of its runs,
  // whether that run sets S on the line or carries it from a line before.
  // (It was the lower of the words the runs set: at the first cut, where
  // the first run keeps the S set before the call and the second run, next
  // to the first pass, sets a higher one, the first run went 10 % too fast.)
  // vc 60 keeps S under the profile's 8000 rpm (at 120 the flat top is
  // clamped there); F300 lets the planner change S on almost every line.
  const std::string header = "%\nG21 G90 G17 G94\nT1 M6\nS4000 M3\nF300\n";
  const std::string tail = "M5\nM30\n%\n";
  // Down to the surface in rapid, so the first cut (X-19) is the first S
  // the plan sets; the subroutine's argument is the pass's Y (the dome's Z
  // differs by under 0.003 mm at y = 0.4, within the contact tolerance).
  const std::string body = std::regex_replace(dome_pass(0), std::regex("\nG1 Z"), "\nG0 Z");
  const std::string between = dome_pass(15);
  const auto at = [&body](const std::string& y) {
    return std::regex_replace(body, std::regex("Y0\\.000000"), "Y" + y);
  };
  const std::string unrolled = header + body + between + at("0.400000") + tail;
  const std::string called = header + "o100 sub\n" + at("[0.000000+#1]") + "o100 endsub\n" +
                             "o100 call [0]\n" + between + "o100 call [0.4]\n" + tail;
  // An inline control: linuxcnc-3axis stops at every S word, and its plan
  // keeps one S per stretch between stops, none inside a pass.
  const auto profile = machines::builtin_profile("generic");
  PostSummary unrolled_summary, called_summary;
  const auto u = s_per_line(run_post(unrolled, profile, settings_for(60), &unrolled_summary));
  const auto c = s_per_line(run_post(called, profile, settings_for(60), &called_summary));
  const auto lines_of = [](const std::string& t) {
    return static_cast<std::size_t>(std::count(t.begin(), t.end(), '\n'));
  };
  const std::size_t h = lines_of(header), b = lines_of(body), p = lines_of(between),
                    t = lines_of(tail);
  ASSERT_EQ(u.size(), h + b + p + b + t);
  ASSERT_EQ(c.size(), h + 1 + b + 1 + 1 + p + 1 + t);
  // The lines of the called program in the order they run, which is the
  // order of the unrolled program's lines (the o-lines hold no S).
  const std::size_t body_at = h + 1, between_at = h + 1 + b + 2, tail_at = between_at + p + 1;
  std::vector<std::size_t> runs;
  const auto add = [&runs](std::size_t first, std::size_t count) {
    for (std::size_t i = 0; i < count; ++i) runs.push_back(first + i);
  };
  add(0, h);
  add(body_at, b);
  add(between_at, p);
  add(body_at, b);
  add(tail_at, t);
  ASSERT_EQ(runs.size(), u.size());
  // The S in effect at each run (the line's own S or the last one before).
  std::vector<double> u_in_effect, c_in_effect;
  double u_s = 0, c_s = 0;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (!u[k].empty()) u_s = std::stod(u[k]);
    if (!c[runs[k]].empty()) c_s = std::stod(c[runs[k]]);
    u_in_effect.push_back(u_s);
    c_in_effect.push_back(c_s);
  }
  std::size_t faster = 0;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (c_in_effect[k] > u_in_effect[k]) {
      ++faster;
      ADD_FAILURE() << "run " << k + 1 << " (line " << runs[k] + 1 << " of the called program) at S"
                    << c_in_effect[k] << ", in the unrolled program at S" << u_in_effect[k];
    }
  }
  EXPECT_EQ(faster, 0u);
  // Each body line: an S word when either run of the unrolled program has
  // one there, and then the lower of the two S in effect at its runs.
  const std::size_t first_run = h, second_run = h + b + p;
  std::size_t both = 0, either = 0, carried = 0;
  for (std::size_t i = 0; i < b; ++i) {
    const std::string& first = u[first_run + i];
    const std::string& second = u[second_run + i];
    std::string expected;
    if (!first.empty() || !second.empty()) {
      ++either;
      if (!first.empty() && !second.empty()) ++both;
      const double lowest = std::min(u_in_effect[first_run + i], u_in_effect[second_run + i]);
      if ((first.empty() || second.empty()) && lowest < std::stod(first + second)) ++carried;
      expected = std::to_string(static_cast<long>(lowest));
    }
    EXPECT_EQ(c[body_at + i], expected) << "body line " << i + 1 << ": S'" << first << "' then S'"
                                        << second << "' in the unrolled program";
  }
  // The pass between the calls is the unrolled program's, word for word.
  for (std::size_t i = 0; i < p; ++i) EXPECT_EQ(c[between_at + i], u[h + b + i]);
  EXPECT_GT(both, 5u);
  // Lines where one run sets S and the other carries a lower one from
  // before: the case whose S used to be the setting run's.
  EXPECT_EQ(carried, 1u);
  std::printf(
      "%zu body lines with an S in both runs, %zu in one run only (%zu of them lower "
      "in the run without)\n",
      both, either - both, carried);
  EXPECT_EQ(called_summary.repeated_lines, either);
  EXPECT_EQ(unrolled_summary.repeated_lines, 0u);
  EXPECT_EQ(called_summary.s_words + both, unrolled_summary.s_words);
}

TEST(PostJob, RepeatLoopAndFanucM98PostWithOneSPerLine) {
  // o101 repeat [2] (rs274ngc) and M98 P1000 L2 (Fanuc): the same motion as
  // the unrolled program, one S word per line, no error.
  const std::string body = dome_pass(0);
  const auto profile = machines::builtin_profile("generic");  // inline: S words inside the pass
  PostSummary summary;
  const std::string repeated = "%\nG21 G90 G17 G94\nT1 M6\nS4000 M3\nF300\no101 repeat [2]\n" +
                               body + "o101 endrepeat\nM5\nM30\n%\n";
  const std::string out = run_post(repeated, profile, settings_for(60), &summary);
  EXPECT_GT(summary.repeated_lines, 0u);
  const auto motions = [](const std::vector<program::Event>& events) {
    return std::count_if(events.begin(), events.end(),
                         [](const program::Event& e) { return program::is_motion(e); });
  };
  EXPECT_EQ(motions(events_of(out)), motions(events_of(repeated)));
  std::istringstream lines(out);
  static const std::regex s_word(R"(S[0-9])");
  for (std::string line; std::getline(lines, line);) {
    EXPECT_LE(std::distance(std::sregex_iterator(line.begin(), line.end(), s_word),
                            std::sregex_iterator()),
              1)
        << line;
  }
  PostSettings fanuc = settings_for(60);
  fanuc.dialect = gcode::fanuc_dialect();
  const std::string called =
      "%\nO0001\nG21 G90 G17 G94\nT1 M6\nS4000 M3\nF300.\n"
      "M98 P1000 L2\nM5\nM30\nO1000\n" +
      body + "M99\n%\n";
  PostSummary fanuc_summary;
  EXPECT_NO_THROW(
      run_post(called, machines::builtin_profile("fanuc-3axis"), fanuc, &fanuc_summary));
  EXPECT_GT(fanuc_summary.repeated_lines, 0u);
}

// The sinumerik-840d profile reads the Siemens language that NX's 840D posts
// write (MSG, G71, G642, T with D), with no --dialect: its CL output is ISO
// (verify reads that in output_dialect_of), its input the control's own.
TEST(PostJob, SinumerikProfileReadsTheSiemensLanguage) {
  std::string program = dome_raster(2.0, 1.0, 5000);
  const std::string header = "%\n(dome raster)\nG21 G90 G17 G94\nT1 M6\n";
  ASSERT_EQ(program.rfind(header, 0), 0u);
  program = "; dome raster\nMSG(\"FINISH D10\")\nG17 G71 G90 G94 G642\nT1 D1\nM6\n" +
            program.substr(header.size(), program.size() - header.size() - 2);  // no "%\n"
  const auto profile = machines::builtin_profile("sinumerik-840d");
  EXPECT_EQ(post::dialect_of(profile).kind, machines::Dialect::sinumerik);
  EXPECT_EQ(post::output_dialect_of(profile).kind, machines::Dialect::fanuc);
  PostSummary summary;
  const std::string out = run_post(program, profile, settings_for(120), &summary);
  EXPECT_GT(summary.s_words, 1u);
  const auto motions = [](const std::string& text) {
    gcode::Interpreter interpreter(text, gcode::sinumerik_dialect());
    std::vector<program::Event> events;
    while (interpreter.next(events)) {
    }
    std::string moves;
    for (const auto& e : events)
      if (program::is_motion(e)) program::append_transcript(moves, e);
    return moves;
  };
  EXPECT_EQ(motions(out), motions(program));
}

// A bull-nose end mill (D 10, rc 2) on a raster written for it: every point
// of the cut touches, only S changes (rs274 reads the same motion), every S
// is within the profile, and vc stays at or under nominal.
TEST(PostJob, BullNosePostKeepsTheMotionAndTheProfile) {
  // Passes 1.25 mm apart: the chord of the step between passes stays within
  // the contact tolerance of the curved surface (1.25^2 / (8 * 38) mm).
  const std::string input = testing::bull_nose_dome_raster(1.25, 1.0, 8000, 10, 2);
  PostSettings settings = settings_for(120);
  settings.point.tool = geometry::Tool::bull_nose(10, 2);
  settings.sample_spacing_mm = 2;
  const auto profile = machines::builtin_profile("generic");  // inline: S words along the passes
  PostSummary summary;
  const std::string output = run_post(input, profile, settings, &summary);
  ASSERT_NE(input, output);
  EXPECT_EQ(summary.touching, summary.samples - summary.lifted);
  EXPECT_EQ(summary.gouging, 0u);
  const auto words = s_words(output, profile);
  ASSERT_GT(words.size(), 2u);
  for (const SWord& word : words) {
    EXPECT_GE(word.rpm, profile.spindle().n_min_rpm);
    EXPECT_LE(word.rpm, profile.spindle().n_max_rpm);
  }
  ASSERT_TRUE(summary.after);
  EXPECT_LE(summary.after->max, 120 * (1 + 1e-9));
  if (std::system("command -v rs274 >/dev/null 2>&1") != 0) GTEST_SKIP() << "rs274 not installed";
  const testing::Folder dir;
  const std::string a = testing::rs274_motion(dir.path(), "in.ngc", input);
  EXPECT_GT(std::count(a.begin(), a.end(), '\n'), 400);
  EXPECT_EQ(a, testing::rs274_motion(dir.path(), "out.ngc", output));
}

}  // namespace
}  // namespace vcpost::post
