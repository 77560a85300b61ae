#include "geometry/occt/box_tree.h"

#include <numeric>

namespace vcpost::occt {

BoxTree::BoxTree(const std::vector<Eigen::AlignedBox3d>& boxes) : boxes_(boxes) {
  if (boxes.empty()) return;
  order_.resize(boxes.size());
  std::iota(order_.begin(), order_.end(), 0);
  std::vector<Eigen::Vector3d> centres(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) centres[i] = boxes[i].center();
  nodes_.reserve(2 * boxes.size() / kLeafSize + 2);
  nodes_.emplace_back();
  build(0, 0, static_cast<int>(boxes.size()), boxes, centres);
  root_box_ = Eigen::AlignedBox3d(Eigen::Vector3d(nodes_[0].lo.data()),
                                  Eigen::Vector3d(nodes_[0].hi.data()));
}

// Median split of the centres along the longest axis of their bounds:
// balanced depth (log2 n / kLeafSize), good enough for tessellations whose
// triangles are of similar size.
void BoxTree::build(int node, int begin, int end, const std::vector<Eigen::AlignedBox3d>& boxes,
                    std::vector<Eigen::Vector3d>& centres) {
  Eigen::AlignedBox3d box, centre_box;
  for (int i = begin; i < end; ++i) {
    box.extend(boxes[order_[i]]);
    centre_box.extend(centres[order_[i]]);
  }
  for (int k = 0; k < 3; ++k) {
    nodes_[node].lo[k] = box.min()[k];
    nodes_[node].hi[k] = box.max()[k];
  }
  if (end - begin <= kLeafSize) {
    nodes_[node].first = begin;
    nodes_[node].count = end - begin;
    return;
  }
  int axis = 0;
  centre_box.sizes().maxCoeff(&axis);
  const int mid = (begin + end) / 2;
  std::nth_element(
      order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
      [&](std::int32_t a, std::int32_t b) { return centres[a][axis] < centres[b][axis]; });
  const int left = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  nodes_.emplace_back();
  nodes_[node].first = left;
  nodes_[node].count = 0;
  build(left, begin, mid, boxes, centres);
  build(left + 1, mid, end, boxes, centres);
}

}  // namespace vcpost::occt
