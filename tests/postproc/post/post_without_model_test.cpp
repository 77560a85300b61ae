// Posting without a model against posting with it (the samples' STEP
// models, whose contact the engine finds on the exact surface: an
// independent computation of every normal) on generated ball-end programs:
// rasters over the B-spline mould and the cylinder, Z-level rings on the
// dome, stepovers 0.25 and 0.5 mm; and a D10 rc2 bull-nose raster on the
// mould (its tip path is the surface offset by the tool: the same normals). The normals found from
// the toolpath are within 0.25 deg of the model's at the 99th percentile, and the S in effect on 95
// % of the lines within 2 % of the post with the model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/analytic_surfaces.h"
#include "geometry/occt/brep_model.h"
#include "machines/builtin.h"
#include "postproc/post/post_job.h"
#include "postproc/samplegen/parts.h"
#include "postproc/samplegen/toolpath.h"

namespace vcpost::post {
namespace {

namespace fs = std::filesystem;

struct Case {
  const char* part;
  samplegen::Pattern pattern;
  double angle, ae;
  double corner = 0;  // a bull-nose's corner radius; 0: a ball
};

void PrintTo(const Case& c, std::ostream* out) {
  *out << c.part << " " << static_cast<int>(c.pattern) << " " << c.angle << " " << c.ae;
}

std::string program_of(const Case& c) {
  const auto part = samplegen::make_part(c.part);
  samplegen::PathSpec path;
  path.pattern = c.pattern;
  path.tool_radius = part->tool_diameter / 2;
  if (c.corner > 0) path.corner_radius = c.corner;
  path.angle_deg = c.angle;
  path.chord_tolerance = samplegen::kSampleChordTolerance;
  if (c.pattern == samplegen::Pattern::raster) {
    path.stepover = c.ae;
    path.step = 0.5;
    path.window = part->raster_window;
    path.window_radius = part->raster_radius;
  } else {  // rings of constant latitude on the dome (R 40): steps in radians
    path.stepover = c.ae / 40;
    path.step = 0.5 / 40;
    path.window = part->iso_window;
  }
  samplegen::ProgramSpec spec;
  spec.tool_diameter = part->tool_diameter;
  if (c.corner > 0) spec.corner_radius = c.corner;
  spec.safe_z = part->safe_z;
  spec.title = "without a model";
  std::ostringstream gcode;
  samplegen::ProgramWriter writer(spec, &gcode, nullptr, nullptr);
  samplegen::generate(*part->surface, path, spec.decimals,
                      [&](const samplegen::PathPoint& p) { writer.add(p); });
  writer.finish();
  return gcode.str();
}

// The S in effect on every line of a G-code program.
std::vector<double> s_in_effect(const std::string& text) {
  std::vector<double> out;
  std::istringstream in(text);
  double s = 0;
  for (std::string line; std::getline(in, line);) {
    const auto at = line.find('S');
    if (at != std::string::npos && line.find('(') == std::string::npos)
      s = std::stod(line.substr(at + 1));
    out.push_back(s);
  }
  return out;
}

struct Posted {
  std::string text;
  std::vector<std::optional<Eigen::Vector3d>> normals;  // per sample, where it touches
  PostSummary summary;
};

Posted post(const std::string& program, const geometry::SurfaceModel& model, bool from_path,
            const geometry::Tool& tool) {
  PostSettings settings;
  settings.point.tool = tool;
  settings.point.vc = 120;
  settings.point.ap = 0.2;
  settings.normals_from_path = from_path;
  Posted out;
  out.summary = post_program(
      program, "generated.nc", model, machines::builtin_profile("generic"), settings,
      [&](std::string_view bytes) { out.text += bytes; }, {},
      [&](const pipeline::PathSample&, const pipeline::PointResult& r, const PointRecord&) {
        out.normals.push_back(r.contact.status == geometry::BallStatus::touching
                                  ? std::optional(r.contact.normal)
                                  : std::nullopt);
      });
  return out;
}

class PostWithoutModel : public ::testing::TestWithParam<Case> {};

TEST_P(PostWithoutModel, NormalsAndSpeedsAsWithTheModel) {
  const Case& c = GetParam();
  const fs::path step = fs::path(VCPOST_SOURCE_DIR) / "samples" / (std::string(c.part) + ".step");
  const auto model = occt::BrepModel::load_step(step);
  const geometry::AnalyticModel none(std::vector<geometry::AnalyticSurface>{});
  const std::string program = program_of(c);
  const double diameter = samplegen::make_part(c.part)->tool_diameter;
  const geometry::Tool tool =
      c.corner > 0 ? geometry::Tool::bull_nose(diameter, c.corner) : geometry::Tool::ball(diameter);
  const Posted with = post(program, model, false, tool);
  const Posted without = post(program, none, true, tool);

  ASSERT_TRUE(without.summary.path_normals);
  ASSERT_EQ(with.normals.size(), without.normals.size());
  std::vector<double> angles;
  for (std::size_t i = 0; i < with.normals.size(); ++i) {
    if (!with.normals[i] || !without.normals[i]) continue;
    angles.push_back(std::acos(std::clamp(with.normals[i]->dot(*without.normals[i]), -1.0, 1.0)) *
                     180 / std::numbers::pi);
  }
  ASSERT_GT(angles.size(), 0.9 * static_cast<double>(with.normals.size()));
  std::sort(angles.begin(), angles.end());
  const double p99 =
      angles[static_cast<std::size_t>(0.99 * static_cast<double>(angles.size() - 1))];
  EXPECT_LE(p99, 0.25);

  const auto s_with = s_in_effect(with.text), s_without = s_in_effect(without.text);
  ASSERT_EQ(s_with.size(), s_without.size());
  std::size_t close = 0;
  for (std::size_t i = 0; i < s_with.size(); ++i)
    close += std::abs(s_without[i] - s_with[i]) <= 0.02 * s_with[i] ? 1 : 0;
  const double share = static_cast<double>(close) / static_cast<double>(s_with.size());
  EXPECT_GE(share, 0.95);
  const auto& n = *without.summary.path_normals;
  std::cout << "normals p99 " << p99 << " deg; S within 2 %: " << 100 * share << " % of "
            << s_with.size() << " lines; " << n.two_sided << " two-sided, " << n.one_sided
            << " one-sided, " << n.kept << " kept\n";
}

INSTANTIATE_TEST_SUITE_P(Generated, PostWithoutModel,
                         ::testing::Values(Case{"wavy", samplegen::Pattern::raster, 30, 0.25},
                                           Case{"wavy", samplegen::Pattern::raster, 0, 0.5},
                                           Case{"cylinder", samplegen::Pattern::raster, 45, 0.2},
                                           Case{"dome", samplegen::Pattern::iso_u, 0, 0.5},
                                           Case{"wavy", samplegen::Pattern::raster, 0, 0.25, 2}));

}  // namespace
}  // namespace vcpost::post
