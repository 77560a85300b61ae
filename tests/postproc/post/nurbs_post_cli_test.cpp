// `vcpost post` on a program with a G5.2/G5.3 NURBS curve (the real
// binary): the curve's blocks pass through byte for byte, the S words
// around it are rewritten, and the curve runs at the speed its steepest
// point asks for, worked by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "tests/postproc/cli_run_support.h"
#include "tests/postproc/temp_folder.h"

namespace vcpost::post {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// The S in effect on each line (the last S word at or before it; the
// program's comments are whole lines).
std::vector<double> s_in_effect(const std::vector<std::string>& lines) {
  std::vector<double> out;
  double s = 0;
  for (const auto& line : lines) {
    const auto at = line.find('S');
    if (at != std::string::npos && !line.starts_with("(")) s = std::stod(line.substr(at + 1));
    out.push_back(s);
  }
  return out;
}

// samples/cylinder.step: radius 100 about the x axis, top line at z = 100.
// Flat passes on the top, then a quadratic NURBS over the cylinder in the
// YZ plane: the ball's (D12) tip path from 0 to 30 deg, a circle of radius
// 106 about (y, z) = (0, -6) (its centre on radius 106), written exactly
// with the middle weight cos 15 deg; then passes along x at 30 deg.
std::string program() {
  std::ostringstream p;
  p << "(flat passes, a NURBS arc over the cylinder in the YZ plane, passes at 30 deg)\n"
       "G21 G90 G17 G94 G40\nT1 M6\nS4000 M3\nG0 Z120\nG0 X0 Y0\nG0 Z100\nG1 X40 F800\n";
  for (int k = 0; k < 6; ++k) p << "Y0.5 Z99.998821\nX0\nY0 Z100\nX40\n";
  p << "X0\nG19\nG5.2 Y28.402397 Z100 P0.9659258263\nY53 Z85.799275 P1\nG5.3\nG17\n";
  for (int k = 0; k < 6; ++k) p << "G1 X40\nX0\n";
  p << "G0 Z120\nM30\n";
  return p.str();
}

TEST(NurbsPost, CurvePassesThroughAndRunsAtItsSteepestPointsSpeed) {
  const fs::path cylinder = fs::path(VCPOST_SOURCE_DIR) / "samples/cylinder.step";
  vcpost::testing::Folder dir;
  const std::string input = program();
  std::ofstream(dir / "in.ngc", std::ios::binary) << input;
  const auto posted = vcpost::testing::run_vcpost(
      "post in.ngc --model '" + cylinder.string() +
          "' --tool ball:12 --vc 150 --ap 0.2 --machine linuxcnc-3axis -o out.ngc -q",
      dir.path());
  ASSERT_EQ(posted.exit_code, 0) << posted.err;
  const auto verified = vcpost::testing::run_vcpost("verify in.ngc out.ngc", dir.path());
  EXPECT_EQ(verified.exit_code, 0) << verified.out << verified.err;

  const auto in = lines_of(input);
  const auto out = lines_of(vcpost::testing::slurp(dir / "out.ngc"));
  ASSERT_EQ(in.size(), out.size());
  std::size_t g53 = 0;  // the G5.3 line
  for (std::size_t k = 0; k < in.size(); ++k) {
    if (in[k].starts_with("G5.2") || in[k].starts_with("Y53") || in[k] == "G19") {
      EXPECT_EQ(out[k], in[k]) << "a NURBS block changed";
    }
    if (in[k] == "G5.3") g53 = k;
  }
  ASSERT_GT(g53, 0u);
  const auto s = s_in_effect(out);
  // The flat top asks for more than the machine's 8000 rpm (working
  // diameter 2 sqrt(6^2 - 5.8^2) = 3.07 mm: 15,540 rpm).
  EXPECT_EQ(s[8], 8000);
  // Policy max: the curve's steepest point, 30 deg, decides its one S.
  // The ball (R 6) cuts ap 0.2 deep there from the normal's angle to the
  // axis, 30 deg, to 30 + acos(5.8 / 6) = 44.84 deg: the working diameter
  // 12 sin(44.84 deg) = 8.460 mm, S = 150,000 / (pi 8.460) = 5643.9 rpm,
  // rounded down to the grid.
  const double d = 12 * std::sin(std::numbers::pi / 6 + std::acos(5.8 / 6));
  const double expected = std::floor(150000 / (std::numbers::pi * d));
  EXPECT_EQ(expected, 5643);
  EXPECT_NEAR(s[g53], expected, 1.0);
  // The passes at 30 deg after it keep that speed.
  EXPECT_NEAR(s[g53 + 2], expected, 1.0);
}

}  // namespace
}  // namespace vcpost::post
