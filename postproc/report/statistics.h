// Streaming statistics of the report: cutting-time-weighted distributions
// of vc before and after, the time the machine's limits bind, contact
// counts and the predicted surface quality. Memory does not grow with the
// number of points (percentiles come from fine fixed-width histograms).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "postproc/post/tallies.h"
#include "postproc/report/point_row.h"

namespace vcpost::report {

// Weighted values in [lo, hi) counted in `bins` equal bins; the exact
// minimum and maximum are kept. A quantile is exact to one bin width
// (hi - lo) / bins and always within [min, max] (q = 0 and 1 give them
// exactly); values outside [lo, hi) count in the first or last bin, where
// quantiles other than 0 and 1 are only known to lie beyond the range.
class WeightedQuantiles {
 public:
  // REQUIRES: lo < hi, bins >= 1.
  WeightedQuantiles(double lo, double hi, std::size_t bins);

  // REQUIRES: value finite, weight >= 0.
  void add(double value, double weight);

  double total_weight() const { return total_; }
  bool empty() const { return total_ <= 0; }
  double min() const { return min_; }
  double max() const { return max_; }
  double mean() const { return total_ > 0 ? weighted_sum_ / total_ : 0; }
  // The value under which a share q in [0, 1] of the weight lies
  // (linear within a bin). REQUIRES: !empty().
  double quantile(double q) const;
  double bin_width() const { return width_; }

 private:
  double lo_, width_;
  std::vector<double> weights_;
  double total_ = 0, weighted_sum_ = 0;
  double min_ = 0, max_ = 0;
};

// Distribution of one quantity over the cutting time.
struct Distribution {
  double min = 0, max = 0, mean = 0, p5 = 0, p50 = 0, p95 = 0;
  double resolution = 0;  // the percentiles' bin width, same unit
};

struct SpeedStatistics {
  std::optional<Distribution> vc;  // m/min; empty when nothing cut
  double within_5_percent = 0;     // share of cutting time with |vc/vc_nom - 1| <= 5 %
  double within_10_percent = 0;
  double below_nominal_time_s = 0;  // vc under nominal by more than 5 %
  double above_nominal_time_s = 0;  // vc over nominal by more than 5 %
  // Cutting time the machine's spindle range bounds: for `before` the
  // program's S outside [n_min, n_max] (the control clamps it); for `after`
  // the plan held at n_max / n_min.
  double clamped_max_time_s = 0, clamped_min_time_s = 0;
  std::optional<double> slew_time_s;  // the plan's acceleration limit decided S (after only)
};

// The points by contact state are the post::ContactCounts it derives from.
struct ReportStatistics : post::ContactCounts {
  std::uint64_t points = 0, cutting_points = 0;  // cutting: with a working diameter
  std::uint64_t no_cut = 0;
  double cutting_time_s = 0;  // sum of the points' weights
  SpeedStatistics before, after;
  std::optional<Distribution> cusp_um, ra_um, rz_um;
  std::uint64_t surface_points = 0;  // points with a predicted cusp height
};

class StatisticsAccumulator {
 public:
  // REQUIRES: vc_nominal > 0, tool_radius > 0.
  StatisticsAccumulator(double vc_nominal, double tool_radius_mm);

  void add(const PointRow& row);
  ReportStatistics result() const;

 private:
  struct Side {
    WeightedQuantiles vc;  // the distribution's percentiles
    post::VcTally tally;   // the bands around nominal
    double clamped_max = 0, clamped_min = 0, slew = 0;
    explicit Side(double vc_nominal) : vc(0, 4 * vc_nominal, 40000) {}
  };
  double vc_nominal_;
  ReportStatistics counts_;
  Side before_, after_;
  WeightedQuantiles cusp_, ra_, rz_;
};

}  // namespace vcpost::report
