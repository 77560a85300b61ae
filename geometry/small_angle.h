// Cosine and sine of a small angle by their series, and a rotation by it:
// the Newton and regula falsi steps of the engines move an angle by less
// than half a radian, where the series is exact to round-off and cheaper
// than libm's sincos (which took a fifth of a bull-nose evaluation).
#pragma once

#include <array>
#include <cmath>
#include <utility>

namespace vcpost::geometry {

// {cos x, sin x} for |x| <= 0.5 (the terms left out are below 1e-21);
// beyond, libm's.
inline std::pair<double, double> cos_sin_small(double x) {
  if (!(std::abs(x) <= 0.5)) return {std::cos(x), std::sin(x)};
  constexpr int kTerms = 9;
  // 1 / ((2k - 1) 2k) and 1 / (2k (2k + 1)), k = 1 .. kTerms: Horner's
  // scheme in x^2 from the last term.
  constexpr auto ratios = [] {
    std::array<std::array<double, 2>, kTerms> r{};
    for (int k = 1; k <= kTerms; ++k)
      r[static_cast<std::size_t>(k - 1)] = {1.0 / ((2 * k - 1) * (2 * k)),
                                            1.0 / ((2 * k) * (2 * k + 1))};
    return r;
  }();
  const double x2 = x * x;
  double c = 1, s = 1;
  for (std::size_t k = kTerms; k-- > 0;) {
    c = 1 - x2 * ratios[k][0] * c;
    s = 1 - x2 * ratios[k][1] * s;
  }
  return {c, x * s};
}

// The unit vector (cos_a, sin_a) turned by x.
inline std::pair<double, double> rotated(double cos_a, double sin_a, double x) {
  const auto [c, s] = cos_sin_small(x);
  return {cos_a * c - sin_a * s, sin_a * c + cos_a * s};
}

}  // namespace vcpost::geometry
