// The material over a point along a direction: the ray walks the cells its
// xy projection crosses (in order, as a grid traversal does), and in each
// cell the ray's z is linear, so where it rises through the cell's top is
// exact for the height field as it is (flat-topped cells).
#include <cmath>
#include <limits>

#include "geometry/stock/height_field.h"

namespace vcpost::geometry::stock {

double HeightField::depth_along(const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                                double max_mm) const {
  const double length = n.norm();
  if (!(length > 0) || !p.allFinite() || !(max_mm > 0)) return 0;
  const Eigen::Vector3d d = n / length;
  const double cell = grid_.cell_mm;
  const double fx = std::floor((p.x() - grid_.min.x()) / cell);
  const double fy = std::floor((p.y() - grid_.min.y()) / cell);
  if (!(fx >= 0 && fy >= 0 && fx < grid_.nx && fy < grid_.ny)) return 0;
  auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy);
  if (!(p.z() <= top(static_cast<std::uint32_t>(ix), static_cast<std::uint32_t>(iy)))) return 0;

  constexpr double kInf = std::numeric_limits<double>::infinity();
  const int step_x = d.x() > 0 ? 1 : -1, step_y = d.y() > 0 ? 1 : -1;
  // The ray parameter at the next cell border in x and in y, and between borders.
  const auto border = [&](double origin, double pos, double dir, std::int64_t i) {
    if (dir == 0) return kInf;
    const double edge = origin + (static_cast<double>(i) + (dir > 0 ? 1 : 0)) * cell;
    return (edge - pos) / dir;
  };
  double next_x = border(grid_.min.x(), p.x(), d.x(), ix);
  double next_y = border(grid_.min.y(), p.y(), d.y(), iy);
  const double delta_x = d.x() == 0 ? kInf : cell / std::abs(d.x());
  const double delta_y = d.y() == 0 ? kInf : cell / std::abs(d.y());
  double t = 0;
  for (;;) {
    const double cell_top = top(static_cast<std::uint32_t>(ix), static_cast<std::uint32_t>(iy));
    const double leave = std::min(next_x, next_y);
    if (d.z() > 0) {
      const double through_top = (cell_top - p.z()) / d.z();
      if (through_top <= leave) return std::clamp(through_top, t, max_mm);
    }
    if (leave >= max_mm) return max_mm;
    t = leave;
    if (next_x <= next_y) {
      ix += step_x;
      next_x += delta_x;
    } else {
      iy += step_y;
      next_y += delta_y;
    }
    if (ix < 0 || iy < 0 || ix >= grid_.nx || iy >= grid_.ny) return t;
    if (p.z() + t * d.z() > top(static_cast<std::uint32_t>(ix), static_cast<std::uint32_t>(iy))) {
      return t;
    }
  }
}

}  // namespace vcpost::geometry::stock
