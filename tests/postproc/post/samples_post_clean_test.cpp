// Every program of samples/ (G-code and CL, as listed in the folder) posts
// with no warning, as a new user runs the README's demo on them: `vcpost
// post --strict` (exit 1 on a gouge, a cutting point off the model or a
// missing end) exits 0 and prints no "warning". The samples' moves stay
// within the generator's chord tolerance, half the default contact
// tolerance (samplegen_test.cpp), and approach by rapid.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(SamplesPostClean, EveryBundledSamplePostsWithoutAWarning) {
  const fs::path samples = fs::path(VCPOST_SOURCE_DIR) / "samples";
  const fs::path work =
      fs::temp_directory_path() / ("vcpost_samples_clean_" + std::to_string(::getpid()));
  fs::create_directories(work);
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
    const fs::path err = work / "err";
    const std::string command = std::string(VCPOST_BINARY) + " post '" + file.string() +
                                "' --model '" + (samples / (part->first + ".step")).string() +
                                "' --tool " + part->second.tool + " --vc 120 --ap " +
                                part->second.ap + " --machine mazak-3axis --strict -o '" +
                                (work / "out.nc").string() + "' 2>'" + err.string() + "'";
    const int status = std::system(command.c_str());
    const std::string stderr_text = read(err);
    ASSERT_TRUE(WIFEXITED(status)) << stderr_text;
    EXPECT_EQ(WEXITSTATUS(status), 0) << stderr_text;
    EXPECT_EQ(stderr_text.find("warning"), std::string::npos) << stderr_text;
    EXPECT_NE(stderr_text.find(" points, "), std::string::npos) << stderr_text;  // it did post
    ++posted;
  }
  fs::remove_all(work);
  EXPECT_EQ(posted, 2 * truths);  // every program, in both forms
  EXPECT_GE(truths, 13);
}

}  // namespace
