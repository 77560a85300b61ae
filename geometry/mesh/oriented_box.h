// The oriented boxes of the mesh index (mesh_hierarchy.cpp): each is fitted
// in a frame rounded to float and its extents rounded up, so that it holds
// every corner of its triangles exactly, and built in a fixed order of
// floating-point operations, so that the index is the same bit for bit
// whatever the compiler's choices or the number of threads.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include "geometry/mesh/corner_spread.h"

namespace vcpost::mesh {

// x rounded to float. The empty asm hides the float from the optimizer:
// GCC 12 at -O3 was seen to use x itself where a later expression reads the
// rounded float back as a double (two lanes of a vectorised conversion),
// which changes the boxes; the build relies on that rounding. On x86-64 the
// float stays in its SSE register: through memory ("+m"), the store and
// reload of the fifteen or so roundings of each box cost a twentieth of
// the build.
inline float to_float(double x) {
  auto f = static_cast<float>(x);
#if defined(__x86_64__)
  __asm__ volatile("" : "+x"(f));
#else
  __asm__ volatile("" : "+m"(f));
#endif
  return f;
}

inline float round_up(double v) {
  float f = to_float(v);
  // std::nextafter(f, +infinity) for a finite f when f < v, without the
  // library call, and chosen without branches: rounded down or up is a
  // coin toss, which the build's millions of these mispredicted half the
  // time. A zero of either sign steps to the least denormal (bits 1).
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  const std::uint32_t next = f > 0 ? bits + 1 : f == 0 ? 1u : bits - 1;
  bits = static_cast<double>(f) < v ? next : bits;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

// The products of the build, summed in a fixed order: the order GCC 12 and
// Eigen 3.4 gave `axes * x` (rows 0 and 1 left to right, row 2 its last two
// terms first) and `axes.transpose() * x` (left to right) when the boxes were
// first fitted, so the index stays the same bit for bit; spelled out, the
// order no longer depends on how the compiler happens to lay out a call.
inline Eigen::Vector3d times(const Eigen::Matrix3d& a, const Eigen::Vector3d& x) {
  return {(a(0, 0) * x[0] + a(0, 1) * x[1]) + a(0, 2) * x[2],
          (a(1, 0) * x[0] + a(1, 1) * x[1]) + a(1, 2) * x[2],
          a(2, 0) * x[0] + (a(2, 1) * x[1] + a(2, 2) * x[2])};
}
inline Eigen::Vector3d transpose_times(const Eigen::Matrix3d& a, const Eigen::Vector3d& x) {
  return {(a(0, 0) * x[0] + a(1, 0) * x[1]) + a(2, 0) * x[2],
          (a(0, 1) * x[0] + a(1, 1) * x[1]) + a(2, 1) * x[2],
          (a(0, 2) * x[0] + a(1, 2) * x[1]) + a(2, 2) * x[2]};
}

// The box of a binary hierarchy node, oriented: |axis[k].(x - centre)| <=
// half[k] for every corner x of the node's triangles (axes: a principal
// frame of the corners, or x, y, z when that box is smaller). Along a
// smooth surface the principal frame hugs the patch, so a ball resting on
// it reaches far fewer boxes than with axis-aligned ones.
struct OrientedBox {
  float centre[3];
  float axis[3][3];
  float half[3];
};

// lo, hi = the extents of the corners that for_each_corner(f) passes to f
// along the rows of `axes`: axes * x summed as Eigen sums that product
// (rows 0 and 1 left to right, row 2 its last two terms first), so the
// extents are the ones the Eigen expression gives. Minima and maxima do not
// depend on the order they are taken in, but for the sign of a zero: a zero
// extent is measured again, in the corners' order.
template <class Corners>
void project(const Corners& for_each_corner, const Eigen::Matrix3d& axes, Eigen::Vector3d& lo,
             Eigen::Vector3d& hi) {
  const double a00 = axes(0, 0), a01 = axes(0, 1), a02 = axes(0, 2);
  const double a10 = axes(1, 0), a11 = axes(1, 1), a12 = axes(1, 2);
  const double a20 = axes(2, 0), a21 = axes(2, 1), a22 = axes(2, 2);
  constexpr double inf = std::numeric_limits<double>::infinity();
  // Locals: writing through lo and hi on every corner stalls on store forwarding.
  double l0 = inf, l1 = inf, l2 = inf, h0 = -inf, h1 = -inf, h2 = -inf;
  const auto one = [&](double x, double y, double z) {
    const double q0 = (a00 * x + a01 * y) + a02 * z;
    const double q1 = (a10 * x + a11 * y) + a12 * z;
    const double q2 = a20 * x + (a21 * y + a22 * z);
    l0 = std::min(l0, q0);
    l1 = std::min(l1, q1);
    l2 = std::min(l2, q2);
    h0 = std::max(h0, q0);
    h1 = std::max(h1, q1);
    h2 = std::max(h2, q2);
  };
  for_each_corner(one);
  if (l0 == 0 || l1 == 0 || l2 == 0 || h0 == 0 || h1 == 0 || h2 == 0) {
    l0 = l1 = l2 = inf;
    h0 = h1 = h2 = -inf;
    for_each_corner(one);
  }
  lo = {l0, l1, l2};
  hi = {h0, h1, h2};
}

// project() over corners given as coordinate arrays (a scratch): the same
// products and sums for every corner, two corners at a time (GCC/Clang
// vector extension: SSE2 on x86-64), the minima and maxima of each lane
// apart and then merged. Taken in another order, they are the same numbers
// but for the sign of a zero; a zero extent is measured again corner by
// corner, in order, as project() does.
void project_arrays(const double* xs, const double* ys, const double* zs, std::size_t n,
                    const Eigen::Matrix3d& axes, Eigen::Vector3d& lo, Eigen::Vector3d& hi);

// The principal frame of a node's corners (rows: the axes, the one of
// least spread first), from their scatter about the mean.
Eigen::Matrix3d principal_frame(const CornerSpread& spread);

// The frame of a leaf (one or two triangles, three corners each, as
// for_each_corner(f) passes them): the sum of the triangles' area vectors
// first, then the longest edge, made orthogonal to it (around one triangle
// that box has the least area, twice the triangle's). As tight as the
// principal frame on the sample moulds and a fraction of the eigen
// solver's cost (leaves are most of the fitted nodes). False for a
// degenerate leaf, which takes the principal frame. corners passes at
// most max_corners corners.
template <int max_corners, class Corners>
bool leaf_frame(const Corners& corners, Eigen::Matrix3d& frame) {
  Eigen::Vector3d p[max_corners];
  int n = 0;
  corners([&](double x, double y, double z) { p[n++] = {x, y, z}; });
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  Eigen::Vector3d longest = Eigen::Vector3d::Zero();
  for (int t = 0; t < n; t += 3) {
    normal += (p[t + 1] - p[t]).cross(p[t + 2] - p[t]);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e = p[t + (k + 1) % 3] - p[t + k];
      if (e.squaredNorm() > longest.squaredNorm()) longest = e;
    }
  }
  if (!(normal.norm() > 0)) return false;
  const Eigen::Vector3d a0 = normal.normalized();
  // Off the plane by more than 60 degrees (two triangles at a sharp angle):
  // too short once projected for an orthonormal frame.
  const Eigen::Vector3d e = longest.normalized();
  const Eigen::Vector3d a2 = e - e.dot(a0) * a0;
  if (!(a2.norm() > 0.5)) return false;
  frame.row(0) = a0;
  frame.row(2) = a2.normalized();
  frame.row(1) = frame.row(2).cross(frame.row(0));
  return true;
}

}  // namespace vcpost::mesh
