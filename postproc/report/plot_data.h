// What the report's plots show, reduced to a size that does not grow with
// the program: min/max decimation along cutting time, a plan-view grid of
// the worst value per cell, deviation histograms and the worst regions.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "postproc/report/point_row.h"

namespace vcpost::report {

// A point of a decimated series: x (cutting time, s) and y.
struct PlotPoint {
  double x = 0, y = 0;
};

// Streams (x, y) pairs with increasing x into at most 2 * max_buckets
// buckets of consecutive pairs (bucket widths double as the stream grows)
// and gives back each bucket's minimum and maximum in x order, so no peak
// or dip of the full series is lost. Series may skip pairs (no value).
class MinMaxDecimator {
 public:
  // `series`: how many y series share the x stream. REQUIRES: max_buckets >= 2.
  MinMaxDecimator(std::size_t series, std::size_t max_buckets);

  // One step of the stream: x and one optional y per series.
  void add(double x, const std::vector<std::optional<double>>& ys);

  // The decimated series k: per bucket its min and max (one point when they
  // coincide), in x order.
  std::vector<PlotPoint> series(std::size_t k) const;
  std::uint64_t steps() const { return steps_; }
  std::size_t bucket_width() const { return width_; }

 private:
  struct Extreme {
    bool any = false;
    PlotPoint min, max;
  };
  struct Bucket {
    std::vector<Extreme> e;
    std::size_t count = 0;
  };
  void merge_pairs();

  std::size_t series_, max_buckets_, width_ = 1;
  std::vector<Bucket> buckets_;
  std::uint64_t steps_ = 0;
};

// A plan-view (xy) raster over [lo, hi]: every cell keeps the value of
// largest magnitude seen in it (the worst deviation, the highest cusp).
class PlanGrid {
 public:
  // Cells are square; the longer side gets `max_cells` of them.
  // REQUIRES: lo < hi componentwise, max_cells >= 1.
  PlanGrid(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, int max_cells);

  void add(const Eigen::Vector2d& p, double value);

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  double cell() const { return cell_; }
  const Eigen::Vector2d& lo() const { return lo_; }
  // Row-major from (lo.x, lo.y); empty cells hold no value.
  const std::vector<std::optional<float>>& cells() const { return cells_; }

 private:
  Eigen::Vector2d lo_;
  double cell_;
  int nx_, ny_;
  std::vector<std::optional<float>> cells_;
};

// Share of cutting time per deviation bin: bins of `step` from -limit to
// +limit, the first and last also holding everything beyond.
struct DeviationHistogram {
  double step = 0.01, limit = 0.5;        // fractions (1 %, 50 %)
  std::vector<double> before_s, after_s;  // cutting time per bin, s
  DeviationHistogram();
  void add(double dev_before, double dev_after, double weight_s);
  std::size_t bin_of(double deviation) const;
};

// A stretch of consecutive cutting points whose vc deviates from nominal
// by more than a threshold: where to look in the program.
struct Region {
  std::uint32_t first_line = 0, last_line = 0;
  double start_cut_s = 0, duration_s = 0;  // along cutting time
  double worst_dev = 0;                    // the signed deviation of largest magnitude
  double vc_min = 0, vc_max = 0;
  double score = 0;  // sum of weight * |dev|: ranks the regions
  Eigen::Vector2d worst_xy = Eigen::Vector2d::Zero();
  plan::Bound bound = plan::Bound::none;  // the plan's bound with the most time in it
};

// Follows one speed series (before or after) and keeps the `keep` regions
// with the largest score.
class RegionTracker {
 public:
  RegionTracker(double threshold, std::size_t keep);
  // A point without vc (no cut) ends an open region.
  void add(const PointRow& row, std::optional<double> vc, std::optional<double> dev,
           double cut_time_s);
  std::vector<Region> result() const;  // by score, largest first

 private:
  void close();
  double threshold_;
  std::size_t keep_;
  std::optional<Region> open_;
  std::array<double, 11> bound_time_{};
  std::vector<Region> regions_;
};

}  // namespace vcpost::report
