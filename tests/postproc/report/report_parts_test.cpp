// The report's parts on hand-made input: a point's speeds, flags and
// surface quality against hand formulas and an independent circle
// construction; weighted percentiles, min/max decimation, the plan grid,
// regions, histogram bins, the CSV columns and the format by file name.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "geometry/revolved_engagement.h"
#include "postproc/report/csv_writer.h"
#include "postproc/report/plot_data.h"
#include "postproc/report/report.h"
#include "postproc/report/statistics.h"

namespace vcpost::report {
namespace {

using Eigen::Vector3d;

ReportInputs inputs() {
  ReportInputs in;
  in.vc_nominal = 120;
  in.n_min_rpm = 50;
  in.n_max_rpm = 12000;
  return in;
}

// A ball touching a convex sphere of radius 40 at the origin, feed along x.
pipeline::PointResult touching_point(double ae) {
  pipeline::PointResult r;
  r.contact.status = geometry::BallStatus::touching;
  r.contact.normal = Vector3d::UnitZ();
  geometry::ModelContact c;
  c.point = Vector3d::Zero();
  c.normal = Vector3d::UnitZ();
  c.curvature =
      geometry::PrincipalCurvatures{1.0 / 40, 1.0 / 40, Vector3d::UnitX(), Vector3d::UnitY()};
  r.contact.contact = c;
  r.feed = Vector3d::UnitX();
  r.ae = ae;
  r.ae_source = pipeline::AeSource::measured;
  geometry::Engagement e;
  e.d_max = 3.0;
  e.d_min = 1.0;
  e.points = geometry::CuttingPoints{};
  e.points->cut.diameter = 2.5;
  r.engagement = e;
  r.d_ref = 3.0;
  r.target_rpm = 1000 * 120 / (std::numbers::pi * 3.0);
  return r;
}

// Cusp between two balls of radius R whose centres lie on a circle of
// radius rho + R, ae/rho apart in angle (convex surface): the point at
// distance R from both, on the bisector, measured from the surface.
double convex_cusp_by_circles(double radius, double ae, double rho) {
  const double half = ae / rho / 2, centre = rho + radius;
  const double a = centre * std::sin(half);
  return centre * std::cos(half) - std::sqrt(radius * radius - a * a) - rho;
}

TEST(ReportRow, SpeedsDeviationFlagsAndSurfaceOfATouchingPoint) {
  pipeline::PathSample sample;
  sample.point = {1, 2, 3};
  const post::PointRecord record{42, 7.5, 0.02, 5000, 12000, plan::Bound::n_max};
  const PointRow row = make_row(sample, touching_point(1.0), record, inputs());
  EXPECT_EQ(row.line, 42u);
  // vc = pi d n / 1000 at d_ref = 3 mm.
  EXPECT_NEAR(*row.vc_before, std::numbers::pi * 3 * 5000 / 1000, 1e-12);  // 47.124
  EXPECT_NEAR(*row.vc_after, std::numbers::pi * 3 * 12000 / 1000, 1e-12);  // 113.097
  EXPECT_NEAR(*row.dev_after, 113.09733552923255 / 120 - 1, 1e-12);        // -5.75 %
  EXPECT_EQ(flags_text(row.flags), "clamped_max");
  EXPECT_DOUBLE_EQ(*row.d_cut, 2.5);
  // Convex sphere, rho = 40, R = 5, ae = 1: 28.22 um (flat would be 25.06).
  const double expected = 1000 * convex_cusp_by_circles(5, 1, 40);
  EXPECT_NEAR(expected, 28.22, 0.01);
  EXPECT_NEAR(*row.cusp_um, expected, 1e-6);
  // Rz of the transverse arc profile is the flat cusp; Ra by brute force:
  // the mean of |z - mean z| over one arc, z = R - sqrt(R^2 - x^2).
  EXPECT_NEAR(*row.rz_um, 1000 * (5 - std::sqrt(25 - 0.25)), 1e-9);
  const int n = 200000;
  double mean = 0;
  std::vector<double> z(n);
  for (int i = 0; i < n; ++i) {
    const double x = -0.5 + (i + 0.5) / n;
    z[static_cast<std::size_t>(i)] = 5 - std::sqrt(25 - x * x);
    mean += z[static_cast<std::size_t>(i)] / n;
  }
  double ra = 0;
  for (double v : z) ra += std::abs(v - mean) / n;
  EXPECT_NEAR(*row.ra_um, 1000 * ra, 1e-3);  // about 6.43 um
}

// A bull-nose (D 10, rc 2) on a level floor with passes 7 mm apart: its
// outline across the feed is the face between quarter circles, so the
// cusp and Rz are rc - sqrt(rc^2 - (ae / 2 - R0)^2) = 63.51 um, wherever
// on the face the floor touches it; on a convex sphere (rho 40) the row
// carries revolved_cusp's cusp for the contact the model gave, and the
// plane's Rz; a point whose section's tool differs from the report's
// first one is drawn with its own.
TEST(ReportRow, BullNoseCuspFromItsOutline) {
  ReportInputs in = inputs();
  in.tool_shape = geometry::Tool::bull_nose(10, 2);
  in.cl_kind = geometry::ClPoint::tip;
  pipeline::PathSample sample;
  sample.point = {0.5, 0, 0};  // the tip; the frame's origin 2 mm above it
  pipeline::PointResult r = touching_point(7.0);
  r.contact.contact->curvature.reset();
  const post::PointRecord record{42, 7.5, 0.02, 5000, 12000, plan::Bound::n_max};
  const PointRow floor = make_row(sample, r, record, in);
  const double expected = 1000 * (2 - std::sqrt(4 - 0.25));
  ASSERT_TRUE(floor.cusp_um && floor.rz_um && floor.ra_um);
  EXPECT_NEAR(*floor.cusp_um, expected, 1e-6);
  EXPECT_NEAR(*floor.rz_um, expected, 1e-6);
  EXPECT_GT(*floor.ra_um, 0);
  EXPECT_LT(*floor.ra_um, *floor.rz_um);
  const PointRow sphere = make_row(sample, touching_point(7.0), record, in);
  const geometry::RevolvedCusp cusp =
      geometry::revolved_cusp(in.tool_shape, {in.ap_mm, 7.0, Vector3d::UnitZ(), Vector3d::UnitX()},
                              1.0 / 40, Vector3d(-0.5, 0, -2));
  ASSERT_TRUE(sphere.cusp_um && cusp.height);
  EXPECT_NEAR(*sphere.cusp_um, 1000 * *cusp.height, 1e-9);
  EXPECT_GT(*sphere.cusp_um, expected);  // convex: higher than on the plane
  EXPECT_NEAR(*sphere.rz_um, expected, 1e-6);
  // In a program whose first section is a ball, the bull-nose section's
  // points carry their own tool: the same cusps.
  in.tool_shape = geometry::Tool::ball(10);
  post::PointRecord own = record;
  own.tool = geometry::Tool::bull_nose(10, 2);
  const PointRow second = make_row(sample, r, own, in);
  ASSERT_TRUE(second.cusp_um);
  EXPECT_NEAR(*second.cusp_um, expected, 1e-6);
  // And a ball section after a bull-nose: the arcs of its own radius (3).
  in.tool_shape = geometry::Tool::bull_nose(10, 2);
  own.tool = geometry::Tool::ball(6);
  const PointRow ball = make_row(sample, touching_point(2.0), own, in);
  ASSERT_TRUE(ball.rz_um);
  EXPECT_NEAR(*ball.rz_um, 1000 * (3 - std::sqrt(9 - 1.0)), 1e-6);
}

TEST(ReportRow, MissedPointHasNoSpeedAndSaysWhy) {
  pipeline::PathSample sample;
  pipeline::PointResult r;  // missed by default
  const post::PointRecord record{7, 1, 0.01, 13000, 13000, plan::Bound::program};
  const PointRow row = make_row(sample, r, record, inputs());
  EXPECT_FALSE(row.vc_before);
  EXPECT_FALSE(row.cusp_um);
  EXPECT_EQ(flags_text(row.flags), "no_contact|program_s|before_over_max");
}

TEST(ReportRow, CuspModelRange) {
  // Flat: h = R - sqrt(R^2 - ae^2/4); R = 5, ae = 2: 101.02 um.
  EXPECT_NEAR(*cusp_height_um(5, 2, 0), 1000 * (5 - std::sqrt(24.0)), 1e-9);
  EXPECT_FALSE(cusp_height_um(5, 10, 0));        // ae >= 2R: the balls do not overlap
  EXPECT_FALSE(cusp_height_um(5, 1, -1.0 / 3));  // hollow of radius 3 < R: gouges
  EXPECT_FALSE(cusp_height_um(5, 0, 0));
  // Concave rho = 50 gives less than flat.
  EXPECT_LT(*cusp_height_um(5, 1, -1.0 / 50), *cusp_height_um(5, 1, 0));
}

TEST(WeightedQuantiles, PercentilesWithinOneBinAndExactMoments) {
  WeightedQuantiles q(0, 200, 20000);  // 0.01 bins
  for (int v = 1; v <= 100; ++v) q.add(v, 1.0);
  EXPECT_NEAR(q.quantile(0.5), 50, 0.01 + 1e-9);
  EXPECT_NEAR(q.quantile(0.05), 5, 0.01 + 1e-9);
  EXPECT_NEAR(q.quantile(0.95), 95, 0.01 + 1e-9);
  EXPECT_DOUBLE_EQ(q.mean(), 50.5);
  EXPECT_EQ(q.min(), 1);
  EXPECT_EQ(q.max(), 100);
  // Weights count: 3 s at 10, 1 s at 20: the median is 10, the mean 12.5.
  WeightedQuantiles w(0, 100, 10000);
  w.add(10, 3);
  w.add(20, 1);
  EXPECT_NEAR(w.quantile(0.5), 10, 0.01);
  EXPECT_NEAR(w.quantile(0.9), 20, 0.01);
  EXPECT_DOUBLE_EQ(w.mean(), 12.5);
  // Out of range values still give the exact extremes.
  w.add(500, 1);
  EXPECT_EQ(w.quantile(1.0), 500);
}

TEST(StatisticsAccumulator, SharesAndClampedTimes) {
  StatisticsAccumulator acc(100, 5);
  auto row = [](double vc_before, double vc_after, double w, std::uint32_t flags) {
    PointRow r;
    r.status = geometry::BallStatus::touching;
    r.vc_before = vc_before;
    r.vc_after = vc_after;
    r.weight_s = w;
    r.flags = flags;
    return r;
  };
  acc.add(row(80, 100, 2, static_cast<std::uint32_t>(PointFlag::slew)));  // before -20 %, after 0
  acc.add(row(96, 92, 1, static_cast<std::uint32_t>(PointFlag::clamped_max)));  // -4 %, -8 %
  acc.add(row(104, 104, 1, 0));                                                 // +4 %, +4 %
  const ReportStatistics s = acc.result();
  EXPECT_EQ(s.cutting_points, 3u);
  EXPECT_DOUBLE_EQ(s.cutting_time_s, 4);
  EXPECT_DOUBLE_EQ(s.before.within_5_percent, 0.5);  // 2 s of 4
  EXPECT_DOUBLE_EQ(s.before.within_10_percent, 0.5);
  EXPECT_DOUBLE_EQ(s.after.within_5_percent, 0.75);
  EXPECT_DOUBLE_EQ(s.after.within_10_percent, 1.0);
  EXPECT_DOUBLE_EQ(s.after.vc->mean, (200 + 92 + 104) / 4.0);
  EXPECT_DOUBLE_EQ(s.after.clamped_max_time_s, 1);
  EXPECT_DOUBLE_EQ(*s.after.slew_time_s, 2);
  EXPECT_FALSE(s.before.slew_time_s);
  EXPECT_DOUBLE_EQ(s.before.below_nominal_time_s, 2);
  EXPECT_DOUBLE_EQ(s.after.below_nominal_time_s, 1);
}

TEST(MinMaxDecimator, KeepsEveryPeakOfAMillionPointsInBoundedSize) {
  MinMaxDecimator d(2, 500);
  const int n = 1000000;
  for (int i = 0; i < n; ++i) {
    double y = std::sin(i * 1e-3);
    if (i == 123457) y = 50;
    if (i == 765432) y = -50;
    d.add(i, {y, i % 2 == 0 ? std::optional<double>(i) : std::nullopt});
  }
  const auto s = d.series(0);
  EXPECT_LE(s.size(), 2u * 2 * 500);
  EXPECT_GE(s.size(), 500u);
  double max_y = -1e9, min_y = 1e9, at_max = 0, at_min = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (k > 0) {
      EXPECT_GE(s[k].x, s[k - 1].x);
    }
    if (s[k].y > max_y) {
      max_y = s[k].y;
      at_max = s[k].x;
    }
    if (s[k].y < min_y) {
      min_y = s[k].y;
      at_min = s[k].x;
    }
  }
  EXPECT_EQ(max_y, 50);
  EXPECT_EQ(at_max, 123457);
  EXPECT_EQ(min_y, -50);
  EXPECT_EQ(at_min, 765432);
  // The sparse series keeps its first and last values (0 and 999998).
  const auto t = d.series(1);
  EXPECT_EQ(t.front().y, 0);
  EXPECT_EQ(t.back().y, 999998);
}

TEST(PlanGrid, WorstValuePerCellAndBorderCells) {
  PlanGrid g({0, 0}, {10, 5}, 10);
  EXPECT_EQ(g.nx(), 10);
  EXPECT_EQ(g.ny(), 5);
  EXPECT_DOUBLE_EQ(g.cell(), 1);
  g.add({2.5, 3.5}, -0.2);
  g.add({2.7, 3.1}, 0.1);
  g.add({20, -3}, 1);
  EXPECT_FLOAT_EQ(*g.cells()[3 * 10 + 2], -0.2f);
  EXPECT_FLOAT_EQ(*g.cells()[0 * 10 + 9], 1.0f);
  EXPECT_FALSE(g.cells()[0]);
}

TEST(RegionTracker, StretchesBeyondTheThresholdRankedByTimeTimesDeviation) {
  RegionTracker t(0.05, 5);
  const double devs[] = {0, -0.1, -0.2, 0, 0.08};
  const double weights[] = {1, 1, 2, 1, 1};
  double cut = 0;
  for (int k = 0; k < 5; ++k) {
    PointRow r;
    r.line = static_cast<std::uint32_t>(10 + k);
    r.weight_s = weights[k];
    r.point = {static_cast<double>(k), 0, 0};
    r.bound = k == 2 ? plan::Bound::slew : plan::Bound::none;
    t.add(r, 100 * (1 + devs[k]), devs[k], cut);
    cut += weights[k];
  }
  const auto regions = t.result();
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_EQ(regions[0].first_line, 11u);
  EXPECT_EQ(regions[0].last_line, 12u);
  EXPECT_DOUBLE_EQ(regions[0].duration_s, 3);
  EXPECT_DOUBLE_EQ(regions[0].score, 0.1 + 0.4);
  EXPECT_DOUBLE_EQ(regions[0].worst_dev, -0.2);
  EXPECT_DOUBLE_EQ(regions[0].start_cut_s, 1);
  EXPECT_EQ(regions[0].bound, plan::Bound::slew);  // 2 s of its 3
  EXPECT_DOUBLE_EQ(regions[0].worst_xy.x(), 2);
  EXPECT_EQ(regions[1].first_line, 14u);
  EXPECT_DOUBLE_EQ(regions[1].worst_dev, 0.08);
}

TEST(DeviationHistogram, OnePercentBinsWithOpenEnds) {
  DeviationHistogram h;
  ASSERT_EQ(h.before_s.size(), 100u);
  EXPECT_EQ(h.bin_of(-0.5), 0u);
  EXPECT_EQ(h.bin_of(-3.0), 0u);
  EXPECT_EQ(h.bin_of(0.0), 50u);
  EXPECT_EQ(h.bin_of(-0.001), 49u);
  EXPECT_EQ(h.bin_of(0.7), 99u);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

TEST(ReportCsv, IssueColumnsFirstAndOneRowPerPoint) {
  const std::string issue =
      "line,x,y,z,cc_x,cc_y,cc_z,n_x,n_y,n_z,f_x,f_y,f_z,ae,d_ref,d_max,d_min,d_cut,s_before,"
      "s_after,vc_before,vc_after,dev_pct,flags";
  ASSERT_EQ(std::string(kCsvHeader).substr(0, issue.size() + 1), issue + ",");
  pipeline::PathSample sample;
  sample.point = {1.25, -2, 3};
  const post::PointRecord record{42, 7.5, 0.02, 5000, 12000, plan::Bound::n_max};
  const PointRow row = make_row(sample, touching_point(1.0), record, inputs());
  const auto fields = split(csv_row(row));
  const auto names = split(std::string(kCsvHeader));
  ASSERT_EQ(fields.size(), names.size());
  auto at = [&](std::string_view name) {
    for (std::size_t k = 0; k < names.size(); ++k) {
      if (names[k] == name) return fields[k];
    }
    return std::string("?");
  };
  EXPECT_EQ(at("line"), "42");
  EXPECT_EQ(at("x"), "1.25");
  EXPECT_EQ(at("y"), "-2");
  EXPECT_EQ(at("n_z"), "1");
  EXPECT_EQ(at("d_ref"), "3");
  EXPECT_EQ(at("s_after"), "12000");
  EXPECT_EQ(at("vc_after"), "113.097");
  EXPECT_EQ(at("dev_pct"), "-5.752");
  EXPECT_EQ(at("flags"), "clamped_max");
  EXPECT_EQ(at("status"), "touching");

  std::string out;
  CsvWriter writer([&](std::string_view bytes) { out.append(bytes); }, 64);
  for (int k = 0; k < 100; ++k) writer.write(row);
  writer.finish();
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 101);
  EXPECT_EQ(writer.rows(), 100u);
}

TEST(ReportFormat, FollowsTheFileName) {
  EXPECT_EQ(format_of("a/b.json"), ReportFormat::json);
  EXPECT_EQ(format_of("R.CSV"), ReportFormat::csv);
  EXPECT_EQ(format_of("r.html"), ReportFormat::html);
  EXPECT_EQ(format_of("r.htm"), ReportFormat::html);
  EXPECT_FALSE(format_of("r.txt"));
  EXPECT_FALSE(format_of("report"));
}

}  // namespace
}  // namespace vcpost::report
