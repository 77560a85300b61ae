// A whole program generated here (roughing, semi-finish, finish over a
// dome) posted with an in-process stock: the ap at each finishing point and
// the S posted for each block against an independent computation: the
// stock's top by brute force over the earlier tools' tip positions (each
// tool's underside over the point), the depth along the normal by marching,
// the working diameter from that ap, S = 1000 vc / (pi d_ref).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <vector>

#include "geometry/analytic_surfaces.h"
#include "geometry/diameter_policy.h"
#include "geometry/engagement.h"
#include "machines/builtin.h"
#include "postproc/post/post_job.h"
#include "postproc/tools/tool_table.h"

namespace vcpost::post {
namespace {

using Eigen::Vector3d;

// The dome: the sphere of radius 50 about (0, 0, -40), top at z = 10.
constexpr double kSphere = 50, kCentreZ = -40;

double surface_z(double r) { return kCentreZ + std::sqrt(kSphere * kSphere - r * r); }

// A pass along X at y: tip heights every kStep mm from x0.
struct Pass {
  double y = 0, x0 = 0;
  std::vector<double> tips;
};
constexpr double kStep = 0.05;

// The tip over (x, y) of a ball of radius R whose centre rides the sphere
// grown by R + allowance.
double ball_tip(double x, double y, double radius, double allowance) {
  const double reach = kSphere + radius + allowance;
  return kCentreZ + std::sqrt(reach * reach - (x * x + y * y)) - radius;
}

// A flat end mill of radius R leaving `leave` over the dome's highest point
// under its end.
double flat_tip(double x, double y, double radius, double leave) {
  return surface_z(std::max(0.0, std::hypot(x, y) - radius)) + leave;
}

struct Tool {
  double radius = 5;
  bool ball = true;
  std::vector<Pass> passes;
};

// The stock's top over (x, y): the block's top under every earlier tool's
// underside at every sampled tip within its radius.
double stock_top(const std::vector<Tool>& tools, double x, double y, double block_top) {
  double top = block_top;
  for (const Tool& t : tools) {
    for (const Pass& p : t.passes) {
      const double dy = y - p.y;
      if (std::abs(dy) > t.radius) continue;
      const auto first = static_cast<long>(std::ceil((x - t.radius - p.x0) / kStep));
      const auto last = static_cast<long>(std::floor((x + t.radius - p.x0) / kStep));
      for (long i = std::max(0L, first); i <= std::min<long>(last, p.tips.size() - 1); ++i) {
        const double dx = x - (p.x0 + static_cast<double>(i) * kStep), d2 = dx * dx + dy * dy;
        if (d2 > t.radius * t.radius) continue;
        const double lift = t.ball ? t.radius - std::sqrt(t.radius * t.radius - d2) : 0;
        top = std::min(top, p.tips[i] + lift);
      }
    }
  }
  return top;
}

void write_pass(std::ostringstream& out, const Pass& p) {
  out << "G0 X" << p.x0 << " Y" << p.y << " Z30.\nG1 Z" << p.tips[0] << " F2000.\n";
  for (std::size_t i = 10; i < p.tips.size(); i += 10)  // moves 0.5 mm long
    out << "G1 X" << p.x0 + static_cast<double>(i) * kStep << " Z" << p.tips[i] << "\n";
  out << "G0 Z30.\n";
}

TEST(InProcessStock, GeneratedProgramApAndSAgainstAnIndependentStock) {
  // Roughing: D10 flat, passes 5 mm apart, 1 mm left; semi-finish: D10
  // ball at 0.3 allowance, 2 mm apart; finish: D6 ball, 0.5 mm apart.
  std::vector<Tool> tools(3);
  tools[0] = {5, false, {}};
  tools[1] = {5, true, {}};
  tools[2] = {3, true, {}};
  for (double y = -25; y <= 25 + 1e-9; y += 5) {
    Pass p{y, -25, {}};
    for (int i = 0; i <= 1000; ++i) p.tips.push_back(flat_tip(-25 + i * kStep, y, 5, 1.0));
    tools[0].passes.push_back(p);
  }
  for (double y = -16; y <= 16 + 1e-9; y += 2) {
    Pass p{y, -20, {}};
    for (int i = 0; i <= 800; ++i) p.tips.push_back(ball_tip(-20 + i * kStep, y, 5, 0.3));
    tools[1].passes.push_back(p);
  }
  for (double y = -8; y <= 8 + 1e-9; y += 0.5) {
    Pass p{y, -10, {}};
    for (int i = 0; i <= 400; ++i) p.tips.push_back(ball_tip(-10 + i * kStep, y, 3, 0));
    tools[2].passes.push_back(p);
  }
  std::ostringstream program;
  program.setf(std::ios::fixed);
  program.precision(4);
  program << "%\nG21 G90 G17 G94\n";
  const char* calls[] = {"T1 M6\nS5000 M3\n", "T2 M6\nS6000 M3\n", "T3 M6\nS8000 M3\n"};
  for (std::size_t t = 0; t < tools.size(); ++t) {
    program << calls[t];
    for (const Pass& p : tools[t].passes) write_pass(program, p);
  }
  program << "M5\nM30\n%\n";

  geometry::SpherePatch sphere;
  sphere.center = {0, 0, kCentreZ};
  sphere.radius = kSphere;
  sphere.max_polar = 0.8;
  const geometry::AnalyticModel dome({sphere});
  PostSettings settings;
  settings.point.ap = 0.3;
  settings.threads = 2;
  tools::ToolChoices& choices = settings.tools.emplace();
  for (const char* t : {"T1=flat:10", "T2=ball:10", "T3=ball:6"})
    choices.table.add(tools::parse_tool_option(t));
  tools::add_stock_option("T2=0.3", choices);
  choices.vc = 80;
  StockSettings& stock = settings.stock.emplace();
  stock.box = Eigen::AlignedBox3d(Vector3d(-30, -30, -5), Vector3d(30, 30, 14));
  stock.cell_mm = 0.05;
  const std::vector<Tool> before_finish(tools.begin(), tools.begin() + 2);

  const geometry::Tool finisher = geometry::Tool::ball(6);
  std::size_t points = 0;
  double worst_ap = 0, worst_target = 0;
  // A block's S holds from where the last one ended: its target is the
  // lowest of its points' and the previous block's last point's.
  std::uint32_t last_line = 0;
  double last_target = 0;
  std::map<std::uint32_t, double> lowest_target;  // per block line: the independent S
  std::map<std::uint32_t, std::pair<double, plan::Bound>> posted;
  std::set<std::uint32_t> plunges;
  post_program(program.str(), "dome.nc", dome, machines::builtin_profile("mazak-3axis"), settings,
               {}, {},
               [&](const pipeline::PathSample& sample, const pipeline::PointResult& r,
                   const PointRecord& record) {
                 if (record.section != 3) return;
                 posted[record.line] = {record.s_after, record.bound};
                 // The plunge at a pass's start holds the program's S (its first
                 // points are in the air): the rows' blocks are compared.
                 if (std::abs(sample.direction.z()) > 0.5) plunges.insert(record.line);
                 if (!r.engagement || !r.contact.contact) return;
                 const Vector3d cc = r.contact.contact->point, n = r.contact.normal;
                 double t = 0;
                 while (t < 6 && cc.z() + (t + 1e-3) * n.z() <=
                                     stock_top(before_finish, cc.x() + (t + 1e-3) * n.x(),
                                               cc.y() + (t + 1e-3) * n.y(), 14))
                   t += 1e-3;
                 worst_ap = std::max(worst_ap, std::abs(r.ap - t));
                 const geometry::CutSetup setup{t, r.ae, n, r.feed, r.side};
                 const auto e = geometry::evaluate_engagement(finisher, setup);
                 const auto d = geometry::reference_diameter(geometry::DiameterPolicy::max, e, [&] {
                   return geometry::engaged_mean_diameter(finisher, setup);
                 });
                 if (!d) return;
                 const double target = 1000 * 80 / (std::numbers::pi * *d);
                 if (r.target_rpm)
                   worst_target = std::max(worst_target, std::abs(*r.target_rpm / target - 1));
                 const double carried =
                     last_line + 1 == record.line ? std::min(target, last_target) : target;
                 auto [it, fresh] = lowest_target.emplace(record.line, carried);
                 if (!fresh) it->second = std::min(it->second, target);
                 last_line = record.line;
                 last_target = target;
                 ++points;
               });
  EXPECT_GT(points, 1000u);
  // The grid reads the top at a cell's centre (0.035 mm away at most) on
  // cusps and the roughing's terraces no steeper than 1:1.
  EXPECT_LE(worst_ap, 0.04);
  // dD/dap = (D - 2 ap) / sqrt(ap (D - ap)) is about 4 at these depths.
  EXPECT_LE(worst_target, 0.03);
  std::size_t blocks = 0;
  double worst_s = 0;
  for (const auto& [line, target] : lowest_target) {
    const auto& [s, bound] = posted.at(line);
    if ((bound != plan::Bound::none && bound != plan::Bound::resolution) || plunges.contains(line))
      continue;
    worst_s = std::max(worst_s, std::abs(s / target - 1));
    ++blocks;
  }
  EXPECT_GT(blocks, 20u);
  EXPECT_LE(worst_s, 0.03);
}

}  // namespace
}  // namespace vcpost::post
