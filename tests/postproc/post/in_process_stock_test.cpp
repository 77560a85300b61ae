// ap per point from the in-process stock (issue 44), against values worked
// out by hand: a flat roughing leaving two known steps then a ball finish
// (ap = the step height under each point); a semi-finish raster with a
// known allowance then the finish (ap = the allowance plus the
// semi-finish's cusp, R - sqrt(R^2 - d^2) at distance d from its nearest
// pass); a drilled hole (no engagement over it). Tolerances: the grid's
// cell (a point reads the cell its contact lies in).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/analytic_surfaces.h"
#include "machines/builtin.h"
#include "postproc/post/post_job.h"
#include "postproc/tools/tool_table.h"

namespace vcpost::post {
namespace {

using Eigen::Vector3d;

// The level face z = 0 over [-40, 40]^2, material below.
geometry::AnalyticModel level_face() {
  geometry::PlanePatch plane;
  plane.u_min = plane.v_min = -40;
  plane.u_max = plane.v_max = 40;
  return geometry::AnalyticModel({plane});
}

struct Point {
  std::uint32_t section = 0;
  Vector3d tip, contact;
  pipeline::PointResult result;
};

struct StockRun {  // NOLINT(bugprone-exception-escape): a test's value
  PostSummary summary;
  std::vector<Point> points;
  std::string program;
};

StockRun post_with_stock(const std::string& program, const std::vector<std::string>& tool_options,
                         const std::vector<std::string>& allowances, const StockSettings& stock,
                         double ap = 0.3) {
  const geometry::AnalyticModel model = level_face();
  PostSettings settings;
  settings.point.ap = ap;
  settings.threads = 2;
  tools::ToolChoices& choices = settings.tools.emplace();
  for (const std::string& t : tool_options) choices.table.add(tools::parse_tool_option(t));
  for (const std::string& a : allowances) tools::add_stock_option(a, choices);
  choices.vc = 150;
  settings.stock = stock;
  const auto profile = machines::builtin_profile("mazak-3axis");
  StockRun run;
  run.summary = post_program(
      program, "stock.nc", model, profile, settings,
      [&](std::string_view bytes) { run.program.append(bytes); }, {},
      [&](const pipeline::PathSample& sample, const pipeline::PointResult& result,
          const PointRecord& record) {
        if (!result.contact.contact) return;
        run.points.push_back({record.section, sample.point, result.contact.contact->point, result});
      });
  return run;
}

StockSettings box_stock(const Vector3d& min, const Vector3d& max, double cell) {
  StockSettings stock;
  stock.box = Eigen::AlignedBox3d(min, max);
  stock.cell_mm = cell;
  return stock;
}

std::string header() { return "%\nG21 G90 G17 G94\n"; }

// Numbers with a decimal point: the Fanuc-style profile reads X10 as 0.01 mm.
std::ostringstream program_stream() {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(3);
  return out;
}

// Passes along X at the given y values, tip at z, from x0 to x1, a rapid
// between passes.
void raster_x(std::ostringstream& out, const std::vector<double>& ys, double x0, double x1,
              double z) {
  for (const double y : ys) {
    out << "G0 X" << x0 << " Y" << y << " Z20.\nG1 Z" << z << " F1000.\nG1 X" << x1
        << "\nG0 Z20.\n";
  }
}

std::vector<double> spaced(double from, double to, double step) {
  std::vector<double> out;
  for (double v = from; v <= to + 1e-9; v += step) out.push_back(v);
  return out;
}

// A D10 flat end mill leaves the face 1.0 mm high for x < 0 and 0.4 mm for
// x > 0 (passes along Y, 5 mm apart, tip at those heights); a D10 ball then
// finishes the face (tip on z = 0): ap is the step under each point, and
// d_ref on a level face is 2 sqrt(ap (D - ap)).
TEST(InProcessStock, FlatRoughingStepsThenBallFinish) {
  std::ostringstream p = program_stream();
  p << header() << "T1 M6\nS6000 M3\n";
  for (const double x : spaced(-25, -5, 5))
    p << "G0 X" << x << " Y-30. Z20.\nG1 Z1. F1000.\nG1 Y30.\nG0 Z20.\n";
  for (const double x : spaced(5, 25, 5))
    p << "G0 X" << x << " Y-30. Z20.\nG1 Z0.4 F1000.\nG1 Y30.\nG0 Z20.\n";
  p << "T2 M6\nS8000 M3\n";
  raster_x(p, spaced(-10, 10, 1), -20, 20, 0);
  p << "M5\nM30\n%\n";
  const double cell = 0.1;
  const StockRun run = post_with_stock(p.str(), {"T1=flat:10", "T2=ball:10"}, {},
                                       box_stock({-30, -30, -5}, {30, 30, 3}, cell));
  ASSERT_TRUE(run.summary.stock);
  const StockSummary& s = *run.summary.stock;
  EXPECT_EQ(s.swept, (std::vector<std::uint32_t>{1}));
  EXPECT_TRUE(s.warnings.empty());
  std::size_t checked = 0;
  for (const Point& point : run.points) {
    if (point.section != 2) continue;
    const double x = point.contact.x();
    if (std::abs(x) < 2 * cell || std::abs(x) > 19) continue;  // the step; the passes' ends
    const double step = x < 0 ? 1.0 : 0.4;
    ASSERT_EQ(point.result.ap_source, pipeline::ApSource::stock) << x;
    EXPECT_NEAR(point.result.ap, step, 1e-3) << x;
    ASSERT_TRUE(point.result.d_ref) << x;
    EXPECT_NEAR(*point.result.d_ref, 2 * std::sqrt(step * (10 - step)), 0.01) << x;
    ++checked;
  }
  EXPECT_GT(checked, 1000u);
  EXPECT_GT(s.over_nominal_points, 0u);  // the 1.0 mm step, above --ap 0.3
  EXPECT_NEAR(s.ap_max_mm, 1.0, 1e-3);
}

// A D10 ball semi-finishes 0.5 mm above the face (--stock T1=0.5) with
// passes 2 mm apart; a D6 ball finishes it: ap = 0.5 + R - sqrt(R^2 - d^2),
// d the distance across to the nearest semi-finishing pass (R = 5), at most
// 0.5 + 5 - sqrt(24) = 0.601 midway.
TEST(InProcessStock, AllowancePlusSemiFinishCusp) {
  std::ostringstream p = program_stream();
  p << header() << "T1 M6\nS6000 M3\n";
  const std::vector<double> semi = spaced(-16, 16, 2);
  raster_x(p, semi, -20, 20, 0.5);
  p << "T2 M6\nS9000 M3\n";
  raster_x(p, spaced(-10, 10, 0.3), -15, 15, 0);
  p << "M5\nM30\n%\n";
  const double cell = 0.05;
  const StockRun run = post_with_stock(p.str(), {"T1=ball:10", "T2=ball:6"}, {"T1=0.5"},
                                       box_stock({-30, -30, -5}, {30, 30, 3}, cell));
  std::size_t checked = 0;
  double worst = 0;
  for (const Point& point : run.points) {
    const double x = point.contact.x(), y = point.contact.y();
    if (std::abs(x) > 14) continue;
    if (point.section == 1) {
      // The block's top at 3 over the offset face at 0.5.
      EXPECT_NEAR(point.result.ap, 2.5, 1e-3);
      continue;
    }
    double d = 1e9;
    for (const double pass : semi) d = std::min(d, std::abs(y - pass));
    const double expected = 0.5 + 5 - std::sqrt(25 - d * d);
    ASSERT_NE(point.result.ap_source, pipeline::ApSource::air) << x << " " << y;
    worst = std::max(worst, std::abs(point.result.ap - expected));
    ++checked;
  }
  EXPECT_GT(checked, 1000u);
  // The cusp's slope is at most d/R = 0.2 here; a contact sits at most
  // cell / sqrt(2) from its cell's centre.
  EXPECT_LE(worst, 0.2 * cell + 2e-3);
  ASSERT_TRUE(run.summary.stock);
  // Over both sections: the semi-finish's 2.5.
  EXPECT_NEAR(run.summary.stock->ap_max_mm, 2.5, 1e-3);
}

// A D8 drill (G81) through 0.3 mm of stock over the face at the origin,
// then a D10 ball along X through the hole: where the contact lies over
// the hole nothing is cut (no engagement, no target: like a point in the
// air); elsewhere ap is the 0.3 mm left.
TEST(InProcessStock, DrilledHoleIsNotEngaged) {
  std::ostringstream p = program_stream();
  p << header() << "T1 M6\nS3000 M3\nG0 X0. Y0. Z20.\nG81 X0. Y0. Z-10. R2. F200.\nG80\nG0 Z20.\n";
  p << "T2 M6\nS8000 M3\n";
  raster_x(p, {0.0}, -15, 15, 0);
  p << "M5\nM30\n%\n";
  const double cell = 0.1;
  const StockRun run = post_with_stock(p.str(), {"T1=drill:8", "T2=ball:10"}, {},
                                       box_stock({-20, -20, -20}, {20, 20, 0.3}, cell));
  ASSERT_TRUE(run.summary.stock);
  EXPECT_EQ(run.summary.stock->swept, (std::vector<std::uint32_t>{1}));
  std::size_t over_hole = 0, beside = 0, air = 0;
  for (const Point& point : run.points) {
    if (point.section != 2) continue;
    const double x = point.contact.x();
    if (point.result.ap_source == pipeline::ApSource::air) ++air;
    if (std::abs(x) < 4 - cell) {
      EXPECT_EQ(point.result.ap_source, pipeline::ApSource::air) << x;
      EXPECT_FALSE(point.result.engagement) << x;
      EXPECT_FALSE(point.result.target_rpm) << x;
      ++over_hole;
    } else if (std::abs(x) > 4 + cell && std::abs(x) < 14) {
      EXPECT_EQ(point.result.ap_source, pipeline::ApSource::stock) << x;
      EXPECT_NEAR(point.result.ap, 0.3, 1e-3) << x;
      EXPECT_TRUE(point.result.target_rpm) << x;
      ++beside;
    }
  }
  EXPECT_GT(over_hole, 10u);
  EXPECT_GT(beside, 10u);
  EXPECT_LE(air - over_hole, 2u);  // at most one point at each edge, within a cell of it
  EXPECT_EQ(run.summary.stock->points_air, air);
}

// Without a stock, --ap everywhere: the source says so.
TEST(InProcessStock, NoStockTakesTheGivenAp) {
  std::ostringstream p = program_stream();
  p << header() << "T2 M6\nS8000 M3\n";
  raster_x(p, {0.0, 1.0}, -10, 10, 0);
  p << "M5\nM30\n%\n";
  const geometry::AnalyticModel model = level_face();
  PostSettings settings;
  settings.point.ap = 0.3;
  settings.tools.emplace().table.add(tools::parse_tool_option("ball:10"));
  settings.tools->vc = 150;
  std::size_t points = 0;
  const PostSummary summary = post_program(
      p.str(), "n.nc", model, machines::builtin_profile("mazak-3axis"), settings, {}, {},
      [&](const pipeline::PathSample&, const pipeline::PointResult& r, const PointRecord&) {
        if (!r.engagement) return;
        EXPECT_EQ(r.ap_source, pipeline::ApSource::given);
        EXPECT_EQ(r.ap, 0.3);
        ++points;
      });
  EXPECT_FALSE(summary.stock);
  EXPECT_GT(points, 10u);
}

}  // namespace
}  // namespace vcpost::post
