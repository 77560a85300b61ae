// Issue 15's first "done when", on the real data: every CL file of
// ../shared/data with an STL of the same name beside it (the SolidWorks CAM
// pairs basemach, Telemecanique-Tilt-Support2, Dem-target2, Teflon-gasket:
// drills, flat mills, peck cycles) posts whole with no --tool, as a user
// runs it. The output reads in LinuxCNC's rs274 to its end; its tool
// changes are the CL's LOAD/TOOL and LOADTL in order; every section whose
// tool is not a ball keeps its programmed speed (rs274's spindle speeds are
// the CL's SPINDL values in order) and every ball section is posted; and
// `vcpost verify` holds against the CL. The pairs hold no ball-end mill
// (their cutters read as drills and flat mills): tool_sections_test.cpp
// posts ball sections of CL input.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "../cldata/cl_support.h"
#include "../cli_run_support.h"
#include "../temp_folder.h"

namespace {

namespace fs = std::filesystem;
using vcpost::testing::CliOutcome;

const fs::path kShared = VCPOST_SHARED_DATA_DIR;

// The CL programs with a model: X.apt|.cls|.clsf beside X.stl|X.STL.
std::vector<std::pair<fs::path, fs::path>> cl_stl_pairs() {
  std::vector<std::pair<fs::path, fs::path>> pairs;
  for (const auto& entry : fs::recursive_directory_iterator(kShared)) {
    const fs::path& p = entry.path();
    const std::string ext = p.extension().string();
    if (ext != ".apt" && ext != ".cls" && ext != ".clsf") continue;
    for (const char* stl : {".stl", ".STL"}) {
      fs::path model = p;
      model.replace_extension(stl);
      if (fs::exists(model)) {
        pairs.emplace_back(p, model);
        break;
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// The numbers of `pattern`'s first group over `text`, in order.
std::vector<double> all(const std::string& text, const std::regex& pattern) {
  std::vector<double> out;
  for (std::sregex_iterator m(text.begin(), text.end(), pattern), end; m != end; ++m)
    out.push_back(std::stod((*m)[1].str()));
  return out;
}

// Runs of one value collapsed to one (a speed written again is no change).
std::vector<double> changes(std::vector<double> values) {
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

TEST(ClStlPairsPost, EveryPairPostsWholeWithoutTool) {
  if (!fs::is_directory(kShared)) GTEST_SKIP() << "shared data absent: " << kShared;
  const auto pairs = cl_stl_pairs();
  EXPECT_GE(pairs.size(), 4u);
  const bool rs274 = vcpost::cldata::testing::have_rs274();
  for (const auto& [cl, stl] : pairs) {
    SCOPED_TRACE(cl.string());
    const vcpost::testing::Folder work;
    const CliOutcome run = vcpost::testing::run_vcpost(
        "post '" + cl.string() + "' --model '" + stl.string() +
            "' --vc 120 --ap 0.3 --machine linuxcnc-3axis -o out.ngc --summary-json s.json",
        work.path());
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const std::string text = vcpost::testing::slurp(cl);

    // Every section decided; a ball posted, anything else kept.
    const auto summary = nlohmann::json::parse(vcpost::testing::slurp(work.path() / "s.json"));
    const std::regex load(R"((?:^|\n)\s*(?:LOADTL\s*/\s*|LOAD\s*/\s*TOOL\s*,\s*)(\d+))");
    const std::vector<double> loads = all(text, load);
    ASSERT_FALSE(loads.empty());
    ASSERT_EQ(summary["sections"].size(), loads.size());
    bool any_ball = false;
    for (std::size_t k = 0; k < loads.size(); ++k) {
      const auto& s = summary["sections"][k];
      EXPECT_EQ(s["tool_number"], static_cast<int>(loads[k])) << "section " << k;
      const bool ball = s["tool"]["shape"] == "ball";
      any_ball = any_ball || ball;
      EXPECT_EQ(s["posted"], ball) << "section " << k;
      if (!ball) {
        EXPECT_EQ(s["words_written"]["s"], 0) << "section " << k;
      }
    }

    // The motion of the CL, tool changes and speeds included.
    const CliOutcome verified = vcpost::testing::run_vcpost(
        "verify '" + cl.string() + "' out.ngc --machine linuxcnc-3axis", work.path());
    EXPECT_EQ(verified.exit_code, 0) << verified.out << verified.err;

    if (!rs274) continue;
    const auto transcript = vcpost::cldata::testing::run_rs274((work.path() / "out.ngc").string());
    ASSERT_TRUE(transcript);
    EXPECT_NE(transcript->find("PROGRAM_END()"), std::string::npos) << transcript->substr(0, 3000);
    EXPECT_EQ(all(*transcript, std::regex(R"(CHANGE_TOOL\((\d+)\))")), loads);
    if (!any_ball) {
      const std::regex spindl(R"((?:^|\n)\s*SPINDL\s*/\s*(?:RPM\s*,\s*)?([0-9.]+))");
      EXPECT_EQ(changes(all(*transcript, std::regex(R"(SET_SPINDLE_SPEED\(0, ([0-9.]+)\))"))),
                changes(all(text, spindl)));
    }
  }
}

}  // namespace
