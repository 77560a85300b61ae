// The hierarchy of the mesh index: median splits from the root down, then
// oriented boxes from the leaves up, laid out four lanes a node.
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <type_traits>

#include "geometry/mesh/mesh_builder.h"
#include "geometry/mesh/oriented_box.h"

namespace vcpost::mesh {
namespace {

constexpr std::uint32_t leaf_size = 2;
// Subtrees at least this big are built as tasks of their own (a few
// hundred microseconds of work: far above a task's cost).
constexpr std::uint32_t task_size = 2048;

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

}  // namespace

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
  OrientedBox box;
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
void MeshModel::Builder::fit_node(OrientedBox& node, std::uint32_t begin, std::uint32_t end,
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
  if (end - begin > leaf_size || !leaf_frame<3 * static_cast<int>(leaf_size)>(corners, principal))
    principal = principal_frame(spread);
  const Eigen::Vector3d& box_lo = spread.lo;
  const Eigen::Vector3d& box_hi = spread.hi;
  const Eigen::AlignedBox3d box(box_lo, box_hi);
  const double floor = 1e-3 * std::max(box.diagonal().norm(), 1e-9);
  // Rows of `frame` are the axes; [lo, hi] the corners' extents along the
  // float-rounded axes, measured when not given. Returns the floored volume.
  const auto fit = [&](const Eigen::Matrix3d& frame, OrientedBox& out,
                       const Eigen::Vector3d* given_lo, const Eigen::Vector3d* given_hi) {
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
  OrientedBox aligned{};
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
void MeshModel::Builder::set_lane(std::uint32_t wide, int lane_index, const OrientedBox& box,
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

}  // namespace vcpost::mesh
