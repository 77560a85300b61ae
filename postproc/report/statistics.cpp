#include "postproc/report/statistics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vcpost::report {
namespace {

std::size_t surface_bins(double radius_mm) {
  // 0.05 um bins up to the ball radius (no cusp is higher).
  return static_cast<std::size_t>(std::clamp(std::ceil(1000 * radius_mm / 0.05), 100.0, 400000.0));
}

std::optional<Distribution> distribution(const WeightedQuantiles& q) {
  if (q.empty()) return std::nullopt;
  return Distribution{q.min(),         q.max(),          q.mean(),     q.quantile(0.05),
                      q.quantile(0.5), q.quantile(0.95), q.bin_width()};
}

}  // namespace

WeightedQuantiles::WeightedQuantiles(double lo, double hi, std::size_t bins)
    : lo_(lo), width_((hi - lo) / static_cast<double>(bins)), weights_(bins, 0.0) {
  // Internal invariant, not the user's input: the ranges are constants of
  // the statistics (invalid_argument: a bug).
  if (!(lo < hi) || bins == 0) throw std::invalid_argument("WeightedQuantiles: empty range");
}

void WeightedQuantiles::add(double value, double weight) {
  if (!(weight > 0)) return;
  const double position = std::floor((value - lo_) / width_);
  const auto last = static_cast<double>(weights_.size() - 1);
  weights_[static_cast<std::size_t>(std::clamp(position, 0.0, last))] += weight;
  if (total_ <= 0) {
    min_ = max_ = value;
  } else {
    min_ = std::min(min_, value);
    max_ = std::max(max_, value);
  }
  total_ += weight;
  weighted_sum_ += weight * value;
}

double WeightedQuantiles::quantile(double q) const {
  if (q <= 0) return min_;
  if (q >= 1) return max_;
  const double target = std::clamp(q, 0.0, 1.0) * total_;
  double below = 0;
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    if (weights_[i] <= 0) continue;
    if (below + weights_[i] >= target) {
      const double fraction = (target - below) / weights_[i];
      const double value = lo_ + (static_cast<double>(i) + fraction) * width_;
      return std::clamp(value, min_, max_);
    }
    below += weights_[i];
  }
  return max_;
}

StatisticsAccumulator::StatisticsAccumulator(double vc_nominal, double tool_radius_mm)
    : vc_nominal_(vc_nominal),
      before_(vc_nominal),
      after_(vc_nominal),
      cusp_(0, 1000 * tool_radius_mm, surface_bins(tool_radius_mm)),
      ra_(0, 1000 * tool_radius_mm, surface_bins(tool_radius_mm)),
      rz_(0, 1000 * tool_radius_mm, surface_bins(tool_radius_mm)) {
  if (!(vc_nominal > 0) || !(tool_radius_mm > 0)) {
    // Internal invariant, not the user's input: --vc and the tool are checked
    // (E2001, E1601) before statistics start.
    throw std::invalid_argument("StatisticsAccumulator: vc_nominal and tool radius must be > 0");
  }
}

void StatisticsAccumulator::add(const PointRow& row) {
  ++counts_.points;
  counts_.count_contact(row.status);
  if (row.has(PointFlag::no_cut)) ++counts_.no_cut;
  const double w = row.weight_s;
  counts_.cutting_time_s += w;
  if (row.vc_before && row.vc_after) {
    ++counts_.cutting_points;
    auto add_side = [&](Side& side, double vc) {
      side.vc.add(vc, w);
      side.tally.add(vc, vc_nominal_, w);
    };
    add_side(before_, *row.vc_before);
    add_side(after_, *row.vc_after);
    if (row.has(PointFlag::before_over_max)) before_.clamped_max += w;
    if (row.has(PointFlag::before_under_min)) before_.clamped_min += w;
    if (row.has(PointFlag::clamped_max)) after_.clamped_max += w;
    if (row.has(PointFlag::clamped_min)) after_.clamped_min += w;
    if (row.has(PointFlag::slew)) after_.slew += w;
  }
  if (row.cusp_um) {
    ++counts_.surface_points;
    cusp_.add(*row.cusp_um, w);
  }
  if (row.ra_um) ra_.add(*row.ra_um, w);
  if (row.rz_um) rz_.add(*row.rz_um, w);
}

ReportStatistics StatisticsAccumulator::result() const {
  ReportStatistics out = counts_;
  auto side_result = [](const Side& side, bool with_slew) {
    SpeedStatistics s;
    s.vc = distribution(side.vc);
    if (const auto vc = side.tally.statistics()) {
      s.within_5_percent = vc->within_5_percent;
      s.within_10_percent = vc->within_10_percent;
    }
    s.below_nominal_time_s = side.tally.bands().below;
    s.above_nominal_time_s = side.tally.bands().above;
    s.clamped_max_time_s = side.clamped_max;
    s.clamped_min_time_s = side.clamped_min;
    if (with_slew) s.slew_time_s = side.slew;
    return s;
  };
  out.before = side_result(before_, false);
  out.after = side_result(after_, true);
  out.cusp_um = distribution(cusp_);
  out.ra_um = distribution(ra_);
  out.rz_um = distribution(rz_);
  return out;
}

}  // namespace vcpost::report
