// An in-process stock as a height field along +z (a Z-map): each cell of a
// regular xy grid holds the top of the material over its centre. The tool
// axis is +z (3-axis; tilted sections are the caller's business: it turns
// points into the stock's frame or leaves such sections out). Overhangs are
// not represented. docs/stock.md describes the model and its limits.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "geometry/tool.h"

namespace vcpost::geometry::stock {

// The shape that removes material, hanging from its tip (the lowest point
// on its axis), axis +z: ball, bull-nose, flat (geometry::Tool), or a
// drill (a flat tool's diameter with a point cone of point_angle_deg).
struct Cutter {
  Tool tool = Tool::flat(10);
  double point_angle_deg = 0;  // > 0: a drill point of this included angle (118 typical)

  static Cutter drill(double diameter, double point_angle_deg = 118) {
    return {Tool::flat(diameter), point_angle_deg};
  }
};

// The cells: cell (ix, iy) has its centre at min + (ix + 0.5, iy + 0.5) * cell_mm.
struct Grid {
  Eigen::Vector2d min = Eigen::Vector2d::Zero();
  double cell_mm = 0.1;
  std::uint32_t nx = 0, ny = 0;

  std::size_t cells() const { return std::size_t{nx} * ny; }
};

// No material at a cell (outside the stock, or cut through).
inline constexpr float kNoMaterial = -std::numeric_limits<float>::infinity();

class HeightField {
 public:
  // A block of stock [min, max]. Throws vcpost::Error (E47xx) for an empty
  // or inverted box, a cell <= 0, or more than memory_limit bytes needed.
  static HeightField block(const Eigen::Vector3d& min, const Eigen::Vector3d& max, double cell_mm,
                           std::size_t memory_limit);
  // The top of a triangle mesh (a stock STL): each cell the highest point
  // of the triangles over its centre; kNoMaterial where none covers it.
  // Triangles as corner triples, 3 per triangle.
  static HeightField from_triangles(std::span<const Eigen::Vector3f> corners, double cell_mm,
                                    std::size_t memory_limit);

  const Grid& grid() const;
  float top(std::uint32_t ix, std::uint32_t iy) const;
  // The top of the cell holding (x, y); kNoMaterial outside the grid.
  float top_at(double x, double y) const;

  // Removes what the cutter sweeps with its tip moving on the straight
  // line from a to b (every cell: top = min(top, lowest point of the swept
  // tool over the cell's centre)).
  void cut(const Cutter& cutter, const Eigen::Vector3d& a, const Eigen::Vector3d& b);
  // A path of tip positions joined by straight moves; the same result as
  // cut() move by move (removal is a min, so order does not matter), in
  // parallel over tiles.
  void cut_path(const Cutter& cutter, std::span<const Eigen::Vector3d> tips);

  // The material over p along the unit direction n: the distance from p
  // to where the ray p + t n first leaves the stock (0 where p is not in
  // the stock), at most max_mm.
  double depth_along(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double max_mm) const;

  std::size_t memory_bytes() const;

 private:
  explicit HeightField(const Grid& grid, float fill);

  Grid grid_;
  std::vector<float> top_;
};

}  // namespace vcpost::geometry::stock
