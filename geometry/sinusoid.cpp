#include "geometry/sinusoid.h"

#include <numbers>

namespace vcpost::geometry {

double wrap_from(double t, double lo) {
  constexpr double two_pi = 2 * std::numbers::pi;
  return t - two_pi * std::floor((t - lo) / two_pi);
}

namespace {
// Whether the direction (x, y) lies on the counter-clockwise arc from the
// unit vector (c0, s0) to (c1, s1) that spans `length` radians.
bool direction_within(double x, double y, double c0, double s0, double c1, double s1,
                      double length) {
  const double after_start = c0 * y - s0 * x, before_end = x * s1 - y * c1;
  if (length <= std::numbers::pi) return after_start >= 0 && before_end >= 0;
  return after_start >= 0 || before_end >= 0;
}
}  // namespace

Extremes sinusoid_extremes(const Sinusoid& f, AngleInterval range) {
  Extremes out;
  if (range.empty()) return out;
  const double c0 = std::cos(range.lo), s0 = std::sin(range.lo);
  const double c1 = std::cos(range.hi), s1 = std::sin(range.hi);
  out.add(f.a * c0 + f.b * s0 + f.c);
  out.add(f.a * c1 + f.b * s1 + f.c);
  // f = c + m cos(t - t*), t* = atan2(b, a): c + m at t*, c - m half a turn on.
  const double m = std::sqrt(f.a * f.a + f.b * f.b), length = range.hi - range.lo;
  if (m == 0) return out;
  if (length >= 2 * std::numbers::pi || direction_within(f.a, f.b, c0, s0, c1, s1, length)) {
    out.add(f.c + m);
  }
  if (length >= 2 * std::numbers::pi || direction_within(-f.a, -f.b, c0, s0, c1, s1, length)) {
    out.add(f.c - m);
  }
  return out;
}

}  // namespace vcpost::geometry
