#include "postproc/post/offset_diagnosis.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace vcpost::post {
namespace {

constexpr double kMinOffset = 0.05;  // mm

std::string mm(double value) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(3);
  out << value << " mm";
  return out.str();
}

// "-1.245": the allowance as an option value, to the um.
std::string option_value(double value) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(3);
  out << (std::abs(value) < 5e-4 ? 0.0 : value);
  return out.str();
}

// The --stock that moves the surface by `offset` from where `stock` put it:
// one value, or radial:axial when the section already has two.
std::string stock_option(const geometry::Allowance& stock, std::optional<int> tool, double offset) {
  std::string value = option_value(stock.radial + offset);
  if (!stock.is_uniform()) value += ":" + option_value(stock.axial + offset);
  // '=' before a negative value: no parser reads it as an option of its own.
  std::string option = "--stock" + std::string(value.front() == '-' ? "=" : " ") + value;
  if (tool) option += " (or --stock T" + std::to_string(*tool) + "=" + value + ")";
  return option;
}

}  // namespace

OffsetHistogram::OffsetHistogram(double tolerance_mm, double radius_mm, geometry::Allowance stock,
                                 std::optional<int> tool)
    : tolerance_(tolerance_mm),
      radius_(radius_mm),
      stock_(stock),
      tool_(tool),
      bins_(static_cast<std::size_t>(2 * kRange / kBin) + 1, 0) {}

std::size_t OffsetHistogram::bin_of(double value) const {
  const double clamped = std::clamp(value, -kRange, kRange);
  return static_cast<std::size_t>(std::lround((clamped + kRange) / kBin));
}

double OffsetHistogram::value_of(std::size_t bin) const {
  return static_cast<double>(bin) * kBin - kRange;
}

bool OffsetHistogram::beyond_tolerance(std::size_t bin, bool gouge) const {
  return gouge ? value_of(bin) + kBin / 2 < -tolerance_ : value_of(bin) - kBin / 2 > tolerance_;
}

void OffsetHistogram::add(double e) {
  if (!std::isfinite(e)) return;
  const std::size_t bin = bin_of(e);
  ++bins_[bin];
  ++points_;
  if (e < -tolerance_) {
    const double depth = -e;
    gouge_min_ = gouges_ == 0 ? depth : std::min(gouge_min_, depth);
    gouge_max_ = std::max(gouge_max_, depth);
    ++gouges_;
    if (!beyond_tolerance(bin, true)) ++gouges_in_tolerance_bin_;
  } else if (e > tolerance_) {
    lift_min_ = lifts_ == 0 ? e : std::min(lift_min_, e);
    lift_max_ = std::max(lift_max_, e);
    ++lifts_;
    if (!beyond_tolerance(bin, false)) ++lifts_in_tolerance_bin_;
  }
}

DepthStatistics OffsetHistogram::depths(bool gouge) const {
  DepthStatistics d;
  d.points = gouge ? gouges_ : lifts_;
  if (d.points == 0) return d;
  d.min = gouge ? gouge_min_ : lift_min_;
  d.max = gouge ? gouge_max_ : lift_max_;
  // The median from the bins wholly beyond the tolerance, walked from the
  // surface out, after the depths in the bin the tolerance falls in: the
  // least ones, counted apart because that bin also holds points within the
  // tolerance. A path on an offset surface just beyond the tolerance piles
  // them up there; skipped, they pushed the median far out.
  const std::uint64_t half = (d.points + 1) / 2;
  std::uint64_t seen = gouge ? gouges_in_tolerance_bin_ : lifts_in_tolerance_bin_;
  if (seen >= half) {
    d.median = d.min;
    return d;
  }
  const std::size_t zero = bin_of(0.0);
  for (std::size_t k = 0; k < bins_.size(); ++k) {
    const std::size_t bin = gouge ? zero - std::min(k, zero) : zero + k;
    if (bin >= bins_.size()) break;
    const double value = value_of(bin);
    if (!beyond_tolerance(bin, gouge)) continue;
    seen += bins_[bin];
    if (seen >= half) {
      d.median = std::clamp(std::abs(value), d.min, d.max);
      break;
    }
    if (gouge && bin == 0) break;
  }
  return d;
}

DepthStatistics OffsetHistogram::gouge() const { return depths(true); }
DepthStatistics OffsetHistogram::lift() const { return depths(false); }

std::optional<OffsetDiagnosis> OffsetHistogram::diagnosis() const {
  if (points_ == 0) return std::nullopt;
  constexpr std::size_t half_window = 20;  // +-0.02 mm
  std::uint64_t window = 0;
  for (std::size_t b = 0; b <= std::min(2 * half_window, bins_.size() - 1); ++b) window += bins_[b];
  std::uint64_t best = window;
  std::size_t best_centre = half_window;
  for (std::size_t centre = half_window + 1; centre + half_window < bins_.size(); ++centre) {
    window += bins_[centre + half_window];
    window -= bins_[centre - half_window - 1];
    if (window > best) {
      best = window;
      best_centre = centre;
    }
  }
  // The mean offset within the window (finer than the bins' grid).
  double sum = 0;
  for (std::size_t b = best_centre - half_window; b <= best_centre + half_window; ++b)
    sum += static_cast<double>(bins_[b]) * value_of(b);
  const double offset = best > 0 ? sum / static_cast<double>(best) : value_of(best_centre);
  const double share = static_cast<double>(best) / static_cast<double>(points_);
  // Chord errors of a coarse path spread over a few hundredths of a mm;
  // an offset worth naming (stock, a tool size, a frame) is larger. A path
  // none of whose points is within the tolerance (it never touches) has no
  // chord error to tell apart: any offset beyond the tolerance is named.
  const bool touches = gouges_ + lifts_ < points_;
  const double min_offset = touches ? std::max(kMinOffset, 3 * tolerance_) : tolerance_;
  if (share < 0.5 || std::abs(offset) <= min_offset) return std::nullopt;
  OffsetDiagnosis d;
  d.offset_mm = offset;
  d.share = share;
  std::ostringstream causes;
  if (std::abs(offset - radius_) <= 0.05) {
    causes << "the offset is the tool radius: the program's points are likely the ball centre "
              "(try --cl-point center)";
  } else if (std::abs(offset + radius_) <= 0.05) {
    causes << "the offset is minus the tool radius: the program's points are likely the tool tip "
              "(try --cl-point tip)";
  } else {
    // An allowance is named only where the tool would be left to take it
    // (a path deeper than the radius into the model is no glue gap).
    const bool takes = radius_ + std::min(stock_.radial, stock_.axial) + offset > 0;
    if (takes) d.option = stock_option(stock_, tool_, offset);
    causes << (offset > 0 ? "stock to leave in the CAM (" : "negative stock to leave in the CAM (")
           << mm(std::abs(offset)) << (stock_.is_zero() ? std::string() : " more than --stock gave")
           << ")" << (takes ? "? post with " + d.option + ";" : ",")
           << " or a program written for a " << (offset > 0 ? "larger" : "smaller")
           << " tool than the one given, the CL point (tip or centre), or the work offset or "
              "frame (the path or the model shifted)";
  }
  d.causes = causes.str();
  return d;
}

}  // namespace vcpost::post
