// `vcpost verify` as a user runs it: exit 0 and the summary line when only
// S/F words differ, --changes and --json listings, exit 1 with positioned
// E71xx diagnostics (at most 20, then "... and K more"), exit 2 for input
// errors; a CL sample posted by `vcpost post` verifies.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../cli_run_support.h"

namespace {

namespace fs = std::filesystem;

using Outcome = vcpost::testing::CliOutcome;
using vcpost::testing::slurp;

const std::string kInput =
    "(finish)\nG21 G90 G17 G94\nT1 M6\nS12000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F800\nG1 X10.5 Y2\nM5\nM30\n";
const std::string kOutput =
    "(finish)\nG21 G90 G17 G94\nT1 M6\nS9870 M3\nG0 X0 Y0 Z5\nG1 Z-1 F750\nG1 X10.5 Y2 "
    "S9500\nM5\nM30\n";

class VerifyCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vcpost_verify_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }

  Outcome run(const std::string& arguments) const {
    return vcpost::testing::run_vcpost(arguments, dir_);
  }

  fs::path dir_;
};

TEST_F(VerifyCli, OnlySAndFChangedExitsZeroWithTheCounts) {
  write("in.nc", kInput);
  write("out.nc", kOutput);
  const Outcome r = run("verify in.nc out.nc");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "verified: only S and F words differ (2 S words, 1 F words changed)\n");
  EXPECT_EQ(r.err, "");
}

TEST_F(VerifyCli, ChangesListsEachWord) {
  write("in.nc", kInput);
  write("out.nc", kOutput);
  const Outcome r = run("verify in.nc out.nc --changes");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out,
            "4: S12000 -> S9870\n"
            "6: F800 -> F750\n"
            "7: + S9500\n"
            "verified: only S and F words differ (2 S words, 1 F words changed)\n");
}

TEST_F(VerifyCli, JsonResult) {
  write("in.nc", kInput);
  write("out.nc", kOutput);
  const Outcome r = run("verify in.nc out.nc --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["verified"], true);
  EXPECT_EQ(j["input_kind"], "gcode");
  EXPECT_EQ(j["s_changes"], 2);
  EXPECT_EQ(j["f_changes"], 1);
  EXPECT_EQ(j["motions"], 3);
  ASSERT_EQ(j["changes"].size(), 3u);
  EXPECT_EQ(j["changes"][2]["line"], 7);
  EXPECT_EQ(j["changes"][2]["column"], 13);
  EXPECT_EQ(j["changes"][2]["added"], true);
  EXPECT_TRUE(j["changes"][2]["old"].is_null());
  EXPECT_EQ(j["changes"][2]["new"], "S9500");
  EXPECT_TRUE(j["violations"].empty());
}

TEST_F(VerifyCli, DifferenceExitsOneWithThePlaceAndCode) {
  write("in.nc", kInput);
  std::string bad = kOutput;
  bad.replace(bad.find("X10.5"), 5, "X10.6");
  write("out.nc", bad);
  const Outcome r = run("verify in.nc out.nc");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("out.nc:7:4: error[E7103]: 'X10.5' changed to 'X10.6'"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("vcpost: error: verify: out.nc differs from in.nc in 1 place(s)"),
            std::string::npos)
      << r.err;
  const Outcome j = run("verify in.nc out.nc --json");
  EXPECT_EQ(j.exit_code, 1);
  const auto json = nlohmann::json::parse(j.out);
  EXPECT_EQ(json["verified"], false);
  EXPECT_EQ(json["violations"][0]["code"], "E7103");
  EXPECT_EQ(json["violations"][0]["line"], 7);
}

TEST_F(VerifyCli, AtMostTwentyDifferencesThenTheRestCounted) {
  std::string input, crlf;
  for (int k = 0; k < 30; ++k) input += "G1 X" + std::to_string(k) + " F100\n";
  for (char c : input) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  write("in.nc", input);
  write("out.nc", crlf);
  const Outcome r = run("verify in.nc out.nc");
  EXPECT_EQ(r.exit_code, 1);
  std::size_t lines = 0;
  for (std::size_t at = 0; (at = r.err.find("error[E7102]", at)) != std::string::npos; ++at)
    ++lines;
  EXPECT_EQ(lines, 20u);
  EXPECT_NE(r.err.find("... and 10 more\n"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("out.nc:1:11: error[E7102]: line ends with CRLF where the input has LF"),
            std::string::npos)
      << r.err;
}

TEST_F(VerifyCli, InputErrorsExitTwo) {
  write("in.nc", kInput);
  Outcome r = run("verify in.nc missing.nc");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'missing.nc': cannot open the program"), std::string::npos) << r.err;
  write("arc.nc", "G1 X1 F100\nG2 X2\nM30\n");
  r = run("verify arc.nc arc.nc");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("arc.nc:2:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("error[E1501]"), std::string::npos) << r.err;
  r = run("verify in.nc in.nc --dialect klingon");
  EXPECT_EQ(r.exit_code, 2);
}

TEST_F(VerifyCli, KlartextInputErrorNamesItsFile) {
  // Block 4's F is over the reader's 1e12 limit at its 13th digit, column 22.
  const std::string bad =
      "1 BEGIN PGM T MM\r\n2 TOOL CALL 5 Z S2500\r\n3 L X+0 Y+0 Z+5 R0 FMAX M3\r\n"
      "4 L Z-1 F3000000000000\r\n5 END PGM T MM\r\n";
  write("bad.h", bad);
  const Outcome r = run("verify bad.h bad.h");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.substr(0, r.err.find('\n')),
            "vcpost: error: bad.h:4:22: error[E3303]: number too large")
      << r.err;
}

TEST_F(VerifyCli, HelpTeachesTheExitCodes) {
  const Outcome r = run("verify --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("1 differences found"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2 usage or input error"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--changes"), std::string::npos);
}

TEST_F(VerifyCli, ClSamplePostedByTheBinaryVerifies) {
  const fs::path samples = fs::path(VCPOST_SOURCE_DIR) / "samples";
  const std::string cl = (samples / "dome_raster_a0_ae3.cls").string();
  const Outcome posted =
      run("post '" + cl + "' --model '" + (samples / "dome.step").string() +
          "' --tool ball:10 --vc 120 --ap 0.3 --machine mazak-3axis -o posted.nc");
  ASSERT_EQ(posted.exit_code, 0) << posted.err;
  const Outcome r = run("verify '" + cl + "' posted.nc --machine mazak-3axis");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("verified: only S and F words differ (", 0), 0u) << r.out;
  EXPECT_NE(r.out.find(" motions match the CL data\n"), std::string::npos) << r.out;
}

}  // namespace
