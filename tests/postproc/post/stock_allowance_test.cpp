// Posting with a CAM allowance (--stock) against the model as it is equals
// posting with none against the model offset by hand: a semi-finishing
// raster left 0.3 mm above a dome and a pass 1.2 mm into it (a glue gap),
// with a ball and with a bull-nose. The contact, S and the whole report
// agree; and turning model and program together (--model-transform)
// leaves every S as it was.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>

#include "geometry/analytic_surfaces.h"
#include "geometry/rigid_transform.h"
#include "machines/builtin.h"
#include "postproc/post/post_job.h"
#include "postproc/report/json_documents.h"
#include "postproc/report/report.h"
#include "postproc/tools/tool_table.h"

namespace vcpost::post {
namespace {

using Eigen::Vector3d;

// The dome of the post tests: the sphere of radius `radius` about (0, 0, -20).
geometry::AnalyticModel dome(double radius) {
  geometry::SpherePatch sphere;
  sphere.center = {0, 0, -20};
  sphere.radius = radius;
  sphere.max_polar = 1.4;
  return geometry::AnalyticModel({sphere});
}

// A zig-zag raster of tool tip points, the tool (core disc radius `disc`,
// corner radius `corner`, a ball: 0 and R) resting on the sphere of radius
// `sphere` about (0, 0, -20), each point then moved by `place`.
std::string raster(double sphere, double disc, double corner, double stepover,
                   const geometry::RigidTransform& place = {}) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(6);
  out << "%\nG21 G90 G17 G94\nT1 M6\nS8000 M3\nF2000\n";
  const auto point = [&](double x, double y) {
    const double off = std::max(0.0, std::hypot(x, y) - disc), reach = sphere + corner;
    const Vector3d p = place.apply({x, y, -20 + std::sqrt(reach * reach - off * off) - corner});
    return "X" + std::to_string(p.x()) + " Y" + std::to_string(p.y()) + " Z" +
           std::to_string(p.z());
  };
  int pass = 0;
  for (; - 15 + pass * stepover <= 15 + 1e-9; ++pass) {
    const double y = -15 + pass * stepover;
    for (int i = 0; i <= 60; ++i) {
      const double x = pass % 2 == 0 ? -15 + 0.5 * i : 15 - 0.5 * i;
      out << (pass == 0 && i == 0 ? "G0 " : "G1 ") << point(x, y) << "\n";
    }
  }
  out << "G0 Z" << place.apply({0, 0, 60}).z() << "\nM5\nM30\n%\n";
  return out.str();
}

struct Outcome {  // NOLINT(bugprone-exception-escape): a test's value, moved once
  std::string program;
  PostSummary summary;
  std::vector<Vector3d> contacts, normals;
  std::vector<double> d_ref;
  nlohmann::json report;
};

Outcome run_post(const std::string& program, const geometry::SurfaceModel& model,
                 const std::string& tool, const std::string& stock) {
  PostSettings settings;
  settings.point.ap = 0.3;
  settings.point.ae = 1.5;
  settings.threads = 1;
  tools::ToolChoices& choices = settings.tools.emplace();
  choices.table.add(tools::parse_tool_option(tool));
  choices.vc = 150;
  if (!stock.empty()) tools::add_stock_option(stock, choices);
  const auto profile = machines::builtin_profile("mazak-3axis");
  report::ReportInputs inputs;
  inputs.tool_shape = *choices.table.every_tool()->geometry();
  inputs.vc_nominal = 150;
  inputs.n_max_rpm = profile.spindle().n_max_rpm;
  inputs.n_min_rpm = profile.spindle().n_min_rpm;
  inputs.plan_min = {-30, -30};
  inputs.plan_max = {30, 30};
  report::ReportCollector collector(inputs);
  Outcome out;
  const PointSink also = collector.point_sink();
  out.summary = post_program(
      program, "dome.nc", model, profile, settings,
      [&](std::string_view bytes) { out.program.append(bytes); }, {},
      [&](const pipeline::PathSample& sample, const pipeline::PointResult& result,
          const PointRecord& record) {
        also(sample, result, record);
        if (!result.contact.contact) return;
        out.contacts.push_back(result.contact.contact->point);
        out.normals.push_back(result.contact.normal);
        out.d_ref.push_back(result.d_ref.value_or(-1));
      });
  out.report = report::report_json(collector.finish(out.summary, 0));
  return out;
}

std::vector<double> s_per_line(const std::string& text) {
  std::vector<double> out;
  std::istringstream in(text);
  static const std::regex s_word(R"(S([0-9.]+))");
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    out.push_back(std::regex_search(line, m, s_word) ? std::stod(m[1].str()) : -1);
  }
  return out;
}

// Every number of two JSON documents within `tolerance` (relative to 1 and
// the value), every other value equal; the keys of `skip` are left out.
void expect_same_json(const nlohmann::json& a, const nlohmann::json& b, double tolerance,
                      const std::string& where = "") {
  static const std::vector<std::string> skip{"stock_mm", "run_time_s"};
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    EXPECT_LE(std::abs(x - y), tolerance * std::max(1.0, std::abs(y))) << where;
  } else if (a.is_object() && b.is_object()) {
    EXPECT_EQ(a.size(), b.size()) << where;
    for (const auto& [key, value] : a.items()) {
      if (std::find(skip.begin(), skip.end(), key) != skip.end()) continue;
      ASSERT_TRUE(b.contains(key)) << where << "/" << key;
      expect_same_json(value, b[key], tolerance, std::string(where).append("/").append(key));
    }
  } else if (a.is_array() && b.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << where;
    for (std::size_t i = 0; i < a.size(); ++i)
      expect_same_json(a[i], b[i], tolerance, where + "/" + std::to_string(i));
  } else {
    EXPECT_EQ(a, b) << where;
  }
}

struct Case {
  const char* tool;
  double disc, corner;  // the core disc's radius and the corner radius, mm
  double stock;         // mm
};

TEST(StockAllowance, PostsAsTheModelOffsetByHand) {
  for (const Case& c : {Case{"ball:10", 0, 5, 0.3}, Case{"ball:10", 0, 5, -1.2},
                        Case{"bull:10:2", 3, 2, 0.3}, Case{"bull:10:2", 3, 2, -1.2}}) {
    SCOPED_TRACE(::testing::Message() << c.tool << " stock " << c.stock);
    // The CAM's program: the tool on the dome grown by the allowance.
    const std::string program = raster(40 + c.stock, c.disc, c.corner, 1.5);
    std::ostringstream stock;
    stock << "T1=" << c.stock;
    const Outcome with_stock = run_post(program, dome(40), c.tool, stock.str());
    const Outcome by_hand = run_post(program, dome(40 + c.stock), c.tool, "");
    // Every point touches: the allowance took the offset away.
    EXPECT_EQ(with_stock.summary.samples, by_hand.summary.samples);
    EXPECT_EQ(with_stock.summary.touching, with_stock.summary.samples);
    EXPECT_EQ(with_stock.summary.gouging + with_stock.summary.lifted, 0u);
    ASSERT_EQ(with_stock.contacts.size(), by_hand.contacts.size());
    for (std::size_t i = 0; i < by_hand.contacts.size(); ++i) {
      ASSERT_LE((with_stock.contacts[i] - by_hand.contacts[i]).norm(), 1e-9) << i;
      ASSERT_LE((with_stock.normals[i] - by_hand.normals[i]).norm(), 1e-9) << i;
      ASSERT_NEAR(with_stock.d_ref[i], by_hand.d_ref[i], 1e-9) << i;
    }
    // The same S words on the same lines.
    EXPECT_EQ(s_per_line(with_stock.program), s_per_line(by_hand.program));
    EXPECT_GT(with_stock.summary.s_words, 10u);
    // The report: the same figures (its stock_mm says which allowance).
    expect_same_json(with_stock.report, by_hand.report, 1e-9);
    ASSERT_EQ(with_stock.summary.sections.size(), 1u);
    EXPECT_EQ(with_stock.summary.sections[0].stock.radial, c.stock);
    EXPECT_EQ(with_stock.report["sections"][0]["stock_mm"]["axial"].get<double>(), c.stock);
    // Without the allowance the path sits |stock| off the model: the
    // diagnosis names the option that posts it.
    const Outcome without = run_post(program, dome(40), c.tool, "");
    ASSERT_TRUE(without.summary.sections[0].offset);
    // The offset found is the mean over the points within 0.02 mm of it:
    // the chords between the program's points move it by a few um.
    EXPECT_NEAR(without.summary.sections[0].offset->offset_mm, c.stock, 0.005);
    std::smatch m;
    const std::string& option = without.summary.sections[0].offset->option;
    ASSERT_TRUE(std::regex_match(
        option, m, std::regex(R"(--stock[ =](-?[0-9]+\.[0-9]{3}) \(or --stock T1=(\S+)\))")))
        << option;
    EXPECT_NEAR(std::stod(m[1].str()), c.stock, 0.005) << option;
    EXPECT_EQ(m[1].str(), m[2].str());
    EXPECT_EQ(option[7], c.stock < 0 ? '=' : ' ') << option;
  }
}

TEST(StockAllowance, TurningModelAndProgramTogetherKeepsEveryS) {
  // A turn about the tool axis keeps a 3-axis program's tool axis (about
  // the origin: the rapid from there to the first point keeps its length,
  // and so the program's times).
  const geometry::RigidTransform turn = geometry::parse_rigid_transform("rz=37");
  const auto base = std::make_shared<geometry::AnalyticModel>(dome(40));
  const geometry::TransformedModel placed(base, turn);
  const Outcome as_is = run_post(raster(40.3, 0, 5, 1.5), *base, "ball:10", "0.3");
  const Outcome turned = run_post(raster(40.3, 0, 5, 1.5, turn), placed, "ball:10", "0.3");
  EXPECT_EQ(turned.summary.touching, as_is.summary.touching);
  ASSERT_EQ(turned.contacts.size(), as_is.contacts.size());
  for (std::size_t i = 0; i < as_is.contacts.size(); ++i) {
    // The program's coordinates are rounded to 1e-6 mm.
    ASSERT_LE((turned.contacts[i] - turn.apply(as_is.contacts[i])).norm(), 1e-5) << i;
    ASSERT_NEAR(turned.d_ref[i], as_is.d_ref[i], 1e-4) << i;
  }
  EXPECT_EQ(s_per_line(turned.program), s_per_line(as_is.program));
}

}  // namespace
}  // namespace vcpost::post
