// Engagement of the bull-nose and flat end mills (MODELS.md section 2).
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
// the curves' ends they are all the candidates.
#include "geometry/revolved_engagement.h"

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
#include "geometry/level_engagement.h"
#include "geometry/quadrature.h"
#include "geometry/small_angle.h"

namespace vcpost::geometry {
namespace {

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
// finer (32 panels a piece to a relative 1e-6) down to kOffLevel: against
// the area integral over the groove taken to 1e-10 (a double quadrature
// of the fibres' front points, the route before; 400 random set-ups with
// |F_z| in 1e-5..1e-3), downhill within 1.6e-5 mm (5 of 214 beyond 1e-5),
// uphill within 1.2e-5 mm (2 of 186), a median 38 us, p90 111 us then
// (now, on 1,024 set-ups with |F_z| in 1e-6..1e-3, a median 20 us, p90
// 59 us). Below kOffLevel both tools go by level_engagement.h with the
// feed turned level (mean_when_level): at F_z = 0 within 6.3e-8 mm of
// that area integral (400 random set-ups), with 0 < |F_z| < 1e-5 within
// 4.2e-4 mm (400; the turn moves the previous tool by up to R |F_z| in
// height, which its corner near the face feels as a square root), in
// about 10 us where the area took 0.1-5 ms.
constexpr double kNearlyEdgeOn = 1e-3;
constexpr double kOffLevel = 1e-5;

// The root of g in [lo, hi], where g(lo) = g_lo < 0 < g(hi) = g_hi:
// Newton's method on g_and_slope(t) = {g, g'} from the bracket's secant,
// a step leaving the bracket bisecting it, until a step is below
// `tolerance`, whose end is the root.
template <class Function>
double newton_root(const Function& g_and_slope, double lo, double hi, double g_lo, double g_hi,
                   double tolerance) {
  double t = lo - g_lo * (hi - lo) / (g_hi - g_lo);
  if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
  for (int i = 0; i < 200 && hi - lo > tolerance; ++i) {
    const auto [g, slope] = g_and_slope(t);
    if (g == 0) return t;
    (g < 0 ? lo : hi) = t;
    const double next = t - g / slope;
    if (std::abs(next - t) <= tolerance && next >= lo && next <= hi) return next;
    t = next > lo && next < hi ? next : 0.5 * (lo + hi);
  }
  return t;
}

// sqrt(x^2 + y^2): the lengths here are mm-sized, far from over- and
// underflow, and std::hypot's care for them took 40 % of an evaluation.
double length_of(double x, double y) { return std::sqrt(x * x + y * y); }

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
    const double phi_end = left ? phi_left_ : phi_right_;
    const Vector3d& foot = left ? foot_left_ : foot_right_;
    const double c_foot = c_foot_[left ? 0 : 1];
    if (c >= c_foot) {
      const double t = (c - c_foot) / normal_.z();
      const Vector3d p = foot + t * Vector3d::UnitZ();
      return {p, side_.dot(p), phi_end, t};
    }
    // Just beside the bottom normal: an edge-on face's end, not its middle.
    const double phi_bottom = phi_bottom_ + (left ? -1e-10 : 1e-10);
    if (c <= c_min_) {
      const Vector3d p = silhouette(phi_bottom);
      return {p, side_.dot(p), phi_bottom, 0};
    }
    double a = left ? phi_end : phi_bottom, b = left ? phi_bottom : phi_end;
    if (corner_ == 0 && !edge_on_) return rim_boundary(c, left);
    // Newton's method on c(phi) = c inside the bracket, bisecting whenever a
    // step leaves it (c is monotone on each side of the bottom).
    const double sign = left ? -1.0 : 1.0;  // c decreases along the left branch
    // Started at the last root on this side (the searches ask at nearby
    // levels one after another), the first time from the bottom's
    // osculating circle: c - c_min = rho (phi - phi_bottom)^2 / 2
    // (finishing set-ups: 27 steps in the 5.8 solves of an evaluation
    // instead of 30 from the bracket's middle).
    double& warm = warm_start_[left ? 0 : 1];
    double phi = 0.5 * (a + b);
    if (warm > a && warm < b) {
      phi = warm;
    } else if (rim_tilt_ > 1e-6) {
      const double rho = bottom_curvature_radius();
      const double guess = phi_bottom_ + sign * std::sqrt(2 * (c - c_min_) / rho);
      if (guess > a && guess < b) phi = guess;
    }
    // c(phi) - c at the bracket's ends, NaN until evaluated there.
    double g_a = std::numeric_limits<double>::quiet_NaN(), g_b = g_a;
    // cos and sin of phi, by rotation from those of the last phi.
    auto [cos_phi, sin_phi] = cos_sin(phi);
    double phi_at = phi, last_step = kInf;
    for (int i = 0; i < 200 && b - a > 1e-14; ++i) {
      std::tie(cos_phi, sin_phi) = rotated(cos_phi, sin_phi, phi - phi_at);
      phi_at = phi;
      const Vector3d u = cos_phi * side_ + sin_phi * normal_;
      const Vector3d du = -sin_phi * side_ + cos_phi * normal_;
      const double length = length_of(u.x(), u.y());
      if (!(length > 1e-300)) {
        phi = 0.5 * (a + b);
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
      if ((g > 0) == (sign > 0)) {
        b = phi;  // c(phi) beyond c: the root is below phi
        g_b = g;
      } else {
        a = phi;
        g_a = g;
      }
      // c' and c'' of c = N.(R0 W + rc U), W = U_xy / |U_xy| = (cos a, sin a):
      // W' = a' W+, W'' = a'' W+ - a'^2 W (W+ = W turned a quarter), a' =
      // (U_xy x U_xy') / |U_xy|^2 and, as U'' = -U, a'' = -2 a' (U_xy.U_xy')
      // / |U_xy|^2; N.U = sin(phi), N.U' = cos(phi).
      const double inverse2 = inverse * inverse;
      const double turn = (u.x() * du.y() - u.y() * du.x()) * inverse2;
      const double turn_rate = -2 * turn * (u.x() * du.x() + u.y() * du.y()) * inverse2;
      const double n_along = (normal_.x() * u.x() + normal_.y() * u.y()) * inverse;
      const double n_across = (normal_.y() * u.x() - normal_.x() * u.y()) * inverse;
      const double slope = flat_radius_ * turn * n_across + corner_ * cos_phi;
      const double bend =
          flat_radius_ * (turn_rate * n_across - turn * turn * n_along) - corner_ * sin_phi;
      // Halley's step (three correct digits for one: from the osculating
      // circle's guess two steps, where Newton's took four), Newton's where
      // Halley's denominator does not keep the step's sign. Converged when
      // the step is round-off and so is the miss in c; where c(phi) is that
      // steep (near an edge-on face a step of 1e-14 still missed by 1e-5 mm)
      // the bracket is bisected onto the steep stretch, whose ends are
      // interpolated below.
      const double halley = slope * slope - 0.5 * g * bend;
      const double step = slope == 0 ? kInf : halley > 0 ? g * slope / halley : g / slope;
      if (std::abs(step) < 1e-14) {
        if (std::abs(g) < 1e-12 * radius_) return root_here();
        phi = 0.5 * (a + b);
        continue;
      }
      // A Halley step below 1e-4 L (L = |U_xy|), over which c' changes by
      // less than 1e-4 of itself, leaves an error of about its cube, and
      // the point at its end by Taylor's polynomial of degree 2 is off by
      // step^3 |p'''| / 6 (|p'''| ~ R / L^3): within 2e-13 R, the solve ends
      // there (p'' = R0 W'' - rc U, W'' = a'' W+ - a'^2 W). Saves the
      // confirming evaluation: 2.95 iterations a solve where the tangent's
      // end below 1e-8 L took 3.3. (Beside an edge-on face c' changes by
      // twice itself over a step of 1e-10: there the test on c'' keeps on
      // solving.)
      if (halley > 0 && std::abs(step) < 1e-4 * length &&
          std::abs(step * bend) < 1e-4 * std::abs(slope) && phi - step > a && phi - step < b) {
        const double wx = u.x() * inverse, wy = u.y() * inverse;
        const Vector3d bend_p(flat_radius_ * (-turn_rate * wy - turn * turn * wx) - corner_ * u.x(),
                              flat_radius_ * (turn_rate * wx - turn * turn * wy) - corner_ * u.y(),
                              -corner_ * u.z());
        const Vector3d root =
            p - step * silhouette_tangent(u, du, inverse) + 0.5 * step * step * bend_p;
        warm = phi - step;
        return {root, side_.dot(root), warm, 0};
      }
      // A step out of the bracket goes to the end it passes when that end
      // was never evaluated (a root at the foot or the bottom is reached in
      // one step, not by 30 bisections), else to the middle (c(phi) jumps
      // across a face nearly parallel to F: the secant of the ends crawled);
      // so does a step not below half the last (across such a jump Halley's
      // steps went to and fro inside the bracket).
      double next = phi - step;
      if (std::abs(step) > 0.5 * last_step) {
        next = 0.5 * (a + b);
      } else if (!(next > a && next < b)) {
        const bool low = !(next > a);
        next = std::isnan(low ? g_a : g_b) && std::isfinite(next) ? (low ? a : b) : 0.5 * (a + b);
      }
      last_step = std::abs(step);
      phi = next;
    }
    warm = 0.5 * (a + b);
    if (a == b) {
      const Vector3d p = silhouette(a);
      return {p, side_.dot(p), a, 0};
    }
    // A bracket still open here has closed onto a jump of c(phi).
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
  // The cusp the previous pass leaves beside this one (MODELS.md section
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

// RadiusExtremes of r over the silhouette from the bottom up to the
// boundary point `end` (to its foot when it is on a shank's ray, the ray
// added): the point with normal U has r = R0 + rc |U_xy| and z = rc U_z,
// so r is smallest where |U_z| peaks (phi = omega + pi, U_z = -|w|) and
// otherwise extreme at the arc's ends, the bottom (U = -N) and the end.
void Groove::silhouette_extremes(const BoundaryPoint& end, bool left, RadiusExtremes& out) const {
  out.add(end.p);
  if (end.ray > 0) out.add(left ? foot_left_ : foot_right_);
  out.add(flat_radius_ + corner_ * rim_tilt_, -corner_ * normal_.z());
  const double top = phi_vertical_;
  if (left ? top >= end.phi && top <= phi_bottom_ : top >= phi_bottom_ && top <= end.phi) {
    // U = -(cos(omega) e + sin(omega) N) there; |U_xy| from its
    // components, not from sqrt(1 - U_z^2), which cancels where U is
    // nearly vertical.
    const Vector3d u = cos_omega_ * side_ + sin_omega_ * normal_;
    out.add(flat_radius_ + corner_ * length_of(u.x(), u.y()), -corner_ * u.z());
  }
}

// The stock line c = c0 up to b_hi = bL(c0) + ae: its front points are an arc
// of the rim (the tool cut by the stock plane), whose ends the other curves
// add. Along the rim r is stationary only where the rim is tangent to a
// horizontal circle of the tool, i.e. where the circle's tangent z x P is
// normal to N too: P in the vertical plane through the axis and N_xy. The
// tool's section by that plane is convex, so the stock line meets it in two
// points, found in closed form piece by piece (shank lines, corner circles,
// face); z is stationary there as well, which the shank test needs.
void Groove::stock_line_extremes(double b_hi, RadiusExtremes& out) const {
  const double s = rim_tilt_;
  if (!(s > 1e-12)) return;  // a level rim: r constant along it
  const Vector3d radial(normal_.x() / s, normal_.y() / s, 0);
  const double nz = normal_.z();
  const double slack = 1e-12 * radius_;
  // Adds the point rho * radial + z * Z with outward tool normal `n` when it
  // leads (F.n >= 0) and lies at b <= b_hi (b >= bL(c0) holds on the tool).
  const auto candidate = [&](double rho, double z, const Vector3d& n) {
    const Vector3d p = rho * radial + z * Vector3d::UnitZ();
    const double b = side_.dot(p);
    if (!leads(n) || b > b_hi + slack) return;
    out.add(std::abs(rho), z);
  };
  // Shank lines rho = +-R, z >= 0.
  for (const double sign : {1.0, -1.0}) {
    const double z = (c0_ - sign * radius_ * s) / nz;
    if (z >= 0) candidate(sign * radius_, z, sign * radial);
  }
  // The face z = -rc, |rho| <= R0 (the flat mill's face is at z = 0).
  const double face_rho = (c0_ + corner_ * nz) / s;
  if (std::abs(face_rho) <= flat_radius_) candidate(face_rho, -corner_, -Vector3d::UnitZ());
  if (!(corner_ > 0)) return;
  // The corner circles: centre (+-R0, 0), radius rc, the outer lower quarter;
  // on the line z = k (c0 - s rho), k = 1 / N_z: a quadratic in rho.
  const double k = 1 / nz;
  for (const double sign : {1.0, -1.0}) {
    const double centre = sign * flat_radius_;
    const double qa = 1 + k * k * s * s;
    const double qb = centre + k * k * s * c0_;  // half of -b
    const double qc = centre * centre + k * k * c0_ * c0_ - corner_ * corner_;
    const double disc = qb * qb - qa * qc;
    if (disc < 0) continue;
    for (const double root : {-1.0, 1.0}) {
      const double rho = (qb + root * std::sqrt(disc)) / qa;
      const double z = k * (c0_ - s * rho);
      if (sign * (rho - centre) < -slack || z > slack) continue;
      candidate(rho, z, ((rho - centre) * radial + z * Vector3d::UnitZ()) / corner_);
    }
  }
}

// The shifted silhouette b = bL(c) + ae, c in [c*, c0]: the edge of the
// previous pass's groove on this tool, i.e. the tool surface cut by the
// surface the previous tool swept. Along such a curve r is stationary
// where the curve is tangent to the tool's horizontal circle, and since
// the curve's tangent is n x u (n the tool's normal, in the meridian plane
// of P; u the swept surface's), that is where u has no component along the
// circle: u_xy parallel to P_xy. z is stationary there too (the tangent's
// z component is n_xy x u_xy). So the extremes are the ends and these
// points, found in closed form on the shank's ray and by 1-D roots on the
// silhouette.
void Groove::shifted_extremes(const BoundaryPoint& left_top, const WidthLevel& level,
                              RadiusExtremes& out) const {
  const double c_star = level.c;
  if (!(c_star < c0_)) return;
  // (One walk at a time: mostly there is one, and the side-by-side
  // walks' bookkeeping cost it 2 %.)
  const auto add_front = [&](const Vector3d& x) {
    const Vector3d x0 = x - feed_.dot(x) * feed_;
    if (const auto p = front_point(x0)) out.add(*p);
  };
  if (const auto& fibre = inner_top_fibre(true)) out.add(fibre->first);
  // At c* > c_min the shifted silhouette ends on the near one: its fibre
  // touches the tool there (no walk onto a tangent line).
  if (c_star > c_min_)
    out.add(level.right.p);
  else
    add_front(level.left.p + ae_ * side_);
  const double c_foot = c_foot_[0];
  if (c_star < c_foot && c_foot < c0_) add_front(foot_left_ + ae_ * side_);
  if (c0_ > c_foot) shifted_ray_extremes(std::max(c_star, c_foot), out);
  if (c_star < c_foot)
    shifted_silhouette_extremes(c0_ > c_foot ? phi_left_ : left_top.phi, level.left.phi, out);
}

// On the shank's ray the shifted fibres fill the vertical plane m.X = d,
// m = unit(z x F): the circle tangent to it touches it at P_xy = d m, on
// the tool's circle of radius |d|.
void Groove::shifted_ray_extremes(double c_lo, RadiusExtremes& out) const {
  const double fxy = length_of(feed_.x(), feed_.y());
  if (!(fxy > 0)) return;
  const Vector3d m(-feed_.y() / fxy, feed_.x() / fxy, 0);
  const double d = m.dot(foot_left_ + ae_ * side_);
  const double reach = std::abs(d) - flat_radius_;
  if (!(reach < corner_)) return;  // the shank's circles: r = R, no interior extreme
  const double z = reach <= 0 ? -corner_ : -std::sqrt(corner_ * corner_ - reach * reach);
  const Vector3d p = d * m + z * Vector3d::UnitZ();
  const double c = normal_.dot(p), slack = 1e-12 * radius_;
  if (c < c_lo - slack || c > c0_ + slack || !leads(surface_normal(p))) return;
  out.add(p);
}

// On the silhouette, by its parameter phi (the previous tool's silhouette
// point S(phi) + ae e, fibre along F): the point x(phi) of the fibre with
// x_xy parallel to u_xy is in closed form, and the stationary points are
// where it lies on the tool (outside_by = 0) as the fibre's front point.
// With c = cos(phi), s = sin(phi), A = (e x N)_z, B = (F x e)_z, C = (F x
// N)_z, D = B c + C s: x = S + ae e + t F, t = -ae A s / D, and
// Delta = x - S has |Delta|^2 = ae^2 + t^2, u.Delta = ae c. x_xy = lambda
// d, d = u_xy / L, L = |u_xy| = sqrt(1 - v^2), v = u_z = c e_z + s N_z, and
// M = (lambda - R0) L = rc L^2 + ae (c - e_z v) - t F_z v (from x.u).
// On each piece of the tool's surface this is a trigonometric polynomial
// (times powers of D, not zero where x exists):
// - the face, z = rc v + ae e_z + t F_z = -rc (either side of the axis):
//   (rc v + rc + ae e_z) D - ae A F_z s, degree 2;
// - the corner, lambda > R0: |x - R0 d|^2 = |rc u + Delta|^2 = rc^2 gives
//   ae A^2 s^2 + (ae + 2 rc c) D^2, degree 3;
// - the corner across the axis, lambda < 0: |x + R0 d|^2 = rc^2, i.e.
//   (2 rc ae c + ae^2 + t^2 + 4 R0^2) L = -4 R0 M, squared:
//   G^2 L^2 - 16 R0^2 (M D)^2 D^2, G = (2 rc ae c + ae^2 + 4 R0^2) D^2 +
//   ae^2 A^2 s^2, degree 8;
// - the shank, lambda = +-R: M = rc L or M = -(R + R0) L, squared: (M D)^2
//   - K^2 L^2 D^2, degree 6 (M D itself, degree 3, for the flat mill's
//   lambda = R, where rc = 0).
// Every root of the piece's equation is a root of its polynomial; the
// polynomials' roots on the arc are isolated by form_roots (a count, not a
// scan), and each is kept if x lies on the tool as a leading point.
void Groove::shifted_silhouette_extremes(double phi_top, double phi_star,
                                         RadiusExtremes& out) const {
  if (corner_ == 0 && !edge_on_) {
    flat_shifted_rim_extremes(std::min(phi_top, phi_star), std::max(phi_top, phi_star), out);
    return;
  }
  // The point, from the silhouette normal's angle given by its cosine and sine.
  const auto meridian_point_at = [&](double cos_phi, double sin_phi) -> std::optional<Vector3d> {
    const Vector3d u = cos_phi * side_ + sin_phi * normal_;
    const double length = length_of(u.x(), u.y());
    if (!(length > 0)) return std::nullopt;
    const Vector3d x =
        (flat_radius_ / length) * Vector3d(u.x(), u.y(), 0) + corner_ * u + ae_ * side_;
    const double across = feed_.x() * u.y() - feed_.y() * u.x();
    if (across == 0) return std::nullopt;
    return x - (x.x() * u.y() - x.y() * u.x()) / across * feed_;
  };
  const double lo = std::min(phi_top, phi_star), hi = std::max(phi_top, phi_star);
  if (!(hi > lo)) return;
  const double ez = side_.z(), nz = normal_.z(), fz = feed_.z();
  // A, B and C above.
  const double en = side_.x() * normal_.y() - side_.y() * normal_.x();
  const double fe = feed_.x() * side_.y() - feed_.y() * side_.x();
  const double fn = feed_.x() * normal_.y() - feed_.y() * normal_.x();
  const double r0 = flat_radius_, rc = corner_, ae = ae_;
  // Whether the shank can hold a point of the groove (c <= c0 there).
  const bool shank = c0_ + radius_ * rim_tilt_ > -1e-9 * radius_;
  // Going uphill (F_z > 0) no point across the axis (x_xy = lambda d,
  // lambda < 0) leads: with U_z = v <= 0 on the lower boundary, U_xy.F_xy =
  // -v F_z, there the corner's normal n = -cos(theta) d + sin(theta) z
  // (theta in [-pi/2, 0]) has n.F = F_z (cos(theta) v / L + sin(theta)) <= 0
  // and the shank's, -d, has n.F = v F_z / L <= 0.
  const bool uphill = !edge_on_ && fz > 0;
  // Arcs of at most pi (the left boundary spans no more): W <= tan(pi / 4) = 1.
  const int arcs = std::max(1, static_cast<int>(std::ceil((hi - lo) / kPi)));
  for (int arc = 0; arc < arcs; ++arc) {
    const double arc_lo = lo + (hi - lo) * arc / arcs, arc_hi = lo + (hi - lo) * (arc + 1) / arcs;
    const ArcForms forms(arc_lo, arc_hi, cos_sin(0.5 * (arc_lo + arc_hi)));
    // A root of a piece's polynomial counts if x lies on that piece (within
    // round-off): beyond the face's rim its plane stays within 1e-9 R of the
    // corner for sqrt(2e-9 R rc), so the surface test alone took the
    // plane's root there for the corner's (D_min 5.3e-8 mm off, D 10, rc 2).
    const double slack = 1e-12 * radius_;
    const auto on_face = [&](const Vector3d& p) {
      return length_of(p.x(), p.y()) <= flat_radius_ + slack;
    };
    const auto on_corner = [&](const Vector3d& p) {
      return length_of(p.x(), p.y()) >= flat_radius_ - slack && p.z() <= slack;
    };
    const auto on_shank = [&](const Vector3d& p) { return p.z() >= -slack; };
    const auto test = [&](const auto& on_piece) {
      return [&](double tau) {
        const auto [cos_phi, sin_phi] = forms.cos_sin_at(tau);
        const auto p = meridian_point_at(cos_phi, sin_phi);
        if (p && on_piece(*p) && std::abs(outside_by(*p)) <= 1e-9 * radius_ &&
            leads(surface_normal(*p)))
          out.add(*p);
      };
    };
    const ArcForm<2> d = forms.linear(fe, fn, 0), v = forms.linear(ez, nz, 0);
    const ArcForm<2>& s = forms.sin();
    // The face, where it leads.
    if (face_leads())
      form_roots(forms.sum(forms.linear(rc * ez, rc * nz, rc + ae * ez) * d, (-ae * en * fz) * s),
                 test(on_face));
    const ArcForm<4> d2 = d * d;
    if (rc > 0) {
      // The corner.
      form_roots(forms.sum((ae * en * en) * (s * s), forms.linear(2 * rc, 0, ae) * d2),
                 test(on_corner));
    }
    // Whether M <= -k L can hold on the arc (lambda <= R0 - k): L >=
    // |F_z| (v^2 <= e_z^2 + N_z^2 = 1 - F_z^2), so not where M > -k |F_z|
    // on the whole arc. First by a bound: where D keeps its sign (its ends'
    // signs agree: an arc < pi then holds no zero of D, and one of pi
    // has ends of opposite signs), M = rc L^2 + ae (c - e_z v) + ae A F_z
    // s v / D >= -ae (1 + |A F_z| / min |D|), |D| least at an end; this
    // decides most finishing set-ups' arcs, for which building M D's form
    // took a fifth of the evaluation. Else by the form: not where D keeps
    // its sign and M D + k |F_z| D has that sign on the whole arc.
    // (D's form at the arc's ends is D (1 + W^2) = D times one's end coefficient.)
    const double d_lo = d.a[0], d_hi = d.a[2];
    const double least_d = std::min(std::abs(d_lo), std::abs(d_hi)) / forms.one().a[0];
    const bool d_keeps_sign = (d_lo > 0 && d_hi > 0) || (d_lo < 0 && d_hi < 0);
    const double m_low = d_keeps_sign ? -ae * (1 + std::abs(en * fz) / least_d) : -kInf;
    // Ruled out without the form: uphill, or by the bound.
    const auto ruled_out = [&](double k) { return uphill || m_low > -k * std::abs(fz); };
    const bool across_possible = rc > 0 && r0 > 0 && !ruled_out(2 * r0);
    if (!shank && !across_possible) continue;
    // M D and L^2.
    const ArcForm<4> l2 = forms.sum(forms.one() * forms.one(), (-1.0) * (v * v));
    const ArcForm<6> md =
        forms.sum(forms.sum(rc * l2, forms.linear(ae * (1 - ez * ez), -ae * ez * nz, 0)) * d,
                  (ae * en * fz) * (s * v));
    const auto may_cross = [&](double k) {
      const ArcForm<6> bound = forms.sum(md, (k * std::abs(fz)) * (d * forms.one() * forms.one()));
      const auto all = [](const auto& form, bool positive) {
        return std::all_of(form.a.begin(), form.a.end(),
                           [positive](double x) { return positive ? x > 0 : x < 0; });
      };
      const bool positive = d.a[0] > 0;
      return !(all(d, positive) && all(bound, positive));
    };
    if (across_possible && may_cross(2 * r0)) {
      // The corner across the axis: lambda <= -R0.
      const ArcForm<6> g = forms.sum(forms.linear(2 * rc * ae, 0, ae * ae + 4 * r0 * r0) * d2,
                                     (ae * ae * en * en) * (s * s));
      form_roots(forms.sum(g * g * l2, (-16 * r0 * r0) * (md * md * d2)), test(on_corner));
    }
    if (!shank) continue;
    if (rc > 0)
      form_roots(forms.sum(md * md, (-rc * rc) * (l2 * d2)), test(on_shank));
    else
      form_roots(md, test(on_shank));
    const double across = radius_ + r0;
    if (!ruled_out(across) && may_cross(across))
      form_roots(forms.sum(md * md, (-across * across) * (l2 * d2)), test(on_shank));
  }
}

// Where the fibre of the previous tool's silhouette point S(phi) + ae e,
// the shifted silhouette's fibre, has its front point on a junction of
// the tool's pieces: the face's rim (when the face leads) and the shank's
// foot (its leading half). The fibre crosses the circle's plane z = h (h =
// -rc on the face, 0 at the foot) at x = x0 + t F, t = (h - x0_z) / F_z,
// and |x_xy| = rho there. With S = R0 U_xy / L + rc U (L = |U_xy|), x_xy =
// R0 U_xy / L + W, F_z W = F_z (rc U_xy + ae e_xy) - (rc U_z + ae e_z -
// h) F_xy, so |x_xy|^2 = rho^2 reads 2 R0 F_z (U_xy.F_z W) = L (F_z^2
// (rho^2 - R0^2) - |F_z W|^2), squared a trigonometric polynomial of
// degree 6 in phi (its roots by form_roots, each kept if x lies on the
// circle and leads). Not for a face all but parallel to F (|F_z| < 1e-5,
// see kNearlyEdgeOn), where the polynomials lose their roots in round-off.
std::vector<double> Groove::shifted_junctions(double lo, double hi) const {
  std::vector<double> out;
  if (!(hi > lo)) return out;
  const Vector3d &e = side_, &n = normal_, &f = feed_;
  const double fz = f.z(), r0 = flat_radius_;
  const int arcs = std::max(1, static_cast<int>(std::ceil((hi - lo) / kPi)));
  for (int arc = 0; arc < arcs; ++arc) {
    const double arc_lo = lo + (hi - lo) * arc / arcs, arc_hi = lo + (hi - lo) * (arc + 1) / arcs;
    const double middle = 0.5 * (arc_lo + arc_hi), quarter = std::tan(0.25 * (arc_hi - arc_lo));
    const ArcForms forms(arc_lo, arc_hi, cos_sin(middle));
    const ArcForm<2> ux = forms.linear(e.x(), n.x(), 0), uy = forms.linear(e.y(), n.y(), 0),
                     uz = forms.linear(e.z(), n.z(), 0);
    const ArcForm<4> l2 = forms.sum(forms.one() * forms.one(), (-1.0) * (uz * uz));
    for (const Junction& j : junctions()) {
      if (j.face && !face_in_front_) continue;
      const double k = ae_ * e.z() - j.z;
      const ArcForm<2> wx =
          forms.linear(corner_ * (fz * e.x() - e.z() * f.x()),
                       corner_ * (fz * n.x() - n.z() * f.x()), ae_ * fz * e.x() - k * f.x());
      const ArcForm<2> wy =
          forms.linear(corner_ * (fz * e.y() - e.z() * f.y()),
                       corner_ * (fz * n.y() - n.z() * f.y()), ae_ * fz * e.y() - k * f.y());
      const ArcForm<4> dot = forms.sum(ux * wx, uy * wy);
      const ArcForm<4> rest =
          forms.sum((fz * fz * (j.rho * j.rho - r0 * r0)) * (forms.one() * forms.one()),
                    (-1.0) * forms.sum(wx * wx, wy * wy));
      form_roots(forms.sum((4 * r0 * r0 * fz * fz) * (dot * dot), (-1.0) * (l2 * rest * rest)),
                 [&](double tau) {
                   const double phi =
                       polished_junction(middle + 2 * std::atan(quarter * (2 * tau - 1)), j);
                   if (!(phi > lo && phi < hi)) return;
                   const Vector3d x = shifted_crossing(phi, j).x;
                   if (std::abs(length_of(x.x(), x.y()) - j.rho) > 1e-7 * radius_) return;
                   if (front_on(j, x.x(), x.y())) out.push_back(phi);
                 });
    }
  }
  return out;
}

Groove::ShiftedCrossing Groove::shifted_crossing(double phi, const Junction& j) const {
  const auto [cos_phi, sin_phi] = cos_sin(phi);
  const auto [p, dp] = silhouette_and_tangent(cos_phi, sin_phi);
  const Vector3d x0 = p + ae_ * side_;
  const Vector3d x = x0 + (j.z - x0.z()) / feed_.z() * feed_;
  const Vector3d dx = dp - dp.z() / feed_.z() * feed_;
  const double rho = length_of(x.x(), x.y());
  return {x, rho - j.rho, (x.x() * dx.x() + x.y() * dx.y()) / rho};
}

// A root of shifted_junctions' polynomial holds only the digits its
// squared form keeps: with F_z -5e-5 (D 16.6, rc 3.6) the crossing raced
// round the face's rim at 6e4 mm per radian of phi, so the form's 1.1e-10
// in phi left it 6.4e-6 mm (8e-7 R) off the circle, the test refused it,
// and the quadrature chased the uncut kink through 20 more panels.
// Newton's method on the miss itself, a few steps (the form's root is close).
double Groove::polished_junction(double phi, const Junction& j) const {
  for (int k = 0; k < 3; ++k) {
    const ShiftedCrossing at = shifted_crossing(phi, j);
    const double step = at.miss / at.slope;
    if (!(std::abs(step) < 1e-3)) break;  // a flat miss: keep the form's root
    phi -= step;
    if (std::abs(step) < 1e-15) break;
  }
  return phi;
}

// The flat mill's silhouette is its rim, S = R d (d a unit horizontal
// vector); the fibre of S + ae e meets the vertical plane through the axis
// and d at t = -ae (e x d)_z / (F x d)_z, which lies on the face (z = 0,
// the shank's r - R there is -ae t (e x F)_z, never zero off a level feed)
// where also t = -ae e_z / F_z: where e_z (F x d)_z = F_z (e x d)_z, i.e.
// d parallel to e_z F_xy - F_z e_xy. Two directions, no root to search.
void Groove::flat_shifted_rim_extremes(double phi_lo, double phi_hi, RadiusExtremes& out) const {
  const double dx = side_.z() * feed_.x() - feed_.z() * side_.x();
  const double dy = side_.z() * feed_.y() - feed_.z() * side_.y();
  const double length = length_of(dx, dy);
  if (!(length > 0)) return;
  const double t = -ae_ * side_.z() / feed_.z();
  for (const double sign : {1.0, -1.0}) {
    const double ux = sign * dx / length, uy = sign * dy / length;
    const double phi = rim_phi(ux, uy);
    if (phi < phi_lo || phi > phi_hi) continue;
    const Vector3d p = Vector3d(radius_ * ux, radius_ * uy, 0) + ae_ * side_ + t * feed_;
    if (std::abs(outside_by(p)) <= 1e-9 * radius_ && leads(surface_normal(p))) out.add(p);
  }
}

// Whether the fibre through a face point lies in the groove: in the stock
// and not strictly inside the previous pass (within `slack`, mm).
bool Groove::face_point_engaged(const Vector3d& p, double slack) const {
  const double b = side_.dot(p), c = normal_.dot(p);
  if (c > c0_ + slack) return false;
  return c <= c_min_ || b - ae_ <= boundary(c, true).b + slack;
}

// The least r on a leading face (F_z < 0, or edge-on). r has no extremum
// inside the face but its centre (r = 0), and the face's edges in the
// groove are the stock line (stock_line_extremes), the rim (r = R0) and
// the edge of the previous pass, found here in the face's own plane: the
// previous tool at ae e + t F cuts the plane in a disk of centre C(t) =
// ae e_xy + t F_xy and radius rho(t) (its circle at the height of this
// face), so the removed part is a union of disks and its edge their
// envelope: Y = C + rho n with n.F_xy = -rho'(t). The point nearest the
// axis has n = -C/|C|, where g(t) = C.F_xy / |C| - rho'(t) = 0; C.F_xy/|C|
// grows along the line and rho' (the corner's circles widening as the
// previous tool sinks) shrinks, so g has one root: bracketed by the
// stretch of t whose disks reach the face at all.
void Groove::face_extremes(RadiusExtremes& out) const {
  const Vector3d centre = -corner_ * Vector3d::UnitZ();
  if (face_point_engaged(centre, 0)) out.add(0, centre.z());
  const double fx = feed_.x(), fy = feed_.y();
  const double cx = ae_ * side_.x(), cy = ae_ * side_.y();
  const double lift = ae_ * side_.z();              // the previous tool's height over this one
  const double sink = edge_on_ ? 0.0 : -feed_.z();  // dh/dt of its circle in this plane: > 0
  // Its circle in this plane is at its own height h(t) = -rc - lift + t sink.
  // (Named members, not a structured binding: clang 14 cannot capture one.)
  const CylinderCrossing crossing = cylinder_crossing(cx, cy, flat_radius_ + radius_);
  const double f2 = crossing.fxy2, beta = crossing.beta, disc = crossing.disc;
  if (!(f2 > 0)) return;
  if (!(disc > 0)) return;
  double t_lo = (-beta - std::sqrt(disc)) / f2;
  const double t_hi = (-beta + std::sqrt(disc)) / f2;
  if (sink == 0) {
    if (!(lift < 0)) return;  // the previous tool's bottom at or above this face
  } else {
    t_lo = std::max(t_lo, lift / sink);  // below, it does not reach the plane
    if (!(t_lo < t_hi)) return;
  }
  const auto height = [&](double t) { return -corner_ - lift + t * sink; };
  const auto disk_radius = [&](double h) {
    return h >= 0 ? radius_ : flat_radius_ + std::sqrt(std::max(0.0, corner_ * corner_ - h * h));
  };
  // g and g' = (|F_xy|^2 |C|^2 - (C.F_xy)^2) / |C|^3 + sink^2 rc^2 / (rc^2 - h^2)^(3/2).
  const auto g_and_slope = [&](double t) {
    const double x = cx + t * fx, y = cy + t * fy, h = height(t);
    const double length = length_of(x, y), along = x * fx + y * fy;
    double g = along / length;
    double slope = (f2 * length * length - along * along) / (length * length * length);
    if (h < 0 && sink > 0 && corner_ > 0) {  // (the flat mill's h < 0 is round-off)
      const double q = corner_ * corner_ - h * h, root_q = std::sqrt(q);
      g += h / root_q * sink;
      slope += sink * sink * corner_ * corner_ / (q * root_q);
    }
    return std::pair{g, slope};
  };
  const double g_lo = g_and_slope(t_lo).first, g_hi = g_and_slope(t_hi).first;
  if (!(g_hi > 0)) return;
  // r = |C| - rho is stationary at the root: its error moves r by its
  // square, and the step below the tolerance leaves an error of its square.
  const double t =
      g_lo >= 0 ? t_lo : newton_root(g_and_slope, t_lo, t_hi, g_lo, g_hi, 1e-9 * (t_hi - t_lo));
  const double x = cx + t * fx, y = cy + t * fy, distance = length_of(x, y);
  if (!(distance > 0)) return;
  const double scale = (distance - disk_radius(height(t))) / distance;
  const Vector3d p(scale * x, scale * y, -corner_);
  if (length_of(p.x(), p.y()) <= flat_radius_ && face_point_engaged(p, 1e-9 * radius_)) out.add(p);
}

RadiusExtremes Groove::extremes() const {
  RadiusExtremes out;
  const BoundaryPoint& left_top = top(true);
  // The far silhouette (away from the previous pass), from the bottom to c0.
  silhouette_extremes(left_top, true, out);
  // The near silhouette below c*.
  const WidthLevel level = width_level();
  silhouette_extremes(level.right, false, out);
  // The shifted silhouette, from c* up to c0.
  shifted_extremes(left_top, level, out);
  // The stock line.
  stock_line_extremes(left_top.b + ae_, out);
  if (face_leads()) face_extremes(out);
  out.r_max = std::min(out.r_max, radius_);
  return out;
}

// The flat mill's test of what the previous pass removed (its mean goes
// circle by circle; the bull-nose's needs no such test, see
// mean_over_boundary): P is removed iff it lies strictly inside the tool
// shifted by ae along e, i.e. seen along F iff q = (e.P - ae, N.P) lies in
// Q, the projection of the solid K = {r <= R, z >= 0}: the ellipse E =
// A disk(R), A = rows e_xy and N_xy, swept along w = (e_z, N_z), the axis
// seen along F. With k = A^-1 q that is iff the ray k - s A^-1 w (s >= 0)
// meets the disk of radius R. (A face seen edge-on makes A singular: such
// feeds, |F_z| < kOffLevel, go by mean_when_level.)
class Groove::Removal {
 public:
  explicit Removal(const Groove& groove) : groove_(groove) {
    const Groove& g = groove;
    Eigen::Matrix2d a;
    a << g.side_.x(), g.side_.y(), g.normal_.x(), g.normal_.y();
    const Eigen::Vector2d w(g.side_.z(), g.normal_.z());
    inverse_ = a.inverse();
    axis_ = inverse_ * w;
    axis_unit_ = axis_.normalized();
    axis_across_ = {-axis_unit_.y(), axis_unit_.x()};
    along_phase_ = std::atan2(axis_unit_.y(), axis_unit_.x());
    origin_ = g.ae_ * inverse_.col(0);
  }

  // Removes from `row` the angles of the circle of radius rho at height z
  // that the previous pass removed, in closed form. k = A^-1 q = P_xy - o,
  // o = ae A^-1 (1, 0) - z A^-1 w, so P is removed iff P_xy lies within R0
  // of the ray o + s A^-1 w (s >= 0): in the disk of radius R0 about o, or
  // in the band of half-width R0 about the ray's line on the ray's side of
  // o; each condition is a sinusoid's sublevel set on the circle.
  void remove_from(AngleSet& row, double rho, double z) const {
    const double r0 = groove_.flat_radius_;
    const Eigen::Vector2d o = origin_ - z * axis_;
    const Eigen::Vector2d& along = axis_unit_;
    const Eigen::Vector2d& across = axis_across_;
    // |P - o|^2 < R0^2, P = rho (cos t, sin t).
    AngleSet disk({-kPi, kPi});
    disk.keep_where({-2 * rho * o.x(), -2 * rho * o.y(), 0}, r0 * r0 - rho * rho - o.squaredNorm());
    // |(P - o).across| < R0 and (P - o).along > 0, as rho cos(t - phase)
    // (the phases fixed by the groove: no atan2 a circle).
    AngleSet band({-kPi, kPi});
    const double phase = along_phase_;
    band.keep_where_polar(
        rho, [&] { return phase + kPi / 2; }, 0, r0 + o.dot(across));
    band.keep_where_polar(
        rho, [&] { return phase - kPi / 2; }, 0, r0 - o.dot(across));
    band.keep_where_polar(
        rho, [&] { return phase + kPi; }, 0, -o.dot(along));
    row.remove(disk);
    row.remove(band);
  }

  // Where a circle of remove_from turns tangent to the removed part's edge
  // (its removed length has a square-root kink there): the radii of the
  // face's circles at height z (about o: |o| -+ R0; the band's sides, whose
  // distances to the axis are |o.across -+ R0|).
  void add_face_breaks(double z, std::vector<double>& breaks) const {
    const double r0 = groove_.flat_radius_;
    const Eigen::Vector2d o = origin_ - z * axis_;
    const double across = o.dot(axis_across_);
    for (const double rho :
         {o.norm() - r0, o.norm() + r0, std::abs(across - r0), std::abs(across + r0)})
      breaks.push_back(rho);
  }
  // The flat mill's shank line through P_xy = (x, y): the height above
  // which the previous pass removed it, +inf where it does not. P - o(z) =
  // d + z A^-1 w moves along the axis as z grows, at a constant distance
  // from o's line across it: if that is under R0 the line enters the disk
  // (from behind, at the lower root of |d + z A^-1 w| = R0) and stays in
  // it or in the band beyond; otherwise it misses both.
  double shank_removed_above(double x, double y) const {
    const double r0 = groove_.flat_radius_;
    const Eigen::Vector2d d = Eigen::Vector2d(x, y) - origin_;
    if (!(std::abs(d.dot(axis_across_)) < r0)) return kInf;
    const double a2 = axis_.squaredNorm(), half_b = d.dot(axis_);
    const double disc = half_b * half_b - a2 * (d.squaredNorm() - r0 * r0);
    return (-half_b - std::sqrt(std::max(0.0, disc))) / a2;
  }
  // The shank's angles t (P_xy = R (cos t, sin t)) where shank_removed_above
  // changes from +inf to finite: the line's distance to o's line across
  // the axis, R cos(t - along - pi/2) - o.across, reaches +-R0.
  void add_shank_line_breaks(std::vector<double>& breaks) const {
    const double r0 = groove_.flat_radius_, radius = groove_.radius_;
    const double offset = origin_.dot(axis_across_);
    for (const double side : {r0, -r0}) {
      const double ratio = (side + offset) / radius;
      if (std::abs(ratio) > 1) continue;
      for (const double sign : {1.0, -1.0})
        breaks.push_back(along_phase_ + kPi / 2 + sign * std::acos(ratio));
    }
  }

 private:
  // The vectors and matrices first (16-byte aligned), then the scalars.
  Eigen::Matrix2d inverse_ = Eigen::Matrix2d::Identity();
  Eigen::Vector2d axis_ = Eigen::Vector2d::Zero();  // A^-1 w
  Eigen::Vector2d axis_unit_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d axis_across_ = Eigen::Vector2d::Zero();  // axis_unit_ turned by +90 deg
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();       // o at z = 0: ae A^-1 (1, 0)
  const Groove& groove_;
  double along_phase_ = 0;  // the azimuth of axis_
};

// The flat mill's area-weighted mean of 2r, circle by circle: the tool
// surface is a stack of horizontal circles (the face's of radius rho, the
// shank's at height z), each with a constant r, so the mean needs only
// the length of the engaged angles on each circle, weighted by its area
// element. On a circle the stock plane and the leading side are sinusoids
// (exact angle sets, angle_set.h), and so are the edges of what the
// previous pass removed (Removal). Capped adaptive quadrature over the
// circles bounds the work whatever the set-up.
double Groove::mean_diameter() const {
  const double tilt = rim_tilt_;
  const double feed_tilt = length_of(feed_.x(), feed_.y());
  const double lead_phase = std::atan2(-feed_.y(), -feed_.x());
  const double level_phase = std::atan2(normal_.y(), normal_.x());
  const Removal removal(*this);
  // Circle of radius rho at height z whose outward normal is (s cos t,
  // s sin t, nz); weight = area per radian per unit of the stack parameter.
  const auto circle = [&](double rho, double z, double s, double nz, double weight) {
    // Both sinusoids keep their phase along the stack (s >= 0): no atan2 a circle.
    AngleSet set({-kPi, kPi});
    set.keep_where_polar(
        rho * tilt, [&] { return level_phase; }, normal_.z() * z, c0_);
    // Leading side F.n >= 0; the face's normal is -z, seen edge-on it leads.
    set.keep_where_polar(
        s * feed_tilt, [&] { return lead_phase; }, -feed_.z() * nz, s == 0 ? kEdgeOn : 0.0);
    removal.remove_from(set, rho, z);
    double length = 0;
    for (int i = 0; i < set.size(); ++i) length += set[i].hi - set[i].lo;
    return std::array<double, 2>{weight * length, weight * 2 * rho * length};
  };
  constexpr double kRelative = 1e-5;
  constexpr int kPanels = 24;  // per piece: at most 15 (2 kPanels - 1) circles
  const double absolute = 1e-12 * radius_ * radius_;
  std::array<double, 2> sum{0, 0};
  const auto add = [&](const std::array<double, 2>& part) {
    sum[0] += part[0];
    sum[1] += part[1];
  };
  // The quadrature starts its panels where a circle's engaged length has
  // a square-root kink (a circle turning tangent to the stock plane or the
  // removed part's edge): inside a panel one fooled its error estimate,
  // 1.2e-3 mm off the circle-by-circle oracle.
  const auto integrate = [&](const auto& f, const std::vector<double>& breaks) {
    return integrate_capped<2>(f, breaks, kRelative, absolute, kPanels);
  };
  // The face at z = 0 (its lowest point must reach the stock).
  if (-radius_ * tilt < c0_) {
    std::vector<double> breaks{std::abs(c0_) / tilt};
    removal.add_face_breaks(0, breaks);
    add(integrate([&](double rho) { return circle(rho, 0, 0, -1, rho); },
                  breaks_within(breaks, 0.0, radius_)));
  }
  // The shank, up to the highest level the stock reaches on it.
  const double top = (c0_ + radius_ * tilt) / normal_.z();
  if (top > 0 && feed_tilt > 0) {
    // The flat mill's by its vertical lines on the leading half (F.P_xy >=
    // 0), each kept from z = 0 up to the stock plane or to where the
    // previous pass removed it: a closed form a line, fewer lines than
    // circles (the circles took 150-165 of a mean's 250-270).
    const double centre = std::atan2(feed_.y(), feed_.x());
    std::vector<double> breaks;
    removal.add_shank_line_breaks(breaks);
    if (const double reach = c0_ / (radius_ * tilt); std::abs(reach) < 1) {
      breaks.push_back(level_phase + std::acos(reach));  // the stock plane crosses the foot (z = 0)
      breaks.push_back(level_phase - std::acos(reach));
    }
    // The breaks onto the leading half's turn.
    for (double& t : breaks) t = centre + std::remainder(t - centre, 2 * kPi);
    const double area = integrate_capped<1>(
        [&](double t) {
          const double x = radius_ * std::cos(t), y = radius_ * std::sin(t);
          const double stock = (c0_ - normal_.x() * x - normal_.y() * y) / normal_.z();
          const double kept = std::min(stock, removal.shank_removed_above(x, y));
          return std::array<double, 1>{radius_ * std::max(0.0, kept)};
        },
        breaks_within(breaks, centre - kPi / 2, centre + kPi / 2), kRelative, absolute, kPanels)[0];
    add({area, 2 * radius_ * area});
  } else if (top > 0) {
    // Below this height the whole circle is in the stock.
    std::vector<double> breaks{(c0_ - radius_ * tilt) / normal_.z()};
    add(integrate([&](double z) { return circle(radius_, z, 1, 0, radius_); },
                  breaks_within(breaks, 0.0, top)));
  }
  return sum[0] > 0 ? sum[1] / sum[0] : 0.0;
}

// The bull-nose's mean by Green's theorem on the tool's surface (where
// the end face is not all but parallel to F, |F_z| >= 1e-5: see
// kNearlyEdgeOn). Around the axis, with s the meridian's arc length from
// the face's centre, the 1-forms H1 dtheta and H2 dtheta with dH1/ds = r
// and dH2/ds = 2 r^2 (r the distance from the axis, theta the angle round
// it) have the area element dA and 2 r dA as their exterior derivatives,
// one 1-form on the whole surface (H continuous across the face's rim and
// the shank's foot, H = 0 on the axis):
//   face (r <= R0):  H1 = r^2 / 2,  H2 = 2 r^3 / 3;
//   corner (r = R0 + rc sin psi, z = -rc cos psi):  H1 = R0^2 / 2 + rc (R0
//     psi + rc (1 - cos psi)),  H2 = 2 R0^3 / 3 + 2 rc (R0^2 psi + 2 R0 rc (1
//     - cos psi) + rc^2 (psi - sin psi cos psi) / 2);
//   shank (z >= 0):  H1 = H1(pi / 2) + R z,  H2 = H2(pi / 2) + 2 R^2 z.
// So the engaged zone E's area and moment are the integrals of H dtheta
// around its boundary, the front points of G's boundary (the front map
// takes G onto E one to one, keeping the orientation; the ratio of the
// two does not depend on it):
// - the far and near silhouettes: the silhouette itself, whose point at
//   the angle theta round the axis (U_xy along it) is in closed form, so
//   H dtheta is integrated in theta (in phi, a face nearly parallel to F
//   sweeps the silhouette round its rim within a sliver of phi);
// - the shanks' rays: vertical lines, dtheta = 0;
// - the shifted silhouette and the stock line: the fibres' front points,
//   walked, their motion from the fibre's, d x0, as x = x0 + t F stays on
//   the tool: dx = d x0 - (n.d x0) / (n.F) F.
// Each piece is cut where its front point changes piece of the tool (a
// kink): the stock line's in closed form (circle_at_level), the shifted
// silhouette's by shifted_junctions, its part beside the shank's ray
// where the vertical plane of its fibres meets the circle. No removal
// test and a one-dimensional quadrature to `relative`, capped at
// `panels` a piece (1e-5 and 16 off level, 1e-6 and 32 nearly level,
// see kNearlyEdgeOn): 16-38 us a mean on the bench's set-ups
// where the area's double quadrature took 180-540 us, within 1.3e-6 mm
// of that taken to 1e-10 (1,440 random set-ups with |F_z| >= 1e-3).
// Feeds just off the threshold need the 16: with |F_z| in 1e-3..3e-3 (200
// set-ups) a cap of 8 left means up to 6.1e-4 mm off (a piece whose front
// points race round the face's rim), 16 within 3e-5 mm at the same median
// time.
class Groove::BoundaryMean {
 public:
  BoundaryMean(const Groove& groove, double relative, int panels)
      : g_(groove),
        relative_(relative),
        panels_(panels),
        absolute_(1e-14 * groove.radius_ * groove.radius_ * groove.radius_),
        at_foot_(corner_potentials(0, 1, kPi / 2)) {}

  // The ratio of the sums: the moment over the area.
  double value() const { return sum_[0] != 0 ? sum_[1] / sum_[0] : 0.0; }

  // The pieces' tolerance from the start as if the stock line, from front
  // point p to q, were in: about H1 times the angle between them round the
  // axis (the lesser way: not more than the line's own), one of the
  // largest pieces. Added last, it left the pieces before it tolerances
  // set by the far silhouette alone, often a sliver: of the nearly level
  // set-ups the slowest chased round-off at a piece's end (beside a top,
  // where the fibres missed the tool for 2e-13 mm) to an absolute 1.2e-7
  // where the pieces' areas came to 19.
  void expect_stock_line(const Vector3d& p, const Vector3d& q) {
    const double turn =
        std::remainder(std::atan2(q.y(), q.x()) - std::atan2(p.y(), p.x()), 2 * kPi);
    expected_ = 0.5 * (potentials(p)[0] + potentials(q)[0]) * std::abs(turn);
  }

  // The silhouette from phi a to phi b, by the angle round the axis
  // (monotone along the lower silhouette: U_xy turns one way).
  void silhouette(double a, double b) {
    if (a == b) return;
    const auto normal_at = [&](double phi) {
      const auto [c, s] = g_.cos_sin(phi);
      return std::pair{Vector3d(c * g_.side_ + s * g_.normal_),
                       Vector3d(-s * g_.side_ + c * g_.normal_)};
    };
    const auto azimuth = [&](double phi) {
      const Vector3d u = normal_at(phi).first;
      return std::atan2(u.y(), u.x());
    };
    const auto [u, du] = normal_at(0.5 * (a + b));
    const double way = (u.x() * du.y() - u.y() * du.x()) * (b - a) > 0 ? 1 : -1;
    const double from = azimuth(a);
    double span = std::remainder(azimuth(b) - from, 2 * kPi);
    if (span * way < 0) span += way * 2 * kPi;
    add([&](double theta) { return silhouette_by_azimuth(theta); }, from, from + span);
  }

  // The shifted silhouette beside the silhouette, from phi a to phi b.
  void shifted_beside_silhouette(double a, double b) {
    const auto shifted = [&](double phi) {
      const auto [c, s] = g_.cos_sin(phi);
      const auto [p, dp] = g_.silhouette_and_tangent(c, s);
      return at_front(p + g_.ae_ * g_.side_, dp);
    };
    const double lo = std::min(a, b), hi = std::max(a, b);
    std::vector<double> cuts = g_.shifted_junctions(lo, hi);
    // At the silhouette's most vertical normal, phi* = omega + pi, |U_xy|
    // = |F_z|: S(phi) races round the face's rim, and the integrand spikes
    // like 1 / ((phi - phi*)^2 + F_z^2). Cut there and at 4^k 4 |F_z| either
    // side (each cut piece a ratio of 4 of the spike's tail): on the
    // nearly level set-ups that chased it, at most 145 -> 117 us a mean.
    const double spike = g_.phi_vertical_;
    if (spike > lo && spike < hi) {
      cuts.push_back(spike);
      double d = 4 * std::abs(g_.feed_.z());
      while (d > 0 && d < 0.25 * (hi - lo)) {
        cuts.push_back(spike - d);
        cuts.push_back(spike + d);
        d *= 4;
      }
    }
    add(shifted, a, b, std::move(cuts));
  }

  // The shifted silhouette beside the shank's ray, by the height h above
  // its foot from h_from to h_to, cut where the vertical plane of its
  // fibres meets the junction circles.
  void shifted_beside_ray(double h_from, double h_to) {
    const Vector3d& feed = g_.feed_;
    const Vector3d start = g_.foot_left_ + g_.ae_ * g_.side_;
    std::vector<double> cuts;
    for (const Junction& j : g_.junctions()) {
      // The fibre of start + h z meets the circle's plane at xy = A + h B.
      const double t = (j.z - start.z()) / feed.z();
      const double ax = start.x() + t * feed.x(), ay = start.y() + t * feed.y();
      const double bx = -feed.x() / feed.z(), by = -feed.y() / feed.z();
      const double qa = bx * bx + by * by, qb = ax * bx + ay * by;
      const double disc = qb * qb - qa * (ax * ax + ay * ay - j.rho * j.rho);
      if (!(qa > 0) || disc < 0) continue;
      for (const double root : {-std::sqrt(disc), std::sqrt(disc)}) {
        const double h = (-qb + root) / qa;
        if (g_.front_on(j, ax + h * bx, ay + h * by)) cuts.push_back(h);
      }
    }
    const auto shifted = [&](double h) {
      return at_front(start + h * Vector3d::UnitZ(), Vector3d::UnitZ());
    };
    add(shifted, h_from, h_to, std::move(cuts));
  }

  // The stock line from b_from to b_to, cut where its front point crosses
  // the face's rim or the shank's foot.
  void stock_line(double b_from, double b_to) {
    std::vector<double> cuts;
    g_.add_junction_cuts(g_.c0_, cuts);
    if (g_.face_in_front_ && g_.corner_ > 0) {
      stock_line_where_the_face_leads(b_from, b_to, cuts);
    } else {
      add([&](double b) { return along_stock(b); }, b_from, b_to, std::move(cuts));
    }
  }

 private:
  using Sums = std::array<double, 2>;

  // H1 and H2 on the corner at the meridian angle psi.
  Sums corner_potentials(double cos_psi, double sin_psi, double psi) const {
    const double r0 = g_.flat_radius_, rc = g_.corner_;
    return {r0 * r0 / 2 + rc * (r0 * psi + rc * (1 - cos_psi)),
            2 * r0 * r0 * r0 / 3 + 2 * rc *
                                       (r0 * r0 * psi + 2 * r0 * rc * (1 - cos_psi) +
                                        rc * rc * (psi - sin_psi * cos_psi) / 2)};
  }
  Sums potentials(const Vector3d& p) const {
    const double r0 = g_.flat_radius_, R = g_.radius_;
    const double r = length_of(p.x(), p.y());
    if (p.z() >= 0) return {at_foot_[0] + R * p.z(), at_foot_[1] + 2 * R * R * p.z()};
    if (r <= r0) return {r * r / 2, 2 * r * r * r / 3};
    const double out = r - r0, down = -p.z(), length = length_of(out, down);
    return corner_potentials(down / length, out / length, std::atan2(out, down));
  }
  // H dtheta / ds at p moving at dp.
  Sums along(const Vector3d& p, const Vector3d& dp) const {
    const double r2 = p.x() * p.x() + p.y() * p.y();
    if (!(r2 > 0)) return {0, 0};
    const double turn = (p.x() * dp.y() - p.y() * dp.x()) / r2;
    const auto h = potentials(p);
    return {h[0] * turn, h[1] * turn};
  }

  // The front point of the fibre through x0. Its walk starts where the
  // fibre meets the tangent plane of the last front point: the tool is
  // convex, so that plane holds it on one side and the start lies beyond
  // the front, as the walk needs (two or three steps from there instead
  // of five or six from the cylinder).
  std::optional<Vector3d> front_of(const Vector3d& x0) const {
    if (last_.lead > 1e-3) {
      CoreWalk walk(x0, last_.normal.dot(last_.p - x0) / last_.lead, -1);
      while (!walk.done) g_.step(walk);
      if (walk.at) return x0 + *walk.at * g_.feed_;
    }
    return g_.front_point(x0);
  }
  // H dtheta / ds at the front point of the fibre through x, moving at dx.
  Sums at_front(const Vector3d& x, const Vector3d& dx) {
    const Vector3d& feed = g_.feed_;
    const std::optional<Vector3d> p = front_of(x - feed.dot(x) * feed);
    last_.lead = 0;
    if (!p) return {0, 0};
    const Vector3d normal = g_.surface_normal(*p);
    const double lead = normal.dot(feed);
    if (!(lead > 1e-12)) return {0, 0};
    last_ = {*p, normal, lead};
    return along(*p, dx - normal.dot(dx) / lead * feed);
  }
  Sums along_stock(double b) { return at_front(b * g_.side_ + g_.c0_ * g_.normal_, g_.side_); }

  // The silhouette's point with U_xy along (cos theta, sin theta): U is
  // normal to F, so cos(phi) (e_xy x d) + sin(phi) (N_xy x d) = 0.
  Sums silhouette_by_azimuth(double theta) const {
    const Vector3d &e = g_.side_, &n = g_.normal_;
    const double dx = std::cos(theta), dy = std::sin(theta);
    const double across_e = e.x() * dy - e.y() * dx;
    const double across_n = n.x() * dy - n.y() * dx;
    const double length = length_of(across_e, across_n);
    double cos_phi = across_n / length, sin_phi = -across_e / length;
    if (cos_phi * (e.x() * dx + e.y() * dy) + sin_phi * (n.x() * dx + n.y() * dy) < 0) {
      cos_phi = -cos_phi;
      sin_phi = -sin_phi;
    }
    return potentials(g_.silhouette_at(cos_phi, sin_phi));
  }

  // Adds f's integral from a to b (either way round), cut at `cuts`. A
  // piece need not be exact beyond `relative` of the pieces' area so far,
  // unsigned, or of the stock line's expected (the pieces' sum is the
  // zone's area, and a sliver of a piece asked to its own relative
  // tolerance took its cap).
  template <class Function>
  void add(const Function& f, double a, double b, std::vector<double> cuts = {}) {
    if (a == b) return;
    const double absolute = std::max(absolute_, 0.1 * relative_ * std::max(scale_, expected_));
    // The moment's tolerance R times the area's, so that the two weigh
    // alike in their ratio (the same one held the moment, in mm^3, R times
    // tighter than the area: p99 123 -> 96 us on the nearly level means).
    const auto v = integrate_smoothed_pieces<2>(
        f, breaks_within(std::move(cuts), std::min(a, b), std::max(a, b)), relative_,
        Sums{absolute, g_.radius_ * absolute}, panels_);
    const double sign = b > a ? 1 : -1;
    sum_[0] += sign * v[0];
    sum_[1] += sign * v[1];
    scale_ += std::abs(v[0]);
  }

  // The stock line from b_from to b_to (cut at `cuts`) where the face
  // leads. The stretch of the corner beside the face's rim goes by a =
  // F.P instead of b: there the rim (the tool cut by the stock plane) runs
  // nearly along F, b moving by about F_z to a's 1, and the fibres that
  // graze the rim make an inner layer, about rc F_z^2 wide in b, that b's
  // quadrature chased to its cap. The rim's point at a lies on the line
  // c0 N + a F + b e, walked onto from the stretch's end outside it (the
  // rim is convex: the end on its outer side, -e where the rim faces -e,
  // is outside on every such line), and moves as dP/da = F - (n.F / n.e)
  // e. Where the rim faces along F (n.e = 0) a curve by a turns back: a
  // stretch holding that point is cut there (bisection on n.e's sign).
  void stock_line_where_the_face_leads(double b_from, double b_to, const std::vector<double>& cuts);
  // Its stretch [lo, hi] of b (front points p_lo, p_hi, n.e of one sign
  // `turn`) by a, from the end `from_lo` says to the other.
  void stock_line_by_feed(double lo, const Vector3d& p_lo, double hi, const Vector3d& p_hi,
                          double turn, bool from_lo);

  struct Front {
    Vector3d p, normal;
    double lead = 0;
  };
  const Groove& g_;
  double relative_;
  int panels_;
  double absolute_;
  Sums at_foot_;  // the potentials at the shank's foot
  Sums sum_{};
  double scale_ = 0;     // the pieces' area so far, unsigned
  double expected_ = 0;  // the stock line's, roughly (expect_stock_line)
  Front last_;           // the last front point met
};

void Groove::BoundaryMean::stock_line_by_feed(double lo, const Vector3d& p_lo, double hi,
                                              const Vector3d& p_hi, double turn, bool from_lo) {
  const Vector3d &feed = g_.feed_, &side = g_.side_;
  const double outer = turn < 0 ? lo : hi, toward = turn < 0 ? 1.0 : -1.0;
  const auto by_feed = [&](double a) -> Sums {
    const Vector3d base = g_.c0_ * g_.normal_ + a * feed;
    CoreWalk walk(base, outer, toward, &side);
    while (!walk.done) g_.step(walk);
    if (!walk.at) return {0, 0};
    const Vector3d p = base + *walk.at * side;
    const Vector3d n = g_.surface_normal(p);
    const double lead = n.dot(feed), across = n.dot(side);
    if (!(lead > 0) || across == 0) return {0, 0};
    return along(p, feed - lead / across * side);
  };
  const double a_lo = feed.dot(p_lo), a_hi = feed.dot(p_hi);
  add(by_feed, from_lo ? a_lo : a_hi, from_lo ? a_hi : a_lo);
}

void Groove::BoundaryMean::stock_line_where_the_face_leads(double b_from, double b_to,
                                                           const std::vector<double>& cuts) {
  const double R = g_.radius_;
  std::vector<double> rim_cuts;
  for (const Vector3d& p : g_.circle_at_level(g_.flat_radius_, -g_.corner_, g_.c0_))
    rim_cuts.push_back(g_.side_.dot(p));
  const auto on_rim = [&](double b) {
    return std::any_of(rim_cuts.begin(), rim_cuts.end(), [&](double r) { return r == b; });
  };
  const auto front_at = [&](double b) {
    return g_.front_point(b * g_.side_ + g_.c0_ * g_.normal_);
  };
  const auto turn_at = [&](const Vector3d& p) { return g_.surface_normal(p).dot(g_.side_); };
  const std::vector<double> pieces =
      breaks_within(cuts, std::min(b_from, b_to), std::max(b_from, b_to));
  const bool from_lo = b_to > b_from;
  for (std::size_t k = 0; k + 1 < pieces.size(); ++k) {
    const double lo = pieces[k], hi = pieces[k + 1];
    const auto p_lo = front_at(lo), p_hi = front_at(hi), p_mid = front_at(0.5 * (lo + hi));
    const bool beside_rim = (on_rim(lo) || on_rim(hi)) && p_lo && p_hi && p_mid && p_mid->z() < 0 &&
                            length_of(p_mid->x(), p_mid->y()) > g_.flat_radius_;
    const double turn_lo = beside_rim ? turn_at(*p_lo) : 0,
                 turn_hi = beside_rim ? turn_at(*p_hi) : 0;
    if (turn_lo * turn_hi > 0) {
      stock_line_by_feed(lo, *p_lo, hi, *p_hi, turn_lo, from_lo);
      continue;
    }
    std::optional<std::pair<double, Vector3d>> facing_f;  // (b, front point) where n.e = 0
    if (turn_lo * turn_hi < 0) {
      double a = lo, b = hi;
      for (int i = 0; i < 200 && b - a > 1e-15 * R; ++i) {
        const double middle = 0.5 * (a + b);
        const auto p = front_at(middle);
        if (!p) break;
        ((turn_at(*p) < 0) == (turn_lo < 0) ? a : b) = middle;
      }
      if (const auto p = front_at(0.5 * (a + b))) facing_f = std::pair{0.5 * (a + b), *p};
    }
    if (!facing_f) {
      add([&](double b) { return along_stock(b); }, from_lo ? lo : hi, from_lo ? hi : lo);
      continue;
    }
    const auto& [cut, p_cut] = *facing_f;
    // In the order of travel.
    if (from_lo) {
      stock_line_by_feed(lo, *p_lo, cut, p_cut, turn_lo, true);
      stock_line_by_feed(cut, p_cut, hi, *p_hi, turn_hi, true);
    } else {
      stock_line_by_feed(cut, p_cut, hi, *p_hi, turn_hi, false);
      stock_line_by_feed(lo, *p_lo, cut, p_cut, turn_lo, false);
    }
  }
}

// The pieces of the boundary, each added to BoundaryMean's sums.
double Groove::mean_over_boundary(double relative, int panels) const {
  BoundaryMean mean(*this, relative, panels);
  const BoundaryPoint& left_top = top(true);
  const WidthLevel level = width_level();
  // The stock line's right end: the shifted silhouette's top or bR(c0).
  if (level.c >= c0_)
    mean.expect_stock_line(top(false).p, left_top.p);
  else if (const auto& fibre = inner_top_fibre(true))
    mean.expect_stock_line(fibre->first, left_top.p);
  // The far silhouette, c0 down to the bottom (a ray above its foot adds nothing).
  mean.silhouette(left_top.ray > 0 ? phi_left_ : left_top.phi, phi_bottom_);
  // The near one, the bottom up to c*.
  mean.silhouette(phi_bottom_, level.right.ray > 0 ? phi_right_ : level.right.phi);
  // The shifted silhouette, c* up to c0: beside the silhouette by phi, and
  // beside the shank's ray by the height above its foot.
  const double c_foot = c_foot_[0];
  if (level.c < c0_ && level.c < c_foot)
    mean.shifted_beside_silhouette(level.left.phi, c0_ > c_foot ? phi_left_ : left_top.phi);
  if (level.c < c0_ && c0_ > c_foot)
    mean.shifted_beside_ray(std::max(0.0, (level.c - c_foot) / normal_.z()),
                            (c0_ - c_foot) / normal_.z());
  // The stock line, from its right end back to bL(c0).
  mean.stock_line(level.c < c0_ ? left_top.b + ae_ : top(false).b, left_top.b);
  return mean.value();
}

// The cut for level_engagement.h: with F turned level, N and e with it,
// when it is not quite (the mean where |F_z| < 1e-5, see kOffLevel).
LevelCut Groove::level_cut() const {
  Vector3d normal = normal_, side = side_;
  const Vector3d level = Vector3d(feed_.x(), feed_.y(), 0).normalized();
  if (!edge_on_) {
    const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(feed_, level);
    normal = turn * normal_;
    side = turn * side_;
  }
  LevelCut cut;
  cut.flat_radius = flat_radius_;
  cut.corner = corner_;
  cut.ae = ae_;
  // ap keeps its meaning, the depth below the tool's lowest point along N.
  cut.stock_level = c0_ - c_min_ - flat_radius_ * length_of(normal.x(), normal.y()) - corner_;
  cut.normal = normal;
  cut.side = side;
  cut.feed = level;
  cut.face_leads = face_leads();
  return cut;
}

double Groove::mean_when_level() const {
  const auto [area, moment] = level_area_and_moment(level_cut());
  return area > 0 ? moment / area : 0.0;
}

RadiusExtremes Groove::level_extremes() const { return geometry::level_extremes(level_cut()); }

// Ra of the transverse profile on the tangent plane, whose peak is the
// cusp at the width level c* (the profile repeats every ae: this tool's right boundary up to the
// cusp, the previous one's left down from it, and a face seen edge-on in
// between at the bottom). Its mean line m and Ra = (1 / ae) int |z - m| db
// over a period, twice the part above m (z - m sums to 0). Below the feet
// the boundaries are Q's silhouette, and in its parameter phi, int z db =
// int (c(phi) - c_min) b'(phi) dphi takes no root (only where z crosses
// m); above a foot, where the profile's sides are rays, by layers: above
// the level t over CC the profile spans w(t) = ae - width(c_min + t) of
// the period, so m = (1 / ae) int_0^rz w and Ra = (2 / ae) int_m^rz w,
// rz = c* - c_min.
double Groove::plane_roughness(const WidthLevel& cusp) const {
  const double top = cusp.c, rz = top - c_min_;
  const BoundaryPoint &left = cusp.left, &right = cusp.right;
  const double scale = 1e-12 * radius_ * ae_;
  if (left.ray == 0 && right.ray == 0) {
    const auto piece = [&](double from, double to, double mean) {
      const auto z_db = [&](double phi) {
        const auto [cos_phi, sin_phi] = cos_sin(phi);
        const auto [p, dp] = silhouette_and_tangent(cos_phi, sin_phi);
        return std::array<double, 1>{std::abs(normal_.dot(p) - c_min_ - mean) * side_.dot(dp)};
      };
      return integrate_capped<1>(z_db, from, to, 1e-8, scale, 64)[0];
    };
    const double bottom = phi_bottom_;
    const double mean = (piece(left.phi, bottom, 0) + piece(bottom, right.phi, 0)) / ae_;
    // z - m sums to 0 over a period: |z - m| to twice its part above m.
    const double left_m = boundary(c_min_ + mean, true).phi,
                 right_m = boundary(c_min_ + mean, false).phi;
    return 2 * (piece(left.phi, left_m, mean) + piece(right_m, right.phi, mean)) / ae_;
  }
  // In u = sqrt(c - c_min): Q's width grows as sqrt(c - c_min) from its
  // bottom (a curve's or a face's ends), w(c) dc = w 2 u du is smooth.
  const auto w = [&](double u) {
    const double c = c_min_ + u * u;
    return std::array<double, 1>{2 * u * (ae_ - (boundary(c, false).b - boundary(c, true).b))};
  };
  // The boundaries bend where they pass onto the shank's rays.
  const auto layers = [&](double from, double to) {
    std::vector<double> feet;
    for (const double c_foot : c_foot_) {
      if (c_foot > c_min_) feet.push_back(std::sqrt(c_foot - c_min_));
    }
    return integrate_capped<1>(
        w, breaks_within(feet, std::sqrt(from - c_min_), std::sqrt(to - c_min_)), 1e-8, scale,
        64)[0];
  };
  const double mean = std::clamp(layers(c_min_, top) / ae_, 0.0, rz);
  return 2 / ae_ * layers(c_min_ + mean, top);
}

// Seen along F both tools are Q: this one touching the surface at its
// bottom CC, the previous one shifted by D across the feed to where it
// touches too, and the cusp is where their outlines meet between the
// contacts: the end X of the chord of Q parallel to D and as long (X and
// X - D both on its boundary), the lower of the two. That chord is the
// width level of the same Q seen in the frame turned about F to e' = D /
// |D| (N' normal to it): the groove with ae' = |D| and no stock level.
// - D: on the tangent plane (ae, 0). On the circle of curvature k the
//   previous pass touches at the arc s from CC, where the surface's normal
//   has turned by k s about F, so with the point of Q whose outward normal
//   is minus that one (its silhouette at phi_bottom - k s): D(s) = CC(s) -
//   that point, and s is where |D(s)| = ae (the pass tracker's ae is the
//   distance across the feed between the tools' positions).
// - The height: above CC on the tangent plane, radially above the circle
//   on a curved surface.
// - Rz: the cusp's height on the tangent plane (D = (ae, 0)); Ra:
//   plane_roughness.
RevolvedCusp Groove::cusp(const Tool& tool, double k, std::optional<double> contact_b) const {
  RevolvedCusp out;
  if (!(ae_ > 0)) return out;
  const double bottom_lo = boundary(c_min_, true).b, bottom_hi = boundary(c_min_, false).b;
  const double b_cc =
      contact_b ? std::clamp(*contact_b, bottom_lo, bottom_hi) : 0.5 * (bottom_lo + bottom_hi);
  // The chord's end X for the shift (db, dc): empty where no chord of Q
  // is that long (ae beyond the tools' reach, or a frame turned past the
  // horizontal).
  const auto meeting = [&](double db, double dc) -> std::optional<WidthLevel> {
    const double length = length_of(db, dc);
    const Vector3d along = (db * side_ + dc * normal_) / length;
    const Vector3d across = (db * normal_ - dc * side_) / length;
    if (!(across.z() > 0)) return std::nullopt;
    // No stock level in reach: ap beyond the feet by twice the tool's width.
    const double ap = std::max(c_foot_[0], c_foot_[1]) - c_min_ + 4 * radius_;
    const Groove turned(tool, feed_, across, along, ap, length);
    const WidthLevel level = turned.width_level();
    if (!(level.c < turned.c0_)) return std::nullopt;
    return level;
  };
  // On the tangent plane (the turned frame is this one): Rz and Ra.
  const std::optional<WidthLevel> flat = meeting(ae_, 0);
  if (!flat) return out;
  out.rz = flat->c - c_min_;
  out.ra = *out.rz > 0 ? plane_roughness(*flat) : 0.0;
  if (!(std::abs(k) > 1e-9 / radius_)) {
    out.height = out.rz;
    return out;
  }
  // D(s), this tool at the origin.
  const auto shift = [&](double s) {
    const auto [cos_ks, sin_ks] = cos_sin_small(k * s);
    const Vector3d p = silhouette(phi_bottom_ - k * s);
    return std::array<double, 2>{b_cc + sin_ks / k - side_.dot(p),
                                 c_min_ - (1 - cos_ks) / k - normal_.dot(p)};
  };
  const auto miss = [&](double s) {
    const auto [db, dc] = shift(s);
    return length_of(db, dc) - ae_;
  };
  // With its slope: D'(s) = (cos ks, -sin ks) + k (e.S', N.S') at phi_bottom - k s.
  const auto miss_and_slope = [&](double s) {
    const auto [db, dc] = shift(s);
    const auto [cos_ks, sin_ks] = cos_sin_small(k * s);
    const auto [cos_phi, sin_phi] = cos_sin(phi_bottom_ - k * s);
    const Vector3d tangent = silhouette_and_tangent(cos_phi, sin_phi).second;
    const double length = length_of(db, dc);
    const double d_db = cos_ks + k * side_.dot(tangent), d_dc = -sin_ks + k * normal_.dot(tangent);
    return std::pair{length - ae_, (db * d_db + dc * d_dc) / length};
  };
  // s from just beside CC (where a face seen edge-on may already reach
  // ae: the previous tool's face then covers CC, no cusp) out to where the
  // normal has turned a quarter turn (a previous pass beyond is none).
  // Just beside: the normal turned by 1e-10, as boundary() steps beside
  // the bottom (a face level within round-off, N_xy 1e-14, took the
  // previous tool's touching point from its middle for its end).
  const double tolerance = 1e-12 * radius_;
  const double s_lo = std::max(tolerance, 1e-10 / std::abs(k)), s_max = kPi / 2 / std::abs(k);
  const double g_lo = miss(s_lo);
  if (g_lo >= 0) {
    out.height = 0;
    return out;
  }
  double s_hi = std::min(ae_, s_max), g_hi = miss(s_hi);
  while (g_hi < 0 && s_hi < s_max) {
    s_hi = std::min(2 * s_hi, s_max);
    g_hi = miss(s_hi);
  }
  if (g_hi < 0) return out;  // the previous pass beyond the model's reach
  const double s = newton_root(miss_and_slope, s_lo, s_hi, g_lo, g_hi, tolerance);
  const auto [db, dc] = shift(s);
  const std::optional<WidthLevel> level = meeting(db, dc);
  if (!level) return out;
  // X, radially above the circle through CC, centre (b_cc, c_min - 1 / k).
  const Vector3d& x = level->right.p;
  const double from_centre = length_of(side_.dot(x) - b_cc, normal_.dot(x) - c_min_ + 1 / k);
  out.height = k > 0 ? from_centre - 1 / k : -1 / k - from_centre;
  return out;
}

struct Prepared {
  Engagement out;
  std::optional<Groove> groove;
  double ae = 0;
};

// Frame and degenerate-input flags, as evaluate_engagement documents them.
Prepared prepare(const Tool& tool, const CutSetup& setup) {
  Prepared prepared;
  Engagement& out = prepared.out;
  if (!(setup.ap > 0)) out.flags.set(EngagementFlag::zero_ap);
  if (!(setup.ae > 0)) out.flags.set(EngagementFlag::zero_ae);
  if (setup.ap >= tool.diameter) out.flags.set(EngagementFlag::ap_exceeds_d);
  const double n_length = setup.normal.norm();
  if (!(n_length > 0) || !(setup.normal.z() / n_length > 0)) {
    out.flags.set(EngagementFlag::undercut);
  } else {
    const Vector3d normal = setup.normal / n_length;
    const Vector3d tangent = setup.feed - setup.feed.dot(normal) * normal;
    if (!(tangent.norm() > 1e-9 * setup.feed.norm())) {
      out.flags.set(EngagementFlag::feed_along_normal);
    } else {
      out.normal = normal;
      out.feed_dir = tangent.normalized();
      out.side_dir = normal.cross(out.feed_dir);
    }
  }
  const std::uint32_t fatal = static_cast<std::uint32_t>(EngagementFlag::zero_ap) |
                              static_cast<std::uint32_t>(EngagementFlag::ap_exceeds_d) |
                              static_cast<std::uint32_t>(EngagementFlag::undercut) |
                              static_cast<std::uint32_t>(EngagementFlag::feed_along_normal);
  if ((out.flags.bits & fatal) == 0) {
    // With ae = 0 the rim still exists: build the groove with ae = 0 for the points.
    const double sign = setup.side == Side::left ? 1.0 : -1.0;
    prepared.ae = std::max(0.0, setup.ae);
    prepared.groove.emplace(tool, out.feed_dir, out.normal, sign * out.side_dir, setup.ap,
                            prepared.ae);
  }
  return prepared;
}

CuttingPoint cutting_point(const Vector3d& p) { return {p, 2 * length_of(p.x(), p.y())}; }

// The Mgherony-Miko points on the rim c = c0, in S0 = side_dir coordinates.
CuttingPoints cutting_points(const Groove& groove, const Engagement& out, Side side, double ae) {
  const bool left = side == Side::left;
  using Fibre = std::optional<std::pair<Vector3d, Vector3d>>;  // front and back
  Vector3d low, high;           // the rim points of least and greatest s
  std::array<Fibre, 2> primes;  // the fibres at s_min + ae and s_max - ae
  if (groove.edge_on()) {
    const LevelRim rim = level_rim(groove.level_cut());
    std::tie(low, high, primes[0], primes[1]) =
        std::tuple{rim.low, rim.high, rim.beside_low, rim.beside_high};
  } else {
    // e = +S0 when left: the smallest s is the left boundary; else the right.
    low = groove.top(left).p;
    high = groove.top(!left).p;
    const double s_min = out.side_dir.dot(low), s_max = out.side_dir.dot(high);
    // The primes' fibres beside the low and the high top (b = bL + ae
    // beside the left top, bR - ae beside the right one); outside (s_min,
    // s_max) there are none.
    if (ae > 0 && s_min + ae < s_max) {
      const auto beside = [&](bool left_top) {
        return left_top ? groove.inner_top_fibre(false)
                        : groove.fibre_beside(groove.top(false), -ae, false);
      };
      primes = {beside(left), beside(!left)};
    }
  }
  CuttingPoints points;
  points.p1 = cutting_point(low);
  points.p2 = cutting_point(high);
  // Without a fibre the far rim point stands for both primes.
  const std::array<Vector3d, 2> fallback{high, low};
  std::array<std::pair<CuttingPoint, CuttingPoint>, 2> pairs;
  for (std::size_t i = 0; i < 2; ++i) {
    pairs[i] = primes[i]
                   ? std::pair{cutting_point(primes[i]->first), cutting_point(primes[i]->second)}
                   : std::pair{cutting_point(fallback[i]), cutting_point(fallback[i])};
  }
  std::tie(points.p1a, points.p1b) = pairs[0];
  std::tie(points.p2a, points.p2b) = pairs[1];
  points.cut = left ? points.p1 : points.p2;
  return points;
}

}  // namespace

Engagement evaluate_revolved_engagement(const Tool& tool, const CutSetup& setup,
                                        CuttingPointsWanted points) {
  Prepared prepared = prepare(tool, setup);
  Engagement& out = prepared.out;
  if (!prepared.groove) {
    out.flags.set(EngagementFlag::nothing_engaged);
    return out;
  }
  const Groove& groove = *prepared.groove;
  if (points == CuttingPointsWanted::yes)
    out.points = cutting_points(groove, out, setup.side, prepared.ae);
  if (!(prepared.ae > 0)) {
    out.flags.set(EngagementFlag::nothing_engaged);
    return out;
  }
  const RadiusExtremes extremes = groove.edge_on() ? groove.level_extremes() : groove.extremes();
  if (!(extremes.r_max >= extremes.r_min)) {
    out.flags.set(EngagementFlag::nothing_engaged);
    return out;
  }
  out.d_min = 2 * extremes.r_min;
  out.d_max = 2 * extremes.r_max;
  if (extremes.z_max > 1e-9 * groove.radius()) {
    // The shank's points are at r = R up to round-off of their position.
    out.flags.set(EngagementFlag::shank_engaged);
    out.d_max = tool.diameter;
  }
  return out;
}

RevolvedCusp revolved_cusp(const Tool& tool, const CutSetup& setup, double curvature_across,
                           const std::optional<Eigen::Vector3d>& contact_offset) {
  // A contact inside the end face: the surface touches the face's plane
  // there, its normal is the axis (a crest's model normal may stand off it
  // by the contact's round-off, 1e-14..5e-10, which tilted the face and
  // moved the contact to its edge: cusps of 2-400 um on the wavy sample's
  // crests).
  CutSetup level = setup;
  // (The face: radius R0, rc below the frame's origin; R and 0 for a flat mill.)
  const double slack = 1e-6 * tool.radius();
  if (contact_offset && std::abs(contact_offset->z() + tool.corner_radius) <= slack &&
      length_of(contact_offset->x(), contact_offset->y()) < tool.flat_radius() - slack) {
    level.normal = Vector3d::UnitZ();
  }
  const Prepared prepared = prepare(tool, level);
  if (!prepared.groove) return {};
  const Groove& groove = *prepared.groove;
  std::optional<double> contact_b;
  if (contact_offset) contact_b = groove.side().dot(*contact_offset);
  return groove.cusp(tool, curvature_across, contact_b);
}

std::optional<double> revolved_mean_diameter(const Tool& tool, const CutSetup& setup) {
  const Prepared prepared = prepare(tool, setup);
  if (!prepared.groove || !(prepared.ae > 0)) return std::nullopt;
  if (tool.kind == ToolKind::bull_nose) {
    const Groove& groove = *prepared.groove;
    switch (groove.mean_route()) {
      case Groove::MeanRoute::boundary:
        return groove.mean_over_boundary(1e-5, 16);
      case Groove::MeanRoute::fine_boundary:
        return groove.mean_over_boundary(1e-6, 32);
      case Groove::MeanRoute::level:
        return groove.mean_when_level();
    }
  }
  // The flat mill: along the profile when level, else circle by circle.
  if (prepared.groove->mean_route() == Groove::MeanRoute::level)
    return prepared.groove->mean_when_level();
  return prepared.groove->mean_diameter();
}

}  // namespace vcpost::geometry
