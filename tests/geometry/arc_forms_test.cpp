#include "geometry/arc_forms.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace vcpost::geometry {
namespace {

constexpr double kPi = std::numbers::pi;

// An arc [lo, hi] and the map from the forms' tau in [0, 1] to its phi:
// phi = mid + 2 atan(w), w = W (2 tau - 1), W = tan((hi - lo) / 4).
struct Arc {
  double lo, hi;
  double mid() const { return 0.5 * (lo + hi); }
  double w(double tau) const { return std::tan(0.25 * (hi - lo)) * (2 * tau - 1); }
  double phi(double tau) const { return mid() + 2 * std::atan(w(tau)); }
  ArcForms forms() const { return {lo, hi, {std::cos(mid()), std::sin(mid())}}; }
};

// cos(phi - alpha) - c, the factor with roots alpha +- acos(c).
struct Factor {
  double alpha, c;
  double at(double phi) const { return std::cos(phi - alpha) - c; }
  ArcForm<2> form(const ArcForms& forms) const {
    return forms.linear(std::cos(alpha), std::sin(alpha), -c);
  }
};

// The taus form_roots reports, as phi.
template <int N>
std::vector<double> roots_phi(const ArcForm<N>& form, const Arc& arc) {
  std::vector<double> out;
  form_roots(form, [&](double tau) { out.push_back(arc.phi(tau)); });
  std::sort(out.begin(), out.end());
  return out;
}

// A form's value at tau is its trigonometric polynomial's at phi(tau)
// times (1 + w^2)^k, k the polynomial's degree (N = 2k): checked on
// products of one, two and three factors over random arcs up to pi long,
// within 1e-13 of the factors' scale; cos_sin_at gives phi's cosine and
// sine within 1e-15.
TEST(ArcForms, FormIsThePolynomialTimesOnePlusWSquaredToItsDegree) {
  std::mt19937 random(3);  // NOLINT(cert-msc32-c,cert-msc51-cpp): the same arcs each run
  std::uniform_real_distribution<double> unit(0, 1);
  double worst_value = 0, worst_angle = 0;
  for (int i = 0; i < 2000; ++i) {
    const double lo = 2 * kPi * (unit(random) - 0.5);
    const Arc arc{lo, lo + kPi * (0.01 + 0.99 * unit(random))};
    const ArcForms forms = arc.forms();
    const Factor f1{2 * kPi * unit(random), 2 * unit(random) - 1},
        f2{2 * kPi * unit(random), 2 * unit(random) - 1},
        f3{2 * kPi * unit(random), 2 * unit(random) - 1};
    const ArcForm<2> one = f1.form(forms);
    const ArcForm<4> two = one * f2.form(forms);
    const ArcForm<6> three = two * f3.form(forms);
    const double tau = unit(random), phi = arc.phi(tau), scale = 1 + arc.w(tau) * arc.w(tau);
    worst_value = std::max({worst_value, std::abs(form_at(one, tau) - f1.at(phi) * scale),
                            std::abs(form_at(two, tau) - f1.at(phi) * f2.at(phi) * scale * scale),
                            std::abs(form_at(three, tau) - f1.at(phi) * f2.at(phi) * f3.at(phi) *
                                                               scale * scale * scale)});
    const auto [c, s] = forms.cos_sin_at(tau);
    worst_angle = std::max({worst_angle, std::abs(c - std::cos(phi)), std::abs(s - std::sin(phi))});
  }
  EXPECT_LE(worst_value, 1e-13);
  EXPECT_LE(worst_angle, 1e-15);
}

// Three factors' six roots on one arc, at least 1e-3 rad apart and from
// the arc's ends: each reported once, within 5e-9 rad of alpha +- acos(c),
// and nothing else. (Newton's last step is below 1e-6 in tau, its end off
// by about its square times |g'' / 2 g'|, up to about 1e3 for roots 1e-3
// apart: 1e-9 in tau, up to 4 times that in phi; 2.6e-9 seen.)
TEST(ArcForms, EverySimpleRootOnTheArcOnce) {
  std::mt19937 random(11);  // NOLINT(cert-msc32-c,cert-msc51-cpp): the same arcs each run
  std::uniform_real_distribution<double> unit(0, 1);
  int arcs = 0;
  double worst = 0;
  while (arcs < 500) {
    const double lo = 2 * kPi * (unit(random) - 0.5);
    const Arc arc{lo, lo + kPi * (0.2 + 0.8 * unit(random))};
    const ArcForms forms = arc.forms();
    std::vector<Factor> factors;
    std::vector<double> truth;
    for (int k = 0; k < 3; ++k) {
      // Roots alpha +- h, both on the arc.
      const double h = 0.25 * (arc.hi - arc.lo) * unit(random);
      const double alpha = arc.lo + h + (arc.hi - arc.lo - 2 * h) * unit(random);
      factors.push_back({alpha, std::cos(h)});
      truth.push_back(alpha - h);
      truth.push_back(alpha + h);
    }
    std::sort(truth.begin(), truth.end());
    bool separated = truth.front() - arc.lo > 1e-3 && arc.hi - truth.back() > 1e-3;
    for (std::size_t k = 1; k < truth.size(); ++k) separated &= truth[k] - truth[k - 1] > 1e-3;
    if (!separated) continue;
    ++arcs;
    const auto found =
        roots_phi(factors[0].form(forms) * factors[1].form(forms) * factors[2].form(forms), arc);
    ASSERT_EQ(found.size(), truth.size()) << "arc " << arc.lo << ".." << arc.hi;
    for (std::size_t k = 0; k < truth.size(); ++k)
      worst = std::max(worst, std::abs(found[k] - truth[k]));
  }
  EXPECT_LE(worst, 5e-9);
}

// A triple root changes the form's sign: it is reported, however flat the
// form is there (within 1e-5 rad: the cube of the distance to it is
// round-off of the form from 1e-5 on).
TEST(ArcForms, RootOfOddMultiplicityIsFound) {
  const Arc arc{0.3, 2.5};
  const ArcForms forms = arc.forms();
  const Factor f{1.2, std::cos(0.4)};  // roots 0.8 and 1.6
  const ArcForm<2> g = f.form(forms);
  const auto found = roots_phi(g * g * g, arc);
  ASSERT_FALSE(found.empty());
  for (const double truth : {0.8, 1.6}) {
    const auto nearest = *std::min_element(found.begin(), found.end(), [&](double a, double b) {
      return std::abs(a - truth) < std::abs(b - truth);
    });
    EXPECT_NEAR(nearest, truth, 1e-5);
  }
  for (const double phi : found)
    EXPECT_TRUE(std::abs(phi - 0.8) <= 1e-5 || std::abs(phi - 1.6) <= 1e-5) << phi;
}

// No root, no report: a form that keeps its sign, also one that comes
// within 1e-2 of zero (cells are halved until their coefficients agree).
TEST(ArcForms, NothingWhereTheFormKeepsItsSign) {
  const Arc arc{-1.0, 1.5};
  const ArcForms forms = arc.forms();
  EXPECT_TRUE(roots_phi(forms.linear(1, 0, 2), arc).empty());  // cos + 2
  const ArcForm<2> g = Factor{0.2, 1}.form(forms);             // cos(phi - 0.2) - 1 <= 0
  EXPECT_TRUE(roots_phi(forms.sum(g * g, 0.01 * (forms.one() * forms.one())), arc).empty());
}

}  // namespace
}  // namespace vcpost::geometry
