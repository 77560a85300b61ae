#include "geometry/mesh/mesh_model.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>

namespace vcpost::mesh {
namespace {

constexpr std::uint32_t leaf_size = 2;
constexpr int max_stack = 128;

float round_up(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace

MeshModel::MeshModel(StlMesh mesh) : mesh_(std::move(mesh)) {
  const std::size_t nf = mesh_.triangles.size();
  const std::size_t nv = mesh_.vertices.size();
  if (nf == 0) throw std::invalid_argument("MeshModel: the mesh has no triangles");
  if (nf >= std::numeric_limits<std::uint32_t>::max() / 2)
    throw std::invalid_argument("MeshModel: too many triangles");
  for (const auto& t : mesh_.triangles)
    for (auto i : t)
      if (i >= nv) throw std::invalid_argument("MeshModel: corner index out of range");

  bounds_.setEmpty();
  for (const auto& p : mesh_.vertices) bounds_.extend(p);

  // Normals: facets, then the pseudo-normals that tell inside from outside
  // at edges (sum of the faces sharing the edge) and vertices (angle-weighted).
  facet_normal_.resize(nf);
  edge_normal_.resize(nf);
  vertex_normal_.assign(nv, Eigen::Vector3d::Zero());
  std::map<std::pair<std::uint32_t, std::uint32_t>, Eigen::Vector3d> edge_sum;
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& t = mesh_.triangles[f];
    Eigen::Vector3d n = (mesh_.vertices[t[1]] - mesh_.vertices[t[0]])
                            .cross(mesh_.vertices[t[2]] - mesh_.vertices[t[0]]);
    const double len = n.norm();
    facet_normal_[f] = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::UnitZ();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = mesh_.vertices[t[(k + 1) % 3]] - mesh_.vertices[t[k]];
      const Eigen::Vector3d e2 = mesh_.vertices[t[(k + 2) % 3]] - mesh_.vertices[t[k]];
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      vertex_normal_[t[k]] += angle * facet_normal_[f];
      const auto key = std::minmax(t[k], t[(k + 1) % 3]);
      auto [it, inserted] = edge_sum.try_emplace({key.first, key.second}, Eigen::Vector3d::Zero());
      it->second += facet_normal_[f];
    }
  }
  for (auto& n : vertex_normal_) {
    const double len = n.norm();
    n = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::UnitZ();
  }
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& t = mesh_.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const auto key = std::minmax(t[k], t[(k + 1) % 3]);
      const Eigen::Vector3d& s = edge_sum.at({key.first, key.second});
      const double len = s.norm();
      edge_normal_[f][k] = len > 0 ? Eigen::Vector3d(s / len) : facet_normal_[f];
    }
  }

  // The hierarchy: median split of the centroids along the box's longest axis.
  std::vector<Eigen::Vector3d> centroids(nf);
  slots_.resize(nf);
  for (std::uint32_t f = 0; f < nf; ++f) {
    const auto& t = mesh_.triangles[f];
    centroids[f] = (mesh_.vertices[t[0]] + mesh_.vertices[t[1]] + mesh_.vertices[t[2]]) / 3.0;
    slots_[f].face = f;
  }
  nodes_.reserve(2 * nf / leaf_size + 2);
  build(0, static_cast<std::uint32_t>(nf), centroids);
  wide_.reserve(nodes_.size() / 3 + 1);
  collapse(0);
  nodes_.clear();
  nodes_.shrink_to_fit();
  slot_of_face_.resize(nf);
  for (std::uint32_t s = 0; s < nf; ++s) {
    Slot& slot = slots_[s];
    const auto& t = mesh_.triangles[slot.face];
    slot.a = mesh_.vertices[t[0]];
    slot.ab = mesh_.vertices[t[1]] - slot.a;
    slot.ac = mesh_.vertices[t[2]] - slot.a;
    slot.normal = facet_normal_[slot.face];
    slot.abab = slot.ab.squaredNorm();
    slot.abac = slot.ab.dot(slot.ac);
    slot.acac = slot.ac.squaredNorm();
    slot_of_face_[slot.face] = s;
  }
}

std::uint32_t MeshModel::build(std::uint32_t begin, std::uint32_t end,
                               std::vector<Eigen::Vector3d>& centroids) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.push_back({});
  Eigen::AlignedBox3d centre_box;
  centre_box.setEmpty();
  for (std::uint32_t s = begin; s < end; ++s) centre_box.extend(centroids[slots_[s].face]);
  fit_node(nodes_[index], begin, end);
  if (end - begin <= leaf_size) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return index;
  }
  int axis = 0;
  centre_box.sizes().maxCoeff(&axis);
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(slots_.begin() + begin, slots_.begin() + mid, slots_.begin() + end,
                   [&](const Slot& x, const Slot& y) {
                     return centroids[x.face][axis] < centroids[y.face][axis];
                   });
  build(begin, mid, centroids);
  const std::uint32_t right = build(mid, end, centroids);
  nodes_[index].first = right;
  nodes_[index].count = 0;
  return index;
}

// The box of the corners of slots [begin, end): in the principal frame of
// the corners or in x, y, z, whichever is smaller (volume, with a floor so
// flat boxes compare by area). The frame is rounded to float first and the
// extents measured in that rounded frame, then rounded up, so the box holds
// every corner exactly; node_distance_squared allows for the rounded frame
// being orthonormal only to float precision.
void MeshModel::fit_node(Node& node, std::uint32_t begin, std::uint32_t end) const {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::AlignedBox3d box;
  box.setEmpty();
  std::size_t corners = 0;
  for (std::uint32_t s = begin; s < end; ++s) {
    for (auto i : mesh_.triangles[slots_[s].face]) {
      mean += mesh_.vertices[i];
      box.extend(mesh_.vertices[i]);
      ++corners;
    }
  }
  mean /= static_cast<double>(corners);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::uint32_t s = begin; s < end; ++s) {
    for (auto i : mesh_.triangles[slots_[s].face]) {
      const Eigen::Vector3d d = mesh_.vertices[i] - mean;
      covariance += d * d.transpose();
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const double floor = 1e-3 * std::max(box.diagonal().norm(), 1e-9);
  const auto fit = [&](const Eigen::Matrix3d& frame, Node& out) {
    // Rows of `frame` are the axes; returns the floored volume.
    Eigen::Matrix3d axes;
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) {
        out.axis[k][j] = static_cast<float>(frame(k, j));
        axes(k, j) = static_cast<double>(out.axis[k][j]);
      }
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (std::uint32_t s = begin; s < end; ++s) {
      for (auto i : mesh_.triangles[slots_[s].face]) {
        const Eigen::Vector3d q = axes * mesh_.vertices[i];
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
      }
    }
    // The centre in world coordinates, rounded to float; the extents about it.
    const Eigen::Vector3d mid = axes.transpose() * ((lo + hi) / 2);
    Eigen::Vector3d centre;
    for (int j = 0; j < 3; ++j) {
      out.centre[j] = static_cast<float>(mid[j]);
      centre[j] = static_cast<double>(out.centre[j]);
    }
    const Eigen::Vector3d c = axes * centre;
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
  Node principal = node, aligned = node;
  const double v_principal = fit(solver.eigenvectors().transpose(), principal);
  const double v_aligned = fit(Eigen::Matrix3d::Identity(), aligned);
  const Node& chosen = v_principal < v_aligned ? principal : aligned;
  std::copy(std::begin(chosen.centre), std::end(chosen.centre), node.centre);
  for (int k = 0; k < 3; ++k) {
    std::copy(std::begin(chosen.axis[k]), std::end(chosen.axis[k]), node.axis[k]);
  }
  std::copy(std::begin(chosen.half), std::end(chosen.half), node.half);
}

// A wide node over binary node `binary`: its children, or grandchildren
// where there is room (up to four lanes; a leaf stays one lane). Each lane
// keeps its binary node's frame, with the centre turned into per-axis
// offsets rounded to float and the half extents grown by that rounding.
std::uint32_t MeshModel::collapse(std::uint32_t binary) {
  std::vector<std::uint32_t> lanes;
  const Node& top = nodes_[binary];
  if (top.count > 0) {
    lanes.push_back(binary);
  } else {
    lanes = {binary + 1, top.first};
    for (std::size_t i = 0; i < lanes.size() && lanes.size() < 4;) {
      const Node& n = nodes_[lanes[i]];
      if (n.count == 0) {
        const std::uint32_t left = lanes[i] + 1, right = n.first;
        lanes[i] = left;
        lanes.insert(lanes.begin() + static_cast<std::ptrdiff_t>(i) + 1, right);
        i += 2;
      } else {
        ++i;
      }
    }
  }
  const auto index = static_cast<std::uint32_t>(wide_.size());
  wide_.emplace_back();
  for (int l = 0; l < 4; ++l) {
    WideNode& w = wide_[index];
    w.child[l] = kNone;
    w.count[l] = 0;
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) w.axis[k][j][l] = 0;
      // An empty lane is unreachable: its box is beyond any point.
      w.offset[k][l] = std::numeric_limits<float>::max();
      w.half[k][l] = 0;
    }
  }
  for (std::size_t l = 0; l < lanes.size(); ++l) {
    const Node n = nodes_[lanes[l]];
    float axis[3][3], offset[3], half[3];
    for (int k = 0; k < 3; ++k) {
      double exact = 0;
      for (int j = 0; j < 3; ++j) {
        axis[k][j] = n.axis[k][j];
        exact += static_cast<double>(n.axis[k][j]) * static_cast<double>(n.centre[j]);
      }
      offset[k] = static_cast<float>(exact);
      const double moved = std::abs(static_cast<double>(offset[k]) - exact);
      // Grown by the rounding of offset and by the query's float error on
      // the offset's side (1e-6 |offset|, see closest_point).
      half[k] = round_up(static_cast<double>(n.half[k]) + moved + 1e-6 * std::abs(exact) + 1e-12);
    }
    const std::uint32_t child = n.count > 0 ? n.first : collapse(lanes[l]);
    WideNode& w = wide_[index];  // collapse may have moved the array
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) w.axis[k][j][l] = axis[k][j];
      w.offset[k][l] = offset[k];
      w.half[k][l] = half[k];
    }
    w.child[l] = child;
    w.count[l] = n.count;
  }
  return index;
}

// Closest point of one triangle by the Voronoi regions of its corners,
// edges and interior (the classic region test on the dot products).
void MeshModel::test_slot(std::uint32_t s, const Eigen::Vector3d& p, Hit& best) const {
  const Slot& t = slots_[s];
  const Eigen::Vector3d ap = p - t.a;
  // The plane is no farther than the triangle: most rejections end here.
  const double plane = t.normal.dot(ap);
  if (plane * plane >= best.d2) return;
  const double d1 = t.ab.dot(ap), d2 = t.ac.dot(ap);
  double v = 0, w = 0;
  int feature = 0;
  if (d1 <= 0 && d2 <= 0) {
    feature = 4;
  } else {
    const double abab = t.abab, abac = t.abac, acac = t.acac;
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
  const Eigen::Vector3d q = t.a + v * t.ab + w * t.ac;
  const double d2q = (p - q).squaredNorm();
  if (d2q < best.d2) {
    best.d2 = d2q;
    best.point = q;
    best.v = v;
    best.w = w;
    best.feature = feature;
    best.face = t.face;
  }
}

geometry::ModelContact MeshModel::make_contact(const Eigen::Vector3d& p, const Hit& hit) const {
  geometry::ModelContact c;
  c.point = hit.point;
  c.distance = std::sqrt(hit.d2);
  c.face = static_cast<int>(hit.face);
  c.uv = {hit.v, hit.w};
  if (hit.feature == 0) {
    c.type = geometry::ContactType::face;
    c.normal = facet_normal_[hit.face];
    return c;
  }
  Eigen::Vector3d pseudo;
  if (hit.feature <= 3) {
    c.type = geometry::ContactType::edge;
    pseudo = edge_normal_[hit.face][hit.feature - 1];
  } else {
    c.type = geometry::ContactType::vertex;
    pseudo = vertex_normal_[mesh_.triangles[hit.face][hit.feature - 4]];
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
  const float px = static_cast<float>(p.x()), py = static_cast<float>(p.y()),
              pz = static_cast<float>(p.z());
  // Rounding of axis.p in float: a few ulps of |p|_1 (the offsets' own
  // share is in the half extents).
  const float margin = 1e-6f * (std::abs(px) + std::abs(py) + std::abs(pz));
  constexpr double shrink = 1 - 1e-5;
  std::uint32_t stack_child[max_stack], stack_count[max_stack];
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
      stack_child[top] = n.child[order[i]];
      stack_count[top] = n.count[order[i]];
      stack_d2[top++] = static_cast<double>(lb[order[i]]) * shrink;
    }
  };
  open(0);
  while (top > 0) {
    --top;
    if (stack_d2[top] >= best.d2) continue;
    const std::uint32_t child = stack_child[top], count = stack_count[top];
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
