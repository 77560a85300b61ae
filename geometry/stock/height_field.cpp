#include "geometry/stock/height_field.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "core/error.h"

namespace vcpost::geometry::stock {

namespace {

std::string point_text(const Eigen::Vector3d& p) {
  std::ostringstream text;
  text << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return text.str();
}

void check_cell(double cell_mm) {
  if (cell_mm > 0 && std::isfinite(cell_mm)) return;
  std::ostringstream text;
  text << "stock: cell size " << cell_mm << " mm is not a positive length";
  throw Error(Code::E4702, text.str());
}

// The grid over [min, max] in xy: whole cells from min on, at least one.
Grid grid_over(const Eigen::Vector2d& min, const Eigen::Vector2d& max, double cell_mm,
               std::size_t memory_limit) {
  Grid grid;
  grid.min = min;
  grid.cell_mm = cell_mm;
  const Eigen::Vector2d cells = ((max - min) / cell_mm).array().ceil().max(1.0);
  const double count = cells.x() * cells.y();
  const double bytes = count * sizeof(float);
  if (!(bytes <= static_cast<double>(memory_limit))) {
    std::ostringstream text;
    text.precision(15);
    text << "stock: " << cells.x() << " x " << cells.y() << " cells of " << cell_mm << " mm need "
         << bytes << " bytes, over the limit of " << memory_limit << " bytes";
    throw Error(Code::E4703, text.str());
  }
  grid.nx = static_cast<std::uint32_t>(cells.x());
  grid.ny = static_cast<std::uint32_t>(cells.y());
  return grid;
}

}  // namespace

HeightField::HeightField(const Grid& grid, float fill) : grid_(grid), top_(grid.cells(), fill) {}

HeightField HeightField::block(const Eigen::Vector3d& min, const Eigen::Vector3d& max,
                               double cell_mm, std::size_t memory_limit) {
  if (!min.allFinite() || !max.allFinite() || !(min.array() < max.array()).all()) {
    throw Error(Code::E4701,
                "stock: block from " + point_text(min) + " to " + point_text(max) +
                    " is empty: each coordinate of the maximum must be above the minimum's");
  }
  check_cell(cell_mm);
  return HeightField(grid_over(min.head<2>(), max.head<2>(), cell_mm, memory_limit),
                     static_cast<float>(max.z()));
}

HeightField HeightField::from_triangles(std::span<const Eigen::Vector3f> corners, double cell_mm,
                                        std::size_t memory_limit) {
  if (corners.size() % 3 != 0) {
    throw Error(Code::E4704, "stock: " + std::to_string(corners.size()) +
                                 " triangle corners, not a whole number of triangles");
  }
  for (std::size_t i = 0; i < corners.size(); ++i) {
    if (!corners[i].allFinite()) {
      throw Error(Code::E4704, "stock: triangle " + std::to_string(i / 3) +
                                   " has a corner that is not a finite point");
    }
  }
  check_cell(cell_mm);
  if (corners.empty()) throw Error(Code::E4705, "stock: the stock mesh has no triangle");
  Eigen::Vector2d lo = corners[0].head<2>().cast<double>(), hi = lo;
  for (const Eigen::Vector3f& c : corners) {
    lo = lo.cwiseMin(c.head<2>().cast<double>());
    hi = hi.cwiseMax(c.head<2>().cast<double>());
  }
  HeightField field(grid_over(lo, hi, cell_mm, memory_limit), kNoMaterial);
  const Grid& g = field.grid_;
  // Each triangle over the cell centres inside its xy projection (edges
  // included, so that neighbours leave no crack): the plane's z there.
  constexpr double kEdge = 1e-9;
  for (std::size_t t = 0; t + 2 < corners.size(); t += 3) {
    const Eigen::Vector3d p0 = corners[t].cast<double>();
    const Eigen::Vector3d p1 = corners[t + 1].cast<double>();
    const Eigen::Vector3d p2 = corners[t + 2].cast<double>();
    const Eigen::Vector2d e1 = (p1 - p0).head<2>(), e2 = (p2 - p0).head<2>();
    const double area = e1.x() * e2.y() - e1.y() * e2.x();
    if (std::abs(area) <= 1e-12 * (e1.squaredNorm() + e2.squaredNorm())) continue;
    const Eigen::Vector2d tlo = p0.head<2>().cwiseMin(p1.head<2>()).cwiseMin(p2.head<2>());
    const Eigen::Vector2d thi = p0.head<2>().cwiseMax(p1.head<2>()).cwiseMax(p2.head<2>());
    const auto first = [&](double v, double origin, std::uint32_t n) {
      return static_cast<std::int64_t>(
          std::clamp(std::ceil((v - origin) / g.cell_mm - 0.5), 0.0, static_cast<double>(n)));
    };
    const auto last = [&](double v, double origin, std::uint32_t n) {
      return static_cast<std::int64_t>(
          std::clamp(std::floor((v - origin) / g.cell_mm - 0.5), -1.0, n - 1.0));
    };
    const std::int64_t ix0 = first(tlo.x(), g.min.x(), g.nx), ix1 = last(thi.x(), g.min.x(), g.nx);
    const std::int64_t iy0 = first(tlo.y(), g.min.y(), g.ny), iy1 = last(thi.y(), g.min.y(), g.ny);
    for (std::int64_t iy = iy0; iy <= iy1; ++iy) {
      const double y = g.min.y() + (static_cast<double>(iy) + 0.5) * g.cell_mm;
      for (std::int64_t ix = ix0; ix <= ix1; ++ix) {
        const double x = g.min.x() + (static_cast<double>(ix) + 0.5) * g.cell_mm;
        const Eigen::Vector2d q(x - p0.x(), y - p0.y());
        const double b1 = (q.x() * e2.y() - q.y() * e2.x()) / area;
        const double b2 = (e1.x() * q.y() - e1.y() * q.x()) / area;
        if (b1 < -kEdge || b2 < -kEdge || b1 + b2 > 1 + kEdge) continue;
        const double z = p0.z() + b1 * (p1.z() - p0.z()) + b2 * (p2.z() - p0.z());
        float& top = field.top_[static_cast<std::size_t>(iy) * g.nx + static_cast<std::size_t>(ix)];
        top = std::max(top, static_cast<float>(z));
      }
    }
  }
  if (std::all_of(field.top_.begin(), field.top_.end(), [](float z) { return z == kNoMaterial; })) {
    throw Error(Code::E4705,
                "stock: no triangle of the stock mesh covers a cell centre seen from +z");
  }
  return field;
}

const Grid& HeightField::grid() const { return grid_; }

float HeightField::top(std::uint32_t ix, std::uint32_t iy) const {
  return top_[std::size_t{iy} * grid_.nx + ix];
}

float HeightField::top_at(double x, double y) const {
  const double fx = std::floor((x - grid_.min.x()) / grid_.cell_mm);
  const double fy = std::floor((y - grid_.min.y()) / grid_.cell_mm);
  if (!(fx >= 0 && fy >= 0 && fx < grid_.nx && fy < grid_.ny)) return kNoMaterial;
  return top(static_cast<std::uint32_t>(fx), static_cast<std::uint32_t>(fy));
}

std::size_t HeightField::memory_bytes() const {
  return sizeof(HeightField) + top_.capacity() * sizeof(float);
}

}  // namespace vcpost::geometry::stock
