#include "postproc/gcode/splines.h"

#include <algorithm>
#include <cmath>

namespace vcpost::gcode {

Eigen::Vector2d bezier_point(const std::vector<Eigen::Vector2d>& control, double t) {
  std::vector<Eigen::Vector2d> p = control;
  for (std::size_t level = p.size(); level > 1; --level)
    for (std::size_t k = 0; k + 1 < level; ++k) p[k] = (1.0 - t) * p[k] + t * p[k + 1];
  return p.front();
}

std::vector<Eigen::Vector2d> spline_polyline(const std::vector<Eigen::Vector2d>& control,
                                             double tolerance) {
  // The second derivative of a degree-d Bezier curve is d (d - 1) times a
  // Bezier curve over the second differences of its control points, so
  // bounded by d (d - 1) times the largest of them.
  const auto degree = static_cast<double>(control.size() - 1);
  double second = 0.0;
  for (std::size_t k = 0; k + 2 < control.size(); ++k)
    second = std::max(second, (control[k] - 2.0 * control[k + 1] + control[k + 2]).norm());
  const double bound = degree * (degree - 1.0) * second;
  const double chords = std::ceil(std::sqrt(bound / (8.0 * tolerance)));
  const int n = std::clamp(static_cast<int>(std::min(chords, 1e9)), 1, kMaxSplineChords);
  std::vector<Eigen::Vector2d> points;
  points.reserve(static_cast<std::size_t>(n));
  for (int k = 1; k < n; ++k) points.push_back(bezier_point(control, static_cast<double>(k) / n));
  points.push_back(control.back());
  return points;
}

}  // namespace vcpost::gcode
