#include "geometry/mesh/mesh_model.h"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/parallel_invoke.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <utility>

#include "geometry/mesh/corner_spread.h"

namespace vcpost::mesh {
namespace {

constexpr std::uint32_t leaf_size = 2;
constexpr int max_stack = 128;
// Subtrees at least this big are built as tasks of their own (a few
// hundred microseconds of work: far above a task's cost).
constexpr std::uint32_t task_size = 2048;
// Faces per task for the per-face loops.
constexpr std::size_t face_grain = 4096;

// The middle of slots [begin, end): where a node splits (the median), so
// the hierarchy's shape is a function of the number of triangles alone.
std::uint32_t middle(std::uint32_t begin, std::uint32_t end) { return begin + (end - begin) / 2; }

// Runs a and b, as two tasks when the range is big enough to pay for them.
template <class A, class B>
void both(std::uint32_t size, const A& a, const B& b) {
  if (size >= task_size) {
    tbb::parallel_invoke(a, b);
  } else {
    a();
    b();
  }
}

// x rounded to float. The empty asm hides the float from the optimizer:
// GCC 12 at -O3 was seen to use x itself where a later expression reads the
// rounded float back as a double (two lanes of a vectorised conversion),
// which changes the boxes; the build relies on that rounding. On x86-64 the
// float stays in its SSE register: through memory ("+m"), the store and
// reload of the fifteen or so roundings of each box cost a twentieth of
// the build.
float to_float(double x) {
  auto f = static_cast<float>(x);
#if defined(__x86_64__)
  __asm__ volatile("" : "+x"(f));
#else
  __asm__ volatile("" : "+m"(f));
#endif
  return f;
}

float round_up(double v) {
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
Eigen::Vector3d times(const Eigen::Matrix3d& a, const Eigen::Vector3d& x) {
  return {(a(0, 0) * x[0] + a(0, 1) * x[1]) + a(0, 2) * x[2],
          (a(1, 0) * x[0] + a(1, 1) * x[1]) + a(1, 2) * x[2],
          a(2, 0) * x[0] + (a(2, 1) * x[1] + a(2, 2) * x[2])};
}
Eigen::Vector3d transpose_times(const Eigen::Matrix3d& a, const Eigen::Vector3d& x) {
  return {(a(0, 0) * x[0] + a(1, 0) * x[1]) + a(2, 0) * x[2],
          (a(0, 1) * x[0] + a(1, 1) * x[1]) + a(2, 1) * x[2],
          (a(0, 2) * x[0] + a(1, 2) * x[1]) + a(2, 2) * x[2]};
}

// The box of a binary hierarchy node, oriented: |axis[k].(x - centre)| <=
// half[k] for every corner x of the node's triangles (axes: a principal
// frame of the corners, or x, y, z when that box is smaller). Along a
// smooth surface the principal frame hugs the patch, so a ball resting on
// it reaches far fewer boxes than with axis-aligned ones.
struct Node {
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
                    const Eigen::Matrix3d& axes, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  using D2 = double __attribute__((vector_size(16)));
  const auto load = [](const double* a) {
    D2 v;
    std::memcpy(&v, a, sizeof v);
    return v;
  };
  const auto splat = [](double x) { return D2{x, x}; };  // x in both lanes
  const D2 a00 = splat(axes(0, 0)), a01 = splat(axes(0, 1)), a02 = splat(axes(0, 2));
  const D2 a10 = splat(axes(1, 0)), a11 = splat(axes(1, 1)), a12 = splat(axes(1, 2));
  const D2 a20 = splat(axes(2, 0)), a21 = splat(axes(2, 1)), a22 = splat(axes(2, 2));
  constexpr double inf = std::numeric_limits<double>::infinity();
  D2 l0 = splat(inf), l1 = l0, l2 = l0;
  D2 h0 = splat(-inf), h1 = h0, h2 = h0;
  // q < l ? q : l lane by lane is std::min(l, q) (minpd on x86-64).
  const auto two = [&](D2 x, D2 y, D2 z) {
    const D2 q0 = (a00 * x + a01 * y) + a02 * z;
    const D2 q1 = (a10 * x + a11 * y) + a12 * z;
    const D2 q2 = a20 * x + (a21 * y + a22 * z);
    l0 = q0 < l0 ? q0 : l0;
    l1 = q1 < l1 ? q1 : l1;
    l2 = q2 < l2 ? q2 : l2;
    h0 = q0 > h0 ? q0 : h0;
    h1 = q1 > h1 ? q1 : h1;
    h2 = q2 > h2 ? q2 : h2;
  };
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) two(load(xs + i), load(ys + i), load(zs + i));
  if (i < n) two(splat(xs[i]), splat(ys[i]), splat(zs[i]));  // an odd last corner in both lanes
  lo = {std::min(l0[0], l0[1]), std::min(l1[0], l1[1]), std::min(l2[0], l2[1])};
  hi = {std::max(h0[0], h0[1]), std::max(h1[0], h1[1]), std::max(h2[0], h2[1])};
  if ((lo.array() != 0).all() && (hi.array() != 0).all()) return;
  const auto in_order = [&](auto& f) {
    for (std::size_t k = 0; k < n; ++k) f(xs[k], ys[k], zs[k]);
  };
  project(in_order, axes, lo, hi);
}

// Unit normal of the triangle a, b, c (counterclockwise seen from outside);
// +z for a degenerate one. The one expression every user of a facet normal
// goes through, so they agree bit for bit.
Eigen::Vector3d unit_normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double len = n.norm();
  return len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::UnitZ();
}

// The principal frame of a node's corners (rows: the axes, the one of
// least spread first), from their scatter about the mean.
Eigen::Matrix3d principal_frame(const CornerSpread& spread) {
  // The closed-form solver: a third of the iterative one's time (which was
  // a quarter of the build). Its vectors may be off orthogonal where two
  // eigenvalues nearly meet, so the frame is made orthonormal again (the
  // boxes hold the corners whatever the axes; the query's bounds need
  // them orthonormal): the smallest one kept, the normal of a flat patch.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(spread.scatter);
  const Eigen::Matrix3d& v = solver.eigenvectors();
  Eigen::Vector3d a0 = v.col(0);
  if (!(a0.norm() > 0.5)) a0 = Eigen::Vector3d::UnitZ();
  a0.normalize();
  Eigen::Vector3d a2 = v.col(2) - v.col(2).dot(a0) * a0;
  a2 = a2.norm() > 0.5 ? Eigen::Vector3d(a2.normalized()) : a0.unitOrthogonal();
  Eigen::Matrix3d principal;
  principal.row(0) = a0;
  principal.row(1) = a2.cross(a0);
  principal.row(2) = a2;
  return principal;
}

// The frame of a leaf (one or two triangles, three corners each, as
// for_each_corner(f) passes them): the sum of the triangles' area vectors
// first, then the longest edge, made orthogonal to it (around one triangle
// that box has the least area, twice the triangle's). As tight as the
// principal frame on the sample moulds and a fraction of the eigen
// solver's cost (leaves are most of the fitted nodes). False for a
// degenerate leaf, which takes the principal frame.
template <class Corners>
bool leaf_frame(const Corners& corners, Eigen::Matrix3d& frame) {
  constexpr int max_corners = 3 * static_cast<int>(leaf_size);
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

}  // namespace

// The index is built in a fixed order of floating-point operations, the
// same whatever the number of threads: the boxes (and so the order in which
// queries visit triangles, which decides ties) do not depend on it.
struct MeshModel::Builder {
  struct Item {
    // In single precision: 16 bytes an item, not 32, for the median
    // splits that move them (the centroids only choose where to split;
    // the boxes are fitted to the corners). Trivially copyable: the
    // splits read the centroid and the face as one 16-byte vector.
    std::array<float, 3> centroid;
    std::uint32_t face;
  };

  // The corners of a subtree's slots [base, base + size) side by side in
  // slot order (three per slot), copied once the splits have put the slots
  // in their final order: below a quarter million triangles the fits read
  // them from here rather than through the triangles (a copy of all the
  // corners at once took 72 bytes a face, 720 MB for 10 M triangles; a
  // block is 19 MB, one a running subtree).
  struct Scratch {
    std::uint32_t base;
    std::unique_ptr<double[]> block;  // x, y, z: 3 scratch_capacity doubles, reused from spare
    double* xyz[3];
  };
  static constexpr std::uint32_t scratch_size = 1u << 18;
  // Blocks of finished subtrees, for the next ones: each subtree's own
  // new and delete of a few MB went back to the system and came back as
  // fresh pages for the kernel to zero (10 M triangles: a third of the
  // 2.8 GB of page faults).
  std::size_t scratch_capacity = 0;  // 3 min(faces, scratch_size): corners per block
  std::mutex spare_mutex;
  std::vector<std::unique_ptr<double[]>> spare;

  MeshModel& m;
  const std::vector<std::array<std::uint32_t, 3>>& triangles;  // until the slots hold them
  std::unique_ptr<Item[]> items;  // in slot order, from the splits to the slots
  std::map<std::uint32_t, std::uint32_t> wide_counts;  // by subtree size; read only in build

  Builder(MeshModel& model, const std::vector<std::array<std::uint32_t, 3>>& t)
      : m(model), triangles(t) {}

  // A face side, in the groups edges() sorts them into.
  struct Side {
    std::uint32_t upper;      // its upper vertex
    std::uint32_t face_side;  // 4 face + side (faces are fewer than 2^30)
    // Left unset (user-provided, so a vector of them is not zero-filled):
    // every one is written, on the threads.
    Side() {}  // NOLINT(modernize-use-equals-default)
    Side(std::uint32_t u, std::uint32_t fs) : upper(u), face_side(fs) {}
  };
  void group_sides(std::vector<Side>& sides, std::vector<std::size_t>& start) const;
  void edges();
  void vertex_normals();
  void splits();
  void boxes();
  void slots();
  template <class F>
  void for_each_corner(std::uint32_t begin, std::uint32_t end, F&& f) const;
  void fit_node(Node& node, std::uint32_t begin, std::uint32_t end, const CornerSpread& spread,
                const Scratch* scratch) const;
  // Not const: they reorder the slots' items (through `items`).
  void split(std::uint32_t begin, std::uint32_t end);
  void split_all(std::uint32_t begin, std::uint32_t end);
  CornerSpread top(std::uint32_t begin, std::uint32_t end, std::uint32_t own, Scratch* scratch);
  CornerSpread expanded(std::uint32_t begin, std::uint32_t end, std::uint32_t wide, int lane,
                        std::uint32_t own_left, std::uint32_t own_right, Scratch* scratch);
  CornerSpread lane(std::uint32_t begin, std::uint32_t end, std::uint32_t wide, int lane,
                    std::uint32_t own, Scratch* scratch);
  std::uint32_t count_wide(std::uint32_t size);
  void clear_lanes(std::uint32_t wide);
  void set_lane(std::uint32_t wide, int lane, const Node& box, std::uint32_t child,
                std::uint32_t count);
};

MeshModel::Vertices::Vertices(std::vector<Eigen::Vector3d>&& points) {
  const bool floats = std::all_of(points.begin(), points.end(), [](const Eigen::Vector3d& p) {
    return p.cast<float>().cast<double>() == p;
  });
  if (!floats) {
    double_ = std::move(points);
    return;
  }
  single_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) single_[i] = points[i].cast<float>();
  std::vector<Eigen::Vector3d>().swap(points);
}

MeshModel::MeshModel(StlMesh mesh) : vertices_(std::move(mesh.vertices)) {
  std::vector<std::array<std::uint32_t, 3>> triangles = std::move(mesh.triangles);
  const std::size_t nf = triangles.size();
  const std::size_t nv = vertices_.size();
  // Internal invariant, not the user's input: the STL reader refuses an empty or
  // oversized mesh first (StlError, E46xx); invalid_argument marks a bug.
  if (nf == 0) throw std::invalid_argument("MeshModel: the mesh has no triangles");
  if (nf >= kMaxFaces) throw std::invalid_argument("MeshModel: too many triangles");
  if (nv >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("MeshModel: too many vertices");
  for (const auto& t : triangles)
    for (auto i : t)
      if (i >= nv) throw std::invalid_argument("MeshModel: corner index out of range");

  bounds_.setEmpty();
  for (std::size_t v = 0; v < nv; ++v) bounds_.extend(vertices_[v]);

  // Phases on oneTBB's threads, mostly one after the other, so that their
  // scratch memory is not held at once (the 10 M-triangle mould peaked at
  // 2.6 GB with the normals and the tree built side by side). The edges and
  // the median splits go side by side (the split of the root, and of its
  // children, is serial: the edges keep the other thread busy meanwhile;
  // their scratch and the centroids together stay below the later peak).
  // The slots are laid out once the splits have ordered them and the
  // triangles go; the boxes then read the corners through the slots, in
  // order (one indirection less than through the triangles); the vertex
  // normals, last (they would be held through the tree), read them there
  // too.
  Builder builder(*this, triangles);
  tbb::parallel_invoke([&] { builder.edges(); }, [&] { builder.splits(); });
  builder.slots();
  std::vector<std::array<std::uint32_t, 3>>().swap(triangles);
  builder.boxes();
  builder.vertex_normals();
}

// Angle-weighted vertex normals. The sums are taken in face order, corner
// by corner (their rounding depends on the order). A block of faces at a
// time: their corners' weighted facet normals computed in parallel (no
// array of them for every face), then added in face order, while the next
// block's are computed (the adding is serial: alone, it left a thread idle
// for a third of this phase).
void MeshModel::Builder::vertex_normals() {
  const std::size_t nf = m.slots_.size();
  const std::size_t nv = m.vertices_.size();
  m.vertex_normal_.assign(nv, Eigen::Vector3d::Zero());
  constexpr std::size_t block = 16 * face_grain;
  using Weighted = std::vector<std::array<Eigen::Vector3d, 3>>;
  Weighted weighted[2] = {Weighted(std::min(nf, block)), Weighted(std::min(nf, block))};
  const auto compute = [&](std::size_t first, Weighted& out) {
    const std::size_t last = std::min(nf, first + block);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(first, last, face_grain), [&](const auto& r) {
      for (std::size_t f = r.begin(); f < r.end(); ++f) {
        const std::uint32_t* t = m.corners_of(static_cast<std::uint32_t>(f));
        const Eigen::Vector3d p[3] = {m.vertices_[t[0]], m.vertices_[t[1]], m.vertices_[t[2]]};
        const Eigen::Vector3d facet = unit_normal(p[0], p[1], p[2]);
        // The third angle from the other two (they sum to pi): one atan2
        // less a face, the third of this phase's time.
        double angle[3];
        for (int k = 0; k < 2; ++k) {
          const Eigen::Vector3d e1 = p[(k + 1) % 3] - p[k];
          const Eigen::Vector3d e2 = p[(k + 2) % 3] - p[k];
          angle[k] = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
        }
        angle[2] = std::max(0.0, std::numbers::pi - angle[0] - angle[1]);
        for (int k = 0; k < 3; ++k) out[f - first][k] = angle[k] * facet;
      }
    });
  };
  const auto add = [&](std::size_t first, const Weighted& in) {
    const std::size_t last = std::min(nf, first + block);
    for (std::size_t f = first; f < last; ++f) {
      const std::uint32_t* t = m.corners_of(static_cast<std::uint32_t>(f));
      for (int k = 0; k < 3; ++k) m.vertex_normal_[t[k]] += in[f - first][k];
    }
  };
  compute(0, weighted[0]);
  for (std::size_t first = 0, b = 0; first < nf; first += block, b ^= 1) {
    if (first + block < nf) {
      tbb::parallel_invoke([&] { add(first, weighted[b]); },
                           [&] { compute(first + block, weighted[b ^ 1]); });
    } else {
      add(first, weighted[b]);
    }
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, face_grain), [&](const auto& r) {
    for (std::size_t v = r.begin(); v < r.end(); ++v) {
      Eigen::Vector3d& n = m.vertex_normal_[v];
      const double len = n.norm();
      n = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::UnitZ();
    }
  });
}

// The face sides grouped by their lower vertex, in face order within each
// group (group v: sides[start[v], start[v + 1])). A counting sort over a
// fixed number of face ranges at once: each range counts its sides per
// vertex, then places them after those of the ranges before it, so the
// order is the one face by face gives, whatever the threads (serial, it
// took 0.4 s of the 10 M-triangle mould's index).
void MeshModel::Builder::group_sides(std::vector<Side>& sides,
                                     std::vector<std::size_t>& start) const {
  constexpr std::uint32_t ranges = 4;
  const auto nf = static_cast<std::uint32_t>(triangles.size());
  const std::size_t nv = m.vertices_.size();
  // cursor[r nv + v]: the number of range r's sides in group v, then where
  // range r puts its next one (32 bits: there are 3 nf < 2^32 sides).
  std::vector<std::uint32_t> cursor(ranges * nv, 0);
  const auto each_range = [&](const auto& body) {
    tbb::parallel_for(std::uint32_t{0}, ranges, [&](std::uint32_t r) {
      const auto first = static_cast<std::uint32_t>(std::uint64_t{nf} * r / ranges);
      const auto last = static_cast<std::uint32_t>(std::uint64_t{nf} * (r + 1) / ranges);
      body(cursor.data() + r * nv, first, last);
    });
  };
  each_range([&](std::uint32_t* count, std::uint32_t first, std::uint32_t last) {
    for (std::uint32_t f = first; f < last; ++f) {
      const auto& t = triangles[f];
      for (int k = 0; k < 3; ++k) ++count[std::min(t[k], t[(k + 1) % 3])];
    }
  });
  start.resize(nv + 1);
  std::size_t at = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    start[v] = at;
    for (std::size_t r = 0; r < ranges; ++r) {
      const std::uint32_t count = cursor[r * nv + v];
      cursor[r * nv + v] = static_cast<std::uint32_t>(at);
      at += count;
    }
  }
  start[nv] = at;
  sides.resize(at);
  each_range([&](std::uint32_t* next, std::uint32_t first, std::uint32_t last) {
    for (std::uint32_t f = first; f < last; ++f) {
      const auto& t = triangles[f];
      for (std::uint32_t k = 0; k < 3; ++k) {
        const auto [lo, hi] = std::minmax(t[k], t[(k + 1) % 3]);
        sides[next[lo]++] = Side(hi, 4 * f + k);
      }
    }
  });
}

// What makes the pseudo-normals that tell inside from outside at edges
// (the sum of the facet normals of the faces sharing the edge, in face
// order): the face across each side, or the sum itself for an edge of
// three faces or more.
void MeshModel::Builder::edges() {
  const auto nf = static_cast<std::uint32_t>(triangles.size());
  const std::size_t nv = m.vertices_.size();
  const auto facet = [&](std::uint32_t f) {
    const auto& t = triangles[f];
    return unit_normal(m.vertices_[t[0]], m.vertices_[t[1]], m.vertices_[t[2]]);
  };

  // Edges: the face sides grouped by their lower vertex, then each group
  // sorted by upper vertex, face and side: a run of equal upper vertices is
  // one edge, in face order.
  std::vector<Side> sides;
  std::vector<std::size_t> start;
  group_sides(sides, start);
  // Two passes over the groups: sort them and note each edge of two sides
  // (the faces across) or one (a border), counting the edges of three or
  // more; then, with every group's first such edge number known, sum their
  // normals.
  m.side_.resize(nf);
  std::vector<std::size_t> first_shared(nv + 1, 0);
  const auto run_end = [](const Side* run, const Side* last) {
    const Side* end = run;
    while (end != last && end->upper == run->upper) ++end;
    return end;
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, face_grain), [&](const auto& range) {
    for (std::size_t v = range.begin(); v < range.end(); ++v) {
      Side* const first = sides.data() + start[v];
      Side* const last = sides.data() + start[v + 1];
      std::sort(first, last, [](const Side& x, const Side& y) {
        return std::tie(x.upper, x.face_side) < std::tie(y.upper, y.face_side);
      });
      std::size_t shared = 0;
      for (const Side* run = first; run != last;) {
        const Side* const end = run_end(run, last);
        const std::uint32_t a = run->face_side;
        if (end - run == 1) {
          m.side_[a / 4][a % 4] = kBorder;
        } else if (end - run == 2) {
          const std::uint32_t b = run[1].face_side;
          m.side_[a / 4][a % 4] = b / 4;
          m.side_[b / 4][b % 4] = a / 4;
        } else {
          ++shared;
        }
        run = end;
      }
      first_shared[v + 1] = shared;
    }
  });
  for (std::size_t v = 0; v < nv; ++v) first_shared[v + 1] += first_shared[v];
  if (first_shared[nv] >= kShared) throw std::invalid_argument("MeshModel: too many edges");
  m.shared_normal_.resize(first_shared[nv]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, face_grain), [&](const auto& range) {
    for (std::size_t v = range.begin(); v < range.end(); ++v) {
      const Side* const last = sides.data() + start[v + 1];
      auto edge = static_cast<std::uint32_t>(first_shared[v]);
      for (const Side* run = sides.data() + start[v]; run != last;) {
        const Side* const end = run_end(run, last);
        if (end - run > 2) {
          Eigen::Vector3d sum = Eigen::Vector3d::Zero();
          for (const Side* s = run; s != end; ++s) sum += facet(s->face_side / 4);
          const double len = sum.norm();
          if (len > 0) m.shared_normal_[edge] = sum / len;
          for (; run != end; ++run)
            m.side_[run->face_side / 4][run->face_side % 4] = len > 0 ? kShared + edge : kNone;
          ++edge;
        }
        run = end;
      }
    }
  });
}

// The hierarchy, in two sweeps: the median splits from the root down (the
// slots in their final order: splits()), then, once slots() has laid them
// out, the boxes from the leaves up (boxes()), each node's principal frame
// from its children's spreads (the corners are read once a level only to
// measure the boxes' extents).
void MeshModel::Builder::splits() {
  const auto nf = static_cast<std::uint32_t>(triangles.size());
  items = std::make_unique_for_overwrite<Item[]>(nf);  // every item is written below
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, nf, face_grain), [&](const auto& range) {
    for (std::uint32_t f = range.begin(); f < range.end(); ++f) {
      const auto& t = triangles[f];
      const Eigen::Vector3f centroid =
          ((m.vertices_[t[0]] + m.vertices_[t[1]] + m.vertices_[t[2]]) / 3.0).cast<float>();
      items[f].centroid = {centroid[0], centroid[1], centroid[2]};
      items[f].face = f;
    }
  });
  split_all(0, nf);
}

void MeshModel::Builder::boxes() {
  const auto nf = static_cast<std::uint32_t>(m.slots_.size());
  m.wide_.resize(count_wide(nf));
  scratch_capacity = 3 * std::size_t{std::min(nf, scratch_size)};
  if (nf <= leaf_size) {
    clear_lanes(0);
    lane(0, nf, 0, 0, 0, nullptr);
  } else {
    top(0, nf, 0, nullptr);
  }
}

// Triangles as the query reads them, in hierarchy order (the split items'
// order), made before the boxes, which read the corners through them. The
// centroids go here: the wide nodes, the build's biggest array, come next.
void MeshModel::Builder::slots() {
  const auto nf = static_cast<std::uint32_t>(triangles.size());
  m.slots_.resize(nf);
  m.slot_of_face_.resize(nf);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, nf, face_grain), [&](const auto& range) {
    for (std::uint32_t s = range.begin(); s < range.end(); ++s) {
      Slot& slot = m.slots_[s];
      slot.face = items[s].face;
      const auto& t = triangles[slot.face];
      for (int k = 0; k < 3; ++k) slot.corner[k] = t[k];
      m.slot_of_face_[slot.face] = s;
    }
  });
  items.reset();
}

// Calls f(x, y, z) with the corners of slots [begin, end), in slot order.
// They are read where they are, not copied side by side first: a copy of
// every corner took 72 bytes a face (720 MB for 10 M triangles).
template <class F>
void MeshModel::Builder::for_each_corner(std::uint32_t begin, std::uint32_t end, F&& f) const {
  const Slot* const slot = m.slots_.data();
  // The slots in order, their corners fetched `ahead` slots early (the
  // build's passes over corners outside the scratch wait on memory
  // otherwise).
  constexpr std::uint32_t ahead = 8;
  for (std::uint32_t s = begin; s < end; ++s) {
    if (s + ahead < end)
      for (const std::uint32_t i : slot[s + ahead].corner) m.vertices_.prefetch(i);
    for (const std::uint32_t i : slot[s].corner) {
      const Eigen::Vector3d v = m.vertices_[i];
      f(v[0], v[1], v[2]);
    }
  }
}

// The hierarchy is built straight into its wide form (four lanes a node):
// the wide node over a binary node ("top": the root or an inner lane) has
// for lanes its children, each inner child replaced by its two children.
// Those replaced children and the root are never fitted; the lanes' places
// are known in advance from the subtree sizes, so the halves are built as
// tasks of their own.

// Splits slots [begin, end) at the median centroid along the longest side
// of the centroids' box (the items of each half before middle(), after it).
// NOLINTNEXTLINE(readability-make-member-function-const): reorders the items
void MeshModel::Builder::split(std::uint32_t begin, std::uint32_t end) {
  Item* const first = items.get() + begin;
  Item* const last = items.get() + end;
  // The centroid and the face in one load, the face's lane ignored (GCC/
  // Clang vector extension); c < lo ? c : lo lane by lane, as lo.cwiseMin(c).
  using F4 = float __attribute__((vector_size(16)));
  static_assert(sizeof(Item) == sizeof(F4) && std::is_trivially_copyable_v<Item>);
  const auto load = [](const Item* it) {
    F4 v;
    std::memcpy(&v, it, sizeof v);
    return v;
  };
  F4 low = load(first), high = low;
  for (const Item* it = first + 1; it != last; ++it) {
    const F4 c = load(it);
    low = c < low ? c : low;
    high = c > high ? c : high;
  }
  const Eigen::Vector3f lo(low[0], low[1], low[2]), hi(high[0], high[1], high[2]);
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  std::nth_element(
      first, items.get() + middle(begin, end), last,
      [axis](const Item& x, const Item& y) { return x.centroid[axis] < y.centroid[axis]; });
}

// Every split below slots [begin, end), down to the leaves.
void MeshModel::Builder::split_all(std::uint32_t begin, std::uint32_t end) {
  if (end - begin <= leaf_size) return;
  split(begin, end);
  const std::uint32_t mid = middle(begin, end);
  both(
      end - begin, [&] { split_all(begin, mid); }, [&] { split_all(mid, end); });
}

// Top node over slots [begin, end) (more than a leaf), its lanes in wide
// node `own` and their subtrees' wide nodes after it. Returns the spread
// of its corners.
CornerSpread MeshModel::Builder::top(std::uint32_t begin, std::uint32_t end, std::uint32_t own,
                                     Scratch* scratch) {
  clear_lanes(own);
  const std::uint32_t mid = middle(begin, end);
  std::uint32_t next = own + 1;
  int next_lane = 0;
  struct Child {
    std::uint32_t begin, end;
    int lane;
    std::uint32_t own[2];  // an inner child's children: their wide nodes
    CornerSpread spread;
  };
  Child children[2] = {{begin, mid, 0, {0, 0}, {}}, {mid, end, 0, {0, 0}, {}}};
  for (Child& c : children) {
    const std::uint32_t size = c.end - c.begin;
    c.lane = next_lane;
    if (size <= leaf_size) {
      next_lane += 1;
    } else {
      next_lane += 2;
      const std::uint32_t halves[2] = {size / 2, size - size / 2};
      for (int h = 0; h < 2; ++h) {
        if (halves[h] > leaf_size) {
          c.own[h] = next;
          next += wide_counts.at(halves[h]);
        }
      }
    }
  }
  const auto run = [&](Child& c) {
    c.spread = c.end - c.begin <= leaf_size
                   ? lane(c.begin, c.end, own, c.lane, 0, scratch)
                   : expanded(c.begin, c.end, own, c.lane, c.own[0], c.own[1], scratch);
  };
  both(
      end - begin, [&] { run(children[0]); }, [&] { run(children[1]); });
  return merged(children[0].spread, children[1].spread);
}

// An inner child of a top node, replaced by its children: lanes `lane`
// and `lane` + 1 of wide node `wide`. Returns the spread of its corners.
CornerSpread MeshModel::Builder::expanded(std::uint32_t begin, std::uint32_t end,
                                          std::uint32_t wide, int lane_index,
                                          std::uint32_t own_left, std::uint32_t own_right,
                                          Scratch* scratch) {
  const std::uint32_t mid = middle(begin, end);
  CornerSpread left, right;
  both(
      end - begin, [&] { left = lane(begin, mid, wide, lane_index, own_left, scratch); },
      [&] { right = lane(mid, end, wide, lane_index + 1, own_right, scratch); });
  return merged(left, right);
}

// Lane `lane` of wide node `wide`: the box of slots [begin, end), fitted
// once its subtree is built (an inner lane is the top of wide node `own`).
// Returns the spread of its corners.
CornerSpread MeshModel::Builder::lane(std::uint32_t begin, std::uint32_t end, std::uint32_t wide,
                                      int lane_index, std::uint32_t own, Scratch* scratch) {
  // A subtree small enough gets its scratch: its corners copied once, in
  // their final order.
  Scratch own_scratch;
  if (scratch == nullptr && end - begin <= scratch_size) {
    {
      const std::lock_guard<std::mutex> lock(spare_mutex);
      if (!spare.empty()) {
        own_scratch.block = std::move(spare.back());
        spare.pop_back();
      }
    }
    if (own_scratch.block == nullptr) own_scratch.block.reset(new double[3 * scratch_capacity]);
    own_scratch.base = begin;
    for (std::size_t k = 0; k < 3; ++k)
      own_scratch.xyz[k] = own_scratch.block.get() + k * scratch_capacity;
    scratch = &own_scratch;
    std::size_t j = 0;
    for_each_corner(begin, end, [&](double x, double y, double z) {
      scratch->xyz[0][j] = x;
      scratch->xyz[1][j] = y;
      scratch->xyz[2][j] = z;
      ++j;
    });
  }
  const bool leaf = end - begin <= leaf_size;
  CornerSpread spread;
  if (leaf) {
    // Leaves are always within a scratch (leaf_size < scratch_size).
    const std::size_t first = 3 * std::size_t{begin - scratch->base};
    spread = spread_of(scratch->xyz[0] + first, scratch->xyz[1] + first, scratch->xyz[2] + first,
                       3 * std::size_t{end - begin});
  } else {
    spread = top(begin, end, own, scratch);
  }
  Node box;
  fit_node(box, begin, end, spread, scratch);
  set_lane(wide, lane_index, box, leaf ? begin : own, leaf ? end - begin : 0);
  if (own_scratch.block != nullptr) {
    const std::lock_guard<std::mutex> lock(spare_mutex);
    spare.push_back(std::move(own_scratch.block));
  }
  return spread;
}

// The box of the corners of slots [begin, end): in the principal frame of
// the corners or in x, y, z, whichever is smaller (volume, with a floor so
// flat boxes compare by area). The frame is rounded to float first and the
// extents measured in that rounded frame, then rounded up, so the box holds
// every corner exactly; node_distance_squared allows for the rounded frame
// being orthonormal only to float precision.
void MeshModel::Builder::fit_node(Node& node, std::uint32_t begin, std::uint32_t end,
                                  const CornerSpread& spread, const Scratch* scratch) const {
  const std::size_t n = 3 * std::size_t{end - begin};
  // The corners in slot order, from the scratch when there is one.
  const auto corners = [&](auto&& f) {
    if (scratch == nullptr) {
      for_each_corner(begin, end, f);
      return;
    }
    const std::size_t first = 3 * std::size_t{begin - scratch->base};
    const double* const xs = scratch->xyz[0] + first;
    const double* const ys = scratch->xyz[1] + first;
    const double* const zs = scratch->xyz[2] + first;
    for (std::size_t i = 0; i < n; ++i) f(xs[i], ys[i], zs[i]);
  };
  Eigen::Matrix3d principal;
  if (end - begin > leaf_size || !leaf_frame(corners, principal))
    principal = principal_frame(spread);
  const Eigen::Vector3d& box_lo = spread.lo;
  const Eigen::Vector3d& box_hi = spread.hi;
  const Eigen::AlignedBox3d box(box_lo, box_hi);
  const double floor = 1e-3 * std::max(box.diagonal().norm(), 1e-9);
  // Rows of `frame` are the axes; [lo, hi] the corners' extents along the
  // float-rounded axes, measured when not given. Returns the floored volume.
  const auto fit = [&](const Eigen::Matrix3d& frame, Node& out, const Eigen::Vector3d* given_lo,
                       const Eigen::Vector3d* given_hi) {
    Eigen::Matrix3d axes;
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) {
        const float a = to_float(frame(k, j));
        out.axis[k][j] = a;
        axes(k, j) = static_cast<double>(a);
      }
    Eigen::Vector3d lo, hi;
    if (given_lo != nullptr) {
      lo = *given_lo;
      hi = *given_hi;
    } else if (scratch != nullptr) {
      const std::size_t first = 3 * std::size_t{begin - scratch->base};
      project_arrays(scratch->xyz[0] + first, scratch->xyz[1] + first, scratch->xyz[2] + first, n,
                     axes, lo, hi);
    } else {
      project(corners, axes, lo, hi);
    }
    // The centre in world coordinates, rounded to float; the extents about it.
    const Eigen::Vector3d mid = transpose_times(axes, (lo + hi) / 2);
    Eigen::Vector3d centre;
    for (int j = 0; j < 3; ++j) {
      const float f = to_float(mid[j]);
      out.centre[j] = f;
      centre[j] = static_cast<double>(f);
    }
    const Eigen::Vector3d c = times(axes, centre);
    double volume = 1;
    for (int k = 0; k < 3; ++k) {
      const double h = std::max(hi[k] - c[k], c[k] - lo[k]);
      // Rounding of the projections above: a few ulps of the coordinates.
      const double slack = 1e-12 * (std::abs(c[k]) + std::abs(h) + 1);
      out.half[k] = round_up(h + slack);
      volume *= static_cast<double>(out.half[k]) + floor;
    }
    return volume;
  };
  const double v_principal = fit(principal, node, nullptr, nullptr);
  // The x, y, z box is almost never the smaller one; it is fitted only when
  // this lower bound of its floored volume does not already lose: each half
  // extent is at least half the box's side (the 1e-12 covers the rounding
  // of that side), and rounded sums and products are monotonic.
  double lower = 1;
  for (int k = 0; k < 3; ++k) lower *= (box_hi[k] - box_lo[k]) * (0.5 * (1 - 1e-12)) + floor;
  if (v_principal < lower) return;
  // In x, y, z the projections are the coordinates themselves (1 x + 0 y +
  // 0 z), so the extents are the box's: exactly, zeros apart (whose sign
  // the projection may flip; those boxes are measured as in any frame).
  Node aligned{};
  const bool zero = (box_lo.array() == 0).any() || (box_hi.array() == 0).any();
  const double v_aligned = zero ? fit(Eigen::Matrix3d::Identity(), aligned, nullptr, nullptr)
                                : fit(Eigen::Matrix3d::Identity(), aligned, &box_lo, &box_hi);
  if (!(v_principal < v_aligned)) node = aligned;
}

// Wide nodes over a binary subtree of `size` triangles: a function of the
// size alone (the median split), so each wide subtree's place is known in
// advance. Sizes of a top's lanes: its children's, an inner child's
// replaced by its children's.
std::uint32_t MeshModel::Builder::count_wide(std::uint32_t size) {
  if (const auto it = wide_counts.find(size); it != wide_counts.end()) return it->second;
  std::uint32_t count = 1;
  if (size > leaf_size) {
    for (const std::uint32_t child : {size / 2, size - size / 2}) {
      if (child <= leaf_size) continue;
      for (const std::uint32_t lane_size : {child / 2, child - child / 2})
        if (lane_size > leaf_size) count += count_wide(lane_size);
    }
  }
  wide_counts[size] = count;
  return count;
}

// All four lanes of a wide node empty (unreachable: beyond any point).
void MeshModel::Builder::clear_lanes(std::uint32_t wide) {
  WideNode& w = m.wide_[wide];
  for (int l = 0; l < 4; ++l) {
    w.link[l] = kNone;
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) w.axis[k][j][l] = 0;
      w.offset[k][l] = std::numeric_limits<float>::max();
      w.half[k][l] = 0;
    }
  }
}

// Lane `lane` of wide node `wide` from a fitted box: its frame, with the
// centre turned into per-axis offsets rounded to float and the half extents
// grown by that rounding.
void MeshModel::Builder::set_lane(std::uint32_t wide, int lane_index, const Node& box,
                                  std::uint32_t child, std::uint32_t count) {
  WideNode& w = m.wide_[wide];
  const auto l = static_cast<std::size_t>(lane_index);
  for (int k = 0; k < 3; ++k) {
    double exact = 0;
    for (int j = 0; j < 3; ++j) {
      w.axis[k][j][l] = box.axis[k][j];
      exact += static_cast<double>(box.axis[k][j]) * static_cast<double>(box.centre[j]);
    }
    const float offset = to_float(exact);
    w.offset[k][l] = offset;
    const double moved = std::abs(static_cast<double>(offset) - exact);
    // Grown by the rounding of offset and by the query's float error on
    // the offset's side (1e-6 |offset|, see closest_point).
    w.half[k][l] =
        round_up(static_cast<double>(box.half[k]) + moved + 1e-6 * std::abs(exact) + 1e-12);
  }
  w.link[l] = child | count << kCountShift;
}

// Closest point of one triangle by the Voronoi regions of its corners,
// edges and interior (the classic region test on the dot products).
void MeshModel::test_slot(std::uint32_t s, const Eigen::Vector3d& p, Hit& best) const {
  const Slot& slot = slots_[s];
  const Eigen::Vector3d a = vertices_[slot.corner[0]];
  const Eigen::Vector3d b = vertices_[slot.corner[1]];
  const Eigen::Vector3d c = vertices_[slot.corner[2]];
  const Eigen::Vector3d ap = p - a;
  const Eigen::Vector3d ab = b - a, ac = c - a;
  // The plane is no farther than the triangle: most rejections end here.
  // With n = ab x ac unnormalised, plane distance^2 = (n.ap)^2 / |n|^2;
  // the 1e-12 keeps the rounding of this product from rejecting a
  // triangle the exact comparison would keep (no square root, no division;
  // a degenerate triangle, n = 0, always goes on to the full test).
  const Eigen::Vector3d n = ab.cross(ac);
  const double plane = n.dot(ap), n2 = n.squaredNorm();
  if (plane * plane >= best.d2 * n2 * (1 + 1e-12) && n2 > 0) return;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  double v = 0, w = 0;
  int feature = 0;
  if (d1 <= 0 && d2 <= 0) {
    feature = 4;
  } else {
    // Gram matrix of the edges.
    const double abab = ab.squaredNorm(), abac = ab.dot(ac), acac = ac.squaredNorm();
    const double d3 = d1 - abab, d4 = d2 - abac;  // dots with p - b
    const double d5 = d1 - abac, d6 = d2 - acac;  // dots with p - c
    if (d3 >= 0 && d4 <= d3) {
      feature = 5;
      v = 1;
    } else if (d6 >= 0 && d5 <= d6) {
      feature = 6;
      w = 1;
    } else {
      const double vc = d1 * d4 - d3 * d2;
      const double vb = d5 * d2 - d1 * d6;
      const double va = d3 * d6 - d5 * d4;
      if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        feature = 1;
        v = d1 / (d1 - d3);
      } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        feature = 3;
        w = d2 / (d2 - d6);
      } else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        feature = 2;
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        v = 1 - w;
      } else {
        const double inv = 1.0 / (va + vb + vc);
        v = vb * inv;
        w = vc * inv;
      }
    }
  }
  const Eigen::Vector3d q = a + v * ab + w * ac;
  const double d2q = (p - q).squaredNorm();
  if (d2q < best.d2) {
    best.d2 = d2q;
    best.point = q;
    best.v = v;
    best.w = w;
    best.feature = feature;
    best.face = slot.face;
  }
}

Eigen::Vector3d MeshModel::facet_normal(int face) const {
  const std::uint32_t* t = corners_of(static_cast<std::uint32_t>(face));
  return unit_normal(vertices_[t[0]], vertices_[t[1]], vertices_[t[2]]);
}

// The sum of the facet normals of the faces on the edge of `face`'s side,
// unit, as the build summed them (two: commutative, so either face's view
// gives the same bits); the face's own normal where they cancel out.
Eigen::Vector3d MeshModel::edge_normal(std::uint32_t face, int side) const {
  const std::uint32_t across = side_[face][static_cast<std::size_t>(side)];
  if (across == kNone) return facet_normal(static_cast<int>(face));
  if (across != kBorder && across >= kShared) return shared_normal_[across - kShared];
  // From zero, as the build: 0 + (-0) is +0, whichever face comes first.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  sum += facet_normal(static_cast<int>(face));
  if (across != kBorder) sum += facet_normal(static_cast<int>(across));
  const double len = sum.norm();
  return len > 0 ? Eigen::Vector3d(sum / len) : facet_normal(static_cast<int>(face));
}

geometry::ModelContact MeshModel::make_contact(const Eigen::Vector3d& p, const Hit& hit) const {
  geometry::ModelContact c;
  c.point = hit.point;
  c.distance = std::sqrt(hit.d2);
  c.face = static_cast<int>(hit.face);
  c.uv = {hit.v, hit.w};
  if (hit.feature == 0) {
    c.type = geometry::ContactType::face;
    c.normal = facet_normal(c.face);
    return c;
  }
  Eigen::Vector3d pseudo;
  if (hit.feature <= 3) {
    c.type = geometry::ContactType::edge;
    pseudo = edge_normal(hit.face, hit.feature - 1);
  } else {
    c.type = geometry::ContactType::vertex;
    pseudo = vertex_normal_[corners_of(hit.face)[hit.feature - 4]];
  }
  const Eigen::Vector3d d = p - hit.point;
  const double len = d.norm();
  // Below this the direction of C - CC is rounding noise.
  if (len <= 1e-12 * std::max(1.0, p.cwiseAbs().maxCoeff())) {
    c.normal = pseudo;
  } else {
    c.normal = d / len;
    if (c.normal.dot(pseudo) < 0) c.normal = -c.normal;
  }
  return c;
}

std::optional<geometry::ModelContact> MeshModel::closest_point(const Eigen::Vector3d& p,
                                                               double max_distance,
                                                               geometry::ContactHint* hint) const {
  if (!(max_distance >= 0)) return std::nullopt;
  Hit best;
  // Inclusive bound: a point exactly max_distance away is still found.
  best.d2 = std::nextafter(max_distance * max_distance, std::numeric_limits<double>::infinity());
  const double limit = best.d2;

  // Warm start: the previous answer's triangle alone gives a bound within a
  // hair of the answer along a coherent path. (Walking on to nearer
  // neighbours first was tried: the hierarchy tests them again anyway, and
  // the walk cost more than the tighter bound saved.)
  bool warm = false;
  if (hint != nullptr && hint->face >= 0 && hint->face < face_count()) {
    test_slot(slot_of_face_[hint->face], p, best);
    warm = best.d2 < limit;
  }
  const double hint_d2 = best.d2;

  // Lower bounds of the squared distance from p to the four lanes' boxes,
  // in single precision: |axis.p - offset| is off by at most a few float
  // ulps of |p|_1 + |offset| (the margin and the grown half extents take
  // that off), and the float axes are orthonormal to ~1e-7 (the final
  // factor takes that back).
  const auto px = static_cast<float>(p.x()), py = static_cast<float>(p.y()),
             pz = static_cast<float>(p.z());
  // Rounding of axis.p in float: a few ulps of |p|_1 (the offsets' own
  // share is in the half extents).
  const float margin = 1e-6f * (std::abs(px) + std::abs(py) + std::abs(pz));
  constexpr double shrink = 1 - 1e-5;
  std::uint32_t stack_link[max_stack];
  double stack_d2[max_stack];
  int top = 0;
  const auto open = [&](std::uint32_t index) {
    const WideNode& n = wide_[index];
    // The lanes' float bounds against best.d2 / shrink, rounded up (the
    // 1e-6 is far above float rounding): a lane is skipped only when its
    // bound times shrink is at least best.d2.
    const auto bound = static_cast<float>(best.d2 / shrink * (1 + 1e-6));
    // Four lanes at once (GCC/Clang vector extension: SSE on x86-64).
    using F4 = float __attribute__((vector_size(16)));
    const auto load = [](const float(&a)[4]) {
      F4 v;
      std::memcpy(&v, a, sizeof v);
      return v;
    };
    using I4 = std::int32_t __attribute__((vector_size(16)));
    const F4 zero = {0, 0, 0, 0};
    const I4 no_sign = {0x7fffffff, 0x7fffffff, 0x7fffffff, 0x7fffffff};
    F4 d2 = zero;
    for (int k = 0; k < 3; ++k) {
      const F4 along = load(n.axis[k][0]) * px + load(n.axis[k][1]) * py + load(n.axis[k][2]) * pz -
                       load(n.offset[k]);
      F4 e = reinterpret_cast<F4>(reinterpret_cast<I4>(along) & no_sign) - load(n.half[k]) - margin;
      e = e > zero ? e : zero;
      d2 += e * e;
    }
    const I4 within = d2 < bound;
    float lb[4];
    std::memcpy(lb, &d2, sizeof lb);
    // Cold, the nearest lanes go on top of the stack so the bound shrinks
    // early; warm, the bound is already (nearly) the answer and the order
    // hardly matters, so they go on as they are.
    int order[4], m = 0;
    for (int l = 0; l < 4; ++l) {
      if (within[l]) {
        int i = m++;
        while (!warm && i > 0 && lb[order[i - 1]] < lb[l]) {
          order[i] = order[i - 1];
          --i;
        }
        order[i] = l;
      }
    }
    for (int i = 0; i < m && top < max_stack; ++i) {
      stack_link[top] = n.link[order[i]];
      stack_d2[top++] = static_cast<double>(lb[order[i]]) * shrink;
    }
  };
  open(0);
  while (top > 0) {
    --top;
    if (stack_d2[top] >= best.d2) continue;
    const std::uint32_t child = stack_link[top] & ((1u << kCountShift) - 1);
    const std::uint32_t count = stack_link[top] >> kCountShift;
    if (count > 0) {
      for (std::uint32_t s = child; s < child + count; ++s) test_slot(s, p, best);
    } else {
      open(child);
    }
  }
  if (!(best.d2 < limit)) return std::nullopt;
  if (hint != nullptr) {
    if (warm && best.d2 == hint_d2) {
      ++hint->warm_queries;
    } else {
      ++hint->cold_queries;
    }
    hint->face = static_cast<int>(best.face);
    hint->uv = {best.v, best.w};
  }
  return make_contact(p, best);
}

}  // namespace vcpost::mesh
