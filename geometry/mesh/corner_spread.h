// The spread of a set of points (a hierarchy node's triangle corners):
// their count, mean, scatter about the mean (the covariance times the
// count) and extents. A node's spread is merged from its children's in
// constant time (Chan, Golub and LeVeque's pairwise update), so the
// principal frames of a whole hierarchy cost one pass over the corners,
// not one per level; the pairwise update keeps the scatter about the mean,
// without the cancellation of sums of squares far from the origin.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <limits>

namespace vcpost::mesh {

struct CornerSpread {
  double count = 0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();  // sum of (x - mean)(x - mean)^T
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
};

// The spread of n points given as coordinate arrays (two passes: the mean,
// then the scatter about it). Summed in scalars, in point order: each sum
// is the one Eigen's `mean += p` and `scatter += d d^T` give (the same
// operations on each entry), without the outer product's temporary, whose
// store and reload stalled the hierarchy's leaves (most of its nodes).
inline CornerSpread spread_of(const double* xs, const double* ys, const double* zs, std::size_t n) {
  CornerSpread s;
  if (n == 0) return s;
  s.count = static_cast<double>(n);
  const double* const c[3] = {xs, ys, zs};
  double sum[3] = {0, 0, 0}, lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = hi[k] = c[k][0];
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      const double x = c[k][i];
      sum[k] += x;
      lo[k] = std::min(lo[k], x);
      hi[k] = std::max(hi[k], x);
    }
  }
  double mean[3], scatter[3][3] = {};
  for (int k = 0; k < 3; ++k) mean[k] = sum[k] / s.count;
  for (std::size_t i = 0; i < n; ++i) {
    const double d[3] = {xs[i] - mean[0], ys[i] - mean[1], zs[i] - mean[2]};
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) scatter[r][k] += d[r] * d[k];
  }
  for (int r = 0; r < 3; ++r) {
    s.mean[r] = mean[r];
    s.lo[r] = lo[r];
    s.hi[r] = hi[r];
    for (int k = 0; k < 3; ++k) s.scatter(r, k) = scatter[r][k];
  }
  return s;
}

// The spread of the union of two disjoint point sets.
inline CornerSpread merged(const CornerSpread& a, const CornerSpread& b) {
  if (a.count == 0) return b;
  if (b.count == 0) return a;
  CornerSpread s;
  s.count = a.count + b.count;
  const Eigen::Vector3d delta = b.mean - a.mean;
  s.mean = a.mean + delta * (b.count / s.count);
  s.scatter = a.scatter + b.scatter + (delta * delta.transpose()) * (a.count * b.count / s.count);
  s.lo = a.lo.cwiseMin(b.lo);
  s.hi = a.hi.cwiseMax(b.hi);
  return s;
}

}  // namespace vcpost::mesh
