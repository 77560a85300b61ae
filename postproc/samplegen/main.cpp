// vcpost-samplegen: finishing programs (ball, bull-nose or flat end mill)
// over sample surfaces with
// exact truth, and the STEP files of those surfaces. Thin: argument
// parsing, files and exit codes; the work is in the samplegen library.
//
//   vcpost-samplegen path PART [options] --gcode F --cl F --truth F
//   vcpost-samplegen step PART FILE
//   vcpost-samplegen stl PART FILE [--triangles N]
//   vcpost-samplegen samples DIR        (regenerates samples/)
//
// Exit codes: 0 ok, 2 usage or input error, 3 internal error.
#include <CLI/CLI.hpp>
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <stdexcept>

#include "geometry/mesh/stl_reader.h"
#include "geometry/occt/sample_parts.h"
#include "geometry/tool.h"
#include "postproc/samplegen/parts.h"
#include "postproc/samplegen/surface_mesh.h"

namespace {

using namespace vcpost::samplegen;
namespace fs = std::filesystem;

struct UsageError : vcpost::Error {
  explicit UsageError(const std::string& message) : vcpost::Error(vcpost::Code::E2001, message) {}
};

// An output file written through a temporary name, renamed on commit().
class OutFile {
 public:
  explicit OutFile(const std::string& path) : path_(path) {
    if (path.empty()) return;
    temp_ = path + ".partial";
    out_.open(temp_, std::ios::binary);
    if (!out_) throw UsageError(path + ": cannot write");
  }
  ~OutFile() {
    if (!temp_.empty() && !committed_) fs::remove(temp_);
  }
  std::ostream* stream() { return path_.empty() ? nullptr : &out_; }
  void commit() {
    if (path_.empty()) return;
    out_.close();
    if (!out_) throw UsageError(path_ + ": write failed");
    fs::rename(temp_, path_);
    committed_ = true;
  }

 private:
  std::string path_, temp_;
  std::ofstream out_;
  bool committed_ = false;
};

Part part_or_throw(const std::string& name) {
  auto p = make_part(name);
  if (!p) throw UsageError("unknown part '" + name + "' (wavy, patches, cylinder, dome)");
  return std::move(*p);
}

void write_step(const Part& part, const fs::path& file) {
  if (const auto* wavy = dynamic_cast<const WavyBspline*>(part.surface.get())) {
    const auto& d = wavy->data();
    const vcpost::occt::BsplineSurfaceSpec spec{d.degree_u, d.degree_v, d.knots_u, d.knots_v,
                                                d.count_u,  d.count_v,  d.poles};
    if (part.step_faces_u * part.step_faces_v == 1) {
      vcpost::occt::write_bspline_face_step(file, spec, "vcpost wavy B-spline mould 120 x 80");
    } else {
      vcpost::occt::write_bspline_patches_step(file, spec, part.step_faces_u, part.step_faces_v,
                                               "vcpost wavy B-spline mould 120 x 80 in " +
                                                   std::to_string(part.step_faces_u) + " x " +
                                                   std::to_string(part.step_faces_v) + " faces");
    }
  } else if (part.name == "cylinder") {
    const auto& c = dynamic_cast<const SemiCylinder&>(*part.surface);
    // Axis x, reference z: the points (h, -R sin a, R cos a), a in [-pi/2, pi/2].
    vcpost::occt::write_cylinder_face_step(file, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                                           Eigen::Vector3d::UnitZ(), c.radius(),
                                           -std::numbers::pi / 2, std::numbers::pi / 2, 0,
                                           c.length(), "vcpost semi-cylinder R100");
  } else {
    const auto& d = dynamic_cast<const Dome&>(*part.surface);
    vcpost::occt::write_sphere_face_step(
        file, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
        d.radius(), std::numbers::pi / 2 - d.max_polar(), std::numbers::pi / 2, "vcpost dome R40");
  }
}

std::uint64_t write_program(const Part& part, const PathSpec& path, const ProgramSpec& program,
                            const std::string& gcode, const std::string& cl,
                            const std::string& truth) {
  OutFile g(gcode), c(cl), t(truth);
  ProgramWriter writer(program, g.stream(), c.stream(), t.stream());
  const std::uint64_t n =
      generate(*part.surface, path, program.decimals, [&](const PathPoint& p) { writer.add(p); });
  writer.finish();
  g.commit();
  c.commit();
  t.commit();
  return n;
}

// The options of `path`.
struct PathArgs {
  std::string part_name, pattern = "raster", gcode, cl, truth, title, tool;
  std::optional<double> diameter;  // --tool-diameter, the ball's
  double angle = 0, ae = 1, step = 1, rpm = 4000, feed = 800, chord = 0;
  std::uint64_t points = 0;
  int decimals = 6;
  std::vector<double> window;
  std::optional<double> radius;
};

CLI::App* add_path_command(CLI::App& app, PathArgs& a) {
  auto* path_cmd = app.add_subcommand("path", "write one program (G-code, APT CL, truth CSV)");
  path_cmd->add_option("part", a.part_name, "wavy | patches | cylinder | dome")->required();
  path_cmd->add_option("--pattern", a.pattern, "raster | iso-u | iso-v")
      ->check(CLI::IsMember({"raster", "iso-u", "iso-v"}));
  path_cmd->add_option("--tool-diameter", a.diameter, "ball diameter, mm (default: the part's)")
      ->check(CLI::PositiveNumber);
  path_cmd->add_option("--tool", a.tool,
                       "the tool: ball:D, bull:D:rc or flat:D, mm (default: the part's ball; "
                       "bull-nose and flat on the raster only)");
  path_cmd->add_option("--angle", a.angle, "raster feed direction in the xy plane, deg from +x");
  path_cmd->add_option("--ae", a.ae, "stepover: mm in xy (raster) or parameter units (iso)")
      ->check(CLI::PositiveNumber);
  path_cmd->add_option("--step", a.step, "largest point spacing along a pass (as --ae)")
      ->check(CLI::PositiveNumber);
  path_cmd
      ->add_option("--chord-tolerance", a.chord,
                   "add points until every straight move is within this of the ball-centre "
                   "path, mm (samples/: 0.005; default 0: the --step grid alone)")
      ->check(CLI::NonNegativeNumber);
  path_cmd->add_option("--window", a.window, "x0,y0,x1,y1 (raster: ball-centre xy; iso: u,v)")
      ->expected(4)
      ->delimiter(',');
  path_cmd->add_option("--radius", a.radius,
                       "raster: also keep the ball centre within this xy radius");
  path_cmd
      ->add_option("--points", a.points,
                   "about this many points: sets --ae = --step to fill the window")
      ->check(CLI::Range(std::uint64_t{10}, std::uint64_t{1'000'000'000}));
  path_cmd->add_option("--decimals", a.decimals, "decimals of the written coordinates (>= 6)")
      ->check(CLI::Range(6, 12));
  path_cmd->add_option("--rpm", a.rpm, "spindle speed S")->check(CLI::PositiveNumber);
  path_cmd->add_option("--feed", a.feed, "feed F, mm/min")->check(CLI::PositiveNumber);
  path_cmd->add_option("--title", a.title, "program title");
  path_cmd->add_option("--gcode", a.gcode, "G-code output file");
  path_cmd->add_option("--cl", a.cl, "APT CL output file");
  path_cmd->add_option("--truth", a.truth, "truth CSV output file");
  return path_cmd;
}

// --tool into the path's tool: its radius and, but for a ball, its corner
// radius. Bull-nose and flat paths are rasters only (PathSpec).
void set_tool(const PathArgs& a, PathSpec& spec) {
  if (a.tool.empty()) return;
  if (a.diameter) {
    throw UsageError(
        "give --tool or --tool-diameter, not both (--tool-diameter D is --tool ball:D)");
  }
  vcpost::geometry::Tool tool;
  try {
    tool = vcpost::geometry::parse_tool(a.tool);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--tool: ") + e.what());
  }
  spec.tool_radius = tool.radius();
  if (tool.kind == vcpost::geometry::ToolKind::ball) return;
  spec.corner_radius = tool.corner_radius;
  if (spec.pattern != Pattern::raster) {
    throw UsageError("--tool " + a.tool + ": a bull-nose or flat end mill is written on the " +
                     "raster pattern only (--pattern raster)");
  }
}

// `path`: one program over a part, with its truth.
void run_path(const PathArgs& a) {
  const Part part = part_or_throw(a.part_name);
  if (a.gcode.empty() && a.cl.empty() && a.truth.empty()) {
    throw UsageError("nothing to write: give --gcode, --cl and/or --truth");
  }
  PathSpec spec;
  spec.pattern = a.pattern == "raster"  ? Pattern::raster
                 : a.pattern == "iso-u" ? Pattern::iso_u
                                        : Pattern::iso_v;
  spec.tool_radius = a.diameter.value_or(part.tool_diameter) / 2;
  set_tool(a, spec);
  spec.angle_deg = a.angle;
  spec.stepover = a.ae;
  spec.step = a.step;
  spec.zigzag = true;
  spec.chord_tolerance = a.chord;
  const bool raster = spec.pattern == Pattern::raster;
  spec.window = raster ? part.raster_window : part.iso_window;
  spec.window_radius = raster ? (a.radius ? a.radius : part.raster_radius) : std::nullopt;
  if (!a.window.empty()) {
    spec.window = Eigen::AlignedBox2d(Eigen::Vector2d(a.window[0], a.window[1]),
                                      Eigen::Vector2d(a.window[2], a.window[3]));
    if (spec.window.isEmpty()) throw UsageError("--window: x0 <= x1 and y0 <= y1 expected");
  }
  if (a.points > 0) {
    double area = spec.window.volume();
    if (spec.window_radius) {
      area = std::min(area, std::numbers::pi * *spec.window_radius * *spec.window_radius);
    }
    spec.stepover = spec.step = std::sqrt(area / static_cast<double>(a.points));
  }
  ProgramSpec program;
  program.title = a.title.empty() ? part.name + " " + a.pattern + " sample" : a.title;
  program.tool_diameter = 2 * spec.tool_radius;
  program.corner_radius = spec.corner_radius;
  program.safe_z = part.safe_z;
  program.spindle_rpm = a.rpm;
  program.feed = a.feed;
  program.decimals = a.decimals;
  const std::uint64_t n = write_program(part, spec, program, a.gcode, a.cl, a.truth);
  std::cerr << "vcpost-samplegen: " << n << " points\n";
}

// `stl`: a binary STL mesh of a part's surface.
void run_stl(const std::string& part_name, const std::string& file, std::uint64_t triangles) {
  const Part part = part_or_throw(part_name);
  const vcpost::mesh::StlMesh m = triangulate(*part.surface, triangles);
  OutFile out(file);
  const std::string bytes =
      vcpost::mesh::to_binary_stl(m, "vcpost-samplegen " + part.name + " surface");
  out.stream()->write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.commit();
  std::cerr << "vcpost-samplegen: " << m.triangles.size() << " triangles\n";
}

// `samples`: the samples/ folder's parts and programs.
void run_samples(const std::string& dir) {
  fs::create_directories(dir);
  for (const auto& name : part_names())
    write_step(part_or_throw(name), fs::path(dir) / (name + ".step"));
  for (const auto& s : sample_programs()) {
    const Part part = part_or_throw(s.part);
    const fs::path base = fs::path(dir) / s.stem;
    const std::uint64_t n = write_program(part, s.path, s.program, base.string() + ".nc",
                                          base.string() + ".cls", base.string() + ".truth.csv");
    std::cerr << s.stem << ": " << n << " points\n";
  }
}

}  // namespace

// The whole body is in the try: building the command line can throw too.
int main(int argc, char** argv) try {
  CLI::App app{"vcpost-samplegen: finishing programs with exact truth over sample surfaces"};
  app.require_subcommand(1);

  PathArgs path_args;
  auto* path_cmd = add_path_command(app, path_args);

  auto* step_cmd = app.add_subcommand("step", "write the STEP file of a part's surface");
  std::string step_part, step_file;
  step_cmd->add_option("part", step_part, "wavy | patches | cylinder | dome")->required();
  step_cmd->add_option("file", step_file, "output .step")->required();

  auto* stl_cmd = app.add_subcommand("stl", "write a binary STL mesh of a part's surface");
  std::string stl_part, stl_file;
  std::uint64_t triangles = 100'000;
  stl_cmd->add_option("part", stl_part, "wavy | patches | cylinder | dome")->required();
  stl_cmd->add_option("file", stl_file, "output .stl")->required();
  stl_cmd->add_option("--triangles", triangles, "about this many triangles (grid of square cells)")
      ->check(CLI::Range(std::uint64_t{2}, std::uint64_t{20'000'000}));

  auto* samples_cmd =
      app.add_subcommand("samples", "regenerate the samples/ folder's parts and programs");
  std::string dir;
  samples_cmd->add_option("dir", dir, "output folder")->required();

  try {
    app.parse(argc, argv);
    if (*path_cmd) {
      run_path(path_args);
    } else if (*step_cmd) {
      write_step(part_or_throw(step_part), step_file);
    } else if (*stl_cmd) {
      run_stl(stl_part, stl_file, triangles);
    } else if (*samples_cmd) {
      run_samples(dir);
    }
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const UsageError& e) {
    std::cerr << "vcpost-samplegen: error: " << e.what() << '\n';
    return 2;
  } catch (const SurfaceError& e) {
    std::cerr << "vcpost-samplegen: error: " << e.what()
              << " (the window reaches beyond the surface; give a smaller --window)\n";
    return 2;
  }
  return 0;
} catch (const std::exception& e) {
  std::cerr << "vcpost-samplegen: internal error: " << e.what() << '\n';
  return 3;
}
