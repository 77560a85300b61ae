// Every program of samples/ (G-code and CL, as listed in the folder) posts
// with no warning, as a new user runs the README's demo on them: `vcpost
// post --strict` (exit 1 on a gouge, a cutting point off the model or a
// missing end) exits 0 and prints no "warning". The samples' moves stay
// within the generator's chord tolerance, half the default contact
// tolerance (samplegen_test.cpp), and approach by rapid.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

#include "../cli_run_support.h"
#include "../temp_folder.h"

namespace {

namespace fs = std::filesystem;
using vcpost::testing::CliOutcome;

TEST(SamplesPostClean, EveryBundledSamplePostsWithoutAWarning) {
  const fs::path samples = fs::path(VCPOST_SOURCE_DIR) / "samples";
  const vcpost::testing::Folder work;
  // The part of a program is its stem's first word; its ball and the
  // demo's cut data (samples/README.md, scripts/demo.sh).
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
            "' --tool " + part->second.tool + " --vc 120 --ap " + part->second.ap +
            " --machine mazak-3axis --strict -o out.nc",
        work.path());
    ASSERT_NE(run.exit_code, -1) << run.err;
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.err.find("warning"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find(" points, "), std::string::npos) << run.err;  // it did post
    ++posted;
  }
  EXPECT_EQ(posted, 2 * truths);  // every program, in both forms
  EXPECT_GE(truths, 13);
}

}  // namespace
