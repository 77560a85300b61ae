// `vcpost machines` end to end (the built binary), and profile_to_toml():
// what `show` prints is a complete profile that loads back to the same
// values, with the source of every key.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

#include "machines/builtin.h"
#include "machines/profile.h"

namespace vcpost::machines {
namespace {

struct Run {
  int exit_code = -1;
  std::string out;  // stdout and stderr
};

Run run(const std::string& args) {
  const std::string command = std::string(VCPOST_BINARY) + " " + args + " 2>&1";
  Run r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

void expect_same(const MachineProfile& a, const MachineProfile& b) {
  EXPECT_EQ(a.name(), b.name());
  EXPECT_EQ(a.description(), b.description());
  EXPECT_EQ(a.dialect(), b.dialect());
  EXPECT_EQ(a.output_format(), b.output_format());
  const auto &s = a.spindle(), &t = b.spindle();
  EXPECT_EQ(s.n_min_rpm, t.n_min_rpm);
  EXPECT_EQ(s.n_max_rpm, t.n_max_rpm);
  EXPECT_EQ(s.acceleration_rpm_per_s, t.acceleration_rpm_per_s);
  EXPECT_EQ(s.deceleration_rpm_per_s, t.deceleration_rpm_per_s);
  EXPECT_EQ(s.s_resolution_rpm, t.s_resolution_rpm);
  EXPECT_EQ(s.min_change_rpm, t.min_change_rpm);
  EXPECT_EQ(s.min_change_percent, t.min_change_percent);
  EXPECT_EQ(s.max_changes_per_s, t.max_changes_per_s);
  EXPECT_EQ(s.change_in_motion, t.change_in_motion);
  EXPECT_EQ(s.change_code, t.change_code);
  EXPECT_EQ(s.stops_path_on_change, t.stops_path_on_change);
  EXPECT_EQ(s.stop_cost_s, t.stop_cost_s);
  EXPECT_EQ(s.at_speed_window_percent, t.at_speed_window_percent);
  EXPECT_EQ(s.s_in_feed, t.s_in_feed);
  EXPECT_EQ(a.control().block_time_s, b.control().block_time_s);
  EXPECT_EQ(a.feed().f_min_mm_per_min, b.feed().f_min_mm_per_min);
  EXPECT_EQ(a.feed().f_max_mm_per_min, b.feed().f_max_mm_per_min);
  EXPECT_EQ(a.feed().rapid_mm_per_min, b.feed().rapid_mm_per_min);
  EXPECT_EQ(a.tool().default_teeth, b.tool().default_teeth);
  const auto &o = a.output(), &q = b.output();
  EXPECT_EQ(o.program_number, q.program_number);
  EXPECT_EQ(o.high_speed_mode, q.high_speed_mode);
  EXPECT_EQ(o.geometry_compensation, q.geometry_compensation);
  EXPECT_EQ(o.work_offset, q.work_offset);
  EXPECT_EQ(o.decimals, q.decimals);
  EXPECT_EQ(o.feed_decimals, q.feed_decimals);
  EXPECT_EQ(o.line_numbers, q.line_numbers);
  EXPECT_EQ(o.canned_cycles, q.canned_cycles);
  EXPECT_EQ(o.cutter_compensation, q.cutter_compensation);
  EXPECT_EQ(o.percent_lines, q.percent_lines);
  EXPECT_EQ(o.tool_change, q.tool_change);
  EXPECT_EQ(o.tool_change_home, q.tool_change_home);
  EXPECT_EQ(o.tool_length_offset, q.tool_length_offset);
  EXPECT_EQ(o.coolant_mist, q.coolant_mist);
  EXPECT_EQ(o.coolant_flood, q.coolant_flood);
  EXPECT_EQ(o.coolant_off, q.coolant_off);
  EXPECT_EQ(o.speed_output, q.speed_output);
  ASSERT_EQ(a.sources().size(), b.sources().size());
  for (std::size_t i = 0; i < a.sources().size(); ++i) {
    EXPECT_EQ(a.sources()[i].key, b.sources()[i].key);
    EXPECT_EQ(a.sources()[i].vendor, b.sources()[i].vendor);
    EXPECT_EQ(a.sources()[i].text, b.sources()[i].text);
  }
}

TEST(ProfileText, EveryShippedProfileReadsBackTheSame) {
  for (const auto& entry : builtin_profiles()) {
    SCOPED_TRACE(std::string(entry.name));
    const auto p = builtin_profile(entry.name);
    expect_same(p, profile_from_toml(profile_to_toml(p), "shown.toml"));
  }
}

TEST(ProfileText, OddValuesSurviveTheRoundTrip) {
  const std::string text = R"([machine]
name = "odd \"quoted\" \\ name"
dialect = "fanuc"
output_format = "mazak"
[spindle]
n_min_rpm = 1.5
n_max_rpm = 1e5
acceleration_rpm_per_s = 333.33333333333331
deceleration_rpm_per_s = 1.001
s_resolution_rpm = 0.05
min_change_rpm = 0
min_change_percent = 0.25
max_changes_per_s = 2.5
change_in_motion = "code"
change_code = "G117"
stops_path_on_change = true
[control]
block_time_s = 0
[feed]
f_min_mm_per_min = 0.5
f_max_mm_per_min = 12345.678
rapid_mm_per_min = 42000
[tool]
default_teeth = 3
[sources]
"feed.rapid_mm_per_min" = "vendor: brochure \"X\", p. 3"
)";
  const auto p = profile_from_toml(text, "odd.toml");
  const std::string shown = profile_to_toml(p);
  expect_same(p, profile_from_toml(shown, "shown.toml"));
  EXPECT_NE(shown.find("# vendor: brochure \"X\", p. 3"), std::string::npos) << shown;
  EXPECT_NE(shown.find("# no source given"), std::string::npos);
}

TEST(MachinesCommand, ListNamesEveryShippedProfile) {
  const auto r = run("machines");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  for (const auto& entry : builtin_profiles())
    EXPECT_NE(r.out.find(std::string(entry.name)), std::string::npos) << entry.name;
  EXPECT_NE(r.out.find("35-12000"), std::string::npos) << r.out;  // mazak's S range
  EXPECT_EQ(run("machines list").out, r.out);
}

TEST(MachinesCommand, ShowPrintsALoadableProfileWithItsSources) {
  const auto r = run("machines show mazak-3axis");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  expect_same(builtin_profile("mazak-3axis"), profile_from_toml(r.out, "shown.toml"));
  // 41 keys, all with an "assumed" note in the shipped file.
  EXPECT_NE(r.out.find("41 keys: 41 assumed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("n_max_rpm = 12000"), std::string::npos);
  EXPECT_NE(r.out.find("change_code = \"G117\""), std::string::npos);
}

TEST(MachinesCommand, ShowChecksAUsersFile) {
  const std::string dir = std::string(VCPOST_SOURCE_DIR) + "/tests/machines/bad/";
  auto r = run("machines show " + dir + "min_above_max.toml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("min_above_max.toml:9:13: error[E5006]: 'spindle.n_min_rpm' (9000) is "
                       "greater than spindle.n_max_rpm (8000)"),
            std::string::npos)
      << r.out;
  r = run("machines show mazak");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("E5009"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mazak-3axis"), std::string::npos) << r.out;
  r = run("machines show " + dir + "no_such_file.toml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("no such file"), std::string::npos) << r.out;
  r = run("machines show");
  EXPECT_EQ(r.exit_code, 2);
  r = run("machines frobnicate");
  EXPECT_EQ(r.exit_code, 2);
}

}  // namespace
}  // namespace vcpost::machines
