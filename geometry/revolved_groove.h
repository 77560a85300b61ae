// The groove of a bull-nose or flat end mill, shared by the files that
// evaluate it along the maths (docs/models.md §2): revolved_extremes.cpp
// (D_max and D_min), revolved_means.cpp (the mean), revolved_cusp.cpp (the
// cusp, Ra and Rz), revolved_engagement.cpp (the cutting points and the
// public entry points of revolved_engagement.h).
//
// The method. F is normal to N, so the volume the tool sweeps along the
// feed line is a prism along F: everything that matters is its projection
// along F onto the (b, c) plane, b = e.P along e = the side of the previous
// pass (+-S0), c = N.P. The tool projects to a convex region Q whose lower
// boundary is the projection of the silhouette (the torus points whose
// normal is normal to F, parametrised by the angle phi of that normal in the
// (e, N) plane) and whose sides are two rays (the shank's silhouette lines).
// Each slice c = const of Q is [bL(c), bR(c)]; the previous pass removes the
// interior of Q shifted by ae along e, so the groove is
//   G = { c_min <= c <= c0, bL(c) <= b <= min(bR(c), bL(c) + ae) },
// and the engaged edge points are the front points (largest a = F.P) of the
// tool above G. r has no local extremum inside G except r = 0 (centre of the
// flat face) and r = R (a plateau that reaches the boundary), so the extremes
// lie on G's boundary curves: the silhouette on the far side, the silhouette
// on the near side below the width-ae level c*, the shifted silhouette above
// c*, and the stock line c = c0. Along each, r and z are stationary only
// where the curve is tangent to a horizontal circle of the tool, and these
// points are found directly: in closed form on the silhouettes, the stock
// line and the shank's ray, as 1-D roots elsewhere (the shifted silhouette's
// as the roots of trigonometric polynomials in its own parameter, counted
// and bracketed by Descartes' rule; the face's in the face's plane); with
//
// The small pieces every part calls in its inner loops (the silhouette,
// the fibre walk's step, the line intervals) are defined in the class
// here, so each part's compiler inlines them as it did when the groove was
// one file.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "geometry/angle_set.h"
#include "geometry/arc_forms.h"
#include "geometry/engagement.h"
#include "geometry/level_engagement.h"
#include "geometry/quadrature.h"
#include "geometry/revolved_engagement.h"
#include "geometry/root_finding.h"
#include "geometry/small_angle.h"

// Internal to the revolved_*.cpp files.
namespace vcpost::geometry::revolved {

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();
// |F_z| below this counts as a feed parallel to the flat face: the face is
// then edge-on (part of the silhouette) and handled in closed form.
constexpr double kEdgeOn = 1e-12;
// The bull-nose's mean goes round the engaged zone's boundary
// (mean_over_boundary) where |F_z| >= kNearlyEdgeOn. Below, the front
// points along the boundary race round the face's rim (their speed grows
// as 1 / |F_z|) and the junctions' polynomials lose digits in round-off
// (their roots are polished: polished_junction), so the boundary goes
// finer (32 panels a piece to a relative 1e-6) down to kOffLevel. Below
// kOffLevel both tools go by level_engagement.h with the feed turned level
// (mean_when_level): the turn moves the previous tool by up to R |F_z| in
// height, which its corner near the face feels as a square root. The
// accuracy and times of each route against the area integral are in
// docs/models.md §2.
constexpr double kNearlyEdgeOn = 1e-3;
constexpr double kOffLevel = 1e-5;

// sqrt(x^2 + y^2): the lengths here are mm-sized, far from over- and
// underflow, and std::hypot's care for them took 40 % of an evaluation.
inline double length_of(double x, double y) { return std::sqrt(x * x + y * y); }

// The cutting situation of one bull-nose or flat tool in the projected
// frame described at the top of this file.
class Groove {
 public:
  Groove(const Tool& tool, const Vector3d& feed, const Vector3d& normal, const Vector3d& side,
         double ap, double ae)
      : radius_(tool.radius()),
        flat_radius_(tool.kind == ToolKind::flat ? tool.radius() : tool.flat_radius()),
        corner_(tool.kind == ToolKind::flat ? 0.0 : tool.corner_radius),
        ae_(ae),
        feed_(feed),
        normal_(normal),
        side_(side) {
    // +z projects to w = (e_z, N_z); the silhouette normal u(phi) has U_z =
    // |w| cos(phi - omega) <= 0 on the lower boundary phi in [phiL, phiR].
    omega_ = std::atan2(normal_.z(), side_.z());
    // cos and sin of omega, for the feet at omega + pi/2 and omega + 3 pi/2
    // and the silhouette's highest-normal point at omega + pi without libm.
    const double w = length_of(side_.z(), normal_.z());
    cos_omega_ = w > 0 ? side_.z() / w : 1;
    sin_omega_ = w > 0 ? normal_.z() / w : 0;
    phi_left_ = omega_ + kPi / 2;
    phi_vertical_ = omega_ + kPi;
    phi_bottom_ = 1.5 * kPi;
    phi_right_ = omega_ + 1.5 * kPi;
    rim_tilt_ = length_of(normal_.x(), normal_.y());
    c_min_ = -flat_radius_ * rim_tilt_ - corner_;
    c0_ = c_min_ + ap;
    foot_left_ = silhouette_at(-sin_omega_, cos_omega_);
    foot_right_ = silhouette_at(sin_omega_, -cos_omega_);
    c_foot_ = {normal_.dot(foot_left_), normal_.dot(foot_right_)};
    edge_on_ = std::abs(feed_.z()) <= kEdgeOn;
    face_in_front_ = !edge_on_ && feed_.z() < 0;
  }

  double radius() const { return radius_; }
  const Vector3d& side() const { return side_; }  // e, toward the previous pass
  // Whether the feed is parallel to the end face (see kEdgeOn).
  bool edge_on() const { return edge_on_; }
  // How the mean is taken (see kNearlyEdgeOn): the bull-nose's round the
  // boundary, finely round it (nearly level); either tool's by the profile
  // (level).
  enum class MeanRoute { boundary, fine_boundary, level };
  MeanRoute mean_route() const {
    const double slope = std::abs(feed_.z());
    return slope >= kNearlyEdgeOn ? MeanRoute::boundary
           : slope >= kOffLevel   ? MeanRoute::fine_boundary
                                  : MeanRoute::level;
  }

  // cos(phi) and sin(phi), turned from the bottom phi = 3 pi / 2: by the
  // series within half a radian of it, where most of the angles asked lie.
  std::pair<double, double> cos_sin(double phi) const {
    const auto [c, s] = cos_sin_small(phi - phi_bottom_);
    return {s, -c};
  }

  // The silhouette point with outward normal U = cos(phi) e + sin(phi) N.
  Vector3d silhouette(double phi) const {
    const auto [cos_phi, sin_phi] = cos_sin(phi);
    return silhouette_at(cos_phi, sin_phi);
  }
  Vector3d silhouette_at(double cos_phi, double sin_phi) const {
    const Vector3d u = cos_phi * side_ + sin_phi * normal_;
    const double length = length_of(u.x(), u.y());
    const double scale = length > 0 ? flat_radius_ / length : 0;
    return {scale * u.x() + corner_ * u.x(), scale * u.y() + corner_ * u.y(), corner_ * u.z()};
  }

  // The silhouette point at phi and its derivative in phi, from cos(phi)
  // and sin(phi) (the edge-on face's phi, where U_xy = 0, has neither: zeros).
  std::pair<Vector3d, Vector3d> silhouette_and_tangent(double cos_phi, double sin_phi) const {
    const Vector3d u = cos_phi * side_ + sin_phi * normal_;
    const Vector3d du = -sin_phi * side_ + cos_phi * normal_;
    const double length = length_of(u.x(), u.y());
    if (!(length > 0)) return {Vector3d::Zero(), Vector3d::Zero()};
    const double inverse = 1 / length;                         // (one division, not four)
    const Vector3d flat(u.x() * inverse, u.y() * inverse, 0);  // the unit U_xy
    return {flat_radius_ * flat + corner_ * u, silhouette_tangent(u, du, inverse)};
  }
  // The same derivative from U, U' and 1 / |U_xy|.
  Vector3d silhouette_tangent(const Vector3d& u, const Vector3d& du, double inverse) const {
    const Vector3d flat(u.x() * inverse, u.y() * inverse, 0);  // the unit U_xy
    const double turn = flat.x() * du.x() + flat.y() * du.y();
    const Vector3d d_flat((du.x() - turn * flat.x()) * inverse,
                          (du.y() - turn * flat.y()) * inverse, 0);
    return flat_radius_ * d_flat + corner_ * du;
  }

  struct BoundaryPoint {
    Vector3d p;      // the tool point on the silhouette (or shank line) at this level
    double b = 0;    // its b = e.P
    double phi = 0;  // the silhouette parameter (the ray foot's on a ray)
    double ray = 0;  // height above the ray foot, mm (0 on the lower boundary)
  };

  // The radius of curvature of Q's lower boundary at its bottom: rc + the
  // ellipse A(disk R0)'s there, R0 det(A)^2 / |A^T N|^3 = R0 F_z^2 / |N_xy|^3
  // (infinite for a level tool: the face is Q's flat bottom).
  double bottom_curvature_radius() const {
    return corner_ + flat_radius_ * feed_.z() * feed_.z() / (rim_tilt_ * rim_tilt_ * rim_tilt_);
  }

  // Q's left or right boundary point at the stock level c0, when first
  // asked (a narrow groove's extremes do without the right one, a level
  // feed's without either).
  const BoundaryPoint& top(bool left) const {
    std::optional<BoundaryPoint>& top = tops_[left ? 0 : 1];
    if (!top) top = boundary(c0_, left);
    return *top;
  }

  // The left (smallest b) or right boundary point of Q at level c.
  BoundaryPoint boundary(double c, bool left) const {
    if (c >= c_foot_[left ? 0 : 1]) return on_shank_ray(c, left);
    // Just beside the bottom normal: an edge-on face's end, not its middle.
    const double phi_bottom = phi_bottom_ + (left ? -1e-10 : 1e-10);
    if (c <= c_min_) {
      const Vector3d p = silhouette(phi_bottom);
      return {p, side_.dot(p), phi_bottom, 0};
    }
    if (corner_ == 0 && !edge_on_) return rim_boundary(c, left);
    return silhouette_boundary(c, left, phi_bottom);
  }

  // Q's side at level c at or above the foot: the shank's silhouette line.
  BoundaryPoint on_shank_ray(double c, bool left) const {
    const Vector3d& foot = left ? foot_left_ : foot_right_;
    const double t = (c - c_foot_[left ? 0 : 1]) / normal_.z();
    const Vector3d p = foot + t * Vector3d::UnitZ();
    return {p, side_.dot(p), left ? phi_left_ : phi_right_, t};
  }

  // The silhouette solve's bracket on phi, with c(phi) - c at its ends (NaN
  // until evaluated there).
  struct Bracket {
    double a, b;
    double g_a = std::numeric_limits<double>::quiet_NaN();
    double g_b = std::numeric_limits<double>::quiet_NaN();

    double middle() const { return 0.5 * (a + b); }
    bool inside(double phi) const { return phi > a && phi < b; }
    // phi, where c(phi) - c = g, becomes the end on its side of the root
    // (`beyond`: c(phi) is past c, the root lies below phi).
    void narrow(double phi, double g, bool beyond) {
      if (beyond) {
        b = phi;
        g_b = g;
      } else {
        a = phi;
        g_a = g;
      }
    }
    // Where the solve goes after a step from phi. A step out of the bracket
    // goes to the end it passes when that end was never evaluated (a root
    // at the foot or the bottom is reached in one step, not by 30
    // bisections), else to the middle (c(phi) jumps across a face nearly
    // parallel to F: the secant of the ends crawled); so does a step not
    // below half the last (across such a jump Halley's steps went to and
    // fro inside the bracket).
    double after_step(double phi, double step, double last_step) const {
      const double next = phi - step;
      if (std::abs(step) > 0.5 * last_step) return middle();
      if (inside(next)) return next;
      const bool low = !(next > a);
      return std::isnan(low ? g_a : g_b) && std::isfinite(next) ? (low ? a : b) : middle();
    }
  };

  // Where the solve on one side starts: at the last root on this side (the
  // searches ask at nearby levels one after another), the first time from
  // the bottom's osculating circle: c - c_min = rho (phi - phi_bottom)^2 / 2
  // (finishing set-ups: 27 steps in the 5.8 solves of an evaluation
  // instead of 30 from the bracket's middle).
  double first_phi(double c, double sign, const Bracket& bracket, double warm) const {
    if (bracket.inside(warm)) return warm;
    if (rim_tilt_ > 1e-6) {
      const double rho = bottom_curvature_radius();
      const double guess = phi_bottom_ + sign * std::sqrt(2 * (c - c_min_) / rho);
      if (bracket.inside(guess)) return guess;
    }
    return bracket.middle();
  }

  // c' and c'' of c = N.(R0 W + rc U), W = U_xy / |U_xy| = (cos a, sin a):
  // W' = a' W+, W'' = a'' W+ - a'^2 W (W+ = W turned a quarter), a' =
  // (U_xy x U_xy') / |U_xy|^2 and, as U'' = -U, a'' = -2 a' (U_xy.U_xy')
  // / |U_xy|^2; N.U = sin(phi), N.U' = cos(phi). From U, U' and 1 / |U_xy|.
  struct LevelDerivatives {
    double turn, turn_rate;  // a', a''
    double slope, bend;      // c', c''
  };
  LevelDerivatives level_derivatives(const Vector3d& u, const Vector3d& du, double inverse,
                                     double cos_phi, double sin_phi) const {
    const double inverse2 = inverse * inverse;
    const double turn = (u.x() * du.y() - u.y() * du.x()) * inverse2;
    const double turn_rate = -2 * turn * (u.x() * du.x() + u.y() * du.y()) * inverse2;
    const double n_along = (normal_.x() * u.x() + normal_.y() * u.y()) * inverse;
    const double n_across = (normal_.y() * u.x() - normal_.x() * u.y()) * inverse;
    return {turn, turn_rate, flat_radius_ * turn * n_across + corner_ * cos_phi,
            flat_radius_ * (turn_rate * n_across - turn * turn * n_along) - corner_ * sin_phi};
  }

  // The silhouette point `step` back from p (at U, U'), by Taylor's
  // polynomial of degree 2 (p'' = R0 W'' - rc U, W'' = a'' W+ - a'^2 W).
  Vector3d stepped_back(const Vector3d& p, const Vector3d& u, const Vector3d& du, double inverse,
                        const LevelDerivatives& d, double step) const {
    const double wx = u.x() * inverse, wy = u.y() * inverse;
    const Vector3d bend_p(
        flat_radius_ * (-d.turn_rate * wy - d.turn * d.turn * wx) - corner_ * u.x(),
        flat_radius_ * (d.turn_rate * wx - d.turn * d.turn * wy) - corner_ * u.y(),
        -corner_ * u.z());
    return p - step * silhouette_tangent(u, du, inverse) + 0.5 * step * step * bend_p;
  }

  // Q's lower boundary at level c between the foot and the bottom (at
  // phi_bottom): the root of c(phi) = c, by Newton's method inside the
  // bracket, bisecting whenever a step leaves it (c is monotone on each
  // side of the bottom).
  BoundaryPoint silhouette_boundary(double c, bool left, double phi_bottom) const {
    const double phi_end = left ? phi_left_ : phi_right_;
    Bracket bracket{left ? phi_end : phi_bottom, left ? phi_bottom : phi_end};
    const double sign = left ? -1.0 : 1.0;  // c decreases along the left branch
    double& warm = warm_start_[left ? 0 : 1];
    double phi = first_phi(c, sign, bracket, warm);
    // cos and sin of phi, by rotation from those of the last phi.
    auto [cos_phi, sin_phi] = cos_sin(phi);
    double phi_at = phi, last_step = kInf;
    for (int i = 0; i < 200 && bracket.b - bracket.a > 1e-14; ++i) {
      std::tie(cos_phi, sin_phi) = rotated(cos_phi, sin_phi, phi - phi_at);
      phi_at = phi;
      const Vector3d u = cos_phi * side_ + sin_phi * normal_;
      const Vector3d du = -sin_phi * side_ + cos_phi * normal_;
      const double length = length_of(u.x(), u.y());
      if (!(length > 1e-300)) {
        phi = bracket.middle();
        continue;
      }
      const double inverse = 1 / length;  // (one division, not six)
      const Vector3d p(flat_radius_ * inverse * u.x() + corner_ * u.x(),
                       flat_radius_ * inverse * u.y() + corner_ * u.y(), corner_ * u.z());
      const double g = normal_.dot(p) - c;
      // On the root: the point just evaluated is the answer.
      const auto root_here = [&] {
        warm = phi;
        return BoundaryPoint{p, side_.dot(p), phi, 0};
      };
      if (g == 0) return root_here();
      bracket.narrow(phi, g, (g > 0) == (sign > 0));
      const LevelDerivatives d = level_derivatives(u, du, inverse, cos_phi, sin_phi);
      // Halley's step (three correct digits for one: from the osculating
      // circle's guess two steps, where Newton's took four), Newton's where
      // Halley's denominator does not keep the step's sign. Converged when
      // the step is round-off and so is the miss in c; where c(phi) is that
      // steep (near an edge-on face a step of 1e-14 still missed by 1e-5 mm)
      // the bracket is bisected onto the steep stretch, whose ends are
      // interpolated (across_jump).
      const double halley = d.slope * d.slope - 0.5 * g * d.bend;
      const double step = d.slope == 0 ? kInf : halley > 0 ? g * d.slope / halley : g / d.slope;
      if (std::abs(step) < 1e-14) {
        if (std::abs(g) < 1e-12 * radius_) return root_here();
        phi = bracket.middle();
        continue;
      }
      // A Halley step below 1e-4 L (L = |U_xy|), over which c' changes by
      // less than 1e-4 of itself, leaves an error of about its cube, and
      // the point at its end by Taylor's polynomial of degree 2 is off by
      // step^3 |p'''| / 6 (|p'''| ~ R / L^3): within 2e-13 R, the solve ends
      // there. Saves the confirming evaluation: 2.95 iterations a solve
      // where the tangent's end below 1e-8 L took 3.3. (Beside an edge-on
      // face c' changes by twice itself over a step of 1e-10: there the
      // test on c'' keeps on solving.)
      if (halley > 0 && std::abs(step) < 1e-4 * length &&
          std::abs(step * d.bend) < 1e-4 * std::abs(d.slope) && bracket.inside(phi - step)) {
        const Vector3d root = stepped_back(p, u, du, inverse, d, step);
        warm = phi - step;
        return {root, side_.dot(root), warm, 0};
      }
      phi = bracket.after_step(phi, step, last_step);
      last_step = std::abs(step);
    }
    warm = bracket.middle();
    return across_jump(c, bracket.a, bracket.b);
  }

  // The point at level c where the solve's bracket [a, b] closed without a
  // root; one still open has closed onto a jump of c(phi).
  BoundaryPoint across_jump(double c, double a, double b) const {
    if (a == b) {
      const Vector3d p = silhouette(a);
      return {p, side_.dot(p), a, 0};
    }
    const Vector3d pa = silhouette(a), pb = silhouette(b);
    Vector3d p = pa;
    if ((pa - pb).norm() > 1e-9 * radius_) {
      // A straight edge of Q (the face seen edge-on): interpolate along it.
      const double ca = normal_.dot(pa), cb = normal_.dot(pb);
      p = pa + (c - ca) / (cb - ca) * (pb - pa);
    }
    return {p, side_.dot(p), 0.5 * (a + b), 0};
  }

  // The flat mill's lower boundary of Q is the end face's rim, an ellipse
  // seen along F: at level c its two points R (cos t, sin t, 0) with
  // N.P = R |N_xy| cos(t - tau) = c, the left one with the smaller b (the
  // branch from the left foot down to the bottom lies on the ellipse's left
  // half, which holds its point with tangent parallel to the shank's rays).
  // The point's silhouette parameter: the support point of the ellipse
  // A(disk), A = rows e_xy and N_xy, in the direction v is R A^T v / |A^T v|,
  // so v is along A^-T P_xy (det A = +-F_z, not zero off edge-on).
  BoundaryPoint rim_boundary(double c, bool left) const {
    const auto [p1, p2] = circle_at_level(radius_, 0, c);
    const double b1 = side_.dot(p1), b2 = side_.dot(p2);
    const bool first = left ? b1 <= b2 : b1 > b2;
    const Vector3d& p = first ? p1 : p2;
    return {p, first ? b1 : b2, rim_phi(p.x(), p.y()), 0};
  }

  // The two points of the horizontal circle of radius rho at height z on
  // the level N.P = c, where rho |N_xy| cos(t - tau) = c - N_z z: at tau -+
  // half, by the angle sums (no trigonometry: cos(tau), sin(tau) =
  // N_xy / |N_xy|). A level the circle misses gives its nearest point twice.
  std::array<Vector3d, 2> circle_at_level(double rho, double z, double c) const {
    const double cos_half = std::clamp((c - normal_.z() * z) / (rho * rim_tilt_), -1.0, 1.0);
    const double sin_half = std::sqrt(1 - cos_half * cos_half);
    const double cos_tau = normal_.x() / rim_tilt_, sin_tau = normal_.y() / rim_tilt_;
    const double along = rho * cos_half, across = rho * sin_half;
    return {Vector3d(along * cos_tau + across * sin_tau, along * sin_tau - across * cos_tau, z),
            Vector3d(along * cos_tau - across * sin_tau, along * sin_tau + across * cos_tau, z)};
  }

  // The silhouette parameter of the flat mill's rim point in the direction
  // (x, y): U_xy = cos(phi) e_xy + sin(phi) N_xy along it, in [phiL, phiL + 2 pi).
  double rim_phi(double x, double y) const {
    const double det = side_.x() * normal_.y() - side_.y() * normal_.x();
    double phi = std::atan2((side_.x() * y - side_.y() * x) / det,
                            (normal_.y() * x - normal_.x() * y) / det);
    while (phi < phi_left_) phi += 2 * kPi;
    while (phi >= phi_left_ + 2 * kPi) phi -= 2 * kPi;
    return phi;
  }

  // The bull-nose's distance from x to its core K = {r <= R0, z >= 0} less
  // rc (the tool is K grown by rc: <= 0 in the tool), its slope along d
  // (n.d on the tool's surface).
  struct Excess {
    double value, slope;
  };
  Excess core_excess_along(const Vector3d& x, const Vector3d& d) const {
    const double rho = length_of(x.x(), x.y());
    const double radial = std::max(0.0, rho - flat_radius_), below = std::min(0.0, x.z());
    const double distance = length_of(radial, below);
    if (!(distance > 0)) return {-corner_, 0};
    const double d_radial = radial > 0 ? (x.x() * d.x() + x.y() * d.y()) / rho : 0;
    return {distance - corner_, (radial * d_radial + below * d.z()) / distance};
  }

  // Where the line x0 + t F crosses the vertical cylinder r = rho: t^2
  // |F_xy|^2 + 2 beta t + gamma = 0, the crossings (-beta -+ sqrt(disc)) /
  // |F_xy|^2.
  struct CylinderCrossing {
    double fxy2, beta, disc;
  };
  CylinderCrossing cylinder_crossing(double x0, double y0, double rho) const {
    const double fxy2 = feed_.x() * feed_.x() + feed_.y() * feed_.y();
    const double beta = x0 * feed_.x() + y0 * feed_.y();
    const double gamma = x0 * x0 + y0 * y0 - rho * rho;
    return {fxy2, beta, beta * beta - fxy2 * gamma};
  }

  // The interval of t over which x0 + t F lies in the tool; empty when the
  // line misses it (a line touching it within 1e-9 R counts as touching;
  // the bull-nose's corner only within round-off, see CoreWalk).
  // With only_front the back end is not walked to (the pair holds the
  // front twice).
  std::optional<std::pair<double, double>> line_interval(const Vector3d& x0,
                                                         bool only_front = false) const {
    return line_intervals(std::array<Vector3d, 1>{x0}, only_front)[0];
  }

  // The same for several lines, their walks side by side: one walk waits
  // on its square roots and divisions, the others fill the wait.
  template <std::size_t M>
  std::array<std::optional<std::pair<double, double>>, M> line_intervals(
      const std::array<Vector3d, M>& x0s, bool only_front) const {
    std::array<std::optional<std::pair<double, double>>, M> out;
    std::array<CoreWalk, 2 * M> walks;
    std::array<bool, M> walked{};
    for (std::size_t i = 0; i < M; ++i) {
      const Vector3d& x0 = x0s[i];
      auto [fxy2, beta, disc] = cylinder_crossing(x0.x(), x0.y(), radius_);
      if (!(fxy2 > 1e-24)) continue;
      if (disc < 0) {
        if (disc < -1e-9 * radius_ * radius_ * fxy2) continue;
        disc = 0;
      }
      const double t1 = (-beta - std::sqrt(disc)) / fxy2, t2 = (-beta + std::sqrt(disc)) / fxy2;
      if (corner_ == 0) {
        // Flat: the solid cylinder above the end face z = 0.
        double lo = t1, hi = t2;
        if (feed_.z() > 0) lo = std::max(lo, -x0.z() / feed_.z());
        if (feed_.z() < 0) hi = std::min(hi, -x0.z() / feed_.z());
        if (feed_.z() == 0 && x0.z() < -1e-12 * radius_) continue;
        if (lo > hi) {
          if (lo - hi > 1e-9 * radius_) continue;
          lo = hi = 0.5 * (lo + hi);
        }
        out[i] = std::pair{lo, hi};
        continue;
      }
      // The walks start where the line enters the slab z >= -rc too, if
      // that is nearer (still outside the core's rc: a step or two fewer).
      double front_start = t2, back_start = t1;
      if (feed_.z() != 0) {
        const double t_face = (-corner_ - x0.z()) / feed_.z();
        (feed_.z() < 0 ? front_start : back_start) = std::clamp(t_face, t1, t2);
      }
      walks[2 * i] = {x0, front_start, -1};
      walks[2 * i + 1] = {x0, back_start, +1};
      walks[2 * i + 1].done = only_front;
      walked[i] = true;
    }
    walk_side_by_side(walks);
    for (std::size_t i = 0; i < M; ++i) {
      if (!walked[i]) continue;
      const std::optional<double> hi = walks[2 * i].at, lo = walks[2 * i + 1].at;
      if (!hi) continue;
      out[i] = only_front || !lo || *lo > *hi ? std::pair{*hi, *hi} : std::pair{*lo, *hi};
    }
    return out;
  }

  // The front point of the fibre x0 + t F (line_interval's walk); empty
  // where it misses.
  std::optional<Vector3d> front_point(const Vector3d& x0) const {
    const auto interval = line_interval(x0, true);
    if (!interval) return std::nullopt;
    return x0 + interval->second * feed_;
  }

  // The front and back tool points (the front twice with only_front) of
  // the fibre at b = top.b + db beside Q's boundary point `top` on the stock
  // level (db > 0 from the left top, < 0 from the right one); empty where it
  // misses. The bull-nose's are walked from near the crossings: near the
  // top the rim (the tool cut by the stock plane) follows its osculating
  // parabola, a - a_top = +-sqrt(2 |db| / k), its curvature k = k_n / |U.e|
  // (Meusnier: the rim's tangent at the top is F, its normal in the plane
  // is along e), k_n the tool's normal curvature along F, F_mer^2 / rc +
  // F_par^2 L / r on the corner (F's meridian and parallel parts, L =
  // |U_xy|, r the top's radius), F_par^2 / R on the shank. From the
  // parabola's crossings, stepping out first where they are inside (see
  // CoreWalk), the walks took 3.9 evaluations on the finishing set-ups,
  // from 1.5 times as far, always outside, 4.7, and from the cylinder r = R
  // 6.5. A start the walk cannot go on from (on the far side of the
  // chord's middle, or in the core) falls back to line_interval's starts.
  std::optional<std::pair<Vector3d, Vector3d>> fibre_beside(const BoundaryPoint& top, double db,
                                                            bool only_front) const {
    const double a_top = feed_.dot(top.p);
    const Vector3d x0 = top.p - a_top * feed_ + db * side_;
    const auto ends = [&](double front, double back) {
      return std::optional{std::pair{x0 + front * feed_, x0 + back * feed_}};
    };
    if (corner_ > 0) {
      const auto [cos_phi, sin_phi] = cos_sin(top.phi);
      const Vector3d u = cos_phi * side_ + sin_phi * normal_;
      const double r = length_of(top.p.x(), top.p.y());
      const double f_par = (top.p.x() * feed_.y() - top.p.y() * feed_.x()) / r;
      const double meridian = top.ray > 0 ? 0.0 : (1 - f_par * f_par) / corner_;
      const double curvature =
          (meridian + f_par * f_par * length_of(u.x(), u.y()) / r) / std::abs(cos_phi);
      const double reach = std::sqrt(2 * std::abs(db) / curvature) + 1e-6 * radius_;
      if (std::isfinite(reach)) {
        std::array<CoreWalk, 2> walks{CoreWalk(x0, a_top + reach, -1),
                                      CoreWalk(x0, a_top - reach, +1)};
        walks[1].done = only_front;
        walks[0].may_start_inside = walks[1].may_start_inside = true;
        walk_side_by_side(walks);
        const auto walked = [](const CoreWalk& walk) { return walk.at && walk.steps > 0; };
        if (walked(walks[0]) && (only_front || walked(walks[1])))
          return ends(*walks[0].at, only_front ? *walks[0].at : *walks[1].at);
      }
    }
    const auto interval = line_interval(x0, only_front);
    if (!interval) return std::nullopt;
    return ends(interval->second, interval->first);
  }

  // fibre_beside(left top, ae): the shifted silhouette's top and the
  // fibre of one pair of cutting points, walked once for both.
  const std::optional<std::pair<Vector3d, Vector3d>>& inner_top_fibre(bool only_front) const {
    if (!inner_top_fibre_ || (!only_front && inner_top_front_only_)) {
      inner_top_fibre_ = fibre_beside(top(true), ae_, only_front);
      inner_top_front_only_ = only_front;
    }
    return *inner_top_fibre_;
  }

  // Bull-nose: a Newton walk along a fibre onto the tool, from outside at t
  // in `direction` (-1 from the front, +1 from the back), to `at` (empty:
  // the fibre misses). The distance to the core K = {r <= R0, z >= 0} is
  // convex along the line, so Newton's method started outside on either
  // side walks monotonically onto the crossing (the tangent of a convex
  // function stays below it), or, when the line misses, turns round (slope
  // <= 0) before reaching it.
  struct CoreWalk {
    Vector3d x0 = Vector3d::Zero();
    double t = 0, direction = 0;
    bool done = true;
    std::optional<double> at;
    int steps = 0;
    const Vector3d* line = nullptr;  // the line's direction: F when null
    // A start inside the tool (not the core) on the walk's side first steps
    // out: the tangent of the convex excess lands at or outside the crossing.
    bool may_start_inside = false;
    CoreWalk() = default;
    CoreWalk(const Vector3d& x0_, double t_, double direction_, const Vector3d* line_ = nullptr)
        : x0(x0_), t(t_), direction(direction_), done(false), line(line_) {}
  };
  // One excess evaluation and Newton's step from it.
  void step(CoreWalk& walk) const {
    // Only round-off counts as touching the corner, and the walk stops only
    // that near it: a fibre nearly parallel to the corner stays close to it
    // over a long stretch, so a line that misses it by 1e-9 R gave a point
    // far along that stretch (D_max / D_min off by up to 3.4e-4 mm against
    // RevolvedReference), and stopping 1e-13 R outside still left 1.2e-6
    // mm; at 1e-14 R the largest error seen is 5e-7 mm (1e-15 R is within
    // round-off of the excess and does worse).
    const double touch = 1e-14 * radius_;
    const Vector3d& line = walk.line ? *walk.line : feed_;
    const Excess e = core_excess_along(walk.x0 + walk.t * line, line);
    walk.done = true;
    // From a start inside, on the walk's side of the chord's middle the
    // slope is negative too, and the step (newton < 0) goes back out.
    const bool stepping_out = walk.may_start_inside && walk.steps == 0 && e.value < -touch;
    if (e.value <= touch && !stepping_out) {
      walk.at = walk.t;
      return;
    }
    const double slope = walk.direction * e.slope;  // must be negative walking inwards
    if (!(slope < 0) || walk.steps == 100) return;
    const double newton = -e.value / slope;
    walk.t += walk.direction * newton;
    ++walk.steps;
    if (stepping_out) {
      walk.done = false;
      return;
    }
    // The step's end is outside (the convex excess lies above its tangent)
    // by at most newton^2 / (2 rc): the distance to the convex core curves
    // by at most 1 / distance, and the lines are unit. Within touch that is
    // the crossing, as the next evaluation would find: a fifth of the
    // walks' evaluations saved, the result unchanged.
    if (newton * newton <= touch * corner_) {
      walk.at = walk.t;
      return;
    }
    walk.done = newton < 1e-15 * radius_;
  }

  // Steps the walks in turn until all are done: one walk waits on its
  // square roots and divisions, the others fill the wait.
  template <std::size_t K>
  void walk_side_by_side(std::array<CoreWalk, K>& walks) const {
    for (bool walking = true; walking;) {
      walking = false;
      for (CoreWalk& walk : walks) {
        if (walk.done) continue;
        step(walk);
        walking = walking || !walk.done;
      }
    }
  }

  RadiusExtremes extremes() const;
  double mean_diameter() const;
  // By level_engagement.h (see level_cut): the mean where |F_z| <
  // kOffLevel, the extremes where the feed is level.
  LevelCut level_cut() const;
  double mean_when_level() const;
  RadiusExtremes level_extremes() const;
  // The cusp the previous pass leaves beside this one (docs/models.md section
  // 3), on a surface whose section across the feed is a circle of signed
  // curvature k (convex > 0; 0 the tangent plane) touched at the level
  // c_min at b = contact_b (empty: the bottom's middle; what matters where
  // the bottom is a face seen edge-on): see revolved_cusp.
  RevolvedCusp cusp(const Tool& tool, double curvature, std::optional<double> contact_b) const;
  // relative: the quadrature's tolerance; panels: its cap a piece.
  double mean_over_boundary(double relative, int panels) const;
  // Its sums round the boundary, piece by piece.
  class BoundaryMean;
  // The phi in [lo, hi] where the shifted fibre leaves the corner (see there).
  std::vector<double> shifted_junctions(double lo, double hi) const;
  // The horizontal circles where the tool's pieces meet: the face's rim
  // and the shank's foot. Where a front point crosses one, the means'
  // integrands have kinks.
  struct Junction {
    double rho, z;
    bool face;
  };
  std::array<Junction, 2> junctions() const {
    return {{{flat_radius_, -corner_, true}, {radius_, 0.0, false}}};
  }
  // Whether the point (x, y) of junction j's circle is a front point: on
  // the rim when the face leads, on the foot's leading half.
  bool front_on(const Junction& j, double x, double y) const {
    return j.face ? face_in_front_ : x * feed_.x() + y * feed_.y() > 0;
  }
  // Where the shifted fibre of S(phi) + ae e crosses junction j's plane,
  // how far it misses the circle there (radially) and that miss's slope in phi.
  struct ShiftedCrossing {
    Vector3d x;
    double miss, slope;
  };
  ShiftedCrossing shifted_crossing(double phi, const Junction& j) const;
  // A root of shifted_junctions' form, refined on the miss.
  double polished_junction(double phi, const Junction& j) const;
  // The b where the level c crosses a junction among the front points.
  void add_junction_cuts(double c, std::vector<double>& cuts) const {
    for (const Junction& j : junctions()) {
      if (!(std::abs(c - normal_.z() * j.z) < j.rho * rim_tilt_)) continue;
      for (const Vector3d& p : circle_at_level(j.rho, j.z, c)) {
        if (front_on(j, p.x(), p.y())) cuts.push_back(side_.dot(p));
      }
    }
  }
  // Which tool points the previous pass removed (the flat mill's mean).
  class Removal;

 private:
  // c* = the level below which the groove spans the whole slice (width of Q
  // at most ae): c0 when the whole groove does, c_min when no level does;
  // with Q's boundary points there.
  struct WidthLevel {
    double c;
    BoundaryPoint left, right;
  };
  // Ra of the profile on the tangent plane whose cusp is the width level
  // `cusp` (where Q is ae wide, above its bottom).
  double plane_roughness(const WidthLevel& cusp) const;
  WidthLevel width_level() const {
    if (const auto level = narrow_width_level()) return *level;
    const BoundaryPoint &left_top = top(true), &right_top = top(false);
    if (right_top.b - left_top.b <= ae_) return {c0_, left_top, right_top};
    const BoundaryPoint left_bottom = boundary(c_min_, true),
                        right_bottom = boundary(c_min_, false);
    if (right_bottom.b - left_bottom.b >= ae_) return {c_min_, left_bottom, right_bottom};
    if (const auto level = flat_width_level()) return *level;
    for (const bool left : {true, false}) {
      const BoundaryPoint& top = left ? left_top : right_top;
      const BoundaryPoint& other = left ? right_top : left_top;
      if (top.ray > 0) {
        if (const auto level = width_level_beside_ray(left, other.phi)) return *level;
      }
    }
    if (const auto level = width_level_on_silhouette(left_top.phi, right_top.phi)) return *level;
    const double c = width_level_by_slices(right_bottom.b - left_bottom.b - ae_);
    return {c, boundary(c, true), boundary(c, false)};
  }

  // A narrow groove has c* just above the bottom: Newton's method starts
  // there, from the bottom's osculating circle of radius rho (the width ae
  // a chord of it), rather than from the levels at c0 (the post's passes
  // ae = 0.02-0.1 mm apart took 3 slices of 2 boundary solves). Tried
  // first, on the bull-nose: the width of Q's slices never decreases up
  // its shank, so a level in (c_min, c0) of width ae is c*, with both its
  // points on the silhouette (the solve fails where one is on a ray), and
  // the right boundary at c0 is not needed (a tenth of an evaluation).
  std::optional<WidthLevel> narrow_width_level() const {
    if (!(corner_ > 0)) return std::nullopt;
    const double rho = bottom_curvature_radius();
    if (!(ae_ < rho)) return std::nullopt;
    const double half_angle = std::asin(0.5 * ae_ / rho);
    if (!(half_angle > 0 && phi_bottom_ - half_angle > top(true).phi &&
          phi_bottom_ + half_angle < phi_right_))
      return std::nullopt;
    return width_level_on_silhouette(phi_bottom_ - half_angle, phi_bottom_ + half_angle);
  }

  // The flat mill's Q is bounded below by the rim's ellipse A disk(R0)
  // (centre c = 0, half-height h = R0 |N_xy|), whose chords along e are
  // 2 R0 |F_z| / |N_xy| sqrt(1 - (c / h)^2) wide (the chord through the
  // centre and the extreme levels' points are conjugate: area pi R0^2
  // |det A|, det A = +-F_z): c* in closed form, when it lies below both
  // feet (else a ray bounds a side).
  std::optional<WidthLevel> flat_width_level() const {
    if (corner_ != 0 || edge_on_ || !(rim_tilt_ > 0)) return std::nullopt;
    const double h = flat_radius_ * rim_tilt_;
    const double chord = 2 * flat_radius_ * std::abs(feed_.z()) / rim_tilt_;
    if (!(ae_ < chord)) return std::nullopt;
    const double ratio = ae_ / chord;
    const double c = -h * std::sqrt(1 - ratio * ratio);
    if (!(c > c_min_ && c < c0_ && c <= c_foot_[0] && c <= c_foot_[1])) return std::nullopt;
    return WidthLevel{c, rim_boundary(c, true), rim_boundary(c, false)};
  }

  // The left (or right) point on its shank's ray, the other on the
  // silhouette at phi: the ray's b is linear in c, so the width at the
  // silhouette point's level is a function of phi alone, for Newton's
  // method (a fifth of the flat mill's finishing set-ups have c* there; the
  // slices took two boundary solves a step). Empty when a step leaves the
  // branch or c* is below the ray's foot.
  std::optional<WidthLevel> width_level_beside_ray(bool left_on_ray, double phi) const {
    const Vector3d& foot = left_on_ray ? foot_left_ : foot_right_;
    const double c_foot = c_foot_[left_on_ray ? 0 : 1], b_foot = side_.dot(foot);
    const double ray_slope = side_.z() / normal_.z();  // db/dc along the ray
    const double sign = left_on_ray ? 1.0 : -1.0;      // width = sign (b - b_ray)
    const double lo = left_on_ray ? phi_bottom_ : phi_left_;
    const double hi = left_on_ray ? phi_right_ : phi_bottom_;
    const double tolerance = 1e-13 * radius_;
    if (!(phi > lo && phi < hi)) phi = left_on_ray ? phi_right_ - 1e-9 : phi_left_ + 1e-9;
    auto [cos_phi, sin_phi] = cos_sin(phi);  // turned with phi
    for (int i = 0; i < 40; ++i) {
      const auto [p, t] = silhouette_and_tangent(cos_phi, sin_phi);
      const double c = normal_.dot(p), b = side_.dot(p);
      const double b_ray = b_foot + (c - c_foot) * ray_slope;
      const double gap = sign * (b - b_ray) - ae_;
      if (std::abs(gap) <= tolerance) {
        if (!(c >= c_foot && c > c_min_ && c < c0_)) return std::nullopt;
        const BoundaryPoint ray_point = boundary(c, left_on_ray);  // closed form on the ray
        const BoundaryPoint silhouette_point{p, b, phi, 0};
        return left_on_ray ? WidthLevel{c, ray_point, silhouette_point}
                           : WidthLevel{c, silhouette_point, ray_point};
      }
      const double slope = sign * (side_.dot(t) - ray_slope * normal_.dot(t));
      if (!(std::abs(slope) > 0)) return std::nullopt;
      const double step = std::clamp(gap / slope, -0.3, 0.3);
      phi -= step;
      std::tie(cos_phi, sin_phi) = rotated(cos_phi, sin_phi, -step);
      if (!(phi > lo && phi < hi)) return std::nullopt;
    }
    return std::nullopt;
  }

  // Both points on the silhouette: two equations, c(phiL) = c(phiR) and
  // b(phiR) - b(phiL) = ae, for Newton's method in (phiL, phiR) with the
  // silhouette's tangent in closed form, two sines and cosines a step. A
  // step that would leave the branches is shortened to half the way to
  // their ends (from the levels at c0, the first steps overshot the bottom
  // on a fifth of the bull-nose finishing set-ups and a third of the flat
  // ones); empty when that keeps happening (c* on a shank's ray, or an
  // edge-on face's jump) or it does not settle, and the slices decide.
  std::optional<WidthLevel> width_level_on_silhouette(double phi_l, double phi_r) const {
    const double tolerance = 1e-13 * radius_;
    int shortened = 0;
    // cos and sin of the two angles, turned with them (steps <= 0.3 rad).
    auto [cos_l, sin_l] = cos_sin(phi_l);
    auto [cos_r, sin_r] = cos_sin(phi_r);
    // The level through the points q_l and q_r at phi_l and phi_r, empty
    // outside (c_min, c0).
    const auto level_at = [&](const Vector3d& q_l,
                              const Vector3d& q_r) -> std::optional<WidthLevel> {
      const double c = 0.5 * (normal_.dot(q_l) + normal_.dot(q_r));
      if (!(c > c_min_ && c < c0_)) return std::nullopt;
      return WidthLevel{c, {q_l, side_.dot(q_l), phi_l, 0}, {q_r, side_.dot(q_r), phi_r, 0}};
    };
    const auto within_branches = [&] {
      return phi_l > phi_left_ && phi_l < phi_bottom_ && phi_r > phi_bottom_ && phi_r < phi_right_;
    };
    for (int i = 0; i < 40; ++i) {
      const auto [p_l, t_l] = silhouette_and_tangent(cos_l, sin_l);
      const auto [p_r, t_r] = silhouette_and_tangent(cos_r, sin_r);
      const double b_l = side_.dot(p_l), b_r = side_.dot(p_r);
      const double level_gap = normal_.dot(p_r) - normal_.dot(p_l), width_gap = b_r - b_l - ae_;
      if (std::abs(level_gap) <= tolerance && std::abs(width_gap) <= tolerance)
        return level_at(p_l, p_r);
      const double j00 = -normal_.dot(t_l), j01 = normal_.dot(t_r);
      const double j10 = -side_.dot(t_l), j11 = side_.dot(t_r);
      const double det = j00 * j11 - j01 * j10;
      if (!(std::abs(det) > 0)) return std::nullopt;
      const double d_l = (-level_gap * j11 + j01 * width_gap) / det;
      const double d_r = (-j00 * width_gap + level_gap * j10) / det;
      // A Newton step below 1e-6 L leaves an error of about its square: its
      // end is the level, the points there the tangents' (off by d^2 |p''|
      // / 2, |p''| ~ R / L^2, L = |U_xy|: 5e-13 R). Saves the confirming
      // evaluation, a quarter of a solve's.
      const double largest = std::max(std::abs(d_l), std::abs(d_r));
      bool small = largest < 1e-6;
      if (small) {
        const double u_l = cos_l * side_.z() + sin_l * normal_.z();
        const double u_r = cos_r * side_.z() + sin_r * normal_.z();
        small = largest < 1e-6 * std::sqrt(1 - std::max(u_l * u_l, u_r * u_r));
      }
      if (small) {
        phi_l += d_l;
        phi_r += d_r;
        if (!within_branches()) return std::nullopt;
        return level_at(p_l + d_l * t_l, p_r + d_r * t_r);
      }
      // Steps of at most 0.3 rad (the start can be far), and within the branches.
      double scale = std::min(1.0, 0.3 / largest);
      const auto keep_within = [&](double phi, double d, double lo, double hi) {
        const double room = d > 0 ? hi - phi : phi - lo;
        if (std::abs(d) * scale >= room) scale = 0.5 * room / std::abs(d);
      };
      const double before = scale;
      keep_within(phi_l, d_l, phi_left_, phi_bottom_);
      keep_within(phi_r, d_r, phi_bottom_, phi_right_);
      if (scale < before && ++shortened > 8) return std::nullopt;
      phi_l += scale * d_l;
      phi_r += scale * d_r;
      std::tie(cos_l, sin_l) = rotated(cos_l, sin_l, scale * d_l);
      std::tie(cos_r, sin_r) = rotated(cos_r, sin_r, scale * d_r);
      if (!within_branches()) return std::nullopt;
    }
    return std::nullopt;
  }

  // The width bR - bL of Q's slices is concave in c (Q is convex), and its
  // slope is known from the boundary points (db/dc = -tan(phi) on the
  // silhouette, e_z / N_z on a ray): Newton's method, whose steps on a
  // concave increasing function land at or below the root, and from below
  // climb onto it; a step out of the bracket is replaced by the secant of
  // the bracket, which lands at or above it (a few steps instead of
  // regula falsi's 22).
  double width_level_by_slices(double excess_bottom) const {
    struct Width {
      double excess, slope;
    };
    const auto width = [&](double c) {
      const BoundaryPoint l = boundary(c, true), r = boundary(c, false);
      const auto slope = [&](const BoundaryPoint& p) {
        return p.ray > 0 ? side_.z() / normal_.z() : -std::tan(p.phi);
      };
      return Width{r.b - l.b - ae_, slope(r) - slope(l)};
    };
    Width at = width(c0_);
    double lo = c_min_, hi = c0_, c = c0_;
    double excess_lo = excess_bottom, excess_hi = at.excess;
    const double tolerance = 1e-13 * radius_;
    for (int i = 0; i < 100 && hi - lo > tolerance; ++i) {
      const double step = at.excess / at.slope;
      if (at.excess == 0 || std::abs(step) < tolerance) return c;
      double next = c - step;
      if (!(next > lo && next < hi)) next = lo - excess_lo * (hi - lo) / (excess_hi - excess_lo);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      c = next;
      at = width(c);
      if (at.excess < 0) {
        lo = c;
        excess_lo = at.excess;
      } else {
        hi = c;
        excess_hi = at.excess;
      }
    }
    return c;
  }

  void silhouette_extremes(const BoundaryPoint& end, bool left, RadiusExtremes& out) const;
  void stock_line_extremes(double b_hi, RadiusExtremes& out) const;
  void shifted_extremes(const BoundaryPoint& left_top, const WidthLevel& level,
                        RadiusExtremes& out) const;
  void shifted_ray_extremes(double c_lo, RadiusExtremes& out) const;
  void shifted_silhouette_extremes(double phi_top, double phi_star, RadiusExtremes& out) const;
  // One arc of the shifted silhouette, piece by piece (revolved_extremes.cpp).
  class ShiftedArc;
  void flat_shifted_rim_extremes(double phi_lo, double phi_hi, RadiusExtremes& out) const;
  bool face_point_engaged(const Vector3d& p, double slack) const;
  // max(-z - rc, r - R, distance to the corner circle - rc): <= 0 exactly
  // in the tool, 0 on its surface.
  double outside_by(const Vector3d& p) const {
    const double r = length_of(p.x(), p.y());
    double value = std::max(-p.z() - corner_, r - radius_);
    if (corner_ > 0 && r > flat_radius_ && p.z() < 0)
      value = std::max(value, length_of(r - flat_radius_, p.z()) - corner_);
    return value;
  }
  // Whether the end face leads: F_z < 0, edge-on counting as leading.
  bool face_leads() const { return edge_on_ || face_in_front_; }
  // Whether a surface point with outward normal n leads (F.n >= 0, within
  // round-off); the face by face_leads().
  bool leads(const Vector3d& n) const {
    if (n.z() == -1) return face_leads();
    return feed_.dot(n) >= -1e-12;
  }
  // The tool's outward normal at a point of its surface (the face's at r <= R0).
  Vector3d surface_normal(const Vector3d& p) const {
    const double r = length_of(p.x(), p.y());
    if (r <= flat_radius_ || !(r > 0)) return -Vector3d::UnitZ();
    Vector3d radial(p.x() / r, p.y() / r, 0);
    if (p.z() >= 0 || !(corner_ > 0)) return radial;
    return ((r - flat_radius_) * radial + p.z() * Vector3d::UnitZ()).normalized();
  }
  void face_extremes(RadiusExtremes& out) const;

  double radius_, flat_radius_, corner_, ae_;
  Vector3d feed_, normal_, side_;
  double omega_ = 0, phi_left_ = 0, phi_bottom_ = 0, phi_right_ = 0;
  double phi_vertical_ = 0;  // omega + pi: the lower silhouette's most vertical normal
  double cos_omega_ = 1, sin_omega_ = 0;
  double c_min_ = 0, c0_ = 0;
  mutable std::array<std::optional<BoundaryPoint>, 2> tops_;  // left and right, see top()
  Vector3d foot_left_, foot_right_;
  std::array<double, 2> c_foot_{};  // N.foot, left and right
  bool edge_on_ = false;
  // The face leads with an area seen along F (its fibres' front points).
  bool face_in_front_ = false;
  double rim_tilt_ = 0;  // |N_xy|
  // inner_top_fibre()'s walk, and whether it left out the back: a cache.
  mutable std::optional<std::optional<std::pair<Vector3d, Vector3d>>> inner_top_fibre_;
  mutable bool inner_top_front_only_ = false;
  // boundary()'s last roots on the left and right: a cache, not state.
  mutable std::array<double, 2> warm_start_{kInf, kInf};
};

}  // namespace vcpost::geometry::revolved
