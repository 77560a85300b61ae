// Normals from the toolpath alone against the exact normals the sample
// generator computes for every point of its programs (closed-form surfaces:
// an independent computation), on rasters, iso-parametric passes and
// Z-level rings with stepovers from 0.1 to 1 mm; and by hand on a cylinder.
#include "postproc/pipeline/path_normals.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "postproc/samplegen/parts.h"
#include "postproc/samplegen/toolpath.h"
#include "tests/sanitizers.h"

namespace vcpost::pipeline {
namespace {

using Eigen::Vector3d;
constexpr double deg = 180 / std::numbers::pi;

struct Errors {
  std::vector<double> angles;  // deg, over the points given a normal
  PathNormalCounts counts;
  double quantile(double q) const {
    if (angles.empty()) return 0;
    std::vector<double> a = angles;
    const auto k = static_cast<std::size_t>(q * static_cast<double>(a.size() - 1));
    std::nth_element(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(k), a.end());
    return a[k];
  }
};

// Estimates the normals of a generated program's tip points (one path, no
// rapid inside) and compares each with the generator's exact normal.
Errors compare(const std::string& part_name, samplegen::PathSpec spec) {
  const auto part = samplegen::make_part(part_name);
  spec.tool_radius = part->tool_diameter / 2;
  if (spec.pattern == samplegen::Pattern::raster) spec.window = part->raster_window;
  if (spec.pattern == samplegen::Pattern::raster) spec.window_radius = part->raster_radius;
  std::vector<Vector3d> tips, truth;
  samplegen::generate(*part->surface, spec, 6, [&](const samplegen::PathPoint& p) {
    tips.push_back(p.tip);
    truth.push_back(p.normal);
  });
  std::vector<std::uint8_t> starts(tips.size(), 0);
  starts[0] = 1;
  PathNormalSettings settings;
  settings.search_radius = part->tool_diameter;
  settings.min_path_gap = 4 * part->tool_diameter;
  const auto normals = estimate_path_normals(tips, starts, settings);
  Errors e;
  e.counts = count_sources(normals);
  for (std::size_t i = 0; i < normals.size(); ++i) {
    if (normals[i].source == NormalSource::kept) continue;
    e.angles.push_back(std::acos(std::clamp(normals[i].normal.dot(truth[i]), -1.0, 1.0)) * deg);
  }
  return e;
}

samplegen::PathSpec raster(double angle, double ae, double step) {
  samplegen::PathSpec s;
  s.pattern = samplegen::Pattern::raster;
  s.angle_deg = angle;
  s.stepover = ae;
  s.step = step;
  s.chord_tolerance = samplegen::kSampleChordTolerance;
  return s;
}

samplegen::PathSpec iso(samplegen::Pattern pattern, double stepover, double step,
                        const Eigen::AlignedBox2d& window) {
  samplegen::PathSpec s;
  s.pattern = pattern;
  s.stepover = stepover;
  s.step = step;
  s.window = window;
  s.chord_tolerance = samplegen::kSampleChordTolerance;
  return s;
}

void report(const std::string& what, const Errors& e) {
  std::cout << what << ": " << e.angles.size() << " points, median " << e.quantile(0.5)
            << " deg, p99 " << e.quantile(0.99) << ", max " << e.quantile(1.0) << "; two-sided "
            << e.counts.two_sided << ", one-sided " << e.counts.one_sided << ", kept "
            << e.counts.kept << "\n";
}

// The bar: within 0.25 deg of the model's normal at the 99th
// percentile for ae <= 0.5 mm; at most 2 % of the points kept (no pass
// near enough: the window's edges, the first ring).
void expect_close(const std::string& what, const Errors& e, double p99 = 0.25) {
  report(what, e);
  EXPECT_LE(e.quantile(0.99), p99) << what;
  const auto all = static_cast<double>(e.counts.two_sided + e.counts.one_sided + e.counts.kept);
  EXPECT_LE(static_cast<double>(e.counts.kept), 0.02 * all) << what;
}

TEST(PathNormals, WavyBsplineRasters) {
  for (const double ae : {0.1, 0.25, 0.5}) {
    if (vcpost::testing::kSanitized && ae < 0.25) continue;  // the densest raster: 60 % of the time
    for (const double angle : {0.0, 30.0, 90.0}) {
      expect_close("wavy raster ae " + std::to_string(ae) + " at " + std::to_string(angle),
                   compare("wavy", raster(angle, ae, 0.5)));
    }
  }
}

TEST(PathNormals, CylinderRasters) {
  for (const double ae : {0.1, 0.2, 0.5}) {
    for (const double angle : {0.0, 45.0, 90.0}) {
      expect_close("cylinder raster ae " + std::to_string(ae) + " at " + std::to_string(angle),
                   compare("cylinder", raster(angle, ae, 0.5)));
    }
  }
}

TEST(PathNormals, DomeRastersAndZLevelRings) {
  const auto part = samplegen::make_part("dome");
  for (const double ae : {0.25, 0.5}) {
    expect_close("dome raster ae " + std::to_string(ae), compare("dome", raster(0, ae, 0.5)));
    // Rings of constant latitude (Z-level): stepover in v (rad) ae / R.
    expect_close(
        "dome rings ae " + std::to_string(ae),
        compare("dome", iso(samplegen::Pattern::iso_u, ae / 40, 0.5 / 40, part->iso_window)));
  }
}

TEST(PathNormals, WavyIsoParametric) {
  const auto part = samplegen::make_part("wavy");
  for (const double ae : {0.1, 0.5}) {
    expect_close("wavy iso-u ae " + std::to_string(ae),
                 compare("wavy", iso(samplegen::Pattern::iso_u, ae, 0.5, part->iso_window)));
    expect_close("wavy iso-v ae " + std::to_string(ae),
                 compare("wavy", iso(samplegen::Pattern::iso_v, ae, 0.5, part->iso_window)));
  }
}

// Fed in pieces with the tracker stepped after each (as the program is
// read), the normals and earlier passes are those of the whole path at
// once, bit for bit: a point is stepped only once its tangent is settled.
// The path repeats some points (a tangent looks past repeats) and starts
// new passes inside it.
TEST(PathNormals, PiecesGiveTheWholePathsAnswersBitForBit) {
  const auto part = samplegen::make_part("wavy");
  samplegen::PathSpec spec = raster(30, 0.5, 0.5);
  spec.tool_radius = part->tool_diameter / 2;
  spec.window = part->raster_window;
  spec.window_radius = part->raster_radius;
  std::vector<Vector3d> points;
  std::vector<std::uint8_t> starts;
  samplegen::generate(*part->surface, spec, 6, [&](const samplegen::PathPoint& p) {
    const std::size_t i = points.size();
    points.push_back(p.tip);
    starts.push_back(i == 0 || i % 997 == 0 ? 1 : 0);
    if (i % 101 == 0) {  // the same point again, twice
      points.insert(points.end(), 2, p.tip);
      starts.insert(starts.end(), 2, 0);
    }
  });
  PathNormalSettings settings;
  settings.search_radius = part->tool_diameter;
  settings.min_path_gap = 4 * part->tool_diameter;
  std::vector<EarlierPass> whole_earlier, pieces_earlier;
  const auto whole = estimate_path_normals(points, starts, settings, &whole_earlier);

  PathNormalEstimator estimator(settings);
  estimator.reserve(100);  // far too few: it grows
  for (std::size_t i = 0; i < points.size(); ++i) {
    estimator.add(points[i], starts[i] != 0);
    if (i % 7 == 0) estimator.track();
  }
  const auto pieces = estimator.finish(&pieces_earlier);

  ASSERT_EQ(pieces.size(), whole.size());
  ASSERT_EQ(pieces_earlier.size(), whole_earlier.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < whole.size(); ++i) {
    const bool same = pieces[i].source == whole[i].source && pieces[i].normal == whole[i].normal &&
                      pieces_earlier[i].found == whole_earlier[i].found &&
                      pieces_earlier[i].point == whole_earlier[i].point &&
                      pieces_earlier[i].normal == whole_earlier[i].normal;
    differ += same ? 0 : 1;
  }
  EXPECT_EQ(differ, 0U) << "of " << whole.size() << " points";
  EXPECT_GT(count_sources(whole).two_sided, whole.size() * 9 / 10);  // a real path, not all kept
}

// Above 0.5 mm the issue sets no bar; at 1 mm the estimate still holds a
// degree.
TEST(PathNormals, WideStepoversStayWithinADegree) {
  expect_close("wavy raster ae 1", compare("wavy", raster(0, 1.0, 0.5)), 1.0);
  expect_close("cylinder raster ae 1 at 45", compare("cylinder", raster(45, 1.0, 0.5)), 1.0);
}

}  // namespace
}  // namespace vcpost::pipeline
