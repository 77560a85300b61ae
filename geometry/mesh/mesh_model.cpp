#include "geometry/mesh/mesh_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace vcpost::mesh {
namespace {

constexpr std::uint32_t leaf_size = 8;
constexpr int max_stack = 96;

float round_down(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

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
  Eigen::AlignedBox3d box, centre_box;
  box.setEmpty();
  centre_box.setEmpty();
  for (std::uint32_t s = begin; s < end; ++s) {
    const auto& t = mesh_.triangles[slots_[s].face];
    for (auto i : t) box.extend(mesh_.vertices[i]);
    centre_box.extend(centroids[slots_[s].face]);
  }
  {
    Node& node = nodes_[index];
    for (int k = 0; k < 3; ++k) {
      node.lo[k] = round_down(box.min()[k]);
      node.hi[k] = round_up(box.max()[k]);
    }
  }
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
  // hair of the answer along a coherent path (its neighbours would only be
  // tested again by the traversal).
  bool warm = false;
  if (hint != nullptr && hint->face >= 0 && hint->face < face_count()) {
    test_slot(slot_of_face_[hint->face], p, best);
    warm = best.d2 < limit;
  }
  const double hint_d2 = best.d2;

  auto box_d2 = [&](const Node& n) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) {
      const double lo = static_cast<double>(n.lo[k]) - p[k];
      const double hi = p[k] - static_cast<double>(n.hi[k]);
      const double d = std::max(std::max(lo, hi), 0.0);
      d2 += d * d;
    }
    return d2;
  };

  std::uint32_t stack[max_stack];
  double stack_d2[max_stack];
  int top = 0;
  const double root_d2 = box_d2(nodes_[0]);
  if (root_d2 < best.d2) {
    stack[top] = 0;
    stack_d2[top++] = root_d2;
  }
  while (top > 0) {
    --top;
    if (stack_d2[top] >= best.d2) continue;
    std::uint32_t ni = stack[top];
    for (;;) {
      const Node& n = nodes_[ni];
      if (n.count > 0) {
        for (std::uint32_t s = n.first; s < n.first + n.count; ++s) test_slot(s, p, best);
        break;
      }
      const std::uint32_t left = ni + 1, right = n.first;
      const double dl = box_d2(nodes_[left]), dr = box_d2(nodes_[right]);
      const bool left_first = dl <= dr;
      const std::uint32_t near = left_first ? left : right, far = left_first ? right : left;
      const double dn = left_first ? dl : dr, df = left_first ? dr : dl;
      if (dn >= best.d2) break;
      if (df < best.d2 && top < max_stack) {
        stack[top] = far;
        stack_d2[top++] = df;
      }
      ni = near;
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
