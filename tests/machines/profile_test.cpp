// Machine profiles: the shipped ones load with the figures their files
// state, every key has a stated source, and each bad file under
// tests/machines/bad gives the diagnostic written in its
// "# expect <code> <line>:<col> <message part>" line ('*' for any column).
#include "machines/profile.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "machines/builtin.h"

namespace vcpost::machines {
namespace {

namespace fs = std::filesystem;

// The smallest valid profile.
constexpr const char* kMinimal = R"([machine]
name = "tiny"
dialect = "rs274ngc"
output_format = "rs274ngc"
[spindle]
n_min_rpm = 500
n_max_rpm = 500
acceleration_rpm_per_s = 1
deceleration_rpm_per_s = 2
s_resolution_rpm = 0.5
min_change_rpm = 0
min_change_percent = 0
max_changes_per_s = 1
change_in_motion = "own_block"
stops_path_on_change = true
[control]
block_time_s = 0
[feed]
f_min_mm_per_min = 10
f_max_mm_per_min = 10
rapid_mm_per_min = 100
[tool]
default_teeth = 4
)";

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(BuiltinProfiles, AllAreShippedAndLoad) {
  std::vector<std::string> names;
  for (const auto& p : builtin_profiles()) {
    SCOPED_TRACE(std::string(p.name));
    names.emplace_back(p.name);
    const auto profile = builtin_profile(p.name);
    EXPECT_EQ(profile.name(), p.name);  // the file's name is the profile's
    EXPECT_EQ(profile.origin(), p.path);
  }
  EXPECT_EQ(names, (std::vector<std::string>{
                       "fanuc-3axis-sar", "fanuc-3axis", "fanuc-3plus2", "generic", "grbl",
                       "heidenhain-tnc640-dmu", "heidenhain-tnc640", "linuxcnc-3axis-m67",
                       "linuxcnc-3axis", "mazak-3axis", "sinumerik-840d"}));  // by file name
}

// Issue 17: how each control takes an S word in motion, and what a stop costs.
TEST(BuiltinProfiles, HowEachControlTakesAnSWordInMotion) {
  struct Expected {
    const char* name;
    bool stops;
    double stop_cost_s;
    double window_percent;
    bool vendor_note;  // the stop behaviour is taken from a document or a measurement
  };
  for (const Expected& e :
       {Expected{"linuxcnc-3axis", true, 0.021, 0, true},
        Expected{"linuxcnc-3axis-m67", true, 0.021, 0, true}, Expected{"grbl", true, 0.05, 0, true},
        Expected{"fanuc-3axis", false, 0, 0, false},
        Expected{"fanuc-3axis-sar", true, 0.1, 10, true},
        Expected{"sinumerik-840d", false, 0, 0, true}, Expected{"mazak-3axis", false, 0, 0, false},
        Expected{"heidenhain-tnc640", true, 0.2, 0, false},
        Expected{"generic", false, 0, 0, false}}) {
    SCOPED_TRACE(e.name);
    const auto p = builtin_profile(e.name);
    EXPECT_EQ(p.spindle().stops_path_on_change, e.stops);
    EXPECT_DOUBLE_EQ(p.spindle().stop_cost_s, e.stop_cost_s);
    EXPECT_DOUBLE_EQ(p.spindle().at_speed_window_percent, e.window_percent);
    const auto* note = p.source_of("spindle.stops_path_on_change");
    ASSERT_NE(note, nullptr);
    EXPECT_EQ(note->vendor, e.vendor_note) << note->text;
  }
  // The measured LinuxCNC figure: +1.07 s for 50 S words.
  EXPECT_NE(builtin_profile("linuxcnc-3axis").source_of("spindle.stop_cost_s")->text.find("1.07 s"),
            std::string::npos);
  // Sinumerik's note names the machine data that decide it.
  const auto sinumerik_profile = builtin_profile("sinumerik-840d");  // the note lives in it
  const std::string& sinumerik = sinumerik_profile.source_of("spindle.stops_path_on_change")->text;
  EXPECT_NE(sinumerik.find("MD22210 $MC_AUXFU_S_SYNC_TYPE"), std::string::npos);
  EXPECT_NE(sinumerik.find("MD22080"), std::string::npos);
}

TEST(ProfileLoading, StopCostAndAtSpeedWindowAreOptionalAndRangeChecked) {
  const std::string base = std::string(kMinimal);
  const auto p = profile_from_toml(base, "min.toml");
  EXPECT_DOUBLE_EQ(p.spindle().stop_cost_s, 0.0);
  EXPECT_DOUBLE_EQ(p.spindle().at_speed_window_percent, 0.0);
  auto with = [&](const std::string& line) {
    std::string text = base;
    text.insert(text.find("stops_path_on_change"), line + "\n");
    return text;
  };
  EXPECT_DOUBLE_EQ(profile_from_toml(with("stop_cost_s = 0.021"), "a.toml").spindle().stop_cost_s,
                   0.021);
  EXPECT_DOUBLE_EQ(profile_from_toml(with("at_speed_window_percent = 1"), "a.toml")
                       .spindle()
                       .at_speed_window_percent,
                   1.0);
  for (const char* bad : {"stop_cost_s = -0.1", "stop_cost_s = 11", "at_speed_window_percent = -1",
                          "at_speed_window_percent = 100"}) {
    SCOPED_TRACE(bad);
    try {
      profile_from_toml(with(bad), "a.toml");
      ADD_FAILURE() << "accepted";
    } catch (const ProfileError& e) {
      EXPECT_EQ(e.code(), Code::E5005) << e.what();
    }
  }
}

TEST(ProfileLoading, ToolChangeFormAndCoolantCodesAreChoicesChecked) {
  const auto p = profile_from_toml(std::string(kMinimal), "min.toml");
  EXPECT_EQ(p.output().tool_change, ToolChange::m6);
  EXPECT_EQ(p.output().tool_change_home, ToolChangeHome::none);
  EXPECT_TRUE(p.output().tool_length_offset);
  EXPECT_TRUE(p.output().percent_lines);
  EXPECT_EQ(p.output().coolant_mist + p.output().coolant_flood + p.output().coolant_off, "M7M8M9");
  auto with = [](const std::string& format, const std::string& output) {
    std::string text = kMinimal;
    text.replace(text.find("output_format = \"rs274ngc\""), 26,
                 "output_format = \"" + format + "\"");
    return text + "[output]\n" + output + "\n";
  };
  const auto q = profile_from_toml(
      with("fanuc",
           "tool_change = \"manual\"\ntool_change_home = \"g28\"\ntool_length_offset = false\n"
           "percent_lines = false\ncoolant_flood = \"M88\""),
      "q.toml");
  EXPECT_EQ(q.output().tool_change, ToolChange::manual);
  EXPECT_EQ(q.output().tool_change_home, ToolChangeHome::g28);
  EXPECT_FALSE(q.output().tool_length_offset);
  EXPECT_FALSE(q.output().percent_lines);
  EXPECT_EQ(q.output().coolant_flood, "M88");
  // An rs274ngc control knows M7-M9 only; no format takes a code that
  // already means something else, or a word that is not an M code.
  for (const auto& [format, bad] :
       std::vector<std::pair<std::string, std::string>>{{"rs274ngc", "coolant_flood = \"M88\""},
                                                        {"fanuc", "coolant_off = \"M6\""},
                                                        {"fanuc", "coolant_mist = \"M30\""},
                                                        {"fanuc", "coolant_mist = \"8\""},
                                                        {"fanuc", "coolant_mist = \"M8.5\""},
                                                        {"fanuc", "coolant_mist = \"M\""},
                                                        {"fanuc", "tool_change = \"auto\""},
                                                        {"fanuc", "tool_change_home = \"g30\""}}) {
    SCOPED_TRACE(bad);
    try {
      profile_from_toml(with(format, bad), "a.toml");
      ADD_FAILURE() << "accepted";
    } catch (const ProfileError& e) {
      EXPECT_EQ(e.code(), Code::E5007) << e.what();
      EXPECT_EQ(e.where().line, 25u) << e.what();  // the key's line: kMinimal has 23, [output] 24
    }
  }
}

// Issue 41: the word that carries the speed, S or LinuxCNC's M67 E<n>.
TEST(ProfileLoading, SpeedWordIsSOrAnAnalogOutputOfLinuxCnc) {
  const auto plain = profile_from_toml(std::string(kMinimal), "min.toml");
  EXPECT_FALSE(plain.output().speed_output);
  auto with = [](const std::string& dialect, const std::string& word) {
    std::string text = kMinimal;
    for (const char* key : {"dialect = \"rs274ngc\"", "output_format = \"rs274ngc\""}) {
      const auto at = text.find(key);
      text.replace(text.find('"', at), 10, "\"" + dialect + "\"");
    }
    return text + "[output]\nspeed_word = \"" + word + "\"\n";
  };
  EXPECT_FALSE(profile_from_toml(with("rs274ngc", "S"), "s.toml").output().speed_output);
  EXPECT_EQ(profile_from_toml(with("rs274ngc", "M67 E0"), "a.toml").output().speed_output, 0);
  EXPECT_EQ(profile_from_toml(with("rs274ngc", "M67 E63"), "a.toml").output().speed_output, 63);
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"rs274ngc", "M67 E64"}, {"rs274ngc", "M67"},   {"rs274ngc", "M68 E0"},
      {"rs274ngc", "M67 E-1"}, {"rs274ngc", "M67E0"}, {"rs274ngc", "s"},
      {"rs274ngc", "M67 E0 "}, {"fanuc", "M67 E0"}};
  for (const auto& [dialect, word] : bad) {
    SCOPED_TRACE(word + " " + dialect);
    try {
      profile_from_toml(with(dialect, word), "a.toml");
      ADD_FAILURE() << "accepted";
    } catch (const ProfileError& e) {
      EXPECT_EQ(e.code(), dialect == "fanuc" ? Code::E5021 : Code::E5020) << e.what();
      EXPECT_EQ(e.where().line, 25u) << e.what();  // the key's line: kMinimal has 23, [output] 24
    }
  }
  // The profile written out loads again with its speed word.
  const auto m67 = builtin_profile("linuxcnc-3axis-m67");
  EXPECT_EQ(profile_from_toml(profile_to_toml(m67), "again.toml").output().speed_output, 0);
}

// linuxcnc-3axis-m67: linuxcnc-3axis's machine with its speed on analog
// output 0, whose changes the planner places as inline S words (no stop,
// nothing to price); its S word still stops the path (the spindle's start).
TEST(BuiltinProfiles, LinuxCncM67PlansItsSpeedChangesInMotion) {
  const auto s = builtin_profile("linuxcnc-3axis");
  const auto m67 = builtin_profile("linuxcnc-3axis-m67");
  EXPECT_EQ(m67.output().speed_output, 0);
  EXPECT_TRUE(m67.spindle().stops_path_on_change);
  const SpindleSpec planned = planned_spindle(m67);
  EXPECT_FALSE(planned.stops_path_on_change);
  EXPECT_EQ(planned.change_in_motion, SChangeInMotion::inline_word);
  EXPECT_DOUBLE_EQ(planned.stop_cost_s, 0);
  EXPECT_DOUBLE_EQ(planned.at_speed_window_percent, 0);
  // The spindle's own limits are linuxcnc-3axis's, and planned as they are.
  for (const SpindleSpec& spec : {m67.spindle(), planned}) {
    EXPECT_DOUBLE_EQ(spec.n_max_rpm, s.spindle().n_max_rpm);
    EXPECT_DOUBLE_EQ(spec.acceleration_rpm_per_s, s.spindle().acceleration_rpm_per_s);
    EXPECT_DOUBLE_EQ(spec.s_resolution_rpm, s.spindle().s_resolution_rpm);
    EXPECT_DOUBLE_EQ(spec.max_changes_per_s, s.spindle().max_changes_per_s);
  }
  // Without a speed output the planned spindle is the profile's.
  EXPECT_TRUE(planned_spindle(s).stops_path_on_change);
  const auto* note = m67.source_of("output.speed_word");
  ASSERT_NE(note, nullptr);
  EXPECT_TRUE(note->vendor);
  EXPECT_NE(note->text.find("m-code.html#mcode:m67"), std::string::npos);
  EXPECT_NE(note->text.find("analog-out"), std::string::npos);
}

TEST(BuiltinProfiles, EmbeddedBytesEqualTheFiles) {
  // The build embeds the files; a stale copy would show here.
  for (const auto& p : builtin_profiles()) {
    SCOPED_TRACE(std::string(p.name));
    EXPECT_EQ(p.text, read(fs::path(VCPOST_SOURCE_DIR) / p.path));
  }
}

TEST(BuiltinProfiles, MazakHasTheFiguresOfItsClass) {
  const auto m = builtin_profile("mazak-3axis");
  EXPECT_EQ(m.dialect(), Dialect::mazak);
  EXPECT_EQ(m.output_format(), OutputFormat::mazak);
  EXPECT_DOUBLE_EQ(m.spindle().n_max_rpm, 12000.0);
  EXPECT_DOUBLE_EQ(m.spindle().s_resolution_rpm, 1.0);  // integer S
  EXPECT_EQ(m.spindle().change_in_motion, SChangeInMotion::code);
  EXPECT_EQ(m.spindle().change_code, "G117");
  EXPECT_TRUE(m.output().high_speed_mode);        // G05 P2
  EXPECT_TRUE(m.output().geometry_compensation);  // G61.1
  EXPECT_DOUBLE_EQ(m.spindle().acceleration_rpm_per_s, 4000.0);
  EXPECT_DOUBLE_EQ(m.feed().rapid_mm_per_min, 42000.0);
  EXPECT_EQ(m.tool().default_teeth, 2);
}

// Issue 38: the TNC 640 of a DMC 105 V class machine. Its S changes only in
// a TOOL CALL S block of its own; no document says whether that block ends
// the look-ahead, so it is taken as a stop, placed where the path stops
// anyway or priced, and the note says it was searched for and not found.
TEST(BuiltinProfiles, HeidenhainTakesSInAToolCallOfItsOwn) {
  const auto h = builtin_profile("heidenhain-tnc640");
  EXPECT_EQ(h.dialect(), Dialect::heidenhain);
  EXPECT_EQ(h.output_format(), OutputFormat::heidenhain);
  EXPECT_EQ(h.spindle().change_in_motion, SChangeInMotion::own_block);
  EXPECT_TRUE(h.spindle().stops_path_on_change);
  EXPECT_EQ(h.spindle().s_in_feed, SInFeed::priced);
  EXPECT_DOUBLE_EQ(h.spindle().n_max_rpm, 18000.0);  // the A programs ask up to S17189
  EXPECT_DOUBLE_EQ(h.spindle().s_resolution_rpm, 1.0);
  EXPECT_DOUBLE_EQ(h.control().block_time_s, 0.0005);
  EXPECT_FALSE(h.output().cutter_compensation);  // CL paths are the tool centre: R0
  EXPECT_TRUE(h.source_of("spindle.change_in_motion")->vendor);
  const auto* stops = h.source_of("spindle.stops_path_on_change");
  EXPECT_FALSE(stops->vendor);
  EXPECT_NE(stops->text.find("M120 LOOK AHEAD"), std::string::npos) << stops->text;
  // `machines show` leaves out the G-code writer's keys, so its text loads.
  const std::string shown = profile_to_toml(h);
  EXPECT_EQ(shown.find("high_speed_mode"), std::string::npos);
  EXPECT_EQ(profile_from_toml(shown, "shown.toml").output_format(), OutputFormat::heidenhain);
}

TEST(ProfileLoading, HeidenhainRefusesCutterCompensationAndManualToolChange) {
  std::string text(kMinimal);
  text.replace(text.find("\"rs274ngc\""), 10, "\"heidenhain\"");
  text.replace(text.find("\"rs274ngc\""), 10, "\"heidenhain\"");
  EXPECT_EQ(profile_from_toml(text, "h.toml").dialect(), Dialect::heidenhain);
  for (const char* bad : {"cutter_compensation = true", "tool_change = \"manual\"",
                          "line_numbers = true", "tool_change_home = \"g28\""}) {
    SCOPED_TRACE(bad);
    try {
      profile_from_toml(text + "[output]\n" + bad + "\n", "h.toml");
      ADD_FAILURE() << "accepted";
    } catch (const ProfileError& e) {
      EXPECT_EQ(e.code(), Code::E5013) << e.what();
    }
  }
}

TEST(BuiltinProfiles, EveryKeyHasAStatedSource) {
  for (const auto& p : builtin_profiles()) {
    const auto profile = builtin_profile(p.name);
    for (const auto key : schema_keys()) {
      SCOPED_TRACE(std::string(p.name) + " " + std::string(key));
      const auto* note = profile.source_of(key);
      ASSERT_NE(note, nullptr);
      EXPECT_FALSE(note->text.empty());
    }
  }
  // The specific note wins over its table's; the kind is kept.
  const auto m = builtin_profile("mazak-3axis");
  const auto* n_max = m.source_of("spindle.n_max_rpm");
  ASSERT_NE(n_max, nullptr);
  EXPECT_EQ(n_max->key, "spindle.n_max_rpm");
  EXPECT_FALSE(n_max->vendor);
  EXPECT_EQ(m.source_of("control.block_time_s")->key, "control");
  const auto l = builtin_profile("linuxcnc-3axis");
  EXPECT_TRUE(l.source_of("machine.dialect")->vendor);
  EXPECT_FALSE(l.source_of("machine.name")->vendor);
}

TEST(BuiltinProfiles, ShippedBandIsWithinTwoPercentFrom300Rpm) {
  // Resolution plus hysteresis threshold: the most a block's S may sit under
  // its target where no limit binds. The issue asks for -2 % at most.
  for (const auto& p : builtin_profiles()) {
    const auto s = builtin_profile(p.name).spindle();
    for (double n = std::max(300.0, s.n_min_rpm); n <= s.n_max_rpm; n += 50.0) {
      const double band =
          s.s_resolution_rpm + std::max(s.min_change_rpm, s.min_change_percent / 100.0 * n);
      EXPECT_LE(band / n, 0.02 + 1e-12) << p.name << " at " << n << " rpm";
    }
  }
}

TEST(BuiltinProfiles, UnknownNameListsTheShippedOnes) {
  try {
    builtin_profile("mazak");
    FAIL() << "no error";
  } catch (const ProfileError& e) {
    EXPECT_EQ(e.code(), Code::E5009);
    EXPECT_NE(std::string(e.what()).find("mazak-3axis"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(is_builtin_profile("generic"));
  EXPECT_FALSE(is_builtin_profile("generic.toml"));
}

TEST(ProfileLoading, OptionalKeysTakeTheirDefaults) {
  // The smallest valid profile: [output] and the description may be absent.
  const std::string text = kMinimal;
  const auto p = profile_from_toml(text, "tiny.toml");
  EXPECT_EQ(p.description(), "");
  EXPECT_EQ(p.output().program_number, 1000);
  EXPECT_EQ(p.output().decimals, 4);
  EXPECT_EQ(p.spindle().change_in_motion, SChangeInMotion::own_block);
  EXPECT_DOUBLE_EQ(p.spindle().deceleration_rpm_per_s, 2.0);
  EXPECT_TRUE(p.sources().empty());
  EXPECT_EQ(p.source_of("spindle.n_min_rpm"), nullptr);
}

TEST(ProfileLoading, EveryBadFileGivesItsExpectedDiagnostic) {
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "tests/machines/bad";
  static const std::regex expect_re(R"(# expect (E\d{4}) (\d+):(\d+|\*) ([^\n]*))");
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string path = entry.path().string();
    SCOPED_TRACE(path);
    const std::string text = read(entry.path());
    std::smatch expect;
    ASSERT_TRUE(std::regex_search(text, expect, expect_re)) << "no '# expect' line";
    try {
      profile_from_toml(text, path);
      ADD_FAILURE() << "loaded without error";
    } catch (const ProfileError& e) {
      EXPECT_EQ(e.id(), expect[1].str());
      EXPECT_EQ(e.where().file, path);
      EXPECT_EQ(e.where().line, std::stoul(expect[2].str()));
      if (expect[3].str() != "*") {
        EXPECT_EQ(e.where().column, std::stoul(expect[3].str()));
      }
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path + ":" + expect[2].str() + ":", 0), 0u) << what;
      EXPECT_NE(what.find("error[" + expect[1].str() + "]"), std::string::npos) << what;
      EXPECT_NE(what.find(expect[4].str()), std::string::npos) << what;
    }
    ++count;
  }
  EXPECT_GE(count, 14);
}

TEST(ProfileLoading, StreamAndTextGiveTheSameProfile) {
  const auto& p = builtin_profiles().front();
  std::istringstream in{std::string(p.text)};
  const auto a = profile_from_stream(in, "x.toml");
  const auto b = profile_from_toml(p.text, "x.toml");
  EXPECT_EQ(a.name(), b.name());
  EXPECT_DOUBLE_EQ(a.spindle().n_max_rpm, b.spindle().n_max_rpm);
  EXPECT_EQ(a.sources().size(), b.sources().size());
}

}  // namespace
}  // namespace vcpost::machines
