#include "postproc/program/timing.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

#include "postproc/program/arc.h"

namespace vcpost::program {

PathClock::PathClock(TimingSettings settings) : settings_(settings) {
  // Internal invariant, not the user's input: the profile reader refuses these
  // values first (E5005, with file:line:col); invalid_argument marks a bug.
  if (!(std::isfinite(settings_.rapid_mm_per_min) && settings_.rapid_mm_per_min > 0.0))
    throw std::invalid_argument("rapid rate must be a positive number of mm/min");
  if (!(std::isfinite(settings_.block_seconds) && settings_.block_seconds >= 0.0))
    throw std::invalid_argument("block processing time must be a number of seconds >= 0");
}

double PathClock::feed_minutes(double length, SourceRef source) const {
  if (length == 0.0) return 0.0;
  switch (mode_) {
    case FeedMode::per_minute:
      if (rate_ > 0.0) return length / rate_;
      throw TimingError(Code::E6101, "feed move with no feed rate in effect", source);
    case FeedMode::inverse_time:
      if (rate_ > 0.0) return 1.0 / rate_;
      throw TimingError(Code::E6102, "inverse-time (G93) move with no F", source);
    case FeedMode::per_revolution:
      if (rate_ > 0.0 && rpm_ > 0.0 && spindle_turning_) return length / (rate_ * rpm_);
      if (rate_ > 0.0)
        throw TimingError(Code::E6103, "feed per revolution (G95) with the spindle stopped",
                          source);
      throw TimingError(Code::E6101, "feed per revolution (G95) move with no feed rate", source);
  }
  return 0.0;
}

EventTime PathClock::advance(const Event& event) {
  double seconds = 0.0;
  bool motion = false;
  std::visit(
      [&](const auto& e) {
        using T = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<T, StraightTraverse>) {
          seconds = 60.0 * (e.end - e.start).norm() / settings_.rapid_mm_per_min;
          motion = true;
        } else if constexpr (std::is_same_v<T, StraightFeed>) {
          seconds = 60.0 * feed_minutes((e.end - e.start).norm(), e.source);
          motion = true;
        } else if constexpr (std::is_same_v<T, ArcFeed>) {
          seconds = 60.0 * feed_minutes(arc_length(e), e.source);
          motion = true;
        } else if constexpr (std::is_same_v<T, SetFeedRate>) {
          rate_ = e.rate;
          mode_ = e.mode;
        } else if constexpr (std::is_same_v<T, SetSpindleSpeed>) {
          rpm_ = e.rpm;
        } else if constexpr (std::is_same_v<T, SpindleOn>) {
          spindle_turning_ = true;
        } else if constexpr (std::is_same_v<T, SpindleOff>) {
          spindle_turning_ = false;
        } else if constexpr (std::is_same_v<T, Dwell>) {
          seconds = e.seconds;
        }
      },
      event);
  if (motion) seconds = std::max(seconds, settings_.block_seconds);
  const EventTime t{elapsed_, seconds};
  elapsed_ += seconds;
  return t;
}

}  // namespace vcpost::program
