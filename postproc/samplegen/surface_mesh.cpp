#include "postproc/samplegen/surface_mesh.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vcpost::samplegen {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// Length of the curve S(uv0 + t (uv1 - uv0)), t in [0, 1], by 64 chords.
double curve_length(const SampleSurface& s, const Vector2d& uv0, const Vector2d& uv1) {
  double length = 0;
  Vector3d previous = s.point(uv0);
  for (int k = 1; k <= 64; ++k) {
    const Vector3d p = s.point(uv0 + (uv1 - uv0) * (k / 64.0));
    length += (p - previous).norm();
    previous = p;
  }
  return length;
}

}  // namespace

mesh::StlMesh triangulate_grid(const SampleSurface& surface, int cells_u, int cells_v) {
  // Internal invariant, not the user's input: samplegen's own parameters
  // (invalid_argument: a bug).
  if (cells_u < 1 || cells_v < 1) throw std::invalid_argument("triangulate_grid: no cells");
  const Eigen::AlignedBox2d box = surface.domain();
  const Vector2d& lo = box.min();
  const Vector2d size = box.max() - box.min();
  mesh::StlMesh m;
  m.vertices.reserve(static_cast<std::size_t>(cells_u + 1) * (cells_v + 1));
  for (int i = 0; i <= cells_u; ++i) {
    for (int j = 0; j <= cells_v; ++j) {
      // The last row and column on the domain's edge exactly.
      const double u = i == cells_u ? box.max().x() : lo.x() + size.x() * i / cells_u;
      const double v = j == cells_v ? box.max().y() : lo.y() + size.y() * j / cells_v;
      m.vertices.push_back(surface.point({u, v}));
    }
  }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (cells_v + 1) + j); };
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, const Vector2d& uv) {
    const Vector3d n = (m.vertices[b] - m.vertices[a]).cross(m.vertices[c] - m.vertices[a]);
    const double scale = std::max((m.vertices[b] - m.vertices[a]).squaredNorm(),
                                  (m.vertices[c] - m.vertices[a]).squaredNorm());
    if (n.norm() <= 1e-12 * scale) return;  // collapsed at a pole
    if (n.dot(surface.normal(uv)) >= 0) {
      m.triangles.push_back({a, b, c});
    } else {
      m.triangles.push_back({a, c, b});
    }
  };
  m.triangles.reserve(2 * static_cast<std::size_t>(cells_u) * cells_v);
  for (int i = 0; i < cells_u; ++i) {
    for (int j = 0; j < cells_v; ++j) {
      const Vector2d centre =
          lo + size.cwiseProduct(Vector2d((i + 0.5) / cells_u, (j + 0.5) / cells_v));
      add(at(i, j), at(i + 1, j), at(i + 1, j + 1), centre);
      add(at(i, j), at(i + 1, j + 1), at(i, j + 1), centre);
    }
  }
  return m;
}

mesh::StlMesh triangulate(const SampleSurface& surface, std::uint64_t triangles) {
  // Internal invariant, not the user's input: samplegen's own parameters.
  if (triangles < 2) throw std::invalid_argument("triangulate: at least 2 triangles");
  const Eigen::AlignedBox2d box = surface.domain();
  const Vector2d &lo = box.min(), &hi = box.max();
  const Vector2d mid = box.center();
  // Extents along the middle iso-lines (enough for the sample parts, whose
  // metric does not vary by much across the domain).
  const double along_u = curve_length(surface, {lo.x(), mid.y()}, {hi.x(), mid.y()});
  const double along_v = curve_length(surface, {mid.x(), lo.y()}, {mid.x(), hi.y()});
  const double cells = static_cast<double>(triangles) / 2;
  const int cells_v =
      std::max(1, static_cast<int>(std::lround(std::sqrt(cells * along_v / along_u))));
  const int cells_u = std::max(1, static_cast<int>(std::lround(cells / cells_v)));
  return triangulate_grid(surface, cells_u, cells_v);
}

}  // namespace vcpost::samplegen
