#include "postproc/gcode/nurbs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "postproc/gcode/splines.h"
#include "postproc/program/bspline.h"

namespace vcpost::gcode {

namespace {

[[noreturn]] void refuse(Code code, std::uint32_t line, std::uint32_t column, std::string message) {
  throw GcodeError(Diagnostic{code, line, column == 0 ? 1u : column, std::move(message)});
}

// The plane's axis pair as rs274's messages name it.
std::string axis_pair(program::Plane plane) {
  switch (plane) {
    case program::Plane::xz:
      return "X and Z";
    case program::Plane::yz:
      return "Y and Z";
    case program::Plane::xy:
      break;
  }
  return "X and Y";
}

}  // namespace

std::vector<double> nurbs_knots(std::size_t points, int order) {
  const auto k = static_cast<std::size_t>(order);
  const std::size_t n = points - 1;
  std::vector<double> knots;
  knots.reserve(n + k + 1);
  for (std::size_t i = 0; i <= n + k; ++i)
    knots.push_back(i < k    ? 0.0
                    : i <= n ? static_cast<double>(i - k + 1)
                             : static_cast<double>(n - k + 2));
  return knots;
}

bool nurbs_polyline(std::span<const NurbsControlPoint> control, int order, double tolerance,
                    std::vector<Eigen::Vector2d>& out, std::size_t max_points) {
  // The curve does not change when all weights are scaled alike: the
  // largest becomes 1, so that w * x stays finite for any weight rs274 takes.
  double top = 0.0;
  for (const auto& c : control) top = std::max(top, c.weight);
  program::BSpline curve;
  curve.degree = order - 1;
  curve.knots = nurbs_knots(control.size(), order);
  curve.control.reserve(control.size());
  for (const auto& c : control) {
    const double w = c.weight / top;
    // A weight more than about 1e308 below the largest becomes 0: a point
    // at infinity, no curve to follow.
    if (!(w >= std::numeric_limits<double>::min())) return false;
    curve.control.emplace_back(w * c.at.x(), w * c.at.y(), 0.0, w);
  }
  std::vector<Eigen::Vector3d> points;
  if (!program::flatten(curve, tolerance, points, max_points)) return false;
  // The clamped curve ends on its last control point: exactly, not as
  // w * x / w.
  points.back().head<2>() = control.back().at;
  Eigen::Vector2d at = control.front().at;
  for (const auto& p : points) {
    const Eigen::Vector2d q = p.head<2>();
    if (!q.allFinite()) return false;
    if (q == at) continue;
    out.push_back(q);
    at = q;
  }
  return true;
}

NurbsCurve::NurbsCurve(std::size_t max_moves) : max_moves_(max_moves) {}

void NurbsCurve::add(const NurbsWords& words, bool continues, bool zero_feed,
                     const Eigen::Vector2d& start, const Eigen::Vector2d& point,
                     const NurbsFrame& frame, std::uint32_t line) {
  const std::string pair = axis_pair(frame.plane);
  const bool has_point = words.first != nullptr && words.second != nullptr;
  if ((words.first == nullptr) != (words.second == nullptr))
    refuse(Code::E1507, line, (words.first ? words.first : words.second)->column,
           "a G5.2 control point needs both " + pair + " (rs274: \"You must specify both " + pair +
               " coordinates for Control Points\")");
  // rs274 checks against the points it keeps, those of a curve that another
  // motion mode abandoned included.
  const bool kept = !points_.empty();
  const Word* p = words.p;
  if (!has_point && p && p->value > 0 && kept)
    refuse(Code::E1507, line, p->column,
           "P without " + pair +
               " is the weight of the curve's first point (the tool's position), given on the "
               "G5.2 that opens the curve only (rs274: \"Can specify P without " +
               pair + " only for the first control point\")");
  // rs274 takes a missing P as -1 and P0 as 0 on the curve's first G5.2 (a
  // curve thrown through infinity where the weights sum to 0): vcpost asks
  // for a positive P wherever one is written or a point is given.
  const std::string weight_rule =
      " (rs274: \"Must specify positive weight P for every Control Point\")";
  if (p && !(p->value > 0 && std::isfinite(p->value)))
    refuse(Code::E1511, line, p->column,
           "P (a control point's weight) must be positive" + weight_rule);
  if (!p && (kept || has_point))
    refuse(Code::E1514, line, words.column,
           "a G5.2 control point needs its weight P" + weight_rule);
  if (zero_feed)
    refuse(Code::E1505, line, words.column,
           "G5.2 with no feed rate (F) in effect (rs274: \"Cannot make a NURBS with 0 "
           "feedrate\")");
  if (!continues) points_.clear();
  if (points_.empty()) {
    points_.push_back(NurbsControlPoint{start, !has_point && p ? p->value : 1.0});
    order_ = 3;
    frame_ = frame;
    first_line_ = line;
  } else if (!(frame == frame_)) {
    refuse(Code::E1515, line, words.column,
           "the plane, the units or an origin offset changed since the G5.2 on line " +
               std::to_string(first_line_) +
               " that opened the curve: its control points would mix two frames");
  }
  if (const Word* l = words.l) {
    if (l->value != std::floor(l->value) || std::abs(l->value) > 1e9)
      refuse(Code::E1511, line, l->column,
             "L (the curve's order) must be a whole number (rs274: \"Non integer value for "
             "integer\")");
    if (l->value > kMaxNurbsOrder)
      refuse(Code::E1511, line, l->column,
             "L (the curve's order) above " + std::to_string(kMaxNurbsOrder) +
                 ": LinuxCNC's evaluation doubles its work with each order (2^(L-1) steps per "
                 "basis function and point), vcpost follows up to L" +
                 std::to_string(kMaxNurbsOrder));
    // rs274: L up to 3 leaves the order as it is.
    if (l->value > 3) order_ = static_cast<int>(l->value);
  }
  if (has_point) {
    if (points_.size() >= max_moves_)
      refuse(Code::E1515, line, words.column,
             "the curve has more than " + std::to_string(max_moves_) +
                 " control points, the limit of moves one block may make");
    points_.push_back(NurbsControlPoint{point, p->value});
  }
}

Eigen::Vector2d NurbsCurve::end(bool open, const NurbsFrame& frame, std::uint32_t column,
                                std::uint32_t line, std::vector<Eigen::Vector2d>& out) {
  if (!open)
    refuse(Code::E1515, line, column,
           "G5.3 ends no curve: the motion mode is not G5.2 (rs274: \"Cannot use G5.3 without "
           "G5.2 first\")");
  if (!(frame == frame_))
    refuse(Code::E1515, line, column,
           "the plane, the units or an origin offset changed since the G5.2 on line " +
               std::to_string(first_line_) +
               " that opened the curve: its control points would mix two frames");
  const std::string order = std::to_string(order_);
  if (points_.size() < static_cast<std::size_t>(order_))
    refuse(Code::E1515, line, column,
           "the curve opened on line " + std::to_string(first_line_) + " has " +
               std::to_string(points_.size()) +
               " control points (the tool's position included), fewer than its order L = " + order +
               " (rs274: \"You must specify a number of control points at least equal to the "
               "order L = " +
               order + "\")");
  if (!nurbs_polyline(points_, order_, kSplineTolerance, out, max_moves_))
    refuse(Code::E1515, line, column,
           "the curve opened on line " + std::to_string(first_line_) + " needs more than " +
               std::to_string(max_moves_) + " straight moves within " +
               std::to_string(kSplineTolerance) +
               " mm, or its weights lie too far apart to compute: check its control points "
               "and weights");
  Eigen::Vector2d last = points_.back().at;
  points_.clear();
  return last;
}

}  // namespace vcpost::gcode
