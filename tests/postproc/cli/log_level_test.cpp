// The levels of the command line's messages (postproc/cli/log.h): on the
// wavy sample the default prints the end-of-run line and -v adds one
// "vcpost: debug:" line per stage with its time and counts before it; on
// the cylinder sample, whose lifted points are a warning, --log-level
// warning prints only the warning and -q nothing.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "tests/postproc/cli_run_support.h"
#include "tests/postproc/temp_folder.h"

namespace {

using vcpost::testing::run_vcpost;

const std::string kSamples = std::string(VCPOST_SOURCE_DIR) + "/samples/";
const std::string kPost = "post " + kSamples + "wavy_raster_a0_ae2.nc --model " + kSamples +
                          "wavy.step --vc 120 --ap 0.3 -o out.nc ";

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::size_t count_starting(const std::vector<std::string>& lines, const std::string& start) {
  std::size_t n = 0;
  for (const std::string& line : lines) n += line.rfind(start, 0) == 0 ? 1 : 0;
  return n;
}

TEST(LogLevel, DebugAddsTheStagesAndTheOtherLevelsDropLines) {
  vcpost::testing::Folder folder;
  const auto plain = run_vcpost(kPost, folder.path());
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const auto lines = lines_of(plain.err);
  ASSERT_EQ(lines.size(), 1U) << plain.err;
  EXPECT_EQ(lines[0].rfind("vcpost: 8704 points, ", 0), 0U) << lines[0];

  const auto debug = run_vcpost(kPost + "-v", folder.path());
  ASSERT_EQ(debug.exit_code, 0) << debug.err;
  const auto debug_lines = lines_of(debug.err);
  // The stages, in order, then the default's lines unchanged.
  const std::vector<std::string> stages = {"vcpost: debug: program ",
                                           "vcpost: debug: machine profile generic: ",
                                           "vcpost: debug: model ", "vcpost: debug: posted in "};
  std::size_t at = 0;
  for (const std::string& stage : stages) {
    while (at < debug_lines.size() && debug_lines[at].rfind(stage, 0) != 0) ++at;
    ASSERT_LT(at, debug_lines.size()) << stage << " missing or out of order:\n" << debug.err;
  }
  EXPECT_NE(debug_lines[at].find(": 8704 points (8704 touching, 0 gouging, 0 in the air)"),
            std::string::npos)
      << debug_lines[at];
  EXPECT_GE(count_starting(debug_lines, "vcpost: debug: posting: "), 1U);
  EXPECT_EQ(debug_lines.back(), lines.back());
  EXPECT_EQ(debug.err.substr(debug.err.size() - plain.err.size()), plain.err);
  EXPECT_EQ(run_vcpost(kPost + "--log-level debug", folder.path()).err.size(), debug.err.size());

  // Points lifted off the cylinder: a warning after the end-of-run lines.
  const std::string lifted = "post " + kSamples + "cylinder_r100_ae0.5_a45.nc --model " + kSamples +
                             "cylinder.step --tool ball:10 --vc 120 --ap 0.3 "
                             "--machine mazak-3axis -o out.nc ";
  const auto warned = run_vcpost(lifted, folder.path());
  ASSERT_EQ(warned.exit_code, 0) << warned.err;
  const auto warned_lines = lines_of(warned.err);
  const std::size_t warnings = count_starting(warned_lines, "vcpost: warning: ");
  ASSERT_GE(warnings, 1U) << warned.err;
  ASSERT_GT(warned_lines.size(), warnings) << warned.err;
  const auto only_warnings = run_vcpost(lifted + "--log-level warning", folder.path());
  EXPECT_EQ(only_warnings.exit_code, 0);
  const auto kept = lines_of(only_warnings.err);
  EXPECT_EQ(kept.size(), warnings) << only_warnings.err;
  EXPECT_EQ(count_starting(kept, "vcpost: warning: "), warnings) << only_warnings.err;
  EXPECT_EQ(run_vcpost(lifted + "-q", folder.path()).err, "");
}

}  // namespace
