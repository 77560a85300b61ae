// The pseudo-normals of the mesh index: what tells a query point inside the
// material from one outside at an edge or a vertex contact.
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <tuple>

#include "geometry/mesh/mesh_builder.h"
#include "geometry/mesh/triangle_normal.h"

namespace vcpost::mesh {

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

}  // namespace vcpost::mesh
