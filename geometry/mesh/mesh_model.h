// An STL triangle mesh as a geometry::SurfaceModel: exact closest points on
// the triangles (inside a face, on an edge, on a vertex) through a bounding
// volume hierarchy of oriented boxes, warm-started from the previous
// answer's triangle.
//
// Units: mm (read_stl_file converts the file's unit). Faces are triangles:
// ModelContact::face is the triangle's index in StlMesh::triangles, uv its
// barycentric weights (of corners 1 and 2; corner 0 has 1 - u - v).
// Normals: a face contact gets the facet normal (corners counterclockwise
// seen from outside, the STL convention); an edge or vertex contact gets
// N = (C - CC)/|C - CC|, turned to point out of the material (the side is
// decided by the angle-weighted pseudo-normal of the edge or vertex, so a
// query point inside a closed solid is seen as inside). curvature is empty:
// a mesh has none worth reporting.
//
// Thread safety: immutable after construction; closest_point may run on
// many threads at once, each with its own ContactHint.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "geometry/mesh/stl_reader.h"
#include "geometry/model.h"

namespace vcpost::mesh {

class MeshModel final : public geometry::SurfaceModel {
 public:
  // Builds the index (O(n log n)), on oneTBB's threads: the index, and so
  // every answer, is the same bit for bit whatever their number. The mesh
  // is taken apart (its corners are kept in single precision when that
  // loses nothing, its triangles in hierarchy order). Throws
  // std::invalid_argument for a mesh without triangles or with a corner
  // index out of range.
  explicit MeshModel(StlMesh mesh);

  // See geometry::SurfaceModel. A hint with a valid face makes the query
  // warm: the previous answer's triangle gives an upper bound that prunes
  // most of the hierarchy from the start; the answer is still the global
  // closest point (the hierarchy is always searched within that bound).
  // ContactHint::warm_queries counts the queries the hint's triangle
  // answered, cold_queries the others.
  std::optional<geometry::ModelContact> closest_point(const Eigen::Vector3d& point,
                                                      double max_distance,
                                                      geometry::ContactHint* hint) const override;
  Eigen::AlignedBox3d bounds() const override { return bounds_; }
  int face_count() const override { return static_cast<int>(slots_.size()); }
  bool faceted() const override { return true; }

  std::size_t vertex_count() const { return vertices_.size(); }
  // Unit facet normal of triangle `face` (UnitZ for a degenerate one).
  Eigen::Vector3d facet_normal(int face) const;

 private:
  // The query hierarchy: the binary one collapsed to four children per
  // node, their boxes side by side in single precision (structure of
  // arrays), so one pass over the four lanes bounds all children at once.
  struct WideNode {
    float axis[3][3][4];  // axis[k][j][lane]: component j of axis k
    float offset[3][4];   // axis[k] . centre
    float half[3][4];     // half extents along the axes
    // Inner lane: the wide node's index; leaf: its first slot + (number of
    // triangles, 1 or 2) << kCountShift; empty lane: kNone. One word, not
    // two: 16 bytes a node (the 10 M-triangle mould has 3 M of them).
    std::uint32_t link[4];
    // Left unset: the build fills every field (on its threads; zeroing a
    // few megabytes first would be serial).
    WideNode() {}
  };
  // A triangle in hierarchy order: its corners (indices into the shared
  // vertices) and its face number. 16 bytes: the edges, normal and Gram
  // matrix the query needs are recomputed from the corners (a few dozen
  // flops against a cache line per triangle; the 10 M-triangle mould's
  // slots took 1.3 GB when they were stored, 128 bytes each).
  struct Slot {
    std::uint32_t corner[3];
    std::uint32_t face;
    Slot() {}  // left unset, as WideNode
  };
  struct Hit {
    double d2 = 0;
    Eigen::Vector3d point;
    double v = 0, w = 0;
    int feature = 0;  // 0 inside, 1..3 edge ab/bc/ca, 4..6 vertex a/b/c
    std::uint32_t face = 0;
  };

  // The shared corners, in single precision when every coordinate is a
  // float exactly (a binary STL in mm: half the memory, the same numbers),
  // else in double; every computation reads them as doubles.
  class Vertices {
   public:
    explicit Vertices(std::vector<Eigen::Vector3d>&& points);
    Eigen::Vector3d operator[](std::size_t i) const {
      return single_.empty() ? double_[i] : single_[i].cast<double>();
    }
    std::size_t size() const { return single_.empty() ? double_.size() : single_.size(); }
    // Asks for corner i's cache line ahead of its use.
    void prefetch(std::size_t i) const {
      if (single_.empty()) {
        __builtin_prefetch(double_.data() + i);
      } else {
        __builtin_prefetch(single_.data() + i);
      }
    }
    bool single() const { return !single_.empty(); }

   private:
    std::vector<Eigen::Vector3f> single_;
    std::vector<Eigen::Vector3d> double_;
  };

  // Builds the pseudo-normals and the hierarchy (mesh_builder.h).
  struct Builder;
  // One closest_point query's descent through the wide nodes (mesh_query.cpp).
  class Walk;
  void test_slot(std::uint32_t slot, const Eigen::Vector3d& p, Hit& best) const;
  geometry::ModelContact make_contact(const Eigen::Vector3d& p, const Hit& hit) const;
  const std::uint32_t* corners_of(std::uint32_t face) const {
    return slots_[slot_of_face_[face]].corner;
  }
  Eigen::Vector3d edge_normal(std::uint32_t face, int side) const;

  Vertices vertices_;
  Eigen::AlignedBox3d bounds_;
  // What the edge pseudo-normal of each face side ab, bc, ca is made of:
  // the face across that edge when the edge has two sides (the normal is
  // recomputed from the two facets when a contact needs it: no 24 bytes an
  // edge kept), kBorder when it has one, kShared + i when it has three or
  // more (shared_normal_[i]); kNone where the faces' normals cancel out.
  std::vector<std::array<std::uint32_t, 3>> side_;
  std::vector<Eigen::Vector3d> shared_normal_;
  std::vector<Eigen::Vector3d> vertex_normal_;  // angle-weighted
  std::vector<std::uint32_t> slot_of_face_;
  static constexpr std::uint32_t kNone = 0xffffffffu;  // an empty lane of a WideNode
  static constexpr int kCountShift = 30;
  static constexpr std::uint32_t kBorder = 0xfffffffeu;
  static constexpr std::uint32_t kShared = 0x80000000u;  // faces are fewer than that
  // Edge sides pack a face and its side in 32 bits, lanes a slot and its count.
  static constexpr std::size_t kMaxFaces = std::size_t{1} << 30;
  std::vector<Slot> slots_;
  std::vector<WideNode> wide_;
};

}  // namespace vcpost::mesh
