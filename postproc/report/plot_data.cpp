#include "postproc/report/plot_data.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vcpost::report {

MinMaxDecimator::MinMaxDecimator(std::size_t series, std::size_t max_buckets)
    : series_(series), max_buckets_(max_buckets) {
  // Internal invariant, not the user's input: callers pass a fixed bucket count
  // (invalid_argument: a bug).
  if (max_buckets < 2) throw std::invalid_argument("MinMaxDecimator: max_buckets must be >= 2");
}

void MinMaxDecimator::add(double x, const std::vector<std::optional<double>>& ys) {
  if (buckets_.empty() || buckets_.back().count >= width_) {
    if (buckets_.size() >= 2 * max_buckets_) merge_pairs();
    if (buckets_.empty() || buckets_.back().count >= width_) {
      buckets_.push_back({std::vector<Extreme>(series_), 0});
    }
  }
  Bucket& b = buckets_.back();
  ++b.count;
  ++steps_;
  for (std::size_t k = 0; k < series_ && k < ys.size(); ++k) {
    if (!ys[k]) continue;
    Extreme& e = b.e[k];
    const PlotPoint p{x, *ys[k]};
    if (!e.any) {
      e = {true, p, p};
    } else {
      if (p.y < e.min.y) e.min = p;
      if (p.y > e.max.y) e.max = p;
    }
  }
}

void MinMaxDecimator::merge_pairs() {
  std::vector<Bucket> merged;
  merged.reserve(buckets_.size() / 2 + 1);
  for (std::size_t i = 0; i < buckets_.size(); i += 2) {
    Bucket b = buckets_[i];
    if (i + 1 < buckets_.size()) {
      const Bucket& c = buckets_[i + 1];
      b.count += c.count;
      for (std::size_t k = 0; k < series_; ++k) {
        const Extreme& e = c.e[k];
        if (!e.any) continue;
        Extreme& d = b.e[k];
        if (!d.any) {
          d = e;
        } else {
          if (e.min.y < d.min.y) d.min = e.min;
          if (e.max.y > d.max.y) d.max = e.max;
        }
      }
    }
    merged.push_back(std::move(b));
  }
  buckets_ = std::move(merged);
  width_ *= 2;
}

std::vector<PlotPoint> MinMaxDecimator::series(std::size_t k) const {
  std::vector<PlotPoint> out;
  out.reserve(2 * buckets_.size());
  for (const Bucket& b : buckets_) {
    const Extreme& e = b.e.at(k);
    if (!e.any) continue;
    if (e.min.x == e.max.x) {
      out.push_back(e.min);
    } else if (e.min.x < e.max.x) {
      out.push_back(e.min);
      out.push_back(e.max);
    } else {
      out.push_back(e.max);
      out.push_back(e.min);
    }
  }
  return out;
}

PlanGrid::PlanGrid(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, int max_cells) : lo_(lo) {
  const Eigen::Vector2d size = hi - lo;
  if (!(size.x() > 0) || !(size.y() > 0) || max_cells < 1) {
    // Internal invariant, not the user's input: a report has points, so an extent.
    throw std::invalid_argument("PlanGrid: empty extent");
  }
  cell_ = size.maxCoeff() / max_cells;
  nx_ = std::max(1, static_cast<int>(std::ceil(size.x() / cell_ - 1e-9)));
  ny_ = std::max(1, static_cast<int>(std::ceil(size.y() / cell_ - 1e-9)));
  cells_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), std::nullopt);
}

void PlanGrid::add(const Eigen::Vector2d& p, double value) {
  if (!std::isfinite(value) || !p.allFinite()) return;
  const int i = std::clamp(static_cast<int>(std::floor((p.x() - lo_.x()) / cell_)), 0, nx_ - 1);
  const int j = std::clamp(static_cast<int>(std::floor((p.y() - lo_.y()) / cell_)), 0, ny_ - 1);
  auto& c = cells_[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) +
                   static_cast<std::size_t>(i)];
  if (!c || std::abs(value) > std::abs(*c)) c = static_cast<float>(value);
}

DeviationHistogram::DeviationHistogram() {
  const auto bins = static_cast<std::size_t>(std::lround(2 * limit / step));
  before_s.assign(bins, 0.0);
  after_s.assign(bins, 0.0);
}

std::size_t DeviationHistogram::bin_of(double deviation) const {
  const double position = std::floor((deviation + limit) / step + 1e-9);
  return static_cast<std::size_t>(
      std::clamp(position, 0.0, static_cast<double>(before_s.size() - 1)));
}

void DeviationHistogram::add(double dev_before, double dev_after, double weight_s) {
  before_s[bin_of(dev_before)] += weight_s;
  after_s[bin_of(dev_after)] += weight_s;
}

RegionTracker::RegionTracker(double threshold, std::size_t keep)
    : threshold_(threshold), keep_(keep) {}

void RegionTracker::add(const PointRow& row, std::optional<double> vc, std::optional<double> dev,
                        double cut_time_s) {
  if (!vc || !dev || std::abs(*dev) <= threshold_) {
    close();
    return;
  }
  if (!open_) {
    open_ = Region{row.line, row.line, cut_time_s,          0,        *dev, *vc,
                   *vc,      0,        row.point.head<2>(), row.bound};
    bound_time_.fill(0);
  }
  Region& r = *open_;
  r.last_line = row.line;
  r.duration_s += row.weight_s;
  r.score += row.weight_s * std::abs(*dev);
  r.vc_min = std::min(r.vc_min, *vc);
  r.vc_max = std::max(r.vc_max, *vc);
  if (std::abs(*dev) > std::abs(r.worst_dev)) {
    r.worst_dev = *dev;
    r.worst_xy = row.point.head<2>();
  }
  const auto b = static_cast<std::size_t>(row.bound);
  if (b < bound_time_.size()) bound_time_[b] += std::max(row.weight_s, 1e-12);
}

void RegionTracker::close() {
  if (!open_) return;
  const auto best = std::max_element(bound_time_.begin(), bound_time_.end());
  open_->bound = static_cast<plan::Bound>(best - bound_time_.begin());
  regions_.push_back(*open_);
  open_.reset();
  // Bounded memory: trim to the best `keep_` now and then.
  if (regions_.size() >= 8 * keep_ + 64) {
    std::partial_sort(regions_.begin(), regions_.begin() + static_cast<std::ptrdiff_t>(keep_),
                      regions_.end(),
                      [](const Region& a, const Region& b) { return a.score > b.score; });
    regions_.resize(keep_);
  }
}

std::vector<Region> RegionTracker::result() const {
  RegionTracker copy = *this;
  copy.close();
  auto out = std::move(copy.regions_);
  std::sort(out.begin(), out.end(),
            [](const Region& a, const Region& b) { return a.score > b.score; });
  if (out.size() > keep_) out.resize(keep_);
  return out;
}

}  // namespace vcpost::report
