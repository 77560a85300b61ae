// Turning the model and the program together changes no S (MODELS.md 5,
// issue 40): a ball and a bull-nose raster over the analytic dome, posted
// untilted, and the same raster written in a tilted working plane (Fanuc
// G68.2 with the frame's origin and Euler angles) against the dome placed
// by that frame (p = R p_model + origin), post to the same S in every
// block within the profile's S resolution (1 rpm; the points differ only
// by the round-off of turning in and out). Tilts: 30 deg
// about X, 30 deg about Y, and a compound one (I20 J35 K-50, origin moved).
// The same tilts written as Sinumerik CYCLE800 (axis by axis X Y Z, the
// angles of the same rotation, about the same origin) post to the same S
// too, read as Sinumerik on the same machine.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../dome_program_support.h"
#include "geometry/analytic_surfaces.h"
#include "geometry/rigid_transform.h"
#include "machines/builtin.h"
#include "postproc/gcode/dialect.h"
#include "postproc/post/post_job.h"
#include "postproc/program/working_frame.h"

namespace vcpost::post {
namespace {

struct Tilt {
  const char* name;
  double i, j, k;          // G68.2's Euler angles, degrees
  Eigen::Vector3d origin;  // mm
};

// The S word of every line (0 where the line has none), the lines the
// tilted program adds (its move to the frame's origin, G68.2, G53.1, G69)
// left out.
std::vector<long> s_by_line(const std::string& program) {
  static const std::regex s_word(R"(\bS([0-9]+))");
  std::vector<long> out;
  std::istringstream in(program);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("G68.2", 0) == 0 || line == "G53.1" || line == "G69" ||
        line.rfind("CYCLE800(", 0) == 0 || line.find("TO THE ORIGIN") != std::string::npos)
      continue;
    std::smatch m;
    out.push_back(std::regex_search(line, m, s_word) ? std::stol(m[1].str()) : 0);
  }
  return out;
}

std::string tilted(const std::string& raster, const Tilt& t) {
  std::ostringstream g;
  g.setf(std::ios::fixed);
  g.precision(6);
  // The tool goes to the frame's origin first, so that it starts the
  // raster from the same point of the part as the untilted program (the
  // plan's first speed depends on the time the first rapid leaves).
  g << "G0 X" << t.origin.x() << " Y" << t.origin.y() << " Z" << t.origin.z()
    << " (TO THE ORIGIN)\n";
  g << "G68.2 X" << t.origin.x() << " Y" << t.origin.y() << " Z" << t.origin.z() << " I" << t.i
    << " J" << t.j << " K" << t.k << "\nG53.1\n";
  std::string out = raster;
  const std::string header = "G21 G90 G17 G94\n";
  out.insert(out.find(header) + header.size(), g.str());
  out.insert(out.find("M5\nM30"), "G69\n");
  return out;
}

// The raster in the Sinumerik language (G71 for mm, `;` comments) tilted
// by CYCLE800 with _MODE 57 (X, then the turned Y, then the twice-turned
// Z): R = Rx(a) Ry(b) Rz(c), so b = asin R(0,2), a = atan2(-R(1,2),
// R(2,2)), c = atan2(-R(0,1), R(0,0)); the reference point X0 Y0 Z0 is the
// frame's origin.
std::string sinumerik_tilted(const std::string& raster, const Tilt& t) {
  const Eigen::Matrix3d r = program::euler_zxz(t.i, t.j, t.k);
  const double deg = 180.0 / std::numbers::pi;
  const double b = std::asin(r(0, 2)) * deg, a = std::atan2(-r(1, 2), r(2, 2)) * deg,
               c = std::atan2(-r(0, 1), r(0, 0)) * deg;
  std::ostringstream g;
  g.setf(std::ios::fixed);
  g.precision(9);
  g << "G0 X" << t.origin.x() << " Y" << t.origin.y() << " Z" << t.origin.z()
    << " ; TO THE ORIGIN\n";
  g << "CYCLE800(0,\"TC1\",0,57," << t.origin.x() << "," << t.origin.y() << "," << t.origin.z()
    << "," << a << "," << b << "," << c << ",0,0,0,1)\n";
  std::string out = raster;
  out.replace(out.find("(dome raster)"), 13, "; dome raster");
  out.replace(out.find("G21 "), 4, "G71 ");
  const std::string header = "G71 G90 G17 G94\n";
  out.insert(out.find(header) + header.size(), g.str());
  out.insert(out.find("M5\nM30"), "CYCLE800()\n");
  return out;
}

std::string post(const std::string& program, const geometry::SurfaceModel& model,
                 const PostSettings& settings, PostSummary& summary) {
  std::string out;
  summary = post_program(program, "dome.nc", model, machines::builtin_profile("fanuc-3axis"),
                         settings, [&](std::string_view bytes) { out.append(bytes); });
  return out;
}

void expect_same_s(const std::string& raster, const geometry::Tool& tool) {
  PostSettings settings;
  settings.point.tool = tool;
  settings.point.ap = 0.3;
  settings.point.vc = 120;
  settings.sample_spacing_mm = 2;
  const auto dome = std::make_shared<geometry::AnalyticModel>(testing::dome());
  PostSummary flat;
  const std::vector<long> expected = s_by_line(post(raster, *dome, settings, flat));
  long changed = 0;
  for (const long s : expected) changed += s > 0 ? 1 : 0;
  ASSERT_GT(changed, 5) << "the untilted post must change S along the raster";
  const Tilt tilts[] = {{"about X", 0, 30, 0, {0, 0, 0}},
                        {"about Y", 90, 30, -90, {0, 0, 0}},
                        {"compound", 20, 35, -50, {120, -40, 75}}};
  for (const Tilt& t : tilts) {
    SCOPED_TRACE(t.name);
    const geometry::RigidTransform placement{program::euler_zxz(t.i, t.j, t.k), t.origin};
    const geometry::TransformedModel turned(dome, placement);
    PostSummary summary;
    const std::vector<long> got = s_by_line(post(tilted(raster, t), turned, settings, summary));
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t line = 0; line < got.size(); ++line)
      EXPECT_LE(std::abs(got[line] - expected[line]), 1) << "line " << line + 1;
    EXPECT_EQ(summary.touching, flat.touching);
    EXPECT_EQ(summary.gouging, flat.gouging);
    // CYCLE800 on the same machine (its program read as Sinumerik).
    PostSettings sinumerik = settings;
    sinumerik.dialect = gcode::sinumerik_dialect();
    PostSummary swivelled;
    const std::vector<long> by_cycle =
        s_by_line(post(sinumerik_tilted(raster, t), turned, sinumerik, swivelled));
    ASSERT_EQ(by_cycle.size(), expected.size());
    for (std::size_t line = 0; line < by_cycle.size(); ++line)
      EXPECT_LE(std::abs(by_cycle[line] - expected[line]), 1) << "CYCLE800, line " << line + 1;
    EXPECT_EQ(swivelled.touching, flat.touching);
  }
}

TEST(TiltedInvariance, BallRasterPostsTheSameSInEveryTilt) {
  expect_same_s(testing::dome_raster(1.0, 1.0, 8000), geometry::Tool::ball(10));
}

TEST(TiltedInvariance, BullNoseRasterPostsTheSameSInEveryTilt) {
  expect_same_s(testing::bull_nose_dome_raster(1.25, 1.0, 8000, 10, 2),
                geometry::Tool::bull_nose(10, 2));
}

// The same rasters in Klartext, untilted and in a PLANE SPATIAL about a
// datum shifted by CYCL DEF 7 (the frame R = Rz(SPC) Ry(SPB) Rx(SPA) about
// that datum: the dome placed at R p + shift), posted for the TNC 640:
// the same TOOL CALL S words, and every sample's cutting speed the same
// (the vc statistics before and after within 1e-9 relative).
std::string klartext(const std::string& raster, const std::string& tilt) {
  static const std::regex word(R"(([XYZ])(-?[0-9.]+))");
  std::ostringstream out;
  int n = 0;
  auto block = [&](const std::string& text) { out << n++ << " " << text << "\n"; };
  block("BEGIN PGM DOME MM");
  std::string line;
  std::istringstream tilt_lines(tilt);
  while (std::getline(tilt_lines, line)) block(line);
  block("TOOL CALL 1 Z S8000");
  block("M3");
  std::istringstream in(raster);
  bool fed = false;  // F2000 written
  while (std::getline(in, line)) {
    if (line.rfind("G0 ", 0) != 0 && line.rfind("G1 ", 0) != 0) continue;
    if (line == "G0 Z60") break;
    std::string l = "L";
    for (std::sregex_iterator w(line.begin(), line.end(), word), e; w != e; ++w)
      l += " " + (*w)[1].str() + (*w)[2].str();
    if (line[1] == '0') {
      l += " FMAX";
    } else if (!fed) {
      l += " F2000";
      fed = true;
    }
    block(l);
  }
  block("L Z60 FMAX");
  block("M30");
  block("END PGM DOME MM");
  return out.str();
}

std::vector<long> tool_call_s(const std::string& program) {
  static const std::regex s_word(R"(TOOL CALL.* S([0-9]+))");
  std::vector<long> out;
  for (std::sregex_iterator m(program.begin(), program.end(), s_word), e; m != e; ++m)
    out.push_back(std::stol((*m)[1].str()));
  return out;
}

void expect_plane_spatial_same(const std::string& raster, const geometry::Tool& tool) {
  PostSettings settings;
  settings.point.tool = tool;
  settings.point.ap = 0.3;
  settings.point.vc = 120;
  settings.sample_spacing_mm = 2;
  const auto profile = machines::builtin_profile("heidenhain-tnc640");
  const auto dome = std::make_shared<geometry::AnalyticModel>(testing::dome());
  auto run = [&](const std::string& program, const geometry::SurfaceModel& model,
                 PostSummary& summary) {
    std::string out;
    summary = post_program(program, "dome.h", model, profile, settings,
                           [&](std::string_view bytes) { out.append(bytes); });
    return out;
  };
  PostSummary flat;
  const std::string untilted = run(klartext(raster, ""), *dome, flat);
  const auto expected = tool_call_s(untilted);
  ASSERT_FALSE(expected.empty());
  ASSERT_TRUE(flat.after && flat.before);
  ASSERT_GT(flat.touching, 300u);  // the raster is evaluated, not kept
  const Eigen::Vector3d shift(30, -20, 10);
  const std::string tilt =
      "L X30 Y-20 Z10 FMAX\nCYCL DEF 7.0 DATUM SHIFT\nCYCL DEF 7.1 X30\n"
      "CYCL DEF 7.2 Y-20\nCYCL DEF 7.3 Z10\nPLANE SPATIAL SPA20 SPB35 SPC-50 TURN\n";
  const geometry::RigidTransform placement{program::spatial_angles(20, 35, -50), shift};
  const geometry::TransformedModel turned(dome, placement);
  PostSummary summary;
  const std::string posted = run(klartext(raster, tilt), turned, summary);
  EXPECT_EQ(tool_call_s(posted), expected);
  ASSERT_TRUE(summary.after && summary.before);
  EXPECT_EQ(summary.touching, flat.touching);
  EXPECT_NEAR(summary.after->mean, flat.after->mean, 1e-9 * flat.after->mean);
  EXPECT_NEAR(summary.after->max, flat.after->max, 1e-9 * flat.after->max);
  EXPECT_NEAR(summary.before->min, flat.before->min, 1e-9 * flat.before->min);
  EXPECT_NEAR(summary.before->mean, flat.before->mean, 1e-9 * flat.before->mean);
}

TEST(TiltedInvariance, PlaneSpatialPostsTheSameAsTheUntiltedKlartext) {
  expect_plane_spatial_same(testing::dome_raster(1.0, 1.0, 8000), geometry::Tool::ball(10));
}

TEST(TiltedInvariance, PlaneSpatialBullNosePostsTheSameAsTheUntiltedKlartext) {
  expect_plane_spatial_same(testing::bull_nose_dome_raster(1.25, 1.0, 8000, 10, 2),
                            geometry::Tool::bull_nose(10, 2));
}

}  // namespace
}  // namespace vcpost::post
