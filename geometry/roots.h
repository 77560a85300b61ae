// One-dimensional root finding for the engines' boundary curves.
#pragma once

#include <cmath>
#include <functional>

namespace vcpost::geometry {

// A root of g in [lo, hi], given that g(lo) and g(hi) differ in sign (either
// may be infinite). Regula falsi with the Illinois modification, falling back
// to bisection whenever a step leaves the bracket or a value is not finite;
// stops when the bracket is below `tolerance` (absolute, in x).
template <class Function>
double bracketed_root(const Function& g, double lo, double hi, double g_lo, double g_hi,
                      double tolerance) {
  int side = 0;
  for (int iteration = 0; iteration < 200 && hi - lo > tolerance; ++iteration) {
    double x = 0.5 * (lo + hi);
    if (std::isfinite(g_lo) && std::isfinite(g_hi) && g_lo != g_hi) {
      const double secant = hi - g_hi * (hi - lo) / (g_hi - g_lo);
      if (secant > lo && secant < hi) x = secant;
    }
    const double g_x = g(x);
    if (g_x == 0) return x;
    if ((g_x < 0) == (g_lo < 0)) {
      lo = x;
      g_lo = g_x;
      if (side == -1 && std::isfinite(g_hi)) g_hi *= 0.5;  // Illinois: unstick the far end
      side = -1;
    } else {
      hi = x;
      g_hi = g_x;
      if (side == 1 && std::isfinite(g_lo)) g_lo *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace vcpost::geometry
