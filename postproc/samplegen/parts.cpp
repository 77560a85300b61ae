#include "postproc/samplegen/parts.h"

#include <cmath>
#include <numbers>
#include <utility>

namespace vcpost::samplegen {
namespace {

constexpr double deg = std::numbers::pi / 180;

Eigen::AlignedBox2d box(double x0, double y0, double x1, double y1) {
  return {Eigen::Vector2d(x0, y0), Eigen::Vector2d(x1, y1)};
}

std::string trim_number(double v) {
  std::string s = fixed(v, 3);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

PathSpec spec(Pattern pattern, double angle, double stepover, double step,
              const Eigen::AlignedBox2d& window) {
  PathSpec s;
  s.pattern = pattern;
  s.angle_deg = angle;
  s.stepover = stepover;
  s.step = step;
  s.window = window;
  return s;
}

}  // namespace

std::vector<std::string> part_names() { return {"wavy", "cylinder", "dome"}; }

std::optional<Part> make_part(const std::string& name) {
  Part p;
  p.name = name;
  if (name == "wavy" || name == "patches") {
    p.surface = std::make_unique<WavyBspline>(WavyBspline::mould());
    if (name == "patches") p.step_faces_u = p.step_faces_v = 10;  // 12 x 8 mm faces
    p.tool_diameter = 10;
    // Slopes stay under 40 deg, so the contact is within 5*sin 40 < 4 mm of
    // the centre's xy: a 10 mm margin keeps it on the patch.
    p.raster_window = box(10, 10, 110, 70);
    p.iso_window = box(8, 8, 112, 72);
  } else if (name == "cylinder") {
    // Mikó-Beňo-Maňková: R100 convex cylinder, D12 ball, slopes 0..36.87 deg
    // (sin = 0.6: the ball centre's y goes to 0.6*(100 + 6) = 63.6 mm).
    p.surface = std::make_unique<SemiCylinder>(100, 40);
    p.tool_diameter = 12;
    p.safe_z = 120;  // the top line is at z = 100
    p.raster_window = box(10, 0, 15, 63.6);
    p.iso_window = box(10, 0, 15, std::asin(0.6));
  } else if (name == "dome") {
    // Walls up to 75 deg; the raster keeps the contact under 74 deg.
    p.surface = std::make_unique<Dome>(40, 75 * deg);
    p.tool_diameter = 10;
    p.raster_window = box(-45, -45, 45, 45);
    p.raster_radius = 45 * std::sin(74 * deg);
    p.iso_window = box(-std::numbers::pi, 10 * deg, std::numbers::pi, 74 * deg);
  } else {
    return std::nullopt;
  }
  return p;
}

std::vector<SampleProgram> sample_programs() {
  std::vector<SampleProgram> out;
  auto add = [&](const std::string& part, const std::string& stem, const std::string& title,
                 PathSpec path, double rpm, double feed) {
    const auto p = make_part(part);
    SampleProgram s{part, stem, title, std::move(path), {}};
    s.path.tool_radius = p->tool_diameter / 2;
    s.path.chord_tolerance = kSampleChordTolerance;
    s.program.safe_z = p->safe_z;
    s.program.title = title;
    s.program.tool_diameter = p->tool_diameter;
    s.program.spindle_rpm = rpm;
    s.program.feed = feed;
    out.push_back(s);
  };
  {
    const auto p = make_part("wavy");
    const PathSpec raster = spec(Pattern::raster, 0, 2, 2, p->raster_window);
    add("wavy", "wavy_raster_a0_ae2", "wavy B-spline mould, D10 ball, XY raster along X, ae 2",
        raster, 4800, 1000);
    const PathSpec iso = spec(Pattern::iso_u, 0, 4, 2, p->iso_window);
    add("wavy", "wavy_iso_u", "wavy B-spline mould, D10 ball, iso-parametric along u, 4 mm apart",
        iso, 4800, 1000);
  }
  {
    const auto p = make_part("cylinder");
    for (double ae : {0.2, 0.5, 0.8}) {
      for (double angle : {0.0, 45.0, 90.0}) {
        const PathSpec raster = spec(Pattern::raster, angle, ae, 2.5, p->raster_window);
        // Feed angle to the cylinder axis (x): 0 along the axis, 90 across it.
        add("cylinder", "cylinder_r100_ae" + trim_number(ae) + "_a" + trim_number(angle),
            "semi-cylinder R100, D12 ball, ap 0.2, ae " + trim_number(ae) + ", feed " +
                trim_number(angle) + " deg to the axis",
            raster, 4000, 800);
      }
    }
  }
  {
    const auto p = make_part("dome");
    PathSpec raster = spec(Pattern::raster, 0, 3, 3, p->raster_window);
    raster.window_radius = p->raster_radius;
    add("dome", "dome_raster_a0_ae3", "dome R40 with 75 deg walls, D10 ball, XY raster, ae 3",
        raster, 4800, 1000);
    PathSpec rings = spec(Pattern::iso_u, 0, 4 * deg, 7.5 * deg, p->iso_window);
    rings.zigzag = false;  // every ring starts at azimuth -180 deg
    add("dome", "dome_iso_rings",
        "dome R40, D10 ball, iso-parametric rings 4 deg apart (to 74 deg)", rings, 4800, 1000);
  }
  return out;
}

}  // namespace vcpost::samplegen
