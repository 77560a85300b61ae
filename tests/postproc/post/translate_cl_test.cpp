// `vcpost post` on APT CL data without --model: the CL is translated for the
// profile with its own speeds (a plain 3-axis post-processor), as the real
// binary does it; G-code and reports still need the model.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../cli_run_support.h"
#include "../temp_folder.h"

namespace vcpost::post {
namespace {

namespace fs = std::filesystem;
using testing::run_vcpost;

const std::string kSamples = (fs::path(VCPOST_SOURCE_DIR) / "samples").string();

TEST(TranslateCl, WithoutAModelTheClIsTranslatedWithItsOwnSpeeds) {
  testing::Folder folder;
  const std::string cl = "'" + kSamples + "/dome_raster_a0_ae3.cls'";
  const auto posted =
      run_vcpost("post " + cl + " --machine linuxcnc-3axis -o out.nc", folder.path());
  ASSERT_EQ(posted.exit_code, 0) << posted.err;
  EXPECT_NE(posted.err.find("no --model: the CL data is translated for linuxcnc-3axis with its "
                            "own speeds"),
            std::string::npos)
      << posted.err;
  // The CL's own S and F: verify finds the motion and not one speed changed.
  const auto verified =
      run_vcpost("verify " + cl + " out.nc --machine linuxcnc-3axis", folder.path());
  EXPECT_EQ(verified.exit_code, 0) << verified.err;
  EXPECT_NE(verified.out.find("(0 S words, 0 F words changed)"), std::string::npos) << verified.out;
}

// G-code without a model is posted with the normals from its toolpath
// (path_normals.h; PostWithoutModel compares it with the post with the
// model), with a report or without (the same program); CL data's S and
// its report need the model.
TEST(TranslateCl, GcodeWithoutModelPostsFromTheToolpathClSpeedsAndReportsNeedTheModel) {
  testing::Folder folder;
  const std::string nc = "'" + kSamples + "/dome_raster_a0_ae3.nc'";
  const std::string cl = "'" + kSamples + "/dome_raster_a0_ae3.cls'";
  auto r = run_vcpost("post " + nc + " --vc 120 --ap 0.3 -o posted.nc", folder.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("no --model: each point's normal from the toolpath: "), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("no gouge check, no cusp map"), std::string::npos) << r.err;
  r = run_vcpost("verify " + nc + " posted.nc", folder.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_vcpost("post " + nc + " --vc 120 -o out.nc", folder.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--ap: required"), std::string::npos) << r.err;
  r = run_vcpost("post " + nc + " --vc 120 --ap 0.3 -o reported.nc --report r.json", folder.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(testing::slurp(folder.path() / "reported.nc"),
            testing::slurp(folder.path() / "posted.nc"));
  r = run_vcpost("post " + cl + " -o out.nc --report r.json", folder.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--model: required (the report of CL data"), std::string::npos) << r.err;
  r = run_vcpost("post " + cl + " --model '" + kSamples + "/dome.step' --ap 0.3 -o out.nc",
                 folder.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--vc: required"), std::string::npos) << r.err;
  r = run_vcpost("post " + cl + " --model '" + kSamples + "/dome.step' --vc 120 -o out.nc",
                 folder.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--ap: required"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(folder.path() / "out.nc"));
}

}  // namespace
}  // namespace vcpost::post
