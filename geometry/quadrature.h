// Numerical integration for the area-weighted means: a fixed 15-point
// Kronrod rule for smooth integrands (by symmetric pairs of nodes) and a
// capped, globally adaptive Gauss-Kronrod (7, 15) scheme for integrands
// with kinks or steep ends.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

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

}  // namespace detail

// The Kronrod nodes on [0, 1], the centre's 0 last: for the pair functions
// below that tabulate by node.
inline constexpr const std::array<double, 8>& kronrod_rule_nodes = detail::kronrod_nodes;

// The 15-point Kronrod rule over [centre - half, centre + half] from f at
// the centre and the sums pair(i, dx) = f(centre - dx) + f(centre + dx),
// dx = half * kronrod_rule_nodes[i], i = 0 .. 6: for integrands whose two
// values at +-dx share work (a sinusoid's pair needs one sine and cosine
// of dx, not two of the nodes), or that tabulate them by node.
template <class Pair>
double kronrod_rule_by_pairs(double f_centre, const Pair& pair, double half) {
  double sum = f_centre * detail::kronrod_weights[7];
  for (std::size_t i = 0; i < 7; ++i)
    sum += detail::kronrod_weights[i] * pair(i, half * detail::kronrod_nodes[i]);
  return sum * half;
}

// f's values (std::array<double, N> each) at the ascending nodes xs: by
// f.sweep(xs) when f has it (an integrand that walks to its nodes side by
// side, each walk waiting on square roots the others fill), else one by
// one in order.
template <class Function, std::size_t M>
concept Sweeps = requires(const Function& f, const std::array<double, M>& xs) {
  f.sweep(xs);
};

template <std::size_t N, class Function, std::size_t M>
std::array<std::array<double, N>, M> values_at(const Function& f, const std::array<double, M>& xs) {
  if constexpr (Sweeps<Function, M>) {
    return f.sweep(xs);
  } else {
    std::array<std::array<double, N>, M> values;
    for (std::size_t i = 0; i < M; ++i) values[i] = f(xs[i]);
    return values;
  }
}

// Integrals of the N components of f (returning std::array<double, N>) over
// [breaks.front(), breaks.back()] by globally adaptive Gauss-Kronrod (7,
// 15), the panels starting as the stretches between the ascending
// `breaks` (where f has kinks the error estimate could miss): the panel
// with the largest error estimate is halved until every component's
// estimate is within relative * |integral| + absolute (absolute a
// component: components in different units need their own), or
// `max_panels` panels are in use. At most 15 (2 max_panels - 1)
// evaluations of f, whatever f does.
template <std::size_t N, class Function>
std::array<double, N> integrate_capped(const Function& f, const std::vector<double>& breaks,
                                       double relative, const std::array<double, N>& absolute,
                                       int max_panels) {
  struct Panel {
    double lo, hi;
    std::array<double, N> value, error;
  };
  const auto rule = [&](double a, double b) {
    Panel panel{a, b, {}, {}};
    const double centre = 0.5 * (a + b), half = 0.5 * (b - a);
    std::array<double, N> kronrod{}, gauss{};
    const auto take = [&](const std::array<double, N>& values, double kw, double gw) {
      for (std::size_t k = 0; k < N; ++k) {
        kronrod[k] += kw * values[k];
        gauss[k] += gw * values[k];
      }
    };
    // Evaluated in one sweep from a to b (an integrand that starts a root
    // search from its last answer starts next to it), summed as the rule lists them.
    std::array<double, 15> xs;
    for (std::size_t i = 0; i < 7; ++i) {
      xs[i] = centre - half * detail::kronrod_nodes[i];
      xs[14 - i] = centre + half * detail::kronrod_nodes[i];
    }
    xs[7] = centre;
    const std::array<std::array<double, N>, 15> values = values_at<N>(f, xs);
    take(values[7], detail::kronrod_weights[7], detail::gauss_weights[3]);
    for (std::size_t i = 0; i < 7; ++i) {
      const double gw = i % 2 == 1 ? detail::gauss_weights[i / 2] : 0.0;
      take(values[i], detail::kronrod_weights[i], gw);
      take(values[14 - i], detail::kronrod_weights[i], gw);
    }
    for (std::size_t k = 0; k < N; ++k) {
      panel.value[k] = kronrod[k] * half;
      panel.error[k] = std::abs((kronrod[k] - gauss[k]) * half);
    }
    return panel;
  };
  std::vector<Panel> panels;
  for (std::size_t i = 1; i < breaks.size(); ++i) {
    if (breaks[i] > breaks[i - 1]) panels.push_back(rule(breaks[i - 1], breaks[i]));
  }
  if (panels.empty()) return {};
  for (;;) {
    std::array<double, N> value{}, error{};
    for (const Panel& p : panels) {
      for (std::size_t k = 0; k < N; ++k) {
        value[k] += p.value[k];
        error[k] += p.error[k];
      }
    }
    bool done = static_cast<int>(panels.size()) >= max_panels;
    if (!done) {
      done = true;
      for (std::size_t k = 0; k < N; ++k) {
        if (error[k] > relative * std::abs(value[k]) + absolute[k]) done = false;
      }
    }
    if (done) return value;
    // Halve the panel whose error weighs most against its component's bound.
    std::size_t worst = 0;
    double worst_share = -1;
    for (std::size_t i = 0; i < panels.size(); ++i) {
      double share = 0;
      for (std::size_t k = 0; k < N; ++k) {
        share = std::max(share, panels[i].error[k] / (relative * std::abs(value[k]) + absolute[k]));
      }
      if (share > worst_share) {
        worst_share = share;
        worst = i;
      }
    }
    const Panel split = panels[worst];
    const double mid = 0.5 * (split.lo + split.hi);
    panels[worst] = rule(split.lo, mid);
    panels.push_back(rule(mid, split.hi));
  }
}

namespace detail {
// One absolute tolerance for every component.
template <std::size_t N>
std::array<double, N> for_each_component(double absolute) {
  std::array<double, N> each;
  each.fill(absolute);
  return each;
}
}  // namespace detail

// The same with one absolute tolerance for every component.
template <std::size_t N, class Function>
std::array<double, N> integrate_capped(const Function& f, const std::vector<double>& breaks,
                                       double relative, double absolute, int max_panels) {
  return integrate_capped<N>(f, breaks, relative, detail::for_each_component<N>(absolute),
                             max_panels);
}

// The same over [lo, hi] with no breaks inside.
template <std::size_t N, class Function>
std::array<double, N> integrate_capped(const Function& f, double lo, double hi, double relative,
                                       double absolute, int max_panels) {
  return integrate_capped<N>(f, std::vector<double>{lo, hi}, relative, absolute, max_panels);
}

// [lo, hi] cut at those of `breaks` strictly inside it: the ascending
// breaks for integrate_capped and integrate_smoothed_pieces.
inline std::vector<double> breaks_within(std::vector<double> breaks, double lo, double hi) {
  std::erase_if(breaks, [&](double x) { return !(x > lo && x < hi); });
  breaks.push_back(lo);
  breaks.push_back(hi);
  std::sort(breaks.begin(), breaks.end());
  return breaks;
}

namespace detail {
// f on one piece in theta (see integrate_smoothed_pieces), sweeping when f does.
template <std::size_t N, class Function>
struct SmoothedPiece {
  const Function& f;
  double middle, half;

  std::array<double, N> operator()(double theta) const {
    std::array<double, N> value = f(middle - half * std::cos(theta));
    const double jacobian = half * std::sin(theta);
    for (double& v : value) v *= jacobian;
    return value;
  }

  template <std::size_t M>
  std::array<std::array<double, N>, M> sweep(
      const std::array<double, M>& thetas) const requires Sweeps<Function, M> {
    std::array<double, M> xs;
    for (std::size_t i = 0; i < M; ++i) xs[i] = middle - half * std::cos(thetas[i]);
    std::array<std::array<double, N>, M> values = f.sweep(xs);
    for (std::size_t i = 0; i < M; ++i) {
      const double jacobian = half * std::sin(thetas[i]);
      for (double& v : values[i]) v *= jacobian;
    }
    return values;
  }
};
}  // namespace detail

// The integrals over [breaks.front(), breaks.back()] (breaks ascending)
// piece by piece, each piece [a, b] in theta, x = m - h cos(theta), m and
// h its middle and half-width: the nodes gather at the ends, where an
// integrand that grows or vanishes as a square root of the distance to
// the end becomes smooth in theta. For integrands whose kinks are known
// (the breaks) and of that kind: a piece then takes one or two panels
// where bisection took many. At most `max_panels` panels a piece.
// (absolute: a component, as integrate_capped's.)
template <std::size_t N, class Function>
std::array<double, N> integrate_smoothed_pieces(const Function& f,
                                                const std::vector<double>& breaks, double relative,
                                                const std::array<double, N>& absolute,
                                                int max_panels) {
  std::array<double, N> sum{};
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double middle = 0.5 * (breaks[k] + breaks[k + 1]);
    const double half = 0.5 * (breaks[k + 1] - breaks[k]);
    if (!(half > 0)) continue;
    const auto piece = integrate_capped<N>(detail::SmoothedPiece<N, Function>{f, middle, half},
                                           std::vector<double>{0.0, std::numbers::pi}, relative,
                                           absolute, max_panels);
    for (std::size_t i = 0; i < N; ++i) sum[i] += piece[i];
  }
  return sum;
}

// The same with one absolute tolerance for every component.
template <std::size_t N, class Function>
std::array<double, N> integrate_smoothed_pieces(const Function& f,
                                                const std::vector<double>& breaks, double relative,
                                                double absolute, int max_panels) {
  return integrate_smoothed_pieces<N>(f, breaks, relative, detail::for_each_component<N>(absolute),
                                      max_panels);
}

}  // namespace vcpost::geometry
