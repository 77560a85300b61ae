// The report fed by a real post job on an analytic dome (a sphere of radius
// 40: every point's curvature is known): its statistics agree with the
// job's own and with exact percentiles of every point, the CSV has a row
// per point, the JSON keeps its documented keys, and the page is one
// self-contained file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "../../geometry/tool_outline.h"
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
  in.tool_shape = geometry::Tool::ball(2 * ball_radius);
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

// A bull-nose (D 10, rc 2) rastered along x over the dome, passes 1.5 mm
// apart, points 0.05 mm apart (so the chords' sag, 0.007 mm^2 / 8 / 42,
// leaves the sweeps on the surface: 1 mm chords gouge it by 2.7 um): the
// report's cusps against a simulation of the two sweeps in the plane
// across the row's feed F (through its contact, so through the sphere's
// centre): the tools' outlines seen along F from their support function
// (tool_outline.h), the previous pass's tool where its chord (between the
// raster's own points, rounded as written) crosses the plane across F
// through this tool's position (where the tracker measures ae), the dome's
// great circle, and the highest material left between the two contacts,
// measured along the sphere's radius. Within 1 um + 1 % of it off the
// crest (30-130 um cusps; 0.1-0.8 um seen: the model shifts this tool
// across F where the previous pass ran along its own chord; a convex dome
// taken for a concave one moves them by 8 um). On the crest, where the
// faces rest on the dome and their overlap decides, the model's cusps of
// 0-4 um differ from the sweeps' by up to 3.2 um.
TEST(ReportJob, BullNoseCuspsMatchASimulationOfTheTwoSweeps) {
  const geometry::Tool tool = geometry::Tool::bull_nose(10, 2);
  const double stepover = 1.5, spacing = 0.05;
  const auto model = dome();
  const auto profile = machines::builtin_profile("mazak-3axis");
  post::PostSettings settings;
  settings.point.tool = tool;
  settings.point.ap = 0.3;
  settings.point.vc = 100;
  // The report's first tool given as a ball: the rows take the bull-nose
  // from their section (PointRecord::tool).
  ReportInputs in;
  in.tool_shape = geometry::Tool::ball(10);
  in.vc_nominal = 100;
  in.n_min_rpm = profile.spindle().n_min_rpm;
  in.n_max_rpm = profile.spindle().n_max_rpm;
  std::vector<PointRow> rows;
  ReportCollector collector(in, 100, 60);
  const auto sink = collector.point_sink([&](const PointRow& row) { rows.push_back(row); });
  post::post_program(
      testing::bull_nose_dome_raster(stepover, spacing, 3000, 10, 2), "dome.ngc", model, profile,
      settings, [](std::string_view) {}, {}, sink);
  // The raster's tool origin over (x, y): its core disc 42 from the
  // sphere's centre (0, 0, -20), the tip as the program writes it.
  const auto origin = [](double x, double y) {
    const double off = std::max(0.0, std::hypot(x, y) - 3);
    const double tip = std::round((-20 + std::sqrt(42.0 * 42.0 - off * off) - 2) * 1e6) / 1e6;
    return Eigen::Vector3d(x, y, tip + 2);
  };
  const Eigen::Vector3d centre(0, 0, -20);
  double worst = 0;
  int checked = 0;
  for (std::size_t i = 0; i < rows.size(); i += 137) {
    const PointRow& r = rows[i];
    // Well inside the raster, off the crest (the previous pass at y -
    // stepover; at |y| >= 6 the dome tilts by 8 deg and more across the
    // feed, and the corner touches it).
    if (!r.cusp_um || r.ae_source != pipeline::AeSource::measured || std::abs(r.point.x()) > 15 ||
        std::abs(r.point.y()) > 15 || std::abs(r.point.y()) < 6)
      continue;
    const Eigen::Vector3d f = r.feed, n = *r.normal, e = n.cross(f), cc = *r.cc;
    const Eigen::Vector3d o1 = r.point + 2 * Eigen::Vector3d::UnitZ();
    // Where the previous pass's chord crosses the plane (X - o1).f = 0.
    const double y2 = o1.y() - stepover;
    double x0 = -20 + spacing * std::floor((o1.x() + 20) / spacing);
    Eigen::Vector3d o2;
    for (int j = 0; j < 100; ++j) {  // the chord the plane crosses
      const Eigen::Vector3d a = origin(x0, y2), b = origin(x0 + spacing, y2);
      const double t = (o1 - a).dot(f) / (b - a).dot(f);
      o2 = a + t * (b - a);
      if (t >= 0 && t <= 1) break;
      x0 += t < 0 ? -spacing : spacing;
    }
    // The tracker's ae, between the tools' positions across the feed.
    EXPECT_NEAR(std::hypot(e.dot(o2 - o1), n.dot(o2 - o1)), r.ae, 5e-3) << r.line;
    const testing::ToolOutline outline{tool, e, n};
    // The material's top over b: the lower of the two outlines.
    const auto top = [&](double x) {
      return std::min(n.dot(o1) + outline.lowest(x - e.dot(o1)),
                      n.dot(o2) + outline.lowest(x - e.dot(o2)));
    };
    // The radial gap at the circle's angle theta (from n at CC, towards e).
    const double radius = (cc - centre).norm();
    const double cb = e.dot(centre), cn = n.dot(centre);
    const auto gap = [&](double theta, const auto& surface) {
      const double ub = std::sin(theta), un = std::cos(theta);
      const auto above = [&](double t) {
        const double x = cb + (radius + t) * ub;
        return surface(x) - (cn + (radius + t) * un);
      };
      double lo = 0, hi = 0.01;
      if (above(lo) <= 0) return 0.0;
      while (above(hi) > 0) hi *= 2;
      for (int j = 0; j < 60; ++j) (above(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
      return lo;
    };
    // The previous tool's contact: where its gap alone is least (golden
    // sections round the angle of the shift).
    const auto alone = [&](double x) { return n.dot(o2) + outline.lowest(x - e.dot(o2)); };
    const double shift = std::atan2(e.dot(o2 - o1), radius);
    double lo = shift - 0.05, hi = shift + 0.05;
    const double golden = (std::sqrt(5.0) - 1) / 2;
    const auto lifted = [&](double theta) {  // lifted by 1 mm: a gap everywhere
      return gap(theta, [&](double x) { return alone(x) + 1.0; });
    };
    for (int j = 0; j < 40; ++j) {  // to 1e-9 rad
      const double p = hi - golden * (hi - lo), q = lo + golden * (hi - lo);
      (lifted(p) < lifted(q) ? hi : lo) = lifted(p) < lifted(q) ? q : p;
    }
    const double theta2 = 0.5 * (lo + hi);
    // The highest: sampled, then by golden sections round the best sample
    // (the gap rises to the outlines' crossing and falls after it).
    int best = 1;
    for (int j = 2; j < 100; ++j) {
      if (gap(theta2 * j / 100, top) > gap(theta2 * best / 100, top)) best = j;
    }
    double a = theta2 * (best - 1) / 100, b = theta2 * (best + 1) / 100;
    for (int j = 0; j < 40; ++j) {
      const double p = b - golden * (b - a), q = a + golden * (b - a);
      (gap(p, top) > gap(q, top) ? b : a) = gap(p, top) > gap(q, top) ? q : p;
    }
    const double highest = gap(0.5 * (a + b), top);
    const double error = std::abs(*r.cusp_um - 1000 * highest);
    EXPECT_LE(error, 1 + 0.01 * *r.cusp_um) << r.line << " at " << r.point.transpose();
    worst = std::max(worst, error);
    ++checked;
  }
  EXPECT_GE(checked, 30);
  RecordProperty("worst_um", std::to_string(worst));
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
