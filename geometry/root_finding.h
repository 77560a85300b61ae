// One root finder for the geometry: a safeguarded Newton's method in a
// bracket, for a function whose slope comes with its value.
#pragma once

#include <cmath>

namespace vcpost::geometry {

// The root of g in [lo, hi], where g(lo) = g_lo < 0 < g(hi) = g_hi:
// Newton's method on g_and_slope(t) = {g, g'} from the bracket's secant,
// a step leaving the bracket bisecting it, until a step is below
// `tolerance`, whose end is the root.
template <class Function>
double newton_root(const Function& g_and_slope, double lo, double hi, double g_lo, double g_hi,
                   double tolerance) {
  double t = lo - g_lo * (hi - lo) / (g_hi - g_lo);
  if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
  for (int i = 0; i < 200 && hi - lo > tolerance; ++i) {
    const auto [g, slope] = g_and_slope(t);
    if (g == 0) return t;
    (g < 0 ? lo : hi) = t;
    const double next = t - g / slope;
    if (std::abs(next - t) <= tolerance && next >= lo && next <= hi) return next;
    t = next > lo && next < hi ? next : 0.5 * (lo + hi);
  }
  return t;
}

}  // namespace vcpost::geometry
