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
#include "geometry/stock/cell_region.h"
#include "geometry/stock/height_field.h"
#include "geometry/stock/swept_move.h"

namespace vcpost::geometry::stock {

namespace {

// Cells whose centres lie within this of a band's or a cap's edge are cut
// by it too (mm): a cell the band needs is never lost to rounding.
constexpr double kEdgePad = 1e-7;
// A joint's wedge overlaps the bands beside it by this (mm).
constexpr double kJointOverlap = 1e-6;
// Cells are cut in chunks of up to kChunk along a line, each left out when
// the move cannot lower it.
constexpr std::int64_t kChunk = 32;
// Tiles of kTile x kTile cells are cut in parallel, each by its own thread.
constexpr std::int64_t kTile = 256;

struct CellBox {
  std::int64_t x0, x1, y0, y1;  // inclusive
};

constexpr double kInf = std::numeric_limits<double>::infinity();

// The highest of count tops, stride apart from first: four running
// maxima, so that the compare latencies overlap.
float highest_of(const float* first, std::ptrdiff_t stride, std::int64_t count) {
  std::array<float, 4> high{kNoMaterial, kNoMaterial, kNoMaterial, kNoMaterial};
  std::int64_t i = 0;
  for (; i + 4 <= count; i += 4) {
    for (int k = 0; k < 4; ++k) high[k] = std::max(high[k], first[(i + k) * stride]);
  }
  for (; i < count; ++i) high[0] = std::max(high[0], first[i * stride]);
  return std::max(std::max(high[0], high[1]), std::max(high[2], high[3]));
}

class Cutting {
 public:
  Cutting(const Grid& grid, std::vector<float>& tops, const CutterProfile& profile)
      : grid_(grid), inverse_cell_(1 / grid.cell_mm), tops_(tops), profile_(profile) {}

  // The move's cutter over the region's cells in the lines from y_lo to
  // y_hi (within box): rows, or (Columns) columns with x and y swapped in
  // the region and the bounds. Chunk by chunk along each line, a chunk left
  // out when the move cannot lower it: its highest top is not above the
  // move's lowest tip plus the cutter's underside at the chunk's least
  // distance from the move.
  template <ProfileKind Kind, bool Columns>
  void cut_lines(const MoveFrame& move, const CellRegion& region, double y_lo, double y_hi,
                 const CellBox& box) const {
    constexpr int kAlong = Columns ? 1 : 0, kAcross = 1 - kAlong;
    const std::int64_t n_along = Columns ? grid_.ny : grid_.nx;
    const std::int64_t n_across = Columns ? grid_.nx : grid_.ny;
    const std::int64_t box_lo = Columns ? box.y0 : box.x0, box_hi = Columns ? box.y1 : box.x1;
    const std::int64_t lines_lo = Columns ? box.x0 : box.y0, lines_hi = Columns ? box.x1 : box.y1;
    const std::ptrdiff_t stride = Columns ? grid_.nx : 1;
    const double cell = grid_.cell_mm, r = profile_.radius;
    const double origin_along = grid_.min[kAlong], origin_across = grid_.min[kAcross];
    const CellRun lines = cells_between(y_lo, y_hi, origin_across, inverse_cell_, n_across);
    const double ux = move.u.x(), uy = move.u.y();
    // One cell on along the line, in the move's frame.
    const double ds = Columns ? cell * uy : cell * ux, de = Columns ? cell * ux : -cell * uy;
    for (std::int64_t il = std::max(lines.lo, lines_lo); il <= std::min(lines.hi, lines_hi); ++il) {
      const double across = origin_across + (static_cast<double>(il) + 0.5) * cell;
      const CellRun run = region.row(origin_along, inverse_cell_, n_along, across);
      const std::int64_t lo = std::max(run.lo, box_lo), hi = std::min(run.hi, box_hi);
      if (lo > hi) continue;
      Eigen::Vector2d centre;
      centre[kAlong] = origin_along + (static_cast<double>(lo) + 0.5) * cell;
      centre[kAcross] = across;
      const Eigen::Vector2d d = centre - move.start;
      const double s0 = d.x() * ux + d.y() * uy, e0 = -d.x() * uy + d.y() * ux;
      float* line = tops_.data() + (Columns ? static_cast<std::size_t>(il)
                                            : static_cast<std::size_t>(il) * grid_.nx);
      for (std::int64_t c0 = lo; c0 <= hi; c0 += kChunk) {
        const std::int64_t c1 = std::min(hi, c0 + kChunk - 1);
        const auto skip = static_cast<double>(c0 - lo);
        const double s = s0 + skip * ds, e = e0 + skip * de;
        const float highest = highest_of(line + c0 * stride, stride, c1 - c0 + 1);
        if (move.lowest_tip >= highest) continue;
        const double half = 0.5 * static_cast<double>(c1 - c0);
        const double s_mid = s + half * ds, e_mid = e + half * de;
        const double beyond = std::min(s_mid, 0.0) + std::max(s_mid - move.length, 0.0);
        const double nearest = std::sqrt(e_mid * e_mid + beyond * beyond) - half * cell;
        if (nearest > r) continue;
        const double clear = std::max(nearest, 0.0);
        if (move.lowest_tip + underside<Kind>(profile_, clear * clear) >= highest) continue;
        cut_cells<Kind, Columns>(profile_, move, line, stride, static_cast<int>(c0),
                                 static_cast<int>(c1), s, e, ds, de);
      }
    }
  }

  // The region's cells by rows from y_lo to y_hi, or by columns from x
  // (given as y_lo and y_hi, the region built with x and y swapped).
  template <bool Columns>
  void cut_region(const MoveFrame& move, const CellRegion& region, double y_lo, double y_hi,
                  const CellBox& box) const {
    with_kind(profile_.kind, [&](auto kind) {
      cut_lines<decltype(kind)::value, Columns>(move, region, y_lo, y_hi, box);
    });
  }

  // The move's band: the cells at s in [s_lo, s_hi] and |e| <= R of its frame.
  void cut_band(const MoveFrame& move, double s_lo, double s_hi, const CellBox& box) const {
    const double r = profile_.radius;
    const Eigen::Vector2d& u = move.u;
    const Eigen::Vector2d n(-u.y(), u.x());
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(kInf), hi = Eigen::Vector2d::Constant(-kInf);
    for (const double s : {s_lo, s_hi}) {
      for (const double e : {-r, r}) {
        const Eigen::Vector2d corner = move.start + s * u + e * n;
        lo = lo.cwiseMin(corner);
        hi = hi.cwiseMax(corner);
      }
    }
    // Fewer and longer lines: columns when the band is taller than wide.
    const bool columns = hi.y() - lo.y() > hi.x() - lo.x();
    const auto swap = [&](const Eigen::Vector2d& v) {
      return columns ? Eigen::Vector2d(v.y(), v.x()) : v;
    };
    CellRegion region(swap(move.start));
    region.keep_side(swap(u), s_lo, kEdgePad);
    region.keep_side(swap(-u), -s_hi, kEdgePad);
    region.keep_side(swap(n), -r, kEdgePad);
    region.keep_side(swap(-n), -r, kEdgePad);
    if (columns) {
      cut_region<true>(move, region, lo.x() - kEdgePad, hi.x() + kEdgePad, box);
    } else {
      cut_region<false>(move, region, lo.y() - kEdgePad, hi.y() + kEdgePad, box);
    }
  }

  // The cutter standing at tip p over its whole disc.
  void cut_cap(const Eigen::Vector3d& p, const CellBox& box) const {
    CellRegion region(p.head<2>());
    region.keep_disc(profile_.radius + kEdgePad);
    const double reach = profile_.radius + kEdgePad;
    cut_region<false>(frame_of(profile_, p, p), region, p.y() - reach, p.y() + reach, box);
  }

  // The cutter at the joint p over the cells of its disc beyond both
  // bands: past the incoming band's end and before the outgoing band's
  // start (a cell before the incoming band's start has the cutter at the
  // joint before, lower there than this one, and so on along the path; one
  // after the outgoing band's end the one at the joint after). The two
  // half-planes overlap the bands by kJointOverlap, so rounding loses no
  // cell between them.
  void cut_joint(const Eigen::Vector3d& p, const MoveFrame& in, const MoveFrame& out,
                 const CellBox& box) const {
    // Going on in the same direction, the bands meet (reaches are >= 0):
    // past one and before the other is nothing but their padded edges.
    const double turn = in.u.x() * out.u.y() - in.u.y() * out.u.x();
    if (std::abs(turn) < 1e-12 && in.u.dot(out.u) > 0) return;
    const Eigen::Vector2d v = p.head<2>();
    // The wedge: |d| <= R, normal[k].d >= offset[k], d = q - v.
    const std::array<Eigen::Vector2d, 2> normal{in.u, -out.u};
    const std::array<double, 2> offset{in.reach_after - kJointOverlap,
                                       out.reach_before - kJointOverlap};
    const auto [y_lo, y_hi] = wedge_rows(normal, offset);
    if (y_lo > y_hi) return;
    // By columns when the wedge is narrower than tall: x and y swapped.
    const auto swap = [](const Eigen::Vector2d& w) { return Eigen::Vector2d(w.y(), w.x()); };
    const std::array<Eigen::Vector2d, 2> swapped{swap(normal[0]), swap(normal[1])};
    const auto [x_lo, x_hi] = wedge_rows(swapped, offset);
    const bool columns = x_hi - x_lo < y_hi - y_lo;
    CellRegion region(columns ? swap(v) : v);
    region.keep_disc(profile_.radius + kEdgePad);
    for (int k = 0; k < 2; ++k)
      region.keep_side(columns ? swapped[k] : normal[k], offset[k], kEdgePad);
    const MoveFrame cap = frame_of(profile_, p, p);
    if (columns) {
      cut_region<true>(cap, region, v.x() + x_lo - kEdgePad, v.x() + x_hi + kEdgePad, box);
    } else {
      cut_region<false>(cap, region, v.y() + y_lo - kEdgePad, v.y() + y_hi + kEdgePad, box);
    }
  }

 private:
  // The lowest and highest d.y of the convex region |d| <= R,
  // (with the normals' x and y swapped: of d.x)
  // normal[k].d >= offset[k] (lowest > highest when it is empty): they lie
  // among the corners of its edges and the circle's own lowest and highest
  // points.
  std::pair<double, double> wedge_rows(const std::array<Eigen::Vector2d, 2>& normal,
                                       const std::array<double, 2>& offset) const {
    const double r = profile_.radius;
    const auto inside = [&](const Eigen::Vector2d& d) {
      for (int k = 0; k < 2; ++k) {
        if (normal[k].dot(d) < offset[k] - 1e-9) return false;
      }
      return d.norm() <= r + 1e-9;
    };
    double y_lo = kInf, y_hi = -kInf;
    const auto take = [&](const Eigen::Vector2d& d) {
      if (!inside(d)) return;
      y_lo = std::min(y_lo, d.y());
      y_hi = std::max(y_hi, d.y());
    };
    take({0, r});
    take({0, -r});
    for (int k = 0; k < 2; ++k) {
      if (std::abs(offset[k]) > r) continue;
      const Eigen::Vector2d along(-normal[k].y(), normal[k].x());
      const double half = std::sqrt(r * r - offset[k] * offset[k]);
      take(offset[k] * normal[k] + half * along);
      take(offset[k] * normal[k] - half * along);
    }
    const double det = normal[0].x() * normal[1].y() - normal[0].y() * normal[1].x();
    if (std::abs(det) > 1e-12) {
      take({(offset[0] * normal[1].y() - offset[1] * normal[0].y()) / det,
            (normal[0].x() * offset[1] - normal[1].x() * offset[0]) / det});
    }
    return {y_lo, y_hi};
  }

  const Grid& grid_;
  double inverse_cell_;
  std::vector<float>& tops_;
  const CutterProfile& profile_;
};

void check_tips(std::span<const Eigen::Vector3d> tips) {
  for (std::size_t i = 0; i < tips.size(); ++i) {
    if (!tips[i].allFinite()) {
      throw Error(Code::E4707, "stock: tip " + std::to_string(i) + " of " +
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
  Cutting(grid_, top_, profile).cut_band(move, -r, move.length + r, whole_grid(grid_));
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
            cutting.cut_band(move, -move.reach_before, move.length + move.reach_after, box);
            if (j == 0) cutting.cut_cap(tip(0), box);
            if (j + 1 == moves) {
              cutting.cut_cap(tip(moves), box);
            } else {
              cutting.cut_joint(tip(j + 1), move, frame_of(profile, tip(j + 1), tip(j + 2)), box);
            }
          }
        }
      });
}

}  // namespace vcpost::geometry::stock
