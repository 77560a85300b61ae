// `vcpost moves` refuses a feed move whose time is undefined as `vcpost post`
// does (issue 42: a CL GOTO in feed before any FEDRAT passed `moves`): the
// same code and file:line:col from both, on the real binary.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tests/postproc/cli_run_support.h"
#include "tests/postproc/temp_folder.h"

namespace vcpost::cli {
namespace {

TEST(MovesTiming, FeedBeforeAnyFedratIsRefusedAsPostRefusesIt) {
  vcpost::testing::Folder dir;
  std::ofstream(dir / "nofeed.cl", std::ios::binary)
      << "UNITS/MM\nGOTO/0,0,10\nGOTO/10,0,10\nFEDRAT/MMPM,500\nGOTO/20,0,10\nEND\n";
  const std::string expected = "nofeed.cl:3:1: error[E6101]: feed move with no feed rate in effect";
  const auto moves = vcpost::testing::run_vcpost("moves nofeed.cl", dir.path());
  EXPECT_EQ(moves.exit_code, 2);
  EXPECT_NE(moves.err.find(expected), std::string::npos) << moves.err;
  const auto post =
      vcpost::testing::run_vcpost("post nofeed.cl --machine linuxcnc-3axis -o out.ngc", dir.path());
  EXPECT_EQ(post.exit_code, 2);
  EXPECT_NE(post.err.find(expected), std::string::npos) << post.err;
}

TEST(MovesTiming, PerRevolutionFeedWithTheSpindleStoppedIsRefused) {
  vcpost::testing::Folder dir;
  std::ofstream(dir / "g95.ngc", std::ios::binary) << "G21 G95 F0.1\nG1 X10\nM2\n";
  const auto moves = vcpost::testing::run_vcpost("moves g95.ngc", dir.path());
  EXPECT_EQ(moves.exit_code, 2);
  EXPECT_NE(moves.err.find("g95.ngc:2:1: error[E6103]"), std::string::npos) << moves.err;
}

}  // namespace
}  // namespace vcpost::cli
