// Cutting the height field: one move over every cell its swept cutter can
// reach (cut, the reference), and a whole path tile by tile in parallel
// (cut_path), each move over its band only, caps at the path's ends and
// at each joint only the cap's cells that neither neighbouring band
// covers (the outer wedge of the turn).
//
// Why the bands and wedges give the same result as cut(): outside its band
// a move's lowest point over a cell is its cutter at one end (the band
// reaches beyond the ends as far as the interior can still be lower:
// MoveFrame's reaches), and a joint's cap is part of both moves it joins,
// so where either band covers a cell the band's value is at most the cap's.
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"
#include "geometry/stock/height_field.h"
#include "geometry/stock/swept_move.h"

namespace vcpost::geometry::stock {

namespace {

// Cells whose centres lie within this of a band's or a cap's edge are cut
// by it too (mm): a cell the band needs is never lost to rounding.
constexpr double kEdgePad = 1e-7;
// Tiles of kTile x kTile cells are cut in parallel, each by its own thread.
constexpr std::int64_t kTile = 128;

struct CellBox {
  std::int64_t x0, x1, y0, y1;  // inclusive
};

// Inclusive cell indices (empty when lo > hi), unclipped.
struct CellRun {
  std::int64_t lo, hi;
};

constexpr double kInf = std::numeric_limits<double>::infinity();

// The cells whose centres lie in [x0, x1], as indices of a grid axis
// starting at origin (kept within a few cells of [0, n) so that infinite
// ends stay representable).
CellRun cells_between(double x0, double x1, double origin, double cell, std::int64_t n) {
  const double limit = static_cast<double>(n) + 2;
  const double lo = std::clamp(std::ceil((x0 - origin) / cell - 0.5), -2.0, limit);
  const double hi = std::clamp(std::floor((x1 - origin) / cell - 0.5), -2.0, limit);
  if (!(lo <= hi)) return {1, 0};
  return {static_cast<std::int64_t>(lo), static_cast<std::int64_t>(hi)};
}

// {x : lo <= alpha x + beta <= hi}, as [first, second] (empty when first > second).
std::pair<double, double> solve_between(double alpha, double beta, double lo, double hi) {
  if (std::abs(alpha) < 1e-12) {
    return beta >= lo && beta <= hi ? std::pair{-kInf, kInf} : std::pair{kInf, -kInf};
  }
  double a = (lo - beta) / alpha, b = (hi - beta) / alpha;
  if (a > b) std::swap(a, b);
  return {a, b};
}

// A move's band: the cells at s in [s_lo, s_hi] and |e| <= R of its frame.
struct Band {
  const MoveFrame* move;
  double s_lo, s_hi, e_max;

  // The rows (y indices) the band's rectangle touches.
  CellRun rows(const Grid& g) const {
    const Eigen::Vector2d n(-move->u.y(), move->u.x());
    double y_lo = kInf, y_hi = -kInf;
    for (const double s : {s_lo - kEdgePad, s_hi + kEdgePad}) {
      for (const double e : {-e_max - kEdgePad, e_max + kEdgePad}) {
        const double y = move->start.y() + s * move->u.y() + e * n.y();
        y_lo = std::min(y_lo, y);
        y_hi = std::max(y_hi, y);
      }
    }
    return cells_between(y_lo, y_hi, g.min.y(), g.cell_mm, g.ny);
  }

  // The cells of the row at y inside the band.
  CellRun row(const Grid& g, double y) const {
    const double ux = move->u.x(), uy = move->u.y();
    const double ax = move->start.x(), dy = y - move->start.y();
    const auto [s0, s1] = solve_between(ux, uy * dy - ux * ax, s_lo - kEdgePad, s_hi + kEdgePad);
    const auto [e0, e1] =
        solve_between(-uy, ux * dy + uy * ax, -e_max - kEdgePad, e_max + kEdgePad);
    return cells_between(std::max(s0, e0), std::min(s1, e1), g.min.x(), g.cell_mm, g.nx);
  }
};

// The disc of the cutter at a tip (a cap).
struct Disc {
  Eigen::Vector2d centre;
  double radius;

  CellRun rows(const Grid& g) const {
    const double r = radius + kEdgePad;
    return cells_between(centre.y() - r, centre.y() + r, g.min.y(), g.cell_mm, g.ny);
  }
  CellRun row(const Grid& g, double y) const {
    const double r = radius + kEdgePad, dy = y - centre.y();
    if (std::abs(dy) > r) return {1, 0};
    const double half = std::sqrt(std::max(0.0, r * r - dy * dy));
    return cells_between(centre.x() - half, centre.x() + half, g.min.x(), g.cell_mm, g.nx);
  }
};

class Cutting {
 public:
  Cutting(const Grid& grid, std::vector<float>& tops, const CutterProfile& profile)
      : grid_(grid), tops_(tops), profile_(profile) {}

  // The move's cutter over the cells [lo, hi] of row iy (clipped to box).
  void cut_run(const MoveFrame& move, std::int64_t iy, CellRun run, const CellBox& box) const {
    const std::int64_t lo = std::max(run.lo, box.x0), hi = std::min(run.hi, box.x1);
    if (lo > hi) return;
    const double cell = grid_.cell_mm;
    const double x = grid_.min.x() + (static_cast<double>(lo) + 0.5) * cell - move.start.x();
    const double y = grid_.min.y() + (static_cast<double>(iy) + 0.5) * cell - move.start.y();
    const double ux = move.u.x(), uy = move.u.y();
    float* row = tops_.data() + static_cast<std::size_t>(iy) * grid_.nx;
    with_kind(profile_.kind, [&](auto kind) {
      cut_cells<decltype(kind)::value>(profile_, move, row, static_cast<int>(lo),
                                       static_cast<int>(hi), x * ux + y * uy, -x * uy + y * ux,
                                       cell * ux, -cell * uy);
    });
  }

  void cut_band(const Band& band, const CellBox& box) const {
    const CellRun rows = band.rows(grid_);
    for (std::int64_t iy = std::max(rows.lo, box.y0); iy <= std::min(rows.hi, box.y1); ++iy) {
      cut_run(*band.move, iy, band.row(grid_, row_y(iy)), box);
    }
  }

  // The cutter standing at tip p over its whole disc.
  void cut_cap(const Eigen::Vector3d& p, const CellBox& box) const {
    const MoveFrame cap = frame_of(profile_, p, p);
    const Disc disc{p.head<2>(), profile_.radius};
    const CellRun rows = disc.rows(grid_);
    for (std::int64_t iy = std::max(rows.lo, box.y0); iy <= std::min(rows.hi, box.y1); ++iy) {
      cut_run(cap, iy, disc.row(grid_, row_y(iy)), box);
    }
  }

  // The cutter at the joint p over the cells of its disc that neither
  // band covers (their edge cells cut twice, so rounding loses none).
  void cut_joint(const Eigen::Vector3d& p, const Band& in, const Band& out,
                 const CellBox& box) const {
    const MoveFrame cap = frame_of(profile_, p, p);
    const Disc disc{p.head<2>(), profile_.radius};
    const CellRun rows = disc.rows(grid_);
    for (std::int64_t iy = std::max(rows.lo, box.y0); iy <= std::min(rows.hi, box.y1); ++iy) {
      const double y = row_y(iy);
      const CellRun whole = disc.row(grid_, y);
      if (whole.lo > whole.hi) continue;
      std::array<CellRun, 2> covered{in.row(grid_, y), out.row(grid_, y)};
      for (CellRun& c : covered) {
        ++c.lo;
        --c.hi;
      }
      if (covered[1].lo < covered[0].lo) std::swap(covered[0], covered[1]);
      std::int64_t next = whole.lo;
      for (const CellRun& c : covered) {
        if (c.lo > c.hi) continue;
        cut_run(cap, iy, {next, std::min(whole.hi, c.lo - 1)}, box);
        next = std::max(next, c.hi + 1);
      }
      cut_run(cap, iy, {next, whole.hi}, box);
    }
  }

 private:
  double row_y(std::int64_t iy) const {
    return grid_.min.y() + (static_cast<double>(iy) + 0.5) * grid_.cell_mm;
  }

  const Grid& grid_;
  std::vector<float>& tops_;
  const CutterProfile& profile_;
};

void check_tips(std::span<const Eigen::Vector3d> tips) {
  for (std::size_t i = 0; i < tips.size(); ++i) {
    if (!tips[i].allFinite()) {
      throw Error("E4707", "stock: tip " + std::to_string(i) + " of " +
                               std::to_string(tips.size()) + " is not a finite point");
    }
  }
}

CellBox whole_grid(const Grid& g) { return {0, std::int64_t{g.nx} - 1, 0, std::int64_t{g.ny} - 1}; }

}  // namespace

void HeightField::cut(const Cutter& cutter, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const CutterProfile profile = CutterProfile::of(cutter);
  const std::array<Eigen::Vector3d, 2> ends{a, b};
  check_tips(ends);
  const MoveFrame move = frame_of(profile, a, b);
  const double r = profile.radius;
  Cutting(grid_, top_, profile).cut_band({&move, -r, move.length + r, r}, whole_grid(grid_));
}

void HeightField::cut_path(const Cutter& cutter, std::span<const Eigen::Vector3d> tips) {
  const CutterProfile profile = CutterProfile::of(cutter);
  check_tips(tips);
  if (tips.empty()) return;
  // Consecutive equal tips make no move and no joint.
  std::vector<std::uint32_t> kept;
  kept.reserve(tips.size());
  for (std::size_t i = 0; i < tips.size(); ++i) {
    if (kept.empty() || tips[i] != tips[kept.back()]) kept.push_back(static_cast<std::uint32_t>(i));
  }
  const Cutting cutting(grid_, top_, profile);
  if (kept.size() == 1) {
    cutting.cut_cap(tips[kept[0]], whole_grid(grid_));
    return;
  }
  const std::size_t moves = kept.size() - 1;
  const auto tip = [&](std::size_t k) -> const Eigen::Vector3d& { return tips[kept[k]]; };

  // Each move goes to the tiles its band and its end caps can reach.
  const std::int64_t tiles_x = (std::int64_t{grid_.nx} + kTile - 1) / kTile;
  const std::int64_t tiles_y = (std::int64_t{grid_.ny} + kTile - 1) / kTile;
  const double tile_mm = static_cast<double>(kTile) * grid_.cell_mm;
  const auto tile_range = [&](std::size_t j) {
    const MoveFrame move = frame_of(profile, tip(j), tip(j + 1));
    const double margin =
        profile.radius + std::max(move.reach_before, move.reach_after) + grid_.cell_mm;
    const Eigen::Vector2d lo = tip(j).head<2>().cwiseMin(tip(j + 1).head<2>()).array() - margin;
    const Eigen::Vector2d hi = tip(j).head<2>().cwiseMax(tip(j + 1).head<2>()).array() + margin;
    const Eigen::Vector2d t0 = ((lo - grid_.min) / tile_mm).array().floor();
    const Eigen::Vector2d t1 = ((hi - grid_.min) / tile_mm).array().floor();
    return CellBox{static_cast<std::int64_t>(std::max(t0.x(), 0.0)),
                   static_cast<std::int64_t>(std::min(t1.x(), static_cast<double>(tiles_x - 1))),
                   static_cast<std::int64_t>(std::max(t0.y(), 0.0)),
                   static_cast<std::int64_t>(std::min(t1.y(), static_cast<double>(tiles_y - 1)))};
  };
  std::vector<std::size_t> start(static_cast<std::size_t>(tiles_x * tiles_y) + 1, 0);
  const auto for_tiles = [&](std::size_t j, auto&& f) {
    const CellBox t = tile_range(j);
    for (std::int64_t ty = t.y0; ty <= t.y1; ++ty) {
      for (std::int64_t tx = t.x0; tx <= t.x1; ++tx) f(static_cast<std::size_t>(ty * tiles_x + tx));
    }
  };
  for (std::size_t j = 0; j < moves; ++j) for_tiles(j, [&](std::size_t t) { ++start[t + 1]; });
  for (std::size_t t = 1; t < start.size(); ++t) start[t] += start[t - 1];
  std::vector<std::uint32_t> bucket(start.back());
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t j = 0; j < moves; ++j) {
      for_tiles(j, [&](std::size_t t) { bucket[fill[t]++] = static_cast<std::uint32_t>(j); });
    }
  }

  const double r = profile.radius;
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, start.size() - 1, 1), [&](const auto& range) {
        for (std::size_t t = range.begin(); t != range.end(); ++t) {
          if (start[t] == start[t + 1]) continue;
          const std::int64_t tx = static_cast<std::int64_t>(t) % tiles_x;
          const std::int64_t ty = static_cast<std::int64_t>(t) / tiles_x;
          const CellBox box{tx * kTile, std::min((tx + 1) * kTile, std::int64_t{grid_.nx}) - 1,
                            ty * kTile, std::min((ty + 1) * kTile, std::int64_t{grid_.ny}) - 1};
          // Tops only go down: the highest now bounds the tile while it is cut.
          float highest = kNoMaterial;
          for (std::int64_t iy = box.y0; iy <= box.y1; ++iy) {
            const float* row = top_.data() + static_cast<std::size_t>(iy) * grid_.nx;
            highest = std::max(highest, *std::max_element(row + box.x0, row + box.x1 + 1));
          }
          for (std::size_t k = start[t]; k < start[t + 1]; ++k) {
            const std::size_t j = bucket[k];
            const MoveFrame move = frame_of(profile, tip(j), tip(j + 1));
            if (move.lowest_tip >= highest) continue;
            const Band band{&move, -move.reach_before, move.length + move.reach_after, r};
            cutting.cut_band(band, box);
            if (j == 0) cutting.cut_cap(tip(0), box);
            if (j + 1 == moves) {
              cutting.cut_cap(tip(moves), box);
            } else {
              const MoveFrame next = frame_of(profile, tip(j + 1), tip(j + 2));
              const Band next_band{&next, -next.reach_before, next.length + next.reach_after, r};
              cutting.cut_joint(tip(j + 1), band, next_band, box);
            }
          }
        }
      });
}

}  // namespace vcpost::geometry::stock
