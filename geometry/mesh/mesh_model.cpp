#include "geometry/mesh/mesh_model.h"

#include <oneapi/tbb/parallel_invoke.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

#include "geometry/mesh/mesh_builder.h"

namespace vcpost::mesh {

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

}  // namespace vcpost::mesh
