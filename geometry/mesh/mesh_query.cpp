// The mesh index's queries: the closest point of the triangles to a point,
// through the hierarchy of oriented boxes, and the contact made of it.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "geometry/mesh/mesh_model.h"
#include "geometry/mesh/triangle_normal.h"

namespace vcpost::mesh {
namespace {

constexpr int max_stack = 128;

}  // namespace

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

// Lower bounds of the squared distance from p to the four lanes' boxes,
// in single precision: |axis.p - offset| is off by at most a few float
// ulps of |p|_1 + |offset| (the margin and the grown half extents take
// that off), and the float axes are orthonormal to ~1e-7 (the final
// factor takes that back). The lanes still to open wait on a stack, each
// with its bound.
class MeshModel::Walk {
 public:
  // warm: the bound is already (nearly) the answer (closest_point's hint).
  Walk(const Eigen::Vector3d& p, bool warm)
      : px_(static_cast<float>(p.x())),
        py_(static_cast<float>(p.y())),
        pz_(static_cast<float>(p.z())),
        // Rounding of axis.p in float: a few ulps of |p|_1 (the offsets'
        // own share is in the half extents).
        margin_(1e-6f * (std::abs(px_) + std::abs(py_) + std::abs(pz_))),
        warm_(warm) {}

  // Pushes the lanes of `n` whose bound is below best_d2.
  void open(const WideNode& n, double best_d2) {
    // The lanes' float bounds against best.d2 / shrink, rounded up (the
    // 1e-6 is far above float rounding): a lane is skipped only when its
    // bound times shrink is at least best.d2.
    const auto bound = static_cast<float>(best_d2 / kShrink * (1 + 1e-6));
    const F4 d2 = lane_bounds(n);
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
        while (!warm_ && i > 0 && lb[order[i - 1]] < lb[l]) {
          order[i] = order[i - 1];
          --i;
        }
        order[i] = l;
      }
    }
    for (int i = 0; i < m && top_ < max_stack; ++i) {
      stack_link_[top_] = n.link[order[i]];
      stack_d2_[top_++] = static_cast<double>(lb[order[i]]) * kShrink;
    }
  }

  // The link of the next lane whose bound is below best_d2; false when
  // none is left.
  bool next(double best_d2, std::uint32_t& link) {
    while (top_ > 0) {
      --top_;
      if (stack_d2_[top_] >= best_d2) continue;
      link = stack_link_[top_];
      return true;
    }
    return false;
  }

 private:
  // Four lanes at once (GCC/Clang vector extension: SSE on x86-64).
  using F4 = float __attribute__((vector_size(16)));
  using I4 = std::int32_t __attribute__((vector_size(16)));
  static constexpr double kShrink = 1 - 1e-5;

  static F4 load(const float (&a)[4]) {
    F4 v;
    std::memcpy(&v, a, sizeof v);
    return v;
  }

  // The four lanes' squared distances from p, at most the true ones.
  F4 lane_bounds(const WideNode& n) const {
    const F4 zero = {0, 0, 0, 0};
    const I4 no_sign = {0x7fffffff, 0x7fffffff, 0x7fffffff, 0x7fffffff};
    F4 d2 = zero;
    for (int k = 0; k < 3; ++k) {
      const F4 along = load(n.axis[k][0]) * px_ + load(n.axis[k][1]) * py_ +
                       load(n.axis[k][2]) * pz_ - load(n.offset[k]);
      F4 e =
          reinterpret_cast<F4>(reinterpret_cast<I4>(along) & no_sign) - load(n.half[k]) - margin_;
      e = e > zero ? e : zero;
      d2 += e * e;
    }
    return d2;
  }

  const float px_, py_, pz_, margin_;
  const bool warm_;
  std::uint32_t stack_link_[max_stack];
  double stack_d2_[max_stack];
  int top_ = 0;
};

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

  Walk walk(p, warm);
  walk.open(wide_[0], best.d2);
  std::uint32_t link = 0;
  while (walk.next(best.d2, link)) {
    const std::uint32_t child = link & ((1u << kCountShift) - 1);
    const std::uint32_t count = link >> kCountShift;
    if (count > 0) {
      for (std::uint32_t s = child; s < child + count; ++s) test_slot(s, p, best);
    } else {
      walk.open(wide_[child], best.d2);
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
