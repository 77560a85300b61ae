// Extremes of f(t) = A cos t + B sin t + C over an interval of angles, and
// the intervals where such a sinusoid stays under a bound: the building
// blocks of the closed-form engagement (circles on the tool).
#pragma once

#include <algorithm>
#include <cmath>

namespace vcpost::geometry {

struct Sinusoid {
  double a = 0, b = 0, c = 0;  // f(t) = a cos t + b sin t + c
  double operator()(double t) const { return a * std::cos(t) + b * std::sin(t) + c; }
};

struct AngleInterval {
  double lo = 0, hi = 0;  // radians, lo <= hi
  bool empty() const { return hi < lo; }
};

struct Extremes {
  double min = HUGE_VAL, max = -HUGE_VAL;
  void add(double value) {
    min = std::min(min, value);
    max = std::max(max, value);
  }
  void add(const Extremes& other) {
    min = std::min(min, other.min);
    max = std::max(max, other.max);
  }
  bool empty() const { return max < min; }
};

// min and max of f over [lo, hi] (hi - lo <= 2 pi): the end points and the
// two stationary points t* = atan2(b, a) (+ pi) where they fall inside.
Extremes sinusoid_extremes(const Sinusoid& f, AngleInterval range);

// The angle t* in [lo, lo + 2 pi) congruent to t.
double wrap_from(double t, double lo);

}  // namespace vcpost::geometry
