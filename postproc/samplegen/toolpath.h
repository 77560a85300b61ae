// Finishing toolpaths of a ball, bull-nose or flat end mill over a
// SampleSurface, with the exact truth per point, and their writers (G-code,
// APT CL, truth CSV). Streaming: a path of any length is produced point by
// point in constant memory.
//
// Units: mm, radians inside (angles in degrees in PathSpec), mm/min, rpm.
// The CL point written is the tool tip (O - rc*z, O the tool frame's
// origin, tool_placement.h; for a ball O is the ball centre C and rc = R).
// Every written position is rounded to ProgramSpec::decimals first, and the
// truth is then computed for the rounded point: CC = the exact closest point
// of the surface to the corner's centre C = tip + rc*z + (offset, 0) as
// written (the ball centre; for a bull-nose the corner circle's centre at
// the contact, for a flat mill the touching rim point), N the surface
// normal there (equal to (C - CC)/|C - CC| up to the rounding of C),
// distance_error = |C - CC| - rc (at most about 10^-decimals; for a flat
// mill unsigned).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>

#include "postproc/samplegen/surfaces.h"

namespace vcpost::samplegen {

enum class Pattern {
  raster,  // drop-cutter: straight lines in the xy plane, the tool resting on the surface
  iso_u,   // iso-parametric, ball only: CC on lines of constant v, moving along u
  iso_v,   // iso-parametric, ball only: CC on lines of constant u, moving along v
};

struct PathSpec {
  Pattern pattern = Pattern::raster;
  double tool_radius = 6;  // mm, R
  // The corner radius rc of a bull-nose (0 < rc < R) or flat (0) end mill;
  // empty: a ball (rc = R). Those two are written on the raster only:
  // iso-parametric contacts would make the axis jump across every crest
  // (the contact's normal turns over while the flat part slides across).
  std::optional<double> corner_radius;
  // raster: feed direction in the xy plane (deg from +x), stepover between
  // the lines (xy plane, mm), largest spacing of points along a line (mm);
  // the tool axis (the ball centre's xy) stays in `window` (and within
  // `window_radius` of the origin when set).
  double angle_deg = 0;
  // iso_u / iso_v: stepover = parameter step between passes, step = largest
  // parameter step along a pass; window = the (u,v) box covered.
  double stepover = 1;
  double step = 0.5;
  Eigen::AlignedBox2d window{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1)};
  std::optional<double> window_radius;
  bool zigzag = true;  // alternate the direction of successive passes
  // Largest distance, mm, of a straight move between two written points
  // from the tool-origin path it stands for (the ball centre's on the
  // offset surface), within
  // a pass and on the link between passes: points are added between the
  // nominal ones until every chord's sagitta is within it (a reader that
  // samples the straight moves sees the tool off the surface by at most
  // this much). 0: the nominal points alone, links straight.
  double chord_tolerance = 0;
};

// One point of the path, as written and with its truth.
struct PathPoint {
  std::uint64_t index = 0;  // 0-based, in path order
  int pass = 0;             // 0-based pass number
  bool pass_start = false;  // the pass's first point (its link's, if it has one)
  bool link = false;        // on the link from the previous pass, not on this pass's line
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();      // CL point as written (rounded)
  Eigen::Vector3d center = Eigen::Vector3d::Zero();   // corner centre tip + rc*z + (offset, 0)
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();   // the contact's core-disc point from the axis
  Eigen::Vector3d cc = Eigen::Vector3d::Zero();       // exact closest surface point to center
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit surface normal at cc
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();       // parameters of cc
  double distance_error = 0;                          // |center - cc| - rc
};

// The number of nominal points `spec` gives (without computing them): all
// of them when its chord_tolerance is 0, else before refinement.
std::uint64_t count_points(const PathSpec& spec);

// Calls sink for every point in order; returns the number of points.
// Throws SurfaceError when the window reaches beyond the surface, and
// std::invalid_argument for an iso-parametric pattern with a tool that is
// not a ball.
std::uint64_t generate(const SampleSurface& surface, const PathSpec& spec, int decimals,
                       const std::function<void(const PathPoint&)>& sink);

// Fixed-point text of v with `decimals` digits ("-0.000000" printed as
// "0.000000"), and the double that text reads back as.
std::string fixed(double v, int decimals);
double round_trip(double v, int decimals);

struct ProgramSpec {
  std::string title;          // one line, printed in comments / PARTNO
  double tool_diameter = 12;  // mm
  // The corner radius of a bull-nose or flat end mill; empty: a ball.
  std::optional<double> corner_radius;
  int tool_number = 1;
  double spindle_rpm = 4000;
  double feed = 800;   // mm/min
  double safe_z = 50;  // mm, tip height of the rapid approach and retract
  int decimals = 6;
};

// Writes the program(s) and the truth as points arrive. Truth CSV columns:
// point, pass, gcode_line, cl_line (1-based line of the point's block; 0
// when that program is not written), tip_x..z (as written), cc_x..z (10
// decimals), n_x..z (12 decimals), distance_error (|C - CC| - rc). Any stream may be
// null (that output is not written). finish() writes the end of the
// programs; call it once after the last point.
class ProgramWriter {
 public:
  ProgramWriter(ProgramSpec spec, std::ostream* gcode, std::ostream* cl, std::ostream* truth);
  void add(const PathPoint& point);
  void finish();

 private:
  void gline(const std::string& text);
  void cline(const std::string& text);

  ProgramSpec spec_;
  std::ostream* gcode_;
  std::ostream* cl_;
  std::ostream* truth_;
  std::uint64_t gcode_line_ = 0, cl_line_ = 0;
  std::string last_[3];  // last written X, Y, Z words (G-code is modal)
  Eigen::Vector3d last_tip_ = Eigen::Vector3d::Zero();
  bool started_ = false;
};

}  // namespace vcpost::samplegen
