#include "postproc/program/bspline.h"

#include <algorithm>
#include <cmath>
#include <span>

namespace vcpost::program {

namespace {

Eigen::Vector3d project(const Eigen::Vector4d& h) { return h.head<3>() / h[3]; }

// Knot span index i with knots[i] <= u < knots[i+1] (the last non-empty span
// for u at the end).
std::size_t find_span(const BSpline& c, double u) {
  const std::size_t n = c.control.size() - 1;
  const auto p = static_cast<std::size_t>(c.degree);
  if (u >= c.knots[n + 1]) return n;
  const auto it = std::upper_bound(c.knots.begin() + static_cast<std::ptrdiff_t>(p),
                                   c.knots.begin() + static_cast<std::ptrdiff_t>(n + 1), u);
  return static_cast<std::size_t>(it - c.knots.begin()) - 1;
}

// de Boor's triangle with parameter xs[r-1] on level r: the blossom of the
// span's polynomial at (xs[0], ..., xs[p-1]); all equal gives the point.
Eigen::Vector4d blossom(const BSpline& c, std::size_t span, std::span<const double> xs) {
  const auto p = static_cast<std::size_t>(c.degree);
  std::vector<Eigen::Vector4d> d(c.control.begin() + static_cast<std::ptrdiff_t>(span - p),
                                 c.control.begin() + static_cast<std::ptrdiff_t>(span + 1));
  for (std::size_t r = 1; r <= p; ++r) {
    for (std::size_t j = p; j >= r; --j) {
      const std::size_t k = span - p + j;  // global index
      const double denom = c.knots[k + p + 1 - r] - c.knots[k];
      const double alpha = denom > 0 ? (xs[r - 1] - c.knots[k]) / denom : 0.0;
      d[j] = (1 - alpha) * d[j - 1] + alpha * d[j];
    }
  }
  return d[p];
}

double distance_to_segment(const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  double t = len2 > 0 ? (q - a).dot(ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return (q - (a + t * ab)).norm();
}

void flatten_bezier(std::vector<Eigen::Vector4d> b, double tolerance, int depth,
                    std::vector<Eigen::Vector3d>& out, std::size_t max_points) {
  if (out.size() >= max_points) return;
  const Eigen::Vector3d a = project(b.front());
  const Eigen::Vector3d e = project(b.back());
  double worst = 0;
  for (std::size_t i = 1; i + 1 < b.size(); ++i) {
    worst = std::max(worst, distance_to_segment(project(b[i]), a, e));
  }
  if (worst <= tolerance || !(worst < 1e300) || depth >= 30) {
    out.push_back(e);
    return;
  }
  // de Casteljau at t = 1/2.
  const std::size_t n = b.size();
  std::vector<Eigen::Vector4d> left(n), right(n);
  for (std::size_t r = 0; r < n; ++r) {
    left[r] = b[0];
    right[n - 1 - r] = b[n - 1 - r];
    for (std::size_t j = 0; j + 1 < n - r; ++j) b[j] = 0.5 * (b[j] + b[j + 1]);
  }
  flatten_bezier(std::move(left), tolerance, depth + 1, out, max_points);
  flatten_bezier(std::move(right), tolerance, depth + 1, out, max_points);
}

}  // namespace

Eigen::Vector3d evaluate(const BSpline& curve, double u) {
  const std::size_t span = find_span(curve, u);
  std::vector<double> xs(static_cast<std::size_t>(curve.degree), u);
  return project(blossom(curve, span, xs));
}

bool flatten(const BSpline& curve, double tolerance, std::vector<Eigen::Vector3d>& out,
             std::size_t max_points) {
  const std::size_t limit = out.size() + max_points;
  const auto p = static_cast<std::size_t>(curve.degree);
  const std::size_t n = curve.control.size() - 1;
  for (std::size_t span = p; span <= n; ++span) {
    const double a = curve.knots[span];
    const double b = curve.knots[span + 1];
    if (!(b > a)) continue;
    std::vector<Eigen::Vector4d> bezier(p + 1);
    std::vector<double> xs(p);
    for (std::size_t k = 0; k <= p; ++k) {
      for (std::size_t r = 0; r < p; ++r) xs[r] = r < p - k ? a : b;
      bezier[k] = blossom(curve, span, xs);
    }
    flatten_bezier(std::move(bezier), tolerance, 0, out, limit);
    if (out.size() >= limit) return false;
  }
  return true;
}

}  // namespace vcpost::program
