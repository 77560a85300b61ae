// LinuxCNC's G5.2/G5.3 NURBS curves, as rs274 reads them (convert_nurbs in
// interp_convert.cc): G5.2 opens a curve whose first control point is where
// the tool stands; each G5.2 block, and each block with axis words while
// G5.2 is the motion mode, adds a control point (the plane's two axis
// words) with its weight P; the tool does not move until G5.3 closes the
// curve and follows it. The curve is a rational B-spline of order L (3
// unless the curve's blocks give L > 3) on rs274's uniform clamped knot
// vector; vcpost follows it as straight feeds within kSplineTolerance.
//
// The interpreter hands each block's words here (NurbsCurve) and emits the
// moves; the rules and rs274's errors are kept in this one place.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "postproc/gcode/block.h"
#include "postproc/gcode/diagnostics.h"
#include "postproc/program/events.h"

namespace vcpost::gcode {

struct NurbsControlPoint {
  // In the plane's axes as rs274 orders them (program::plane_axes: X Y,
  // Z X, Y Z), mm.
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  double weight = 1.0;
};

// The highest order (L) vcpost follows. rs274 evaluates its basis functions
// by the plain recursion, 2^(L-1) calls per function and point: at L = 20
// a curve of 20 points already costs the control about a minute; no CAM
// system writes more than a handful. (vcpost's own cost grows as L^3 per
// span.)
inline constexpr int kMaxNurbsOrder = 20;

// rs274's knot vector (nurbs_G5_knot_vector_creator) for `points` control
// points of order `order` (2 <= order <= points): `order` zeros, then
// 1, 2, ..., points - order, then `order` times points - order + 1.
std::vector<double> nurbs_knots(std::size_t points, int order);

// Appends to `out` the points of the polyline that follows the curve from
// its first control point (not appended) to its last (appended, exactly),
// no point of the curve farther than `tolerance` from it; points that
// repeat the one before are left out. False (`out` partly filled) when
// more than `max_points` would be needed, or a point is not finite
// (weights too far apart for double arithmetic).
bool nurbs_polyline(std::span<const NurbsControlPoint> control, int order, double tolerance,
                    std::vector<Eigen::Vector2d>& out, std::size_t max_points);

// What a curve's control points are measured in: a change of plane, units
// or origin offsets between its G5.2 and its G5.3 is refused (rs274 keeps
// the points as numbers of the frame they were given in and mixes them).
struct NurbsFrame {
  program::Plane plane = program::Plane::xy;
  bool inches = false;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  bool operator==(const NurbsFrame&) const = default;
};

// One block's words for the curve, by their role in the working plane.
struct NurbsWords {
  const Word* first = nullptr;   // the plane's first axis word (X in G17, Z in G18, Y in G19)
  const Word* second = nullptr;  // its second (Y, X, Z)
  const Word* p = nullptr;       // the weight
  const Word* l = nullptr;       // the order
  std::uint32_t column = 1;      // the block's G5.2 word, or its first axis word
};

// The control points rs274 keeps: from a G5.2 to the G5.3 that ends the
// curve. A curve that another motion mode abandons keeps them until the
// next G5.2 (rs274's checks of that block count them, so it needs its P).
// Errors throw GcodeError at `line`.
class NurbsCurve {
 public:
  // `max_moves`: the control points a curve may have and the straight
  // moves it may make (InterpreterLimits::max_cycle_moves).
  explicit NurbsCurve(std::size_t max_moves);

  // A G5.2 block. `continues`: the motion mode before the block was G5.2
  // (else a curve starts at `start`, the tool's position); `point` the
  // block's control point when it gives both axis words; `zero_feed` a
  // feed per minute of 0 (rs274 refuses it on every G5.2 block).
  void add(const NurbsWords& words, bool continues, bool zero_feed, const Eigen::Vector2d& start,
           const Eigen::Vector2d& point, const NurbsFrame& frame, std::uint32_t line);
  // G5.3 (its word at `column`): `open` when the motion mode is G5.2. The
  // polyline (nurbs_polyline) appended to `out`; returns the curve's end,
  // its last control point, and clears the curve.
  Eigen::Vector2d end(bool open, const NurbsFrame& frame, std::uint32_t column, std::uint32_t line,
                      std::vector<Eigen::Vector2d>& out);

 private:
  std::size_t max_moves_;
  std::vector<NurbsControlPoint> points_;
  int order_ = 3;
  NurbsFrame frame_;
  std::uint32_t first_line_ = 0;  // the G5.2 that opened the curve
};

}  // namespace vcpost::gcode
