// Issue 38 end to end on the shared hyperMILL program W5246NS01007A8.h
// (setup A, bull-nose D4.01 R0.5, 16,813 blocks): posted for the TNC 640
// with the design STL placed by --model-transform rz=-90, it gets TOOL CALL
// S blocks, its blocks stay numbered 1, 2, 3 ... to END PGM, vc holds
// within +-10 % after, and `vcpost verify` holds. The job leaves 0.5 mm
// (DR:0+0.5 in its name): --stock 0.5.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/postproc/cli_run_support.h"

namespace vcpost {
namespace {

namespace fs = std::filesystem;

const fs::path kSetupA = fs::path(VCPOST_SHARED_DATA_DIR) / "corpus" / "heidenhain";

TEST(KlartextPostCli, HyperMillFinishingProgramPostsAndVerifies) {
  const fs::path program = kSetupA / "W5246NS01007A" / "W5246NS01007A8.h";
  if (!fs::exists(program)) GTEST_SKIP() << "no shared data at " << kSetupA;
  const fs::path dir =
      fs::temp_directory_path() / ("vcpost_klartext_post_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const testing::CliOutcome post = testing::run_vcpost(
      "post " + program.string() + " --model " + (kSetupA / "W5246NS01007_design.stl").string() +
          " --model-transform rz=-90 --machine heidenhain-tnc640 --vc 150 --ap 0.15 --ae 1.9"
          " --stock 0.5 -o posted.h --summary-json summary.json",
      dir);
  ASSERT_EQ(post.exit_code, 0) << post.err;
  const std::string input = testing::slurp(program);
  const std::string output = testing::slurp(dir / "posted.h");

  // Block numbers 1, 2, ... to END PGM; the inserted blocks are bare TOOL
  // CALL S, and there are as many more blocks as were inserted.
  std::istringstream lines(output);
  std::size_t expected = 1, inserted = 0, count = 0;
  for (std::string line; std::getline(lines, line); ++count) {
    const std::size_t blank = line.find(' ');
    ASSERT_EQ(line.substr(0, blank), std::to_string(expected)) << line;
    ++expected;
    if (line.compare(blank + 1, 11, "TOOL CALL S") == 0) ++inserted;  // A8 has none of its own
  }
  EXPECT_GT(inserted, 0u);
  EXPECT_EQ(count, 16813u + inserted);
  EXPECT_NE(output.rfind(std::to_string(16813 + inserted) + " END PGM W5246NS01007A8 MM"),
            std::string::npos);

  const auto summary = nlohmann::json::parse(testing::slurp(dir / "summary.json"));
  EXPECT_EQ(summary["inputs"]["kind"], "heidenhain");
  EXPECT_EQ(summary["words_written"]["s"].get<std::size_t>(), inserted);  // the TOOL CALL kept
  EXPECT_DOUBLE_EQ(summary["after"]["within_10_percent"].get<double>(), 1.0);
  // The bull-nose's section touches the offset model (1,455 of 17,112
  // points on 2026-12-07; the rest sit about 0.1 mm off it).
  EXPECT_GT(summary["sections"][1]["points"]["touching"].get<int>(), 1000);

  const testing::CliOutcome verify = testing::run_vcpost(
      "verify " + program.string() + " posted.h --machine heidenhain-tnc640", dir);
  EXPECT_EQ(verify.exit_code, 0) << verify.err;
  EXPECT_NE(verify.out.find(std::to_string(inserted) + " TOOL CALL S blocks inserted"),
            std::string::npos)
      << verify.out;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vcpost
