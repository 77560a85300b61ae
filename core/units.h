// The inch, for programs written in it: vcpost works in millimetres.
#pragma once

namespace vcpost {

inline constexpr double kMmPerInch = 25.4;

}  // namespace vcpost
