// How MeshModel builds its index (mesh_model.cpp runs the phases): the
// pseudo-normals that tell inside from outside (mesh_normals.cpp) and the
// hierarchy of oriented boxes (mesh_hierarchy.cpp). Seen only by those files.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "geometry/mesh/corner_spread.h"
#include "geometry/mesh/mesh_model.h"
#include "geometry/mesh/oriented_box.h"

namespace vcpost::mesh {

// Faces per task for the per-face loops.
inline constexpr std::size_t face_grain = 4096;

// The index is built in a fixed order of floating-point operations, the
// same whatever the number of threads: the boxes (and so the order in which
// queries visit triangles, which decides ties) do not depend on it.
struct MeshModel::Builder {
  struct Item {
    // In single precision: 16 bytes an item, not 32, for the median
    // splits that move them (the centroids only choose where to split;
    // the boxes are fitted to the corners). Trivially copyable: the
    // splits read the centroid and the face as one 16-byte vector.
    std::array<float, 3> centroid;
    std::uint32_t face;
  };

  // The corners of a subtree's slots [base, base + size) side by side in
  // slot order (three per slot), copied once the splits have put the slots
  // in their final order: below a quarter million triangles the fits read
  // them from here rather than through the triangles (a copy of all the
  // corners at once took 72 bytes a face, 720 MB for 10 M triangles; a
  // block is 19 MB, one a running subtree).
  struct Scratch {
    std::uint32_t base;
    std::unique_ptr<double[]> block;  // x, y, z: 3 scratch_capacity doubles, reused from spare
    double* xyz[3];
  };
  static constexpr std::uint32_t scratch_size = 1u << 18;
  // Blocks of finished subtrees, for the next ones: each subtree's own
  // new and delete of a few MB went back to the system and came back as
  // fresh pages for the kernel to zero (10 M triangles: a third of the
  // 2.8 GB of page faults).
  std::size_t scratch_capacity = 0;  // 3 min(faces, scratch_size): corners per block
  std::mutex spare_mutex;
  std::vector<std::unique_ptr<double[]>> spare;

  MeshModel& m;
  const std::vector<std::array<std::uint32_t, 3>>& triangles;  // until the slots hold them
  std::unique_ptr<Item[]> items;  // in slot order, from the splits to the slots
  std::map<std::uint32_t, std::uint32_t> wide_counts;  // by subtree size; read only in build

  Builder(MeshModel& model, const std::vector<std::array<std::uint32_t, 3>>& t)
      : m(model), triangles(t) {}

  // A face side, in the groups edges() sorts them into.
  struct Side {
    std::uint32_t upper;      // its upper vertex
    std::uint32_t face_side;  // 4 face + side (faces are fewer than 2^30)
    // Left unset (user-provided, so a vector of them is not zero-filled):
    // every one is written, on the threads.
    Side() {}  // NOLINT(modernize-use-equals-default)
    Side(std::uint32_t u, std::uint32_t fs) : upper(u), face_side(fs) {}
  };
  void group_sides(std::vector<Side>& sides, std::vector<std::size_t>& start) const;
  void edges();
  void vertex_normals();
  void splits();
  void boxes();
  void slots();
  template <class F>
  void for_each_corner(std::uint32_t begin, std::uint32_t end, F&& f) const;
  void fit_node(OrientedBox& node, std::uint32_t begin, std::uint32_t end,
                const CornerSpread& spread, const Scratch* scratch) const;
  // Not const: they reorder the slots' items (through `items`).
  void split(std::uint32_t begin, std::uint32_t end);
  void split_all(std::uint32_t begin, std::uint32_t end);
  CornerSpread top(std::uint32_t begin, std::uint32_t end, std::uint32_t own, Scratch* scratch);
  CornerSpread expanded(std::uint32_t begin, std::uint32_t end, std::uint32_t wide, int lane,
                        std::uint32_t own_left, std::uint32_t own_right, Scratch* scratch);
  CornerSpread lane(std::uint32_t begin, std::uint32_t end, std::uint32_t wide, int lane,
                    std::uint32_t own, Scratch* scratch);
  std::uint32_t count_wide(std::uint32_t size);
  void clear_lanes(std::uint32_t wide);
  void set_lane(std::uint32_t wide, int lane, const OrientedBox& box, std::uint32_t child,
                std::uint32_t count);
};

}  // namespace vcpost::mesh
