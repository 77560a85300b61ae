// Cosine and sine of a small angle by their series, a rotation by it, and
// the arc tangent of a small turn: the Newton, Halley and secant steps of
// the engines and of the tool's contact move an angle by less than half a
// radian, where the series are exact to round-off and cheaper than libm's
// sincos and atan2 (which took a fifth of a bull-nose evaluation, and of a
// bull-nose contact).
#pragma once

#include <cmath>
#include <utility>

namespace vcpost::geometry {

// {cos x, sin x} for |x| <= 0.5, beyond libm's: the series to x^14 and
// x^15, whose next terms are below 1e-18 there. Each tail after the
// first term is summed by Estrin's scheme (pairs of terms, then pairs of
// pairs: a chain of 4 products where Horner's had 8, and no branch on the
// angle's size) and added to it last, within an ulp.
inline std::pair<double, double> cos_sin_small(double x) {
  if (!(std::abs(x) <= 0.5)) return {std::cos(x), std::sin(x)};
  // The series' terms (-1)^k / n!, n = 2k or 2k + 1.
  constexpr auto term = [](int n) {
    double factorial = 1;
    for (int i = 2; i <= n; ++i) factorial *= i;
    return (n / 2 % 2 == 0 ? 1 : -1) / factorial;
  };
  const double y = x * x, y2 = y * y, y4 = y2 * y2;
  // sum over k = 1 .. 7 of term(2k + odd) y^(k - 1)
  const auto tail = [&](int odd) {
    const auto pair = [&](int k) { return term(2 * k + odd) + term(2 * k + 2 + odd) * y; };
    return (pair(1) + pair(3) * y2) + (pair(5) + term(14 + odd) * y2) * y4;
  };
  return {1 + y * tail(0), x + x * y * tail(1)};
}

// atan2(y, x): by atan's series where |y| <= 0.1 x (to the 15th power,
// whose next term is below 6e-18 of it there: the late secant steps' small
// turns), libm's elsewhere.
inline double atan2_small(double y, double x) {
  if (!(x > 0 && std::abs(y) <= 0.1 * x)) return std::atan2(y, x);
  const double t = y / x, u = t * t, u2 = u * u, u4 = u2 * u2;
  // atan t = t + t u (the sum over k = 1 .. 7 of c(k) u^(k - 1)), c(k) =
  // (-1)^k / (2k + 1), summed by Estrin's scheme as above.
  constexpr auto c = [](int k) { return (k % 2 == 0 ? 1.0 : -1.0) / (2 * k + 1); };
  const auto pair = [&](int k) { return c(k) + c(k + 1) * u; };
  return t + t * u * ((pair(1) + pair(3) * u2) + (pair(5) + c(7) * u2) * u4);
}

// The vector (cos_a, sin_a) turned by x (any length: the turn is linear).
inline std::pair<double, double> rotated(double cos_a, double sin_a, double x) {
  const auto [c, s] = cos_sin_small(x);
  return {cos_a * c - sin_a * s, sin_a * c + cos_a * s};
}

}  // namespace vcpost::geometry
