// `--model-transform` and `--stock` as a user runs them: a plane exported
// upside down posts once turned over (by steps or by a VERICUT project), a
// path 1.245 mm into the model is refused with the option that posts it,
// which then posts it; bad option text is refused with its reason. The shared
// Heidenhain VERICUT projects place their design STL as their BLK FORMs say.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../cli_run_support.h"
#include "../temp_folder.h"
#include "postproc/cli/model_placement.h"

namespace vcpost::testing {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The plane z = 0 over x, y in [-30, 30] with its normal down (-z): as a
// part exported turned over.
void write_plane_upside_down(const fs::path& path) {
  write(path,
        "solid plane\n"
        "facet normal 0 0 -1\nouter loop\nvertex -30 -30 0\nvertex -30 30 0\nvertex 30 30 0\n"
        "endloop\nendfacet\n"
        "facet normal 0 0 -1\nouter loop\nvertex -30 -30 0\nvertex 30 30 0\nvertex 30 -30 0\n"
        "endloop\nendfacet\nendsolid plane\n");
}

// A raster of a D10 ball's tip at height `z` over x, y in [-20, 20].
void write_raster(const fs::path& path, double z) {
  std::ostringstream out;
  out << "%\nG21 G90 G17 G94\nT1 M6\nS6000 M3\nF1500\nG0 X-20 Y-20 Z" << z + 5 << "\nG1 Z" << z
      << "\n";
  for (int pass = 0; pass <= 20; ++pass) {
    const double y = -20 + 2 * pass;
    out << "G1 Y" << y << "\nG1 X" << (pass % 2 == 0 ? 20 : -20) << "\n";
  }
  out << "G0 Z50\nM5\nM30\n%\n";
  write(path, out.str());
}

constexpr const char* kJob = "post part.nc --model plane.stl --tool ball:10 --vc 150 --ap 0.2 ";

TEST(PlacementCli, UpsideDownPlanePostsTurnedOverByStepsOrByAProject) {
  Folder work;
  write_plane_upside_down(work / "plane.stl");
  write_raster(work / "part.nc", 0);
  const CliOutcome as_exported = run_vcpost(std::string(kJob) + "-o out.nc", work.path());
  EXPECT_EQ(as_exported.exit_code, 2) << as_exported.err;
  const CliOutcome turned = run_vcpost(
      std::string(kJob) + "--model-transform rx=180 -o out.nc --summary-json s.json", work.path());
  ASSERT_EQ(turned.exit_code, 0) << turned.err;
  const auto summary = nlohmann::json::parse(slurp(work / "s.json"));
  // Every point on the plane touches (the plunge from 5 mm above is in the air).
  EXPECT_EQ(summary["points"]["gouging"], 0);
  EXPECT_GE(summary["points"]["touching"].get<int>(), 1700) << summary["points"];
  EXPECT_EQ(summary["inputs"]["model"]["description"], "2 triangles, placed by rx=180");

  // The same turn as a VERICUT project places it: the STL turned 180 about
  // X and lifted 100 on a stock whose program zero (NCS) is lifted 100 too.
  write(work / "setup.vcproject",
        "<VcProject>\n<Build>\n"
        "<Component Name=\"Stock\" Type=\"stock\">\n<Attach>Attach</Attach>\n"
        "<Position X=\"0\" Y=\"0\" Z=\"0\" />\n<Rotation I=\"0\" J=\"0\" K=\"0\" />\n"
        "</Component>\n"
        "<Component Name=\"Design\" Type=\"design\">\n<Attach>Stock</Attach>\n"
        "<Position X=\"0\" Y=\"0\" Z=\"0\" />\n<Rotation I=\"0\" J=\"0\" K=\"0\" />\n"
        "<STL Unit=\"millimeter\">\n<File>plane.stl</File>\n"
        "<Position X=\"0\" Y=\"0\" Z=\"100\" />\n<Rotation I=\"180\" J=\"0\" K=\"0\" />\n</STL>\n"
        "</Component>\n</Build>\n"
        "<CSystems>\n<CSystem Name=\"NCS\" Type=\"component\">\n<Attach>Stock</Attach>\n"
        "<Position X=\"0\" Y=\"0\" Z=\"100\" />\n<Rotation I=\"0\" J=\"0\" K=\"0\" />\n"
        "</CSystem>\n</CSystems>\n</VcProject>\n");
  const CliOutcome project = run_vcpost(
      std::string(kJob) + "--model-transform vcproject:setup.vcproject -o out2.nc", work.path());
  ASSERT_EQ(project.exit_code, 0) << project.err;
  EXPECT_EQ(slurp(work / "out2.nc"), slurp(work / "out.nc"));
}

TEST(PlacementCli, APathIntoTheModelNamesTheStockThatPostsIt) {
  Folder work;
  write_plane_upside_down(work / "plane.stl");
  write_raster(work / "part.nc", -1.245);
  const std::string job = std::string(kJob) + "--model-transform rx=180 ";
  const CliOutcome refused = run_vcpost(job + "-o out.nc", work.path());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("does not match the model"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("sit 1.245 mm into it: likely negative stock to leave in the CAM "
                             "(1.245 mm)? post with --stock=-1.245 (or --stock T1=-1.245)"),
            std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(work / "out.nc"));
  for (const char* stock : {"--stock=-1.245", "--stock T1=-1.245"}) {
    const CliOutcome posted =
        run_vcpost(job + stock + " -o out.nc --summary-json s.json", work.path());
    ASSERT_EQ(posted.exit_code, 0) << stock << ": " << posted.err;
    const auto summary = nlohmann::json::parse(slurp(work / "s.json"));
    EXPECT_EQ(summary["points"]["gouging"], 0) << stock;
    EXPECT_GE(summary["points"]["touching"].get<int>(), 1700) << stock;
    EXPECT_EQ(summary["sections"][0]["stock_mm"]["radial"], -1.245) << stock;
  }
}

TEST(PlacementCli, BadOptionTextIsRefusedWithItsReason) {
  Folder work;
  write_plane_upside_down(work / "plane.stl");
  write_raster(work / "part.nc", 0);
  const struct {
    std::string options, words;
  } cases[] = {
      {"--model-transform rz=ninety", "'rz=ninety': 'ninety' is not a number"},
      {"--model-transform matrix=2,0,0,0,0,2,0,0,0,0,2,0,0,0,0,1", "it scales or shears"},
      {"--model-transform vcproject:missing.vcproject", "cannot read 'missing.vcproject'"},
      {"--model-transform rx=180 --stock 0.1:abc", "'abc' is not a number"},
      {"--model-transform rx=180 --stock 0.1 --stock 0.2", "given twice for every tool"},
      {"--model-transform rx=180 --stock 0.2:0.1", "a ball has one allowance"},
      {"--model-transform rx=180 --stock=-5", "leaves no tool to touch the model"},
  };
  for (const auto& c : cases) {
    const CliOutcome r = run_vcpost(std::string(kJob) + c.options + " -o out.nc", work.path());
    EXPECT_EQ(r.exit_code, 2) << c.options;
    EXPECT_NE(r.err.find(c.words), std::string::npos) << c.options << ": " << r.err;
    EXPECT_FALSE(fs::exists(work / "out.nc")) << c.options;
  }
  write(work / "setup.vcproject", "<VcProject><Build></Build></VcProject>");
  const CliOutcome r = run_vcpost(
      std::string(kJob) + "--model-transform vcproject:setup.vcproject -o out.nc", work.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no component of Type=\"design\""), std::string::npos) << r.err;
}

TEST(PlacementCli, SharedHeidenhainProjectsPlaceTheirDesignStl) {
  const fs::path dir = fs::path(VCPOST_SHARED_DATA_DIR) / "corpus" / "heidenhain";
  if (!fs::exists(dir)) GTEST_SKIP() << "shared data absent: " << dir;
  // Set-up A: the STL turned -90 about Z, in place (STL and NCS both at Z 192.25).
  const auto a = cli::read_vcproject_placement(
      slurp(dir / "W5246NS01007A" / "W5246NS01007A.vcproject"), "A.vcproject");
  EXPECT_EQ(a.model_file, "W5246NS01007_design.stl");
  EXPECT_EQ(a.csystem, "NCS");
  const geometry::RigidTransform rz = geometry::parse_rigid_transform("rz=-90");
  EXPECT_LE((a.transform.rotation - rz.rotation).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE(a.transform.shift.norm(), 1e-9);
  // Set-up B: turned over (X -180, Z 180: x -> -x, z -> -z), the STL at
  // Z 217.5 against the NCS at Z 239.5: lowered 22 (its stock's top at 0).
  const auto b = cli::read_vcproject_placement(
      slurp(dir / "W5246NS01007B" / "W5246NS01007B.vcproject"), "B.vcproject");
  EXPECT_LE((b.transform.rotation - Eigen::Vector3d(-1, 1, -1).asDiagonal().toDenseMatrix())
                .cwiseAbs()
                .maxCoeff(),
            1e-12);
  EXPECT_NEAR(b.transform.shift.x(), 0, 1e-9);
  EXPECT_NEAR(b.transform.shift.y(), -1.916e-13, 1e-9);
  EXPECT_NEAR(b.transform.shift.z(), -22, 1e-9);
}

}  // namespace
}  // namespace vcpost::testing
