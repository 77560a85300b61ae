// Every program of samples/ (G-code and CL, as listed in the folder) posts
// with no warning, as a new user runs the README's demo on them: `vcpost
// post --strict` (exit 1 on a gouge, a cutting point off the model or a
// missing end) with no --tool exits 0 and prints no "warning". The programs
// name their ball themselves: the G-code in a Fusion 360 comment, the CL in
// CUTTER/, read as the part's ball. The samples' moves stay
// within the generator's chord tolerance, half the default contact
// tolerance (samplegen_test.cpp), and approach by rapid.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "../cli_run_support.h"
#include "../temp_folder.h"

namespace {

namespace fs = std::filesystem;
using vcpost::testing::CliOutcome;

TEST(SamplesPostClean, EveryBundledSamplePostsWithoutAWarning) {
  const fs::path samples = fs::path(VCPOST_SOURCE_DIR) / "samples";
  const vcpost::testing::Folder work;
  // The part of a program is its stem's first word; its ball (as
  // parts.cpp makes it) and the demo's cut data (samples/README.md,
  // scripts/demo.sh).
  struct Job {
    const char* tool;
    const char* ap;
  };
  const std::map<std::string, Job> parts = {
      {"wavy", {"ball:10", "0.3"}}, {"cylinder", {"ball:12", "0.2"}}, {"dome", {"ball:10", "0.3"}}};
  int posted = 0, truths = 0;
  for (const auto& entry : fs::directory_iterator(samples)) {
    const fs::path file = entry.path();
    const std::string name = file.filename().string();
    if (name.ends_with(".truth.csv")) ++truths;
    if (file.extension() != ".nc" && file.extension() != ".cls") continue;
    SCOPED_TRACE(name);
    const auto part = parts.find(name.substr(0, name.find('_')));
    ASSERT_NE(part, parts.end()) << "a sample of an unknown part";
    const CliOutcome run = vcpost::testing::run_vcpost(
        "post '" + file.string() + "' --model '" + (samples / (part->first + ".step")).string() +
            "' --vc 120 --ap " + part->second.ap +
            " --machine mazak-3axis --strict -o out.nc --summary-json s.json",
        work.path());
    ASSERT_NE(run.exit_code, -1) << run.err;
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.err.find("warning"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find(" points, "), std::string::npos) << run.err;  // it did post
    const auto summary = nlohmann::json::parse(vcpost::testing::slurp(work.path() / "s.json"));
    EXPECT_EQ(summary["inputs"]["tool"], part->second.tool);
    ASSERT_EQ(summary["sections"].size(), 1u);
    EXPECT_EQ(summary["sections"][0]["tool"]["source"],
              file.extension() == ".nc" ? "comment" : "CL record");
    ++posted;
  }
  EXPECT_EQ(posted, 2 * truths);  // every program, in both forms
  EXPECT_GE(truths, 13);
}

}  // namespace
