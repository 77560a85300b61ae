// Invariants of the motion events that every reader must keep, checked on
// every event the fuzz drivers see (see fuzz/finding.h).
#pragma once

#include <cmath>
#include <string>
#include <type_traits>
#include <variant>

#include "fuzz/finding.h"
#include "postproc/program/events.h"

namespace vcpost::fuzz {

// Every number an event carries must be finite: a NaN or infinite
// coordinate, feed or speed would reach the machine.
inline void check_finite(const program::Event& event) {
  auto finite = [](const Eigen::Vector3d& v) { return v.allFinite(); };
  const bool ok = std::visit(
      [&](const auto& e) {
        using T = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<T, program::StraightTraverse> ||
                      std::is_same_v<T, program::StraightFeed>)
          return finite(e.start) && finite(e.end);
        else if constexpr (std::is_same_v<T, program::ArcFeed>)
          return finite(e.start) && finite(e.end) && finite(e.centre);
        else if constexpr (std::is_same_v<T, program::SetFeedRate>)
          return std::isfinite(e.rate) && (!e.path_rate || std::isfinite(*e.path_rate));
        else if constexpr (std::is_same_v<T, program::SetSpindleSpeed>)
          return std::isfinite(e.rpm);
        else if constexpr (std::is_same_v<T, program::Dwell>)
          return std::isfinite(e.seconds);
        else if constexpr (std::is_same_v<T, program::CannedCycle>)
          return std::isfinite(e.x) && std::isfinite(e.y) && std::isfinite(e.top_z) &&
                 std::isfinite(e.r_z) && std::isfinite(e.bottom_z) && std::isfinite(e.peck) &&
                 std::isfinite(e.dwell_s);
        else
          return true;
      },
      event);
  if (!ok) {
    const auto s = program::source_of(event);
    throw FuzzFinding("non-finite number in an event at line " + std::to_string(s.line));
  }
}

}  // namespace vcpost::fuzz
