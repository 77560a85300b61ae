// The cells a move, a cap or a joint's wedge cuts: a convex region of the
// plane (half-planes, and a disc for caps and wedges), row by row. A row's
// cells are those whose centres lie in the region's x-window at the row's
// y, its edges linear in y, so a row costs a few multiplications. Every
// bound is padded outward: more cells than needed only cost time (the
// kernels give each cell its exact value), a cell lost would be an error.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "geometry/stock/height_field.h"

namespace vcpost::geometry::stock {

// Inclusive cell indices along an axis (empty when lo > hi).
struct CellRun {
  std::int64_t lo, hi;
};

// The cells of a grid axis (origin, cell, n) whose centres lie in [x0, x1],
// kept within a few cells of [0, n) so that infinite ends stay whole numbers.
inline CellRun cells_between(double x0, double x1, double origin, double inverse_cell,
                             std::int64_t n) {
  const double limit = static_cast<double>(n) + 2;
  const double lo = std::clamp((x0 - origin) * inverse_cell - 0.5, -2.0, limit);
  const double hi = std::clamp((x1 - origin) * inverse_cell - 0.5, -2.0, limit);
  // floor(hi) and ceil(lo) = -floor(-lo) by truncating positive values
  // (rounding can only add a cell whose centre is a rounding error outside).
  const double shift = limit + 1;
  const auto whole = static_cast<std::int64_t>(shift);
  return {whole - static_cast<std::int64_t>(shift - lo), static_cast<std::int64_t>(hi + 3) - 3};
}

class CellRegion {
 public:
  static constexpr double kInf = std::numeric_limits<double>::infinity();

  // Anchored at o: the half-planes and the disc are about o.
  explicit CellRegion(const Eigen::Vector2d& o) : origin_(o) {}

  // Keeps the points q with n.(q - o) >= t - pad (at most two such sides
  // bound x from below and two from above). A normal almost along y bounds
  // no row's x (the rows' range bounds it: only more cells).
  void keep_side(const Eigen::Vector2d& n, double t, double pad) {
    if (std::abs(n.x()) < 1e-9) return;
    const Edge edge{origin_.x() + (t - pad) / n.x(), -n.y() / n.x()};
    if (n.x() > 0) {
      lower_.at(lowers_++) = edge;
    } else {
      upper_.at(uppers_++) = edge;
    }
  }
  // Keeps the points within r of o.
  void keep_disc(double r) { disc_ = r; }

  // The cells of the line (a row, or a column with x and y swapped
  // throughout) whose centre is at y, along an axis of n cells from origin.
  CellRun row(double origin, double inverse_cell, std::int64_t n, double y) const {
    const double dy = y - origin_.y();
    double x0 = std::max(lower_[0].c + lower_[0].k * dy, lower_[1].c + lower_[1].k * dy);
    double x1 = std::min(upper_[0].c + upper_[0].k * dy, upper_[1].c + upper_[1].k * dy);
    if (disc_ < kInf) {
      const double half_sq = disc_ * disc_ - dy * dy;
      if (half_sq < 0) return {1, 0};
      const double half = std::sqrt(half_sq);
      x0 = std::max(x0, origin_.x() - half);
      x1 = std::min(x1, origin_.x() + half);
    }
    return cells_between(x0, x1, origin, inverse_cell, n);
  }

 private:
  struct Edge {
    double c = 0, k = 0;  // x = c + k * dy
  };
  Eigen::Vector2d origin_;
  // Unused edges bound nothing: x >= -inf, x <= inf.
  std::array<Edge, 2> lower_{Edge{-kInf, 0}, Edge{-kInf, 0}};
  std::array<Edge, 2> upper_{Edge{kInf, 0}, Edge{kInf, 0}};
  int lowers_ = 0, uppers_ = 0;
  double disc_ = kInf;
};

}  // namespace vcpost::geometry::stock
