// Cosine and sine of a small angle by their series, and a rotation by it:
// the Newton and regula falsi steps of the engines move an angle by less
// than half a radian, where the series is exact to round-off and cheaper
// than libm's sincos (which took a fifth of a bull-nose evaluation).
#pragma once

#include <array>
#include <cmath>
#include <utility>

namespace vcpost::geometry {

// {cos x, sin x} for |x| <= 0.5, beyond libm's. The series stops before
// the first term below 1e-18 (x^(2k + 2) / (2k + 2)! for k terms): 7 terms
// up to |x| = 0.5, 5 up to 0.16, 3 up to 0.02 (late Newton steps are tiny).
inline std::pair<double, double> cos_sin_small(double x) {
  const double size = std::abs(x);
  if (!(size <= 0.5)) return {std::cos(x), std::sin(x)};
  constexpr std::size_t kTerms = 7;
  // 1 / ((2k - 1) 2k) and 1 / (2k (2k + 1)), k = 1 .. kTerms: Horner's
  // scheme in x^2 from the last term.
  constexpr auto ratios = [] {
    std::array<std::array<double, 2>, kTerms> r{};
    for (std::size_t k = 1; k <= kTerms; ++k)
      r[k - 1] = {1.0 / static_cast<double>((2 * k - 1) * (2 * k)),
                  1.0 / static_cast<double>((2 * k) * (2 * k + 1))};
    return r;
  }();
  const double x2 = x * x;
  double c = 1, s = 1;
  const std::size_t terms = size <= 0.02 ? 3 : size <= 0.16 ? 5 : kTerms;
  for (std::size_t k = terms; k-- > 0;) {
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
