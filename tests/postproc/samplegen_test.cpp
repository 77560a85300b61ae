// The sample generator: its B-spline against an independent de Boor
// evaluation, its truth against the closed forms (1e-9), the programs read
// back by the G-code interpreter and the CL reader, samples/ as the
// generator writes it today, the 100-face STEP model of "patches" against
// the truth, the STL meshes against the surfaces, and the bull-nose and
// flat rasters against hand-computed tool positions and vcpost's post.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <sstream>

#include "geometry/mesh/stl_reader.h"
#include "geometry/occt/brep_model.h"
#include "geometry/occt/sample_parts.h"
#include "postproc/cldata/cl_reader.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/samplegen/parts.h"
#include "postproc/samplegen/surface_mesh.h"
#include "postproc/samplegen/surfaces.h"
#include "postproc/samplegen/tool_placement.h"
#include "postproc/samplegen/toolpath.h"
#include "tests/postproc/cli_run_support.h"
#include "tests/postproc/rs274_support.h"

namespace vcpost::samplegen {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
namespace fs = std::filesystem;

// de Boor's algorithm on one knot vector (independent of bspline_basis).
double de_boor(const std::vector<double>& t, int p, const std::vector<double>& c, double x) {
  int k = p;
  while (k + 1 < static_cast<int>(c.size()) && x >= t[k + 1]) ++k;
  std::vector<double> d(c.begin() + (k - p), c.begin() + k + 1);
  for (int r = 1; r <= p; ++r) {
    for (int j = p; j >= r; --j) {
      const int i = j + k - p;
      const double a = (x - t[i]) / (t[i + p + 1 - r] - t[i]);
      d[j] = (1 - a) * d[j - 1] + a * d[j];
    }
  }
  return d[p];
}

// The derivative curve's knots and coefficients (degree p - 1).
std::pair<std::vector<double>, std::vector<double>> derivative(const std::vector<double>& t, int p,
                                                               const std::vector<double>& c) {
  std::vector<double> dc;
  for (std::size_t i = 0; i + 1 < c.size(); ++i)
    dc.push_back(p * (c[i + 1] - c[i]) / (t[i + p + 1] - t[i + 1]));
  return {std::vector<double>(t.begin() + 1, t.end() - 1), dc};
}

// h, hx, hy of the mould by de Boor in v, then in u (tensor product).
std::array<double, 3> mould_height(const WavyBspline& s, double x, double y) {
  const auto& d = s.data();
  std::vector<double> column(d.count_u), dcolumn(d.count_u);
  for (int i = 0; i < d.count_u; ++i) {
    std::vector<double> row(d.count_v);
    for (int j = 0; j < d.count_v; ++j) row[j] = d.poles[i * d.count_v + j].z();
    column[i] = de_boor(d.knots_v, 3, row, y);
    const auto [tv, dv] = derivative(d.knots_v, 3, row);
    dcolumn[i] = de_boor(tv, 2, dv, y);
  }
  const auto [tu, du] = derivative(d.knots_u, 3, column);
  return {de_boor(d.knots_u, 3, column, x), de_boor(tu, 2, du, x),
          de_boor(d.knots_u, 3, dcolumn, x)};
}

TEST(Bspline, BasisIsAPartitionOfUnityWithMatchingDerivatives) {
  const std::vector<double> knots = {0, 0, 0, 0, 1, 2.5, 3, 5, 5, 5, 5};
  for (double x = 0; x <= 5; x += 0.0625) {
    std::array<std::array<double, 8>, 3> d{}, dp{}, dm{};
    bspline_basis(knots, 3, x, d);
    double sum = 0, dsum = 0, ddsum = 0;
    for (int k = 0; k <= 3; ++k) {
      sum += d[0][k];
      dsum += d[1][k];
      ddsum += d[2][k];
    }
    EXPECT_NEAR(sum, 1, 1e-14);
    EXPECT_NEAR(dsum, 0, 1e-12);
    EXPECT_NEAR(ddsum, 0, 1e-11);
    // Central differences inside a span (same span on both sides).
    const double h = 1e-5;
    if (x - h > 0 && x + h < 5 &&
        bspline_basis(knots, 3, x - h, dm) == bspline_basis(knots, 3, x + h, dp) &&
        bspline_basis(knots, 3, x, d) == bspline_basis(knots, 3, x + h, dp)) {
      for (int k = 0; k <= 3; ++k) {
        EXPECT_NEAR(d[1][k], (dp[0][k] - dm[0][k]) / (2 * h), 1e-8);
        EXPECT_NEAR(d[2][k], (dp[1][k] - dm[1][k]) / (2 * h), 1e-7);
      }
    }
  }
}

TEST(Bspline, MouldIsTheGraphOfItsBspline) {
  const WavyBspline s = WavyBspline::mould();
  for (double x = 0; x <= 120; x += 3.7) {
    for (double y = 0; y <= 80; y += 2.9) {
      const Vector3d p = s.point({x, y});
      EXPECT_NEAR(p.x(), x, 1e-12);  // poles at the Greville abscissae: x(u) = u
      EXPECT_NEAR(p.y(), y, 1e-12);
      const auto ref = mould_height(s, x, y);
      EXPECT_NEAR(p.z(), ref[0], 1e-12);
      const auto h = s.height({x, y});
      EXPECT_NEAR(h[1], ref[1], 1e-11);
      EXPECT_NEAR(h[2], ref[2], 1e-11);
    }
  }
}

// The smallest concave radius of the mould (a D12 ball must fit everywhere).
TEST(Bspline, MouldConcaveRadiiExceedTheBall) {
  const WavyBspline s = WavyBspline::mould();
  double largest_concave = 0;  // largest positive principal curvature of z = h (concave up)
  for (double x = 0; x <= 120; x += 0.5) {
    for (double y = 0; y <= 80; y += 0.5) {
      const auto h = s.height({x, y});
      const double w = std::sqrt(1 + h[1] * h[1] + h[2] * h[2]);
      // Second fundamental form over the first (graph surface), eigenvalues.
      Eigen::Matrix2d I, II;
      I << 1 + h[1] * h[1], h[1] * h[2], h[1] * h[2], 1 + h[2] * h[2];
      II << h[3] / w, h[4] / w, h[4] / w, h[5] / w;
      const Eigen::Vector2cd k = (I.inverse() * II).eigenvalues();
      largest_concave = std::max({largest_concave, k[0].real(), k[1].real()});
    }
  }
  EXPECT_LT(largest_concave, 1.0 / 6.0);
}

struct Row {
  std::uint64_t point, gcode_line, cl_line;
  int pass;
  Vector3d tip, cc, n;
  double error;
};

std::vector<Row> parse_truth(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(
      line,
      "point,pass,gcode_line,cl_line,tip_x,tip_y,tip_z,cc_x,cc_y,cc_z,n_x,n_y,n_z,distance_error");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream fields(line);
    std::string f;
    while (std::getline(fields, f, ',')) v.push_back(std::stod(f));
    EXPECT_EQ(v.size(), 14u);
    rows.push_back({static_cast<std::uint64_t>(v[0]), static_cast<std::uint64_t>(v[2]),
                    static_cast<std::uint64_t>(v[3]), static_cast<int>(v[1]),
                    Vector3d(v[4], v[5], v[6]), Vector3d(v[7], v[8], v[9]),
                    Vector3d(v[10], v[11], v[12]), v[13]});
  }
  return rows;
}

struct Written {
  std::string gcode, cl, truth;
  std::vector<PathPoint> points;
};

Written write(const SampleProgram& s) {
  const auto part = make_part(s.part);
  std::ostringstream g, c, t;
  Written w;
  ProgramWriter writer(s.program, &g, &c, &t);
  const auto n = generate(*part->surface, s.path, s.program.decimals, [&](const PathPoint& p) {
    writer.add(p);
    w.points.push_back(p);
  });
  writer.finish();
  EXPECT_EQ(n, w.points.size());
  EXPECT_LE(count_points(s.path), n);  // the nominal grid, before chord refinement
  w.gcode = g.str();
  w.cl = c.str();
  w.truth = t.str();
  return w;
}

// Closed-form checks of one truth point: CC on the surface, N its normal,
// C - CC along N (CC is a foot of the perpendicular), distance ~ R.
void check_truth(const std::string& part, const PathPoint& p, double r) {
  const Vector3d d = p.center - p.cc;
  Vector3d n_exact;
  if (part == "cylinder") {
    EXPECT_NEAR(std::hypot(p.cc.y(), p.cc.z()), 100, 1e-9);
    n_exact = Vector3d(0, p.cc.y(), p.cc.z()) / 100;
    EXPECT_NEAR(p.cc.x(), p.center.x(), 1e-9);
  } else if (part == "dome") {
    EXPECT_NEAR(p.cc.norm(), 40, 1e-9);
    n_exact = p.cc / 40;
  } else {
    const WavyBspline s = WavyBspline::mould();
    const auto h = mould_height(s, p.cc.x(), p.cc.y());
    EXPECT_NEAR(p.cc.z(), h[0], 1e-9);
    n_exact = Vector3d(-h[1], -h[2], 1).normalized();
  }
  EXPECT_NEAR((p.normal - n_exact).norm(), 0, 1e-9);
  EXPECT_NEAR((d - d.norm() * n_exact).norm(), 0, 1e-9);
  EXPECT_NEAR(p.distance_error, d.norm() - r, 1e-12);
  // Rounding the tip to 6 decimals moves C by at most sqrt(3)*5e-7.
  EXPECT_LE(std::abs(p.distance_error), 8.7e-7);
}

TEST(SampleGenerator, TruthAgreesWithTheClosedForms) {
  for (const auto& s : sample_programs()) {
    SCOPED_TRACE(s.stem);
    const Written w = write(s);
    ASSERT_GT(w.points.size(), 100u);
    for (const auto& p : w.points) check_truth(s.part, p, s.path.tool_radius);
  }
}

// No point of the surface is closer to C than the truth's CC (a grid of
// 200 x 200 over the patch, checked for every 40th point).
TEST(SampleGenerator, TruthIsTheGlobalClosestPoint) {
  for (const auto& s : sample_programs()) {
    if (s.stem.find("ae0.2") != std::string::npos) continue;  // same surface, fewer runs
    SCOPED_TRACE(s.stem);
    const auto part = make_part(s.part);
    const auto box = part->surface->domain();
    const Written w = write(s);
    for (std::size_t i = 0; i < w.points.size(); i += 40) {
      const auto& p = w.points[i];
      const double truth = (p.center - p.cc).norm();
      double grid = INFINITY;
      const int nu = 200, nv = 200;
      for (int a = 0; a <= nu; ++a) {
        for (int b = 0; b <= nv; ++b) {
          const Vector2d uv =
              box.min() +
              (box.max() - box.min()).cwiseProduct(Vector2d(double(a) / nu, double(b) / nv));
          grid = std::min(grid, (part->surface->point(uv) - p.center).norm());
        }
      }
      EXPECT_GE(grid, truth - 1e-9) << "point " << i;
    }
  }
}

TEST(SampleGenerator, RasterPointsAreOnTheirLines) {
  for (const auto& s : sample_programs()) {
    if (s.path.pattern != Pattern::raster) continue;
    SCOPED_TRACE(s.stem);
    const Written w = write(s);
    const double a = s.path.angle_deg * std::numbers::pi / 180;
    const Vector2d n(-std::sin(a), std::cos(a));
    double first_offset = 0;
    for (const auto& p : w.points) {
      const Vector2d xy = p.tip.head<2>();
      EXPECT_TRUE(s.path.window.exteriorDistance(xy) < 1e-6);
      if (p.link) continue;  // between two lines
      if (p.index == 0) first_offset = n.dot(xy);
      // Line offsets are multiples of ae from the first (to the 6-decimal rounding).
      const double k = (n.dot(xy) - first_offset) / s.path.stepover;
      EXPECT_NEAR(k, std::round(k), 2e-6 / s.path.stepover);
      EXPECT_NEAR(std::round(k), p.pass, 0.5);
    }
  }
}

TEST(SampleGenerator, GcodeReadsBackAsTheTruthPoints) {
  for (const auto& s : sample_programs()) {
    SCOPED_TRACE(s.stem);
    const Written w = write(s);
    const auto rows = parse_truth(w.truth);
    ASSERT_EQ(rows.size(), w.points.size());
    for (const auto& dialect : {gcode::rs274ngc_dialect(), gcode::fanuc_dialect()}) {
      gcode::Interpreter in(w.gcode, dialect);
      std::vector<program::Event> events;
      while (in.next(events)) {
      }
      std::size_t k = 0;
      bool spindle = false, tool = false, end = false;
      for (const auto& e : events) {
        // The approach: a rapid straight down to point 0.
        if (const auto* r = std::get_if<program::StraightTraverse>(&e);
            r && k == 0 && r->source.line == rows[0].gcode_line) {
          EXPECT_EQ(r->end, w.points[0].tip);
          ++k;
        } else if (const auto* f = std::get_if<program::StraightFeed>(&e)) {
          ASSERT_GT(k, 0u) << "a feed move before the approach";
          ASSERT_LT(k, rows.size());
          EXPECT_EQ(f->end, w.points[k].tip) << "point " << k;  // the same decimal, the same double
          EXPECT_EQ(f->source.line, rows[k].gcode_line);
          ++k;
        } else if (const auto* sp = std::get_if<program::SetSpindleSpeed>(&e)) {
          EXPECT_EQ(sp->rpm, s.program.spindle_rpm);
          spindle = true;
        } else if (const auto* t = std::get_if<program::ChangeTool>(&e)) {
          EXPECT_EQ(t->number, 1);
          tool = true;
        } else if (std::holds_alternative<program::ProgramEnd>(e)) {
          end = true;
        }
      }
      EXPECT_EQ(k, rows.size());
      EXPECT_TRUE(spindle && tool && end);
    }
  }
}

TEST(SampleGenerator, ClReadsBackAsTheTruthPoints) {
  for (const auto& s : sample_programs()) {
    SCOPED_TRACE(s.stem);
    const Written w = write(s);
    const auto rows = parse_truth(w.truth);
    std::istringstream text(w.cl);
    cldata::ClReader reader(text, s.stem + ".cls");
    std::size_t k = 0;
    bool end = false;
    while (const auto e = reader.next()) {
      if (const auto* r = std::get_if<program::StraightTraverse>(&*e);
          r && k == 0 && r->source.line == rows[0].cl_line) {
        EXPECT_EQ(r->end, w.points[0].tip);  // the approach: RAPID, GOTO point 0
        ++k;
      } else if (const auto* f = std::get_if<program::StraightFeed>(&*e)) {
        ASSERT_GT(k, 0u) << "a feed move before the approach";
        ASSERT_LT(k, rows.size());
        EXPECT_EQ(f->end, w.points[k].tip) << "point " << k;
        EXPECT_EQ(f->source.line, rows[k].cl_line);
        ++k;
      } else if (std::holds_alternative<program::ProgramEnd>(*e)) {
        end = true;
      }
    }
    EXPECT_EQ(k, rows.size());
    EXPECT_TRUE(end);
    EXPECT_TRUE(reader.warnings().empty());
    ASSERT_EQ(reader.cutters().size(), 1u);
    ASSERT_TRUE(reader.cutters()[0].tool.has_value());
    EXPECT_EQ(reader.cutters()[0].diameter(), s.program.tool_diameter);
  }
}

// Signed distance of a ball centre from the part's offset surface (the
// centres of a ball of radius r resting on it), mm: closed forms for the
// cylinder and the dome, the generator's Newton foot point for the mould.
double offset_distance(const Part& part, const Vector3d& c, double r, const Vector2d& guess) {
  if (part.name == "cylinder") return std::hypot(c.y(), c.z()) - (100 + r);
  if (part.name == "dome") return c.norm() - (40 + r);
  return (c - part.surface->point(part.surface->closest(c, guess))).norm() - r;
}

// Every straight move of a sample program (the feed moves between
// successive points, within and between passes) stays within the chord
// tolerance of the offset surface (checked at 32 points along each), so a
// reader sampling the moves sees neither a gouge nor a lift beyond it.
TEST(SampleGenerator, SampleMovesStayWithinTheChordTolerance) {
  for (const auto& s : sample_programs()) {
    SCOPED_TRACE(s.stem);
    EXPECT_EQ(s.path.chord_tolerance, kSampleChordTolerance);
    const auto part = make_part(s.part);
    const Written w = write(s);
    const double r = s.path.tool_radius;
    double worst = 0;
    for (std::size_t k = 1; k < w.points.size(); ++k) {
      const PathPoint& a = w.points[k - 1];
      const PathPoint& b = w.points[k];
      for (int j = 1; j < 32; ++j) {
        const Vector3d c = a.center + (b.center - a.center) * (j / 32.0);
        worst = std::max(worst, std::abs(offset_distance(*part, c, r, a.uv)));
      }
    }
    // The rounding of the written points to 6 decimals moves C by < 1e-6.
    EXPECT_LE(worst, kSampleChordTolerance + 1e-6);
  }
}

// Without a chord tolerance the path is the nominal grid (count_points);
// with one, points are added until the chords are within it: on the
// dome's lowest ring (74 deg), points 7.5 deg apart are joined by chords
// of half-length h = 45 sin 74 deg sin 3.75 deg whose middle is
// sqrt(45^2 - h^2) from the centre, 0.089 mm inside the 45 mm sphere of
// the ball centres; refined to 0.005 mm.
TEST(SampleGenerator, ChordToleranceRefinesTheNominalGrid) {
  const auto part = make_part("dome");
  PathSpec spec;
  spec.pattern = Pattern::iso_u;
  spec.tool_radius = 5;
  spec.window = part->iso_window;
  spec.stepover = 4 * std::numbers::pi / 180;
  spec.step = 7.5 * std::numbers::pi / 180;
  spec.zigzag = false;
  auto worst_chord = [&](std::uint64_t& count) {
    std::optional<PathPoint> last;
    double worst = 0;
    count = generate(*part->surface, spec, 6, [&](const PathPoint& p) {
      if (last) {
        for (int j = 1; j < 32; ++j) {
          const Vector3d c = last->center + (p.center - last->center) * (j / 32.0);
          worst = std::max(worst, std::abs(c.norm() - 45));
        }
      }
      last = p;
    });
    return worst;
  };
  std::uint64_t nominal = 0, refined = 0;
  const double coarse = worst_chord(nominal);
  EXPECT_EQ(nominal, count_points(spec));
  const double h =
      45 * std::sin(74 * std::numbers::pi / 180) * std::sin(3.75 * std::numbers::pi / 180);
  EXPECT_NEAR(coarse, 45 - std::sqrt(45 * 45 - h * h), 1e-5);
  spec.chord_tolerance = 0.005;
  const double fine = worst_chord(refined);
  EXPECT_LE(fine, 0.005 + 1e-6);
  EXPECT_GT(refined, nominal);
  EXPECT_EQ(count_points(spec), nominal);  // count_points: the grid before refinement
}

TEST(SampleGenerator, TruthCsvHoldsThePoints) {
  const auto s = sample_programs().front();
  const Written w = write(s);
  const auto rows = parse_truth(w.truth);
  ASSERT_EQ(rows.size(), w.points.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].point, i);
    EXPECT_EQ(rows[i].pass, w.points[i].pass);
    EXPECT_EQ(rows[i].tip, w.points[i].tip);
    EXPECT_NEAR((rows[i].cc - w.points[i].cc).cwiseAbs().maxCoeff(), 0, 5.1e-11);
    EXPECT_NEAR((rows[i].n - w.points[i].normal).cwiseAbs().maxCoeff(), 0, 5.1e-13);
  }
}

// samples/ holds exactly what `vcpost-samplegen samples` writes (programs
// and truth byte for byte; the STEP files carry a time stamp).
TEST(SampleGenerator, SamplesFolderIsUpToDate) {
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "samples";
  for (const auto& s : sample_programs()) {
    SCOPED_TRACE(s.stem);
    const Written w = write(s);
    for (const auto& [ext, text] : {std::pair{".nc", &w.gcode}, std::pair{".cls", &w.cl},
                                    std::pair{".truth.csv", &w.truth}}) {
      std::ifstream in(dir / (s.stem + ext), std::ios::binary);
      ASSERT_TRUE(in) << "missing " << (dir / (s.stem + ext));
      std::ostringstream file;
      file << in.rdbuf();
      EXPECT_TRUE(file.str() == *text) << s.stem << ext << " differs: regenerate samples/ (README)";
    }
  }
  for (const auto& name : part_names()) EXPECT_TRUE(fs::exists(dir / (name + ".step"))) << name;
}

// LinuxCNC's interpreter reads the committed programs as the same moves:
// the rapid down to point 0, a feed to every other (rs274 prints 4 decimals).
TEST(SampleGenerator, Rs274ReadsTheSamplePrograms) {
  if (!fs::exists("/usr/bin/rs274")) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "samples";
  for (const auto& s : sample_programs()) {
    SCOPED_TRACE(s.stem);
    const Written w = write(s);
    const std::string command =
        vcpost::testing::rs274_command("-g '" + (dir / (s.stem + ".nc")).string() + "'") +
        " < /dev/null 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string out;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, pipe) != nullptr) out += buf;
    pclose(pipe);
    std::istringstream lines(out);
    std::string line;
    std::size_t k = 0;
    std::optional<Vector3d> approach;  // the last rapid's end before the first feed
    while (std::getline(lines, line)) {
      const bool feed = line.find("STRAIGHT_FEED(") != std::string::npos;
      const auto at = line.find(feed ? "STRAIGHT_FEED(" : "STRAIGHT_TRAVERSE(");
      if (at == std::string::npos) continue;
      double x = 0, y = 0, z = 0;
      ASSERT_EQ(std::sscanf(line.c_str() + line.find('(', at) + 1, "%lf, %lf, %lf", &x, &y, &z), 3)
          << line;
      if (!feed) {
        if (k == 0) approach = Vector3d(x, y, z);
        continue;
      }
      if (k == 0) {  // the approach: a rapid straight down to point 0
        ASSERT_TRUE(approach.has_value());
        EXPECT_LE((*approach - w.points[0].tip).cwiseAbs().maxCoeff(), 5.01e-5);
        ++k;
      }
      ASSERT_LT(k, w.points.size());
      EXPECT_LE((Vector3d(x, y, z) - w.points[k].tip).cwiseAbs().maxCoeff(), 5.01e-5) << line;
      ++k;
    }
    EXPECT_EQ(k, w.points.size());
    EXPECT_EQ(out.find("error"), std::string::npos) << out.substr(0, 400);
  }
}

TEST(SampleGenerator, ScalesToAGivenPointCountInConstantMemory) {
  const auto part = make_part("wavy");
  PathSpec spec;
  spec.tool_radius = 5;
  spec.window = part->raster_window;
  spec.stepover = spec.step = std::sqrt(spec.window.volume() / 200000.0);
  std::uint64_t n = 0;
  double worst = 0;
  generate(*part->surface, spec, 6, [&](const PathPoint& p) {
    ++n;
    worst = std::max(worst, std::abs(p.distance_error));
  });
  EXPECT_NEAR(static_cast<double>(n), 200000.0, 2000.0);
  EXPECT_LE(worst, 8.7e-7);
}

TEST(SampleGenerator, WindowBeyondTheSurfaceIsRefused) {
  const auto part = make_part("cylinder");
  PathSpec spec;
  spec.window = Eigen::AlignedBox2d(Vector2d(0, 0), Vector2d(10, 120));  // y beyond R + r
  EXPECT_THROW(generate(*part->surface, spec, 6, [](const PathPoint&) {}), SurfaceError);
}

// A temporary folder removed at the end of the test.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() /
           ("vcpost_samplegen_test_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

// "patches" is the wavy mould with the same truth; only its STEP model is
// cut into 10 x 10 faces.
TEST(SampleGenerator, PatchesIsTheWavyMouldInTenByTenFaces) {
  const auto patches = make_part("patches");
  const auto wavy = make_part("wavy");
  ASSERT_TRUE(patches && wavy);
  EXPECT_EQ(patches->step_faces_u, 10);
  EXPECT_EQ(patches->step_faces_v, 10);
  EXPECT_EQ(wavy->step_faces_u * wavy->step_faces_v, 1);
  EXPECT_EQ(patches->raster_window.min(), wavy->raster_window.min());
  EXPECT_EQ(patches->raster_window.max(), wavy->raster_window.max());
  for (const Vector2d& uv : {Vector2d(0, 0), Vector2d(37.5, 61.25), Vector2d(120, 80)})
    EXPECT_EQ(patches->surface->point(uv), wavy->surface->point(uv));
}

// The STEP model written as `vcpost-samplegen step patches` writes it: 100
// faces, and every truth CC of a patches program is on it (1e-6 mm) and is
// the closest point the loaded model finds for the ball centre (1e-6 mm),
// across the faces' shared edges.
TEST(SampleGenerator, PatchesStepHoldsTheTruth) {
  const auto part = make_part("patches");
  const auto& d = dynamic_cast<const WavyBspline&>(*part->surface).data();
  const TempDir dir;
  const fs::path file = dir.path / "patches.step";
  occt::write_bspline_patches_step(
      file, {d.degree_u, d.degree_v, d.knots_u, d.knots_v, d.count_u, d.count_v, d.poles},
      part->step_faces_u, part->step_faces_v, "patches test");
  const auto model = occt::BrepModel::load_step(file);
  EXPECT_EQ(model.face_count(), 100);
  EXPECT_EQ(model.info().faces, 100);
  // The faces together are the 120 x 80 patch (the model's box is grown by
  // its tessellation margin, under 0.5 mm here).
  const Eigen::AlignedBox3d b = model.bounds();
  EXPECT_LE(b.min().x(), 0);
  EXPECT_GT(b.min().x(), -0.5);
  EXPECT_GE(b.max().x(), 120);
  EXPECT_LT(b.max().x(), 120.5);
  EXPECT_LE(b.min().y(), 0);
  EXPECT_GT(b.min().y(), -0.5);
  EXPECT_GE(b.max().y(), 80);
  EXPECT_LT(b.max().y(), 80.5);

  PathSpec spec;
  spec.tool_radius = part->tool_diameter / 2;
  // Ball centres over x 5..115, y 5..75; the contacts are within 4 mm of
  // them in xy (slopes under 40 deg), so they reach every one of the
  // 12 x 8 mm faces and stay on the patch.
  spec.window = Eigen::AlignedBox2d(Vector2d(5, 5), Vector2d(115, 75));
  spec.stepover = 2.3;  // not a multiple of the 12 x 8 mm faces: points fall near their edges
  spec.step = 0.7;
  std::vector<PathPoint> points;
  generate(*part->surface, spec, 6, [&](const PathPoint& p) { points.push_back(p); });
  ASSERT_GT(points.size(), 3000u);
  geometry::ContactHint hint;
  std::vector<bool> faces_hit(100, false);
  double worst_on = 0, worst_closest = 0, worst_normal = 0;
  for (const auto& p : points) {
    const auto on = model.closest_point(p.cc, 1.0, nullptr);
    ASSERT_TRUE(on.has_value());
    worst_on = std::max(worst_on, on->distance);
    const auto c = model.closest_point(p.center, 2 * spec.tool_radius, &hint);
    ASSERT_TRUE(c.has_value());
    worst_closest = std::max(worst_closest, (c->point - p.cc).norm());
    worst_normal = std::max(worst_normal, (c->normal - p.normal).norm());
    faces_hit[static_cast<std::size_t>(c->face)] = true;
  }
  EXPECT_LE(worst_on, 1e-6);
  EXPECT_LE(worst_closest, 1e-6);
  EXPECT_LE(worst_normal, 1e-6);
  EXPECT_EQ(std::count(faces_hit.begin(), faces_hit.end(), true), 100);
}

// The mesh of the wavy mould: about the asked number of triangles, every
// vertex on the surface (an independent de Boor evaluation, 1e-9 mm), the
// triangles facing the tool, and the binary STL reads back as the mesh to
// float precision.
TEST(SampleGenerator, StlMeshOfTheMouldIsOnTheSurface) {
  const WavyBspline s = WavyBspline::mould();
  for (const std::uint64_t n : {std::uint64_t{1000}, std::uint64_t{100000}}) {
    SCOPED_TRACE(n);
    const mesh::StlMesh m = triangulate(s, n);
    EXPECT_NEAR(static_cast<double>(m.triangles.size()), static_cast<double>(n),
                0.05 * static_cast<double>(n));
    double worst = 0;
    for (const auto& v : m.vertices) {
      ASSERT_GE(v.x(), 0);
      ASSERT_LE(v.x(), 120);
      ASSERT_GE(v.y(), 0);
      ASSERT_LE(v.y(), 80);
      worst = std::max(worst, std::abs(v.z() - mould_height(s, v.x(), v.y())[0]));
    }
    EXPECT_LE(worst, 1e-9);
    double area = 0;
    for (const auto& t : m.triangles) {
      const Vector3d a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
      const Vector3d normal = (b - a).cross(c - a);
      ASSERT_GT(normal.z(), 0);  // graph surface, normal up
      area += normal.z() / 2;    // projected area
    }
    EXPECT_NEAR(area, 120.0 * 80.0, 1e-7);  // the grid covers the domain exactly
    const mesh::StlMesh r = mesh::parse_stl(mesh::to_binary_stl(m, "test"), "mould.stl");
    ASSERT_EQ(r.triangles.size(), m.triangles.size());
    for (std::size_t i = 0; i < m.triangles.size(); i += 97) {
      for (int k = 0; k < 3; ++k) {
        const Vector3d a = m.vertices[m.triangles[i][k]], b = r.vertices[r.triangles[i][k]];
        EXPECT_LE((a - b).cwiseAbs().maxCoeff(), 120 * std::ldexp(1.0, -24)) << i;
      }
    }
  }
}

// Grid sizes: cells in the ratio of the surface's extents.
TEST(SampleGenerator, StlGridCellsAreAboutSquare) {
  const WavyBspline s = WavyBspline::mould();
  const mesh::StlMesh m = triangulate(s, 100000);
  // Vertex rows: (cells_u + 1) * (cells_v + 1) vertices; cells_v = vertices
  // with x == 0 minus one.
  const auto cells_v = std::count_if(m.vertices.begin(), m.vertices.end(),
                                     [](const Vector3d& v) { return v.x() == 0; }) -
                       1;
  const auto cells_u = static_cast<long>(m.vertices.size()) / (cells_v + 1) - 1;
  const double ratio = static_cast<double>(cells_u) / static_cast<double>(cells_v);
  // Along y the middle line x = 60 is 80 mm long plus its waves; along x
  // (y = 40) 120 mm plus the slope and waves: a ratio near 1.5.
  EXPECT_GT(ratio, 1.35);
  EXPECT_LT(ratio, 1.65);
  // The dome's pole collapses a row of cells: those lose one triangle each.
  const Dome dome(40, 75 * std::numbers::pi / 180);
  const mesh::StlMesh dm = triangulate_grid(dome, 36, 10);
  EXPECT_EQ(dm.triangles.size(), 2u * 36 * 10 - 36);
  for (const auto& t : dm.triangles) {
    const Vector3d a = dm.vertices[t[0]], b = dm.vertices[t[1]], c = dm.vertices[t[2]];
    EXPECT_GT((b - a).cross(c - a).dot((a + b + c) / 3), 0);  // outward, to the tool
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(dm.vertices[t[k]].norm(), 40, 1e-12);
  }
}

// The tool origin touching a point with its corner, by hand (R0 3, rc 2):
// the corner circle's centre X + 2n, then 3 mm along n's horizontal part.
TEST(ToolPlacement, OriginTouchingIsTheHandComputedPosition) {
  const Vector3d x(1, 2, 3);
  // n = (0.6, 0, 0.8): X + 2n = (2.2, 2, 4.6), then +3 along x.
  EXPECT_NEAR((origin_touching(x, Vector3d(0.6, 0, 0.8), 3, 2) - Vector3d(5.2, 2, 4.6)).norm(), 0,
              1e-12);
  // n = (-2, -1, 2)/3: |n_xy| = sqrt(5)/3, the horizontal unit (-2, -1)/sqrt(5).
  const Vector3d n = Vector3d(-2, -1, 2) / 3;
  const Vector3d hand(1 - 4.0 / 3 - 6 / std::sqrt(5.0), 2 - 2.0 / 3 - 3 / std::sqrt(5.0),
                      3 + 4.0 / 3);
  EXPECT_NEAR((origin_touching(x, n, 3, 2) - hand).norm(), 0, 1e-12);
  // A horizontal spot: the flat part on it, the axis above it.
  EXPECT_NEAR((origin_touching(x, Vector3d::UnitZ(), 3, 2) - Vector3d(1, 2, 5)).norm(), 0, 1e-12);
  // A ball (R0 0): its centre; a flat mill (rc 0): the rim on X.
  EXPECT_NEAR((origin_touching(x, n, 0, 5) - (x + 5 * n)).norm(), 0, 1e-12);
  EXPECT_NEAR((origin_touching(x, Vector3d(0.6, 0, 0.8), 5, 0) - Vector3d(6, 2, 3)).norm(), 0,
              1e-12);
}

// A raster of `tool` over the dome, 12 decimals, axis within 30 mm of the
// pole (the flat part over the pole included).
std::vector<PathPoint> dome_raster(double radius, double corner) {
  const auto part = make_part("dome");
  PathSpec spec;
  spec.tool_radius = radius;
  spec.corner_radius = corner;
  spec.window = Eigen::AlignedBox2d(Vector2d(-30, -30), Vector2d(30, 30));
  spec.window_radius = 30;
  spec.stepover = 2.9;  // passes at y = -30 + 2.9 k: two within R0 = 3 mm of the pole
  spec.step = 1.3;
  std::vector<PathPoint> points;
  generate(*part->surface, spec, 12, [&](const PathPoint& p) { points.push_back(p); });
  return points;
}

// Every point of a bull-nose (D10, rc 2) raster over the dome (R40 about
// the origin) is the tool position computed by hand for its axis: the core
// circle's point nearest the dome's centre is |p| - R0 off the axis (0 when
// the axis is within R0 of the pole: the flat part on the pole), at
// 40 + rc from the centre; the contact X is that point's foot on the
// sphere and the CL point the origin X + rc n + R0 n_xy/|n_xy| less rc.
TEST(SampleGenerator, BullNoseRasterIsTheHandComputedToolPosition) {
  const double r0 = 3, rc = 2, reach = 40 + rc;
  const auto points = dome_raster(5, rc);
  ASSERT_GT(points.size(), 500u);
  int over_the_pole = 0;
  for (const auto& p : points) {
    SCOPED_TRACE(p.index);
    const Vector2d axis = p.tip.head<2>();
    const double off = std::max(0.0, axis.norm() - r0);
    const Vector2d radial = axis.norm() > 0 ? Vector2d(axis.normalized()) : Vector2d(1, 0);
    const Vector3d corner_centre(off * radial.x(), off * radial.y(),
                                 std::sqrt(reach * reach - off * off));
    const Vector3d n = corner_centre / reach, x = 40 * n;
    Vector3d origin = corner_centre;
    if (off > 0) origin += r0 * Vector3d(radial.x(), radial.y(), 0);
    if (off == 0) {
      ++over_the_pole;
    } else {
      EXPECT_NEAR((origin.head<2>() - axis).norm(), 0, 1e-9);  // the formula's axis is the axis
    }
    EXPECT_NEAR(p.tip.z(), origin.z() - rc, 1e-9);
    EXPECT_NEAR((p.cc - x).norm(), 0, 1e-9);
    EXPECT_NEAR((p.normal - n).norm(), 0, 1e-9);
    EXPECT_NEAR((p.center - corner_centre).norm(), 0, 1e-9);
    EXPECT_NEAR(p.distance_error, 0, 1e-9);
  }
  EXPECT_GT(over_the_pole, 3);
}

// Lowest height, over a grid of mould points within `radius` of the axis,
// of a tool resting with its origin at `origin`: the distance of each
// point from the core disc less rc (negative: inside the tool, or under
// the shank above the origin's plane).
double clearance(const WavyBspline& mould, const Vector3d& origin, double radius, double corner) {
  const double r0 = radius - corner, h = 0.05;
  double lowest = HUGE_VAL;
  for (double dx = -radius; dx <= radius; dx += h) {
    for (double dy = -radius; dy <= radius; dy += h) {
      const Vector3d x = mould.point(origin.head<2>() + Vector2d(dx, dy));
      const double rho = std::hypot(dx, dy), dz = x.z() - origin.z();
      if (rho > radius) continue;
      if (dz > 0) {
        lowest = std::min(lowest, -dz);  // under the end's plane or the shank
        continue;
      }
      lowest = std::min(lowest, std::hypot(std::max(rho - r0, 0.0), dz) - corner);
    }
  }
  return lowest;
}

// Bull-nose and flat rasters over the wavy mould, valleys included (where
// a tool placed on one contact would cut into the rising sides): no mould
// point within the tool's reach of the axis is inside the tool (a 0.05 mm
// grid, 1e-6 mm for the 6-decimal rounding), and the tool touches (within
// the grid's error).
TEST(SampleGenerator, BullNoseAndFlatRastersDoNotCutIntoTheMould) {
  const auto part = make_part("wavy");
  const auto& mould = dynamic_cast<const WavyBspline&>(*part->surface);
  for (const double corner : {2.0, 0.0}) {
    SCOPED_TRACE(corner);
    PathSpec spec;
    spec.tool_radius = 5;
    spec.corner_radius = corner;
    spec.window = part->raster_window;
    spec.stepover = 7.3;
    spec.step = 3.1;
    std::vector<PathPoint> points;
    generate(mould, spec, 6, [&](const PathPoint& p) { points.push_back(p); });
    ASSERT_GT(points.size(), 200u);
    double worst = HUGE_VAL, loosest = -HUGE_VAL;
    for (std::size_t i = 0; i < points.size(); i += 3) {
      const Vector3d origin = points[i].tip + Vector3d(0, 0, corner);
      const double c = clearance(mould, origin, 5, corner);
      worst = std::min(worst, c);
      loosest = std::max(loosest, c);
    }
    EXPECT_GE(worst, -1e-6);
    EXPECT_LE(loosest, 0.05);  // a flat mill's rim contact falls between the grid's points
  }
}

// A bull-nose (D10, rc 2) raster over the wavy mould posts as a user runs
// it, `vcpost post` with no --tool: the G-code's Fusion 360 comment and the
// CL's CUTTER/ name the bull-nose, and no point gouges (E2011). A few
// points (about 2 %) read as lifted off: where the contact crosses a valley
// to the other flank, vcpost's contact search, warm-started on the rim
// where the last point touched, stops in the distance's local minimum on
// the old flank, 0.01-0.5 mm off, while the tool touches on the new one (a
// 0.02 mm grid of the mould put every such point of this program within
// 0.003 mm of the surface when this test was written). Hence no --strict.
TEST(SampleGenerator, BullNoseProgramPostsWithoutAGouge) {
  const auto part = make_part("wavy");
  const auto& d = dynamic_cast<const WavyBspline&>(*part->surface).data();
  const TempDir dir;
  occt::write_bspline_face_step(
      dir.path / "wavy.step",
      {d.degree_u, d.degree_v, d.knots_u, d.knots_v, d.count_u, d.count_v, d.poles}, "bull test");
  PathSpec spec;
  spec.tool_radius = 5;
  spec.corner_radius = 2;
  spec.window = Eigen::AlignedBox2d(Vector2d(20, 15), Vector2d(100, 65));  // valleys and crests
  spec.stepover = 5;
  spec.step = 2;
  spec.chord_tolerance = kSampleChordTolerance;
  ProgramSpec program;
  program.title = "wavy bull-nose test";
  program.tool_diameter = 10;
  program.corner_radius = 2;
  {
    std::ofstream g(dir.path / "bull.nc"), c(dir.path / "bull.cls");
    ProgramWriter writer(program, &g, &c, nullptr);
    generate(*part->surface, spec, 6, [&](const PathPoint& p) { writer.add(p); });
    writer.finish();
  }
  for (const char* name : {"bull.nc", "bull.cls"}) {
    SCOPED_TRACE(name);
    const auto run = testing::run_vcpost(
        std::string("post ") + name +
            " --model wavy.step --vc 120 --ap 0.3 --machine mazak-3axis -o out.nc"
            " --summary-json s.json",
        dir.path);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.err.find("E2011"), std::string::npos) << run.err;
    const auto summary = nlohmann::json::parse(testing::slurp(dir.path / "s.json"));
    EXPECT_EQ(summary["inputs"]["tool"], "bull:10:2");  // the tool the program names
    const auto& points = summary["points"];
    EXPECT_GT(points["total"].get<int>(), 2000);
    EXPECT_EQ(points["gouging"], 0);
    EXPECT_EQ(points["missed"], 0);
    EXPECT_LE(points["lifted"].get<int>() * 20, points["total"].get<int>());
  }
}

}  // namespace
}  // namespace vcpost::samplegen
