// What the post summary (post_job.h) and the report (report/statistics.h)
// both count over the evaluated points, computed in this one place so that
// the two give the same numbers: the points in each contact state, and the
// cutting speed over the cutting time (minimum, maximum, time-weighted
// mean, and the time in bands around the nominal vc).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include "geometry/model.h"

namespace vcpost::post {

// Points by how the ball sits on the model. The summary, its sections and
// the report's statistics are such counts (they derive from it).
struct ContactCounts {
  std::uint64_t touching = 0, lifted = 0, gouging = 0, missed = 0;

  void count_contact(geometry::BallStatus status) {
    switch (status) {
      case geometry::BallStatus::touching:
        ++touching;
        break;
      case geometry::BallStatus::lifted:
        ++lifted;
        break;
      case geometry::BallStatus::gouging:
        ++gouging;
        break;
      case geometry::BallStatus::missed:
        ++missed;
        break;
    }
  }
};

// How near vc runs to its nominal value, as cutting time in bands around
// it: the one definition of the 5 % and 10 % bands.
struct VcBandTimes {
  double within_5 = 0;   // s with |vc / nominal - 1| <= 5 %
  double within_10 = 0;  // s with |vc / nominal - 1| <= 10 %
  double below = 0;      // s more than 5 % under nominal
  double above = 0;      // s more than 5 % over nominal

  void add(double vc, double nominal, double weight_s) {
    constexpr double slack = 1e-12;  // a vc on a band's edge counts as inside
    const double deviation = vc / nominal - 1;
    if (std::abs(deviation) <= 0.05 + slack) within_5 += weight_s;
    if (std::abs(deviation) <= 0.10 + slack) within_10 += weight_s;
    if (deviation < -0.05 - slack) below += weight_s;
    if (deviation > 0.05 + slack) above += weight_s;
  }
};

// Statistics of the cutting speed over the cutting samples, weighted by
// cutting time. vc in m/min at the reference diameter.
struct VcStatistics {
  double min = 0, max = 0, mean = 0;
  double within_5_percent = 0;   // share of cutting time with |vc/vc_nom - 1| <= 5 %
  double within_10_percent = 0;  // ... <= 10 %
};

// The cutting speed of points added one by one with the cutting time each
// stands for (a weight <= 0 counts nothing).
class VcTally {
 public:
  void add(double vc, double nominal, double weight_s) {
    if (weight_s <= 0) return;
    min_ = std::min(min_, vc);
    max_ = std::max(max_, vc);
    weighted_sum_ += weight_s * vc;
    bands_.add(vc, nominal, weight_s);
    weight_s_ += weight_s;
  }

  double weight_s() const { return weight_s_; }
  const VcBandTimes& bands() const { return bands_; }
  // Empty when nothing was added.
  std::optional<VcStatistics> statistics() const {
    if (weight_s_ <= 0) return std::nullopt;
    return VcStatistics{min_, max_, weighted_sum_ / weight_s_, bands_.within_5 / weight_s_,
                        bands_.within_10 / weight_s_};
  }

 private:
  double min_ = HUGE_VAL, max_ = -HUGE_VAL;
  double weighted_sum_ = 0;
  VcBandTimes bands_;
  double weight_s_ = 0;
};

}  // namespace vcpost::post
