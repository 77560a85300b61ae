// A small bounding-volume hierarchy over axis-aligned boxes, for
// nearest-first searches with a shrinking distance bound.
//
// Nodes sit in one array (children of node i are consecutive), primitives
// are reordered indices, leaves hold up to kLeafSize of them: two cache
// lines per node visit. Immutable after construction; searches are const
// and thread-safe. Units: whatever the boxes are in (mm here).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace vcpost::occt {

class BoxTree {
 public:
  BoxTree() = default;
  explicit BoxTree(const std::vector<Eigen::AlignedBox3d>& boxes);

  bool empty() const { return nodes_.empty(); }
  const Eigen::AlignedBox3d& bounds() const { return root_box_; }

  // Calls visit(primitive, box_distance_squared) for every primitive whose
  // box is nearer to p than sqrt(bound_squared), nearer subtrees first;
  // visit returns the (possibly smaller) new bound_squared, which prunes
  // the rest of the search.
  template <class Visit>
  void search(const Eigen::Vector3d& p, double bound_squared, Visit&& visit) const;

 private:
  static constexpr int kLeafSize = 4;
  struct Node {
    std::array<double, 3> lo, hi;
    std::int32_t first = 0;  // leaf: first slot in order_; inner: index of the left child
    std::int32_t count = 0;  // leaf: number of primitives; inner: 0
  };

  static double distance_squared(const Node& n, const Eigen::Vector3d& p) {
    double d = 0;
    for (int k = 0; k < 3; ++k) {
      const double below = n.lo[k] - p[k], above = p[k] - n.hi[k];
      const double e = std::max({below, above, 0.0});
      d += e * e;
    }
    return d;
  }

  void build(int node, int begin, int end, const std::vector<Eigen::AlignedBox3d>& boxes,
             std::vector<Eigen::Vector3d>& centres);

  std::vector<Node> nodes_;
  std::vector<std::int32_t> order_;
  std::vector<Eigen::AlignedBox3d> boxes_;  // by primitive index
  Eigen::AlignedBox3d root_box_;
};

template <class Visit>
void BoxTree::search(const Eigen::Vector3d& p, double bound_squared, Visit&& visit) const {
  if (nodes_.empty()) return;
  std::array<std::pair<double, std::int32_t>, 64> stack;
  int top = 0;
  const double d_root = distance_squared(nodes_[0], p);
  if (d_root >= bound_squared) return;
  stack[top++] = {d_root, 0};
  while (top > 0) {
    const auto [d, index] = stack[--top];
    if (d >= bound_squared) continue;
    const Node& n = nodes_[index];
    if (n.count > 0) {
      for (int i = 0; i < n.count; ++i) {
        const std::int32_t prim = order_[n.first + i];
        const double dp = boxes_[prim].squaredExteriorDistance(p);
        if (dp < bound_squared) bound_squared = visit(prim, dp);
      }
      continue;
    }
    const double dl = distance_squared(nodes_[n.first], p);
    const double dr = distance_squared(nodes_[n.first + 1], p);
    // Push the farther child first so the nearer one is searched first.
    if (dl <= dr) {
      if (dr < bound_squared) stack[top++] = {dr, n.first + 1};
      if (dl < bound_squared) stack[top++] = {dl, n.first};
    } else {
      if (dl < bound_squared) stack[top++] = {dl, n.first};
      if (dr < bound_squared) stack[top++] = {dr, n.first + 1};
    }
  }
}

}  // namespace vcpost::occt
