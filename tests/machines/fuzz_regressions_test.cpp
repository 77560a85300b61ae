// Profiles the fuzzer found (fuzz/regressions/profile_fuzz/), replayed
// through the ordinary build with the fuzz target's driver
// (fuzz/profile_driver.h): each must load with its documented outcome, and
// a valid one must survive its own TOML round trip (profile_to_toml, then
// profile_from_toml, gives the same text). Expected outcomes worked out by
// hand from each input (comments).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include "fuzz/profile_driver.h"
#include "machines/profile.h"

namespace vcpost::fuzz {
namespace {

namespace fs = std::filesystem;

const fs::path kFolder = fs::path(VCPOST_SOURCE_DIR) / "fuzz" / "regressions" / "profile_fuzz";

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const std::map<std::string, std::string> kCases = {
    // A [sources] note with a form feed ("\f" escape): written back as a
    // comment, where TOML allows no control character, so the written
    // profile did not load. Notes are one line of text: E5008.
    {"note_form_feed.toml", "E5008"},
    // A note with "\n" escapes: the written comment ended at the line break
    // and the rest ("[spindle] n_max_rpm = 99999") became TOML. E5008.
    {"note_line_break.toml", "E5008"},
    // A description with DEL ("\u007F"), valid TOML: it was written back
    // unescaped, which TOML forbids. Loads, and now round-trips: ok.
    {"description_del.toml", "ok"},
    // block_time_s = -0.0 (>= 0, valid) was written back as "-0", which
    // TOML reads as the integer 0, written "0": the text changed. ok now.
    {"negative_zero.toml", "ok"},
};

TEST(FuzzRegressions, ProfilesGiveTheirDocumentedOutcome) {
  for (const auto& [name, expected] : kCases) {
    const fs::path path = kFolder / name;
    ASSERT_TRUE(fs::is_regular_file(path)) << path;
    EXPECT_EQ(run_profile(read_file(path)), expected) << name;
  }
}

// The message names the note's key and its place in the file.
TEST(FuzzRegressions, ControlCharacterInANoteIsNamed) {
  try {
    machines::profile_from_toml(read_file(kFolder / "note_line_break.toml"), "p.toml");
    FAIL() << "loaded";
  } catch (const machines::ProfileError& e) {
    EXPECT_EQ(e.code(), Code::E5008);
    EXPECT_EQ(e.where().line, 44u);
    EXPECT_NE(std::string(e.what()).find("'sources.\"feed\"' must be one line of text"),
              std::string::npos)
        << e.what();
  }
}

// The DEL character is kept through the round trip (escaped, not dropped).
TEST(FuzzRegressions, DescriptionKeepsItsDelCharacter) {
  const auto profile =
      machines::profile_from_toml(read_file(kFolder / "description_del.toml"), "p.toml");
  EXPECT_EQ(profile.description(), "cautious\x7flimits");
  const std::string text = machines::profile_to_toml(profile);
  EXPECT_NE(text.find(R"(description = "cautious\u007flimits")"), std::string::npos) << text;
  EXPECT_EQ(machines::profile_from_toml(text, "again.toml").description(), "cautious\x7flimits");
}

// Negative zero is written as "0" and reads back as zero.
TEST(FuzzRegressions, NegativeZeroIsWrittenAsZero) {
  const auto profile =
      machines::profile_from_toml(read_file(kFolder / "negative_zero.toml"), "p.toml");
  EXPECT_EQ(profile.control().block_time_s, 0.0);
  const std::string text = machines::profile_to_toml(profile);
  EXPECT_NE(text.find("block_time_s = 0 "), std::string::npos) << text;
  EXPECT_EQ(text.find("-0"), std::string::npos) << text;
}

// A saved input without an expected outcome would never be checked.
TEST(FuzzRegressions, EverySavedProfileHasACase) {
  for (const auto& entry : fs::directory_iterator(kFolder))
    EXPECT_TRUE(kCases.contains(entry.path().filename().string()))
        << entry.path().filename() << " has no case";
}

}  // namespace
}  // namespace vcpost::fuzz
