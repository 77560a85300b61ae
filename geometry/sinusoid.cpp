#include "geometry/sinusoid.h"

#include <numbers>

namespace vcpost::geometry {

double wrap_from(double t, double lo) {
  constexpr double two_pi = 2 * std::numbers::pi;
  return t - two_pi * std::floor((t - lo) / two_pi);
}

Extremes sinusoid_extremes(const Sinusoid& f, AngleInterval range) {
  Extremes out;
  if (range.empty()) return out;
  out.add(f(range.lo));
  out.add(f(range.hi));
  const double peak = std::atan2(f.b, f.a);  // f is largest here, smallest a half turn on
  for (const double t : {peak, peak + std::numbers::pi}) {
    const double inside = wrap_from(t, range.lo);
    if (inside <= range.hi) out.add(f(inside));
  }
  return out;
}

}  // namespace vcpost::geometry
