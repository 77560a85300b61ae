// Trigonometric polynomials on an arc, as polynomials in the Bernstein
// basis, and their roots on the arc by Descartes' rule of signs (a count,
// not a scan): the bull-nose and flat mill's shifted silhouette
// (revolved_engagement.cpp) has its stationary points of r and z at the
// roots of such polynomials in its own parameter phi.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "geometry/small_angle.h"

namespace vcpost::geometry {

// The form of a trigonometric polynomial on an arc of phi. On [lo, hi] (hi - lo <= pi), with w =
// tan((phi - mid) / 2), mid = (lo + hi) / 2, cos(phi - mid) = (1 - w^2) / (1 + w^2) and sin(phi -
// mid) = 2 w / (1 + w^2): a trigonometric polynomial of degree k in phi times (1 + w^2)^k is a
// polynomial of degree 2k in w, and phi <-> w is one to one on the arc. With w = W (2 tau - 1), W =
// tan((hi - lo) / 4) <= 1, it is kept in the Bernstein basis of tau in [0, 1], scaled: the
// coefficients a_i of the form sum a_i (1 - tau)^(N - i) tau^i (the
// Bernstein coefficients times C(N, i), the same signs), whose products are
// plain convolutions.
template <int N>
struct ArcForm {
  std::array<double, N + 1> a{};
};

template <int N, int M>
ArcForm<N + M> operator*(const ArcForm<N>& x, const ArcForm<M>& y) {
  ArcForm<N + M> out;
  for (int i = 0; i <= N; ++i)
    for (int j = 0; j <= M; ++j) out.a[i + j] += x.a[i] * y.a[j];
  return out;
}

template <int N>
ArcForm<N> operator*(double k, ArcForm<N> x) {
  for (double& a : x.a) a *= k;
  return x;
}

// The forms of cos(phi), sin(phi) and 1 (degree 2) on one arc.
class ArcForms {
 public:
  // cos_sin_mid: cos and sin of the arc's middle.
  ArcForms(double lo, double hi, std::pair<double, double> cos_sin_mid)
      : cos_mid_(cos_sin_mid.first), sin_mid_(cos_sin_mid.second) {
    const auto [cos_quarter, sin_quarter] = cos_sin_small(0.25 * (hi - lo));
    half_ = sin_quarter / cos_quarter;
    const double w2 = half_ * half_;
    // Bernstein coefficients of 1 - w^2, 2w and 1 + w^2 on [-W, W]: the
    // values at the ends and f(-W) + W f'(-W) in the middle, scaled.
    const std::array<double, 3> cos_rel{1 - w2, 2 * (1 + w2), 1 - w2};
    const std::array<double, 3> sin_rel{-2 * half_, 0, 2 * half_};
    one_.a = {1 + w2, 2 * (1 - w2), 1 + w2};
    for (int i = 0; i <= 2; ++i) {
      cos_.a[i] = cos_mid_ * cos_rel[i] - sin_mid_ * sin_rel[i];
      sin_.a[i] = sin_mid_ * cos_rel[i] + cos_mid_ * sin_rel[i];
    }
  }

  // a cos(phi) + b sin(phi) + k.
  ArcForm<2> linear(double a, double b, double k) const {
    ArcForm<2> out;
    for (int i = 0; i <= 2; ++i) out.a[i] = a * cos_.a[i] + b * sin_.a[i] + k * one_.a[i];
    return out;
  }
  const ArcForm<2>& sin() const { return sin_; }
  const ArcForm<2>& one() const { return one_; }

  // x + y, the lower degree raised by factors 1 + w^2 (trigonometric
  // polynomials' forms differ in degree by even numbers).
  template <int N, int M>
  ArcForm<std::max(N, M)> sum(const ArcForm<N>& x, const ArcForm<M>& y) const {
    if constexpr (N < M) {
      return sum(x * one_, y);
    } else if constexpr (M < N) {
      return sum(x, y * one_);
    } else {
      ArcForm<N> out = x;
      for (int i = 0; i <= N; ++i) out.a[i] += y.a[i];
      return out;
    }
  }

  // cos(phi) and sin(phi) at tau.
  std::pair<double, double> cos_sin_at(double tau) const {
    const double w = half_ * (2 * tau - 1), w2 = w * w;
    const double c = (1 - w2) / (1 + w2), s = 2 * w / (1 + w2);
    return {cos_mid_ * c - sin_mid_ * s, sin_mid_ * c + cos_mid_ * s};
  }

 private:
  double cos_mid_ = 1, sin_mid_ = 0, half_ = 0;
  ArcForm<2> cos_, sin_, one_;
};

// The form's value at tau: Horner's rule in tau with the powers of 1 - tau
// carried along (no division; every term of the basis is positive on [0, 1]).
template <int N>
double form_at(const ArcForm<N>& f, double tau) {
  const double u = 1 - tau;
  double sum = f.a[N], power = 1;
  for (int i = N - 1; i >= 0; --i) {
    power *= u;
    sum = sum * tau + f.a[i] * power;
  }
  return sum;
}

namespace form_roots_detail {

// 1 / C(N, i) and N C(N - 1, i), fixed at compile time (their divisions
// took a tenth of a shifted silhouette's roots).
template <int N>
inline constexpr auto kBinomials = [] {
  std::array<std::array<double, N + 1>, 2> out{};
  double binomial = 1, slope_binomial = N;
  for (int i = 0; i <= N; ++i) {
    out[0][i] = 1 / binomial;
    out[1][i] = slope_binomial;
    binomial = binomial * (N - i) / (i + 1);
    slope_binomial = slope_binomial * (N - 1 - i) / (i + 1);
  }
  return out;
}();

// A piece [lo, hi] of (0, 1) and the form's Bernstein coefficients on it.
template <int N>
struct Cell {
  std::array<double, N + 1> b;
  double lo, hi;
};

template <int N>
int sign_changes(const std::array<double, N + 1>& b) {
  int changes = 0;
  double last = 0;
  for (const double x : b) {
    if (x == 0) continue;
    if (last != 0 && (x < 0) != (last < 0)) ++changes;
    last = x;
  }
  return changes;
}

// The root in [lo, hi], where the form changes sign (its values at the
// ends g_lo, g_hi): Newton's method (with the derivative's form `slope`)
// kept in the shrinking bracket (a step leaving it bisects), until a step
// is below 1e-6: that step's end is the root, within about the step
// squared (the roots are stationary points of r and z, which their error
// moves by its square again; at 1e-9 the polish took a sixth more steps
// for the same extremes within 1e-10 mm).
template <int N>
double polished_root(const ArcForm<N>& f, const ArcForm<N - 1>& slope, double lo, double hi,
                     double g_lo, double g_hi) {
  double x = lo - g_lo * (hi - lo) / (g_hi - g_lo);
  for (int i = 0; i < 100; ++i) {
    const double g = form_at(f, x);
    if (g == 0) return x;
    if ((g < 0) == (g_lo < 0))
      lo = x;
    else
      hi = x;
    const double newton = x - g / form_at(slope, x), step = std::abs(newton - x);
    if (step <= 1e-6) return newton;
    if (hi - lo <= 2e-16) return 0.5 * (lo + hi);
    x = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
  }
  return x;
}

// de Casteljau at the middle of `cell`: the left half's coefficients are
// the triangle's left edge, the right half's its right edge.
template <int N>
void halve(const Cell<N>& cell, Cell<N>& left, Cell<N>& right) {
  // (In place, unrolled: the row stays in registers; vectorised, the
  // averaging stalled on its own stores.)
  std::array<double, N + 1> row = cell.b;
  [&]<int... K>(std::integer_sequence<int, K...>) {
    const auto level = [&]<int k>(std::integral_constant<int, k>) {
      left.b[k] = row[0];
      right.b[N - k] = row[N - k];
      [&]<int... I>(std::integer_sequence<int, I...>) {
        ((row[I] = 0.5 * (row[I] + row[I + 1])), ...);
      }
      (std::make_integer_sequence<int, N - k>{});
    };
    (level(std::integral_constant<int, K>{}), ...);
  }
  (std::make_integer_sequence<int, N + 1>{});
  const double middle = 0.5 * (cell.lo + cell.hi);
  left.lo = cell.lo;
  left.hi = right.lo = middle;
  right.hi = cell.hi;
}

}  // namespace form_roots_detail

// Calls found(tau) at every root of the form in (0, 1), and perhaps at a
// few points that are not roots. Descartes' rule of signs in the Bernstein
// basis: the roots in a cell number the sign changes of its coefficients
// less an even number, so a cell without changes holds none, one with a
// single change exactly one (its first and last coefficients, the values
// at its ends, differ in sign: a bracket, closed by Newton's method kept
// in it); the others are halved (de Casteljau) down to 2^-40, where a cell
// still ambiguous (a double root, a cluster) gives its middle. A root of
// odd multiplicity changes the sign of the values and so of the end
// coefficients around it: round-off in the coefficients cannot hide it.
template <int N, class Found>
void form_roots(const ArcForm<N>& f, const Found& found) {
  using namespace form_roots_detail;
  constexpr int kMaxDepth = 40;
  std::array<Cell<N>, kMaxDepth + 8> stack;
  int size = 0;
  Cell<N>& first = stack[size++];
  first.lo = 0;
  first.hi = 1;
  for (int i = 0; i <= N; ++i) first.b[i] = f.a[i] * kBinomials<N>[0][i];
  // The derivative's form (degree N - 1), for Newton's steps.
  ArcForm<N - 1> slope;
  for (int i = 0; i < N; ++i) slope.a[i] = kBinomials<N>[1][i] * (first.b[i + 1] - first.b[i]);
  while (size > 0) {
    const Cell<N> cell = stack[--size];
    const double b_lo = cell.b[0], b_hi = cell.b[N];
    // A root on a cell's end (shared with the next cell, whose count
    // leaves out the zero coefficient).
    if (b_lo == 0 && cell.lo > 0) found(cell.lo);
    if (b_hi == 0 && cell.hi < 1) found(cell.hi);
    const int changes = sign_changes<N>(cell.b);
    if (changes == 0) continue;
    if (changes == 1 && b_lo != 0 && b_hi != 0) {
      found(polished_root(f, slope, cell.lo, cell.hi, b_lo, b_hi));
      continue;
    }
    if (cell.hi - cell.lo <= std::ldexp(1.0, -kMaxDepth)) {
      found(0.5 * (cell.lo + cell.hi));
      continue;
    }
    Cell<N>& right = stack[size++];
    Cell<N>& left = stack[size++];
    halve(cell, left, right);
  }
}

}  // namespace vcpost::geometry
