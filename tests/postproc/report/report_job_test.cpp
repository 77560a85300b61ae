// The report fed by a real post job on an analytic dome (a sphere of radius
// 40: every point's curvature is known): its statistics agree with the
// job's own and with exact percentiles of every point, the CSV has a row
// per point, the JSON keeps its documented keys, and the page is one
// self-contained file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "../dome_program_support.h"
#include "geometry/analytic_surfaces.h"
#include "geometry/surface_quality.h"
#include "machines/builtin.h"
#include "postproc/post/post_job.h"
#include "postproc/report/csv_writer.h"
#include "postproc/report/report.h"

namespace vcpost::report {
namespace {

constexpr double ball_radius = testing::dome_ball_radius;

using testing::dome;
using testing::dome_raster;

struct DomeRun {
  post::PostSummary summary;
  std::optional<ReportData> data;
  std::vector<PointRow> rows;
  std::string csv;
};

DomeRun run_dome(const std::string& machine, int spindle, double vc) {
  const auto model = dome();
  const auto profile = machines::builtin_profile(machine);
  post::PostSettings settings;
  settings.point.tool = geometry::Tool::ball(2 * ball_radius);
  settings.point.ap = 0.3;
  settings.point.vc = vc;
  ReportInputs in;
  in.program = "dome.ngc";
  in.tool_radius_mm = ball_radius;
  in.vc_nominal = vc;
  in.n_min_rpm = profile.spindle().n_min_rpm;
  in.n_max_rpm = profile.spindle().n_max_rpm;
  in.plan_min = {-30, -30};
  in.plan_max = {30, 30};
  DomeRun run;
  ReportCollector collector(in, 100, 60);
  CsvWriter csv([&](std::string_view bytes) { run.csv.append(bytes); });
  const auto sink = collector.point_sink([&](const PointRow& row) {
    run.rows.push_back(row);
    csv.write(row);
  });
  run.summary = post::post_program(
      dome_raster(2, 1, spindle), "dome.ngc", model, profile, settings, [](std::string_view) {}, {},
      sink);
  csv.finish();
  run.data = collector.finish(run.summary, 0.5);
  return run;
}

// The exact weighted quantile of (value, weight) pairs.
double exact_quantile(std::vector<std::pair<double, double>> v, double q) {
  std::sort(v.begin(), v.end());
  double total = 0;
  for (const auto& p : v) total += p.second;
  double below = 0;
  for (const auto& p : v) {
    below += p.second;
    if (below >= q * total) return p.first;
  }
  return v.back().first;
}

TEST(ReportJob, StatisticsAgreeWithTheJobAndWithExactPercentiles) {
  const DomeRun run = run_dome("mazak-3axis", 3000, 100);
  const ReportStatistics& s = run.data->statistics;
  ASSERT_GT(s.cutting_points, 1000u);
  EXPECT_EQ(s.points, run.summary.samples);
  EXPECT_EQ(s.touching, run.summary.touching);
  EXPECT_EQ(s.gouging, run.summary.gouging);
  EXPECT_NEAR(s.cutting_time_s, run.summary.cutting_time_s, 1e-6 * run.summary.cutting_time_s);
  // The job keeps d_ref as float: agreement to 1e-5 relative, shares to 1e-3.
  ASSERT_TRUE(run.summary.after && s.after.vc);
  EXPECT_NEAR(s.after.vc->mean, run.summary.after->mean, 1e-5 * run.summary.after->mean);
  EXPECT_NEAR(s.after.vc->min, run.summary.after->min, 1e-4 * run.summary.after->min);
  EXPECT_NEAR(s.before.vc->max, run.summary.before->max, 1e-4 * run.summary.before->max);
  EXPECT_NEAR(s.after.within_10_percent, run.summary.after->within_10_percent, 1e-3);
  EXPECT_NEAR(s.before.within_5_percent, run.summary.before->within_5_percent, 1e-3);
  // Percentiles: within one histogram bin (vc_nom / 10^4 = 0.01 m/min) of exact.
  std::vector<std::pair<double, double>> after, before;
  for (const auto& r : run.rows) {
    if (r.vc_after && r.weight_s > 0) {
      after.emplace_back(*r.vc_after, r.weight_s);
      before.emplace_back(*r.vc_before, r.weight_s);
    }
  }
  const double bin = s.after.vc->resolution;
  EXPECT_NEAR(bin, 0.01, 1e-12);
  EXPECT_NEAR(s.after.vc->p5, exact_quantile(after, 0.05), bin + 1e-9);
  EXPECT_NEAR(s.after.vc->p50, exact_quantile(after, 0.5), bin + 1e-9);
  EXPECT_NEAR(s.before.vc->p95, exact_quantile(before, 0.95), bin + 1e-9);
  // The rewrite helps: more time within 10 % after than before.
  EXPECT_GT(s.after.within_10_percent, s.before.within_10_percent);
}

TEST(ReportJob, ConvexDomeCuspsExceedTheFlatFormula) {
  const DomeRun run = run_dome("mazak-3axis", 3000, 100);
  int checked = 0;
  for (const auto& r : run.rows) {
    if (!r.cusp_um) continue;
    // A convex surface raises the cusp over a flat one at the same ae.
    EXPECT_GT(*r.cusp_um, 1000 * geometry::flat_cusp_height(ball_radius, r.ae)) << r.line;
    ++checked;
  }
  EXPECT_GT(checked, 500);
  // The summary's extremes are the rows' own.
  double highest = 0;
  for (const auto& r : run.rows) highest = std::max(highest, r.cusp_um.value_or(0));
  ASSERT_TRUE(run.data->statistics.cusp_um);
  EXPECT_EQ(run.data->statistics.cusp_um->max, highest);
}

TEST(ReportJob, SlowMachineClampsAndTheTimeIsCounted) {
  // At 200 m/min a D10 ball on the dome's top (D_max ~ 3.4 mm) needs
  // ~18,700 rpm: more than the generic profile's n_max.
  const DomeRun run = run_dome("generic", 3000, 200);
  const ReportStatistics& s = run.data->statistics;
  double clamped = 0;
  for (const auto& r : run.rows) {
    if (r.vc_after && r.has(PointFlag::clamped_max)) clamped += r.weight_s;
  }
  EXPECT_GT(clamped, 0);
  EXPECT_NEAR(s.after.clamped_max_time_s, clamped, 1e-9);
  // Held at n_max: S never above it (the planner names n_max where it
  // decides the larger share of the shortfall, so S may sit a little under).
  for (const auto& r : run.rows) {
    if (r.has(PointFlag::clamped_max)) {
      EXPECT_LE(r.s_after, run.data->inputs.n_max_rpm) << r.line;
    }
  }
}

TEST(ReportJob, CsvHasOneRowPerPointAndTheJsonItsKeys) {
  const DomeRun run = run_dome("mazak-3axis", 3000, 100);
  EXPECT_EQ(static_cast<std::uint64_t>(std::count(run.csv.begin(), run.csv.end(), '\n')),
            run.summary.samples + 1);
  const nlohmann::json j = report_json(*run.data);
  for (const char* key : {"schema", "inputs", "profile", "vc_nominal", "points", "time_s", "before",
                          "after", "words_written", "surface", "run_time_s"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  for (const char* side : {"before", "after"}) {
    for (const char* key : {"min", "max", "mean", "p5", "p50", "p95"}) {
      EXPECT_TRUE(j[side]["vc"].contains(key)) << side << "." << key;
    }
    for (const char* key : {"clamped_n_max", "clamped_n_min", "slew"}) {
      EXPECT_TRUE(j[side]["time_s"].contains(key)) << side << "." << key;
    }
    EXPECT_TRUE(j[side].contains("within_5_percent"));
    EXPECT_TRUE(j[side].contains("within_10_percent"));
  }
  EXPECT_EQ(j["points"]["total"], run.summary.samples);
  EXPECT_EQ(j["points"]["gouging"], run.summary.gouging);
  EXPECT_EQ(j["points"]["no_contact"], run.summary.lifted + run.summary.missed);
  EXPECT_DOUBLE_EQ(j["vc_nominal"].get<double>(), 100);
  for (const char* key : {"cusp_um", "ra_um", "rz_um"})
    EXPECT_TRUE(j["surface"][key].is_object()) << key;
}

TEST(ReportJob, PlotsKeepTheExtremesOfEveryPoint) {
  const DomeRun run = run_dome("mazak-3axis", 3000, 100);
  double lowest = 1e9, highest = 0;
  for (const auto& r : run.rows) {
    if (r.vc_after) {
      lowest = std::min(lowest, *r.vc_after);
      highest = std::max(highest, *r.vc_after);
    }
  }
  double plot_low = 1e9, plot_high = 0;
  for (const auto& p : run.data->vc_after) {
    plot_low = std::min(plot_low, p.y);
    plot_high = std::max(plot_high, p.y);
  }
  EXPECT_EQ(plot_low, lowest);
  EXPECT_EQ(plot_high, highest);
  EXPECT_LE(run.data->vc_after.size(), 2u * 2 * 100);
  EXPECT_GT(run.data->plot_bucket_points, 1u);
}

TEST(ReportJob, PageIsSelfContainedAndInlinesTheLibraryOnce) {
  const DomeRun run = run_dome("mazak-3axis", 3000, 100);
  const std::string library = "/* fake chart library */ window.Chart = function () {};";
  const std::string page = render_html(*run.data, library);
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(page.find(library), page.rfind(library));
  EXPECT_NE(page.find(library), std::string::npos);
  EXPECT_EQ(page.find(" src="), std::string::npos);   // no external script or image
  EXPECT_EQ(page.find(" href="), std::string::npos);  // no style sheet or link
  EXPECT_EQ(page.find("http://"), std::string::npos);
  EXPECT_EQ(page.find("https://"), std::string::npos);
  EXPECT_THROW(render_html(*run.data, "var a = '</SCRIPT>';"), std::invalid_argument);
}

}  // namespace
}  // namespace vcpost::report
