// `vcpost post` on a whole program with two tools, as a user runs it: the
// shipped dome raster cut first by a flat end mill T1, then by a ball-end
// mill T2, the tools named in Fusion 360 comments or on the command line
// or in a tools file. T1's bytes stay, T2's S words are rewritten, the
// posted program verifies, the summary lists both sections.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

namespace {

namespace fs = std::filesystem;

const std::string kSamples = std::string(VCPOST_SOURCE_DIR) + "/samples/";

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

int run(const std::string& arguments) {
  const std::string command = std::string(VCPOST_BINARY) + " " + arguments;
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class ToolSectionsCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vcpost_tools_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The sample's moves (from its first motion to its M5) twice, behind
  // T1 M6 and T2 M6, with `header` (tool comments) on top.
  fs::path two_tools(const std::string& header) {
    const std::string sample = read(kSamples + "dome_raster_a0_ae3.nc");
    const std::size_t begin = sample.find("G0 Z50.000000\n");
    const std::size_t end = sample.find("M5\n");
    const std::string moves = sample.substr(begin, end - begin);
    const fs::path path = dir_ / "two.nc";
    std::ofstream(path, std::ios::binary) << "%\n"
                                          << header << "G21 G90 G17 G94 G40\nT1 M6\nS4800 M3\n"
                                          << moves << "M5\nT2 M6\nS4800 M3\n"
                                          << moves << "M5\nM30\n%\n";
    return path;
  }

  // Posts `program` with `options`; expects T1 kept, T2 posted.
  void expect_t1_kept_t2_posted(const fs::path& program, const std::string& options) {
    const fs::path out = dir_ / "two.out.nc", summary = dir_ / "s.json", err = dir_ / "err";
    ASSERT_EQ(run("post " + program.string() + " --model " + kSamples +
                  "dome.step --vc 120 --ap 0.3 --machine mazak-3axis " + options + " -o " +
                  out.string() + " --summary-json " + summary.string() + " 2>" + err.string()),
              0)
        << read(err);
    const std::string in = read(program), posted = read(out);
    const std::size_t t2 = in.find("T2 M6");
    EXPECT_EQ(posted.substr(0, t2), in.substr(0, t2));  // T1 byte for byte
    EXPECT_NE(posted, in);
    const auto s = nlohmann::json::parse(read(summary));
    ASSERT_EQ(s["sections"].size(), 2u);
    const auto& t1 = s["sections"][0];
    const auto& t2s = s["sections"][1];
    EXPECT_EQ(t1["tool_number"], 1);
    EXPECT_EQ(t1["tool"]["shape"], "flat");
    EXPECT_EQ(t1["posted"], false);
    EXPECT_EQ(t1["words_written"]["s"], 0);
    EXPECT_EQ(t2s["tool_number"], 2);
    EXPECT_EQ(t2s["tool"]["shape"], "ball");
    EXPECT_EQ(t2s["posted"], true);
    EXPECT_GT(t2s["words_written"]["s"].get<int>(), 0);
    EXPECT_EQ(t2s["words_written"]["s"], s["words_written"]["s"]);
    EXPECT_EQ(s["inputs"]["tool"], "ball:10");
    // The terminal lists both sections.
    const std::string messages = read(err);
    EXPECT_NE(messages.find("T1 flat D10.000"), std::string::npos) << messages;
    EXPECT_NE(messages.find("T2 ball D10.000"), std::string::npos) << messages;
    // Only S words differ, and the motion reads the same.
    EXPECT_EQ(run("verify " + program.string() + " " + out.string() +
                  " --machine mazak-3axis >/dev/null 2>&1"),
              0);
  }

  fs::path dir_;
};

TEST_F(ToolSectionsCli, FusionCommentsWithoutTool) {
  const fs::path program = two_tools(
      "(T1 D=10. CR=0. - ZMIN=-5. - flat end mill)\n(T2 D=10. CR=5. - ZMIN=-5. - ball end mill)\n");
  expect_t1_kept_t2_posted(program, "");
  const auto s = nlohmann::json::parse(read(dir_ / "s.json"));
  EXPECT_EQ(s["sections"][1]["tool"]["source"], "comment");
  EXPECT_EQ(s["sections"][1]["tool"]["where"], program.string() + ":3");
}

TEST_F(ToolSectionsCli, ToolsPerNumberOnTheCommandLine) {
  expect_t1_kept_t2_posted(two_tools(""), "--tool T1=flat:10 --tool T2=ball:10");
}

TEST_F(ToolSectionsCli, ToolsFile) {
  std::ofstream(dir_ / "shop.toml") << "[[tool]]\nnumber = 1\nshape = \"flat\"\ndiameter = 10\n\n"
                                       "[[tool]]\nnumber = 2\nshape = \"ball\"\ndiameter = 10\n";
  expect_t1_kept_t2_posted(two_tools(""), "--tools " + (dir_ / "shop.toml").string());
  const auto s = nlohmann::json::parse(read(dir_ / "s.json"));
  EXPECT_EQ(s["sections"][1]["tool"]["source"], "tools file");
}

// --adjust-feed with --fz: each section's F is fz * z * S with its own
// tool's teeth z. Two ball-end mills over the same raster, T1 with teeth = 2
// in the tools file (beating --teeth 4), T2 with none (so --teeth 4). On
// every feed move of the posted program, the F in effect (mazak-3axis
// writes whole mm/min, rounded down) satisfies 0 <= fz*z*S - F < 1 for the
// S in effect: fz = F/(z*S) = 0.02 mm within one F step, per tool.
TEST_F(ToolSectionsCli, AdjustFeedTakesEachToolsTeeth) {
  std::ofstream(dir_ / "shop.toml") << "[[tool]]\nnumber = 1\nshape = \"ball\"\ndiameter = 10\n"
                                       "teeth = 2\n\n"
                                       "[[tool]]\nnumber = 2\nshape = \"ball\"\ndiameter = 10\n";
  const fs::path program = two_tools(""), out = dir_ / "two.out.nc", err = dir_ / "err";
  ASSERT_EQ(run("post " + program.string() + " --model " + kSamples +
                "dome.step --vc 120 --ap 0.3 --machine mazak-3axis --tools " +
                (dir_ / "shop.toml").string() + " --adjust-feed --fz 0.02 --teeth 4 -o " +
                out.string() + " 2>" + err.string()),
            0)
      << read(err);
  const double fz = 0.02;
  std::istringstream lines(read(out));
  std::string line;
  int teeth = 0, mode = -1;
  double s = 0, f = 0;
  std::map<int, int> checked;  // teeth -> feed moves checked
  while (std::getline(lines, line)) {
    if (line == "T1 M6" || line == "T2 M6") {
      teeth = line == "T1 M6" ? 2 : 4;
      f = 0;
      continue;
    }
    bool moves = false;
    for (std::size_t k = 0; k < line.size(); ++k) {
      const char c = line[k];
      if (c == 'X' || c == 'Y' || c == 'Z') moves = true;
      if (c != 'G' && c != 'S' && c != 'F') continue;
      const double value = std::strtod(line.c_str() + k + 1, nullptr);
      if (c == 'G' && (value == 0 || value == 1)) mode = static_cast<int>(value);
      if (c == 'S') s = value;
      if (c == 'F') f = value;
    }
    if (teeth == 0 || mode != 1 || !moves || f == 0) continue;
    const double by_hand = fz * teeth * s;
    EXPECT_GE(by_hand - f, 0.0) << line;
    EXPECT_LT(by_hand - f, 1.0) << line;
    ++checked[teeth];
  }
  // Every feed move of both sections (2,747 each in the raster).
  EXPECT_GT(checked[2], 2000);
  EXPECT_EQ(checked[2], checked[4]);
}

// PyCAM's own program (../shared/data/corpus/gcode/PyCAM_tiny_cat_outline.ngc)
// posts with no --tool: its settings block names a CylindricalCutter of
// radius 0.79375 mm, read as T1 flat D1.5875 and kept byte for byte.
TEST_F(ToolSectionsCli, PycamProgramNamesItsToolInItsSettings) {
  const fs::path program =
      fs::path(VCPOST_SHARED_DATA_DIR) / "corpus" / "gcode" / "PyCAM_tiny_cat_outline.ngc";
  if (!fs::exists(program)) GTEST_SKIP() << "shared data absent: " << program;
  const fs::path out = dir_ / "cat.ngc", summary = dir_ / "s.json", err = dir_ / "err";
  ASSERT_EQ(
      run("post " + program.string() + " --model " + kSamples + "wavy.step --vc 120 --ap 0.3 -o " +
          out.string() + " --summary-json " + summary.string() + " 2>" + err.string()),
      0)
      << read(err);
  EXPECT_EQ(read(out), read(program));
  const auto s = nlohmann::json::parse(read(summary));
  ASSERT_EQ(s["sections"].size(), 1u);
  const auto& tool = s["sections"][0]["tool"];
  EXPECT_EQ(s["sections"][0]["tool_number"], 1);
  EXPECT_EQ(tool["shape"], "flat");
  EXPECT_DOUBLE_EQ(tool["diameter"].get<double>(), 1.5875);
  EXPECT_EQ(tool["source"], "comment");
  EXPECT_EQ(tool["where"], program.string() + ":26");
  EXPECT_EQ(s["sections"][0]["posted"], false);
}

TEST_F(ToolSectionsCli, NoToolAnywhereIsAUsageError) {
  const fs::path err = dir_ / "err";
  EXPECT_EQ(
      run("post " + two_tools("").string() + " --model " + kSamples +
          "dome.step --vc 120 --ap 0.3 -o " + (dir_ / "o.nc").string() + " 2>" + err.string()),
      2);
  EXPECT_NE(read(err).find("--tool: required"), std::string::npos) << read(err);
  EXPECT_FALSE(fs::exists(dir_ / "o.nc"));
}

TEST_F(ToolSectionsCli, BadToolOptionsExit2) {
  const std::string job = two_tools("").string() + " --model " + kSamples +
                          "dome.step --ap 0.3 -o " + (dir_ / "o.nc").string() + " 2>" +
                          (dir_ / "err").string();
  EXPECT_EQ(run("post " + job + " --vc 120 --tool T1=cone:10"), 2);
  EXPECT_NE(read(dir_ / "err").find("unknown shape 'cone'"), std::string::npos);
  EXPECT_EQ(run("post " + job + " --vc T2=0"), 2);
  EXPECT_NE(read(dir_ / "err").find("--vc 'T2=0': must be > 0"), std::string::npos);
  std::ofstream(dir_ / "bad.toml") << "[[tool]]\nnumber = 1\nshape = \"ball\"\n";
  EXPECT_EQ(run("post " + job + " --vc 120 --tools " + (dir_ / "bad.toml").string()), 2);
  EXPECT_NE(read(dir_ / "err").find("bad.toml:1:1: error[E1604]"), std::string::npos)
      << read(dir_ / "err");
  EXPECT_FALSE(fs::exists(dir_ / "o.nc"));
}

}  // namespace
