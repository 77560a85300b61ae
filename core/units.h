// Units the programs are written in: vcpost works in millimetres and
// radians.
#pragma once

#include <numbers>

namespace vcpost {

inline constexpr double kMmPerInch = 25.4;
inline constexpr double kDeg = std::numbers::pi / 180.0;  // one degree, rad

}  // namespace vcpost
