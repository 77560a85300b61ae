// Numerical integration for the area-weighted means: a fixed 15-point
// Kronrod rule for smooth integrands and an adaptive Gauss-Kronrod (7, 15)
// scheme for integrands with kinks or steep ends.
#pragma once

#include <array>
#include <cmath>

namespace vcpost::geometry {

namespace detail {
// Gauss-Kronrod (7, 15) nodes on [-1, 1] (non-negative half), their Kronrod
// weights, and the Gauss weights of the odd-indexed nodes (QUADPACK's qk15).
inline constexpr std::array<double, 8> kronrod_nodes{
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
inline constexpr std::array<double, 8> kronrod_weights{
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
inline constexpr std::array<double, 4> gauss_weights{
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct KronrodResult {
  double value, error;
};

template <class Function>
KronrodResult kronrod15(const Function& f, double lo, double hi) {
  const double centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  const double f0 = f(centre);
  double kronrod = f0 * kronrod_weights[7];
  double gauss = f0 * gauss_weights[3];
  for (std::size_t i = 0; i < 7; ++i) {
    const double dx = half * kronrod_nodes[i];
    const double pair = f(centre - dx) + f(centre + dx);
    kronrod += kronrod_weights[i] * pair;
    if (i % 2 == 1) gauss += gauss_weights[i / 2] * pair;
  }
  return {kronrod * half, std::abs((kronrod - gauss) * half)};
}

template <class Function>
double adaptive(const Function& f, double lo, double hi, double tolerance, int depth) {
  const KronrodResult whole = kronrod15(f, lo, hi);
  if (whole.error <= tolerance || depth >= 40) return whole.value;
  const double mid = 0.5 * (lo + hi);
  return adaptive(f, lo, mid, 0.5 * tolerance, depth + 1) +
         adaptive(f, mid, hi, 0.5 * tolerance, depth + 1);
}
}  // namespace detail

// Integral of a smooth f over [lo, hi] by the 15-point Kronrod rule.
template <class Function>
double kronrod_rule(const Function& f, double lo, double hi) {
  return detail::kronrod15(f, lo, hi).value;
}

// Integral of f over [lo, hi] to about `tolerance` (absolute), bisecting
// where the Gauss and Kronrod estimates disagree.
template <class Function>
double integrate_adaptive(const Function& f, double lo, double hi, double tolerance) {
  if (!(hi > lo)) return 0;
  return detail::adaptive(f, lo, hi, tolerance, 0);
}

// The same on `panels` equal panels, each adaptive: an integrand that is
// zero on most of [lo, hi] cannot hide from the first estimates.
template <class Function>
double integrate_panels(const Function& f, double lo, double hi, double tolerance, int panels = 16) {
  if (!(hi > lo)) return 0;
  double sum = 0;
  const double width = (hi - lo) / panels;
  for (int i = 0; i < panels; ++i) {
    sum += detail::adaptive(f, lo + i * width, lo + (i + 1) * width, tolerance / panels, 0);
  }
  return sum;
}

}  // namespace vcpost::geometry
