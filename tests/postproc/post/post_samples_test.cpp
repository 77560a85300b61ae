// The post job on the bundled samples (STEP models, G-code and CL): vc at
// the reference diameter never exceeds nominal, stays within the band the
// profile's resolution and hysteresis allow (-2 % with the shipped
// profiles) wherever no limit binds, and more cutting time is near nominal
// than at the program's constant S. Prints both shares for each sample.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "geometry/occt/brep_model.h"
#include "machines/builtin.h"
#include "postproc/post/post_job.h"

namespace vcpost::post {
namespace {

namespace fs = std::filesystem;

struct Case {
  const char* program;
  const char* model;
  double diameter, vc, ap;
};

void PrintTo(const Case& c, std::ostream* out) { *out << c.program; }

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class PostSamples : public ::testing::TestWithParam<Case> {};

TEST_P(PostSamples, VcStaysAtOrJustUnderNominalWhereNoLimitBinds) {
  const Case& c = GetParam();
  const fs::path samples = fs::path(VCPOST_SOURCE_DIR) / "samples";
  const auto model = occt::BrepModel::load_step(samples / c.model);
  const auto profile = machines::builtin_profile("mazak-3axis");
  PostSettings settings;
  settings.point.tool = geometry::Tool::ball(c.diameter);
  settings.point.vc = c.vc;
  settings.point.ap = c.ap;

  // Per block: the lowest target over its points and over the point it
  // starts from (the last point before it: the block's S holds from its
  // start), whether every one of those points cuts, the planned S, its bound.
  struct Block {
    double target = INFINITY, s_after = 0;
    bool all_cut = true;
    plan::Bound bound = plan::Bound::none;
  };
  std::map<std::uint64_t, Block> blocks;  // by NC line
  std::uint64_t points = 0;
  std::optional<double> previous;  // target of the previous point
  std::uint64_t previous_line = 0;
  const auto summary = post_program(
      read(samples / c.program), c.program, model, profile, settings, {}, {},
      [&](const pipeline::PathSample&, const pipeline::PointResult& r, const PointRecord& p) {
        ++points;
        const bool first = !blocks.contains(p.line);
        Block& b = blocks[p.line];
        if (first && previous_line + 1 == p.line) {
          b.all_cut = previous.has_value();
          if (previous) b.target = *previous;
        }
        b.all_cut = b.all_cut && r.target_rpm.has_value();
        if (r.target_rpm) b.target = std::min(b.target, *r.target_rpm);
        b.s_after = p.s_after;
        b.bound = p.bound;
        previous = r.target_rpm;
        previous_line = p.line;
      });
  EXPECT_EQ(points, summary.samples);
  const auto& spindle = profile.spindle();
  int banded = 0;
  for (const auto& [line, b] : blocks) {
    if (!std::isfinite(b.target) || b.bound == plan::Bound::n_min) continue;
    EXPECT_LE(b.s_after, b.target + 1e-9) << "line " << line;  // vc <= vc_nom
    if (b.all_cut && (b.bound == plan::Bound::none || b.bound == plan::Bound::resolution ||
                      b.bound == plan::Bound::hysteresis)) {
      const double floor = std::min(b.target, spindle.n_max_rpm) * 0.98;
      EXPECT_GE(b.s_after, floor) << "line " << line << " bound " << plan::to_string(b.bound);
      ++banded;
    }
  }
  EXPECT_GT(banded, 0);
  ASSERT_TRUE(summary.before && summary.after);
  EXPECT_GT(summary.after->within_10_percent, summary.before->within_10_percent);
  std::printf("%s: cutting time within +-10 %% of vc %.0f m/min: %.1f %% before, %.1f %% after\n",
              c.program, c.vc, 100 * summary.before->within_10_percent,
              100 * summary.after->within_10_percent);
}

INSTANTIATE_TEST_SUITE_P(
    Samples, PostSamples,
    ::testing::Values(Case{"wavy_raster_a0_ae2.nc", "wavy.step", 10, 120, 0.3},
                      Case{"wavy_iso_u.cls", "wavy.step", 10, 120, 0.3},
                      Case{"cylinder_r100_ae0.5_a45.cls", "cylinder.step", 12, 150, 0.2},
                      Case{"cylinder_r100_ae0.2_a0.nc", "cylinder.step", 12, 150, 0.2},
                      Case{"dome_iso_rings.nc", "dome.step", 10, 120, 0.3},
                      Case{"dome_raster_a0_ae3.cls", "dome.step", 10, 120, 0.3}),
    [](const ::testing::TestParamInfo<Case>& test) {
      std::string name = test.param.program;
      for (char& ch : name) {
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      }
      return name;
    });

}  // namespace
}  // namespace vcpost::post
