// The engaged zone of a ball mill, in the frame (a, b, c) = (F.P, S0.P, N.P)
// of cut_frame.h. The stock layer and both parts of the previous pass's
// sweep are prisms along F (F is normal to N and to S0), so they only
// constrain the projection p = (b, c); the leading-side condition picks the
// front half (a >= 0). Seen along F, the tool projects to a "2-D ball-end
// mill": the disk |p| <= R (the ball) plus a half-strip of width 2R (the
// shank) along d, the projection of the tool axis. The edge points engaged
// on the sphere are therefore those with
//   (1) c <= c0 = -(R - ap)                  inside the stock layer,
//   (2) a >= 0                               on the leading side,
//   (3) |p - o| >= R, o = (sigma ae, 0)     outside the previous ball's sweep,
//   (4) not (|u'| < R and v' > 0)            outside the previous shank's sweep,
// where u', v' are the coordinates of p - o across and along d. Where the
// zone's sphere point lies above the equator the tool's front is its shank
// (r = R); the zone is connected, so it reaches the shank exactly when the
// largest z on the sphere zone is >= 0.
// On the sphere r^2 = R^2 - z^2, so the extremes of r are those of z, a
// linear function: they lie on the zone's boundary or at the poles. The
// boundary consists of circles (the rim c = c0, the silhouette a = 0, the
// shank sweep's edges |u'| = R) where z is a sinusoid, and the previous
// ball's edge |p - o| = R, a curve on which z's stationary points are found
// by bracketed root finding on pieces where dz is monotone.
#include "geometry/ball_engagement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "geometry/angle_set.h"
#include "geometry/quadrature.h"
#include "geometry/sinusoid.h"

namespace vcpost::geometry {
namespace {

constexpr double half_pi = std::numbers::pi / 2;

double clamp_unit(double x) { return std::clamp(x, -1.0, 1.0); }
double sqrt0(double x) { return std::sqrt(std::max(0.0, x)); }

// cos and sin of half * kronrod_rule_nodes[i] for half <= pi/2 (an arc of
// the front half), by their Taylor series to the 21st order (the first
// term left out is below 2e-17 at pi/2), nested, all nodes at once:
// independent lanes where libm's seven calls, with their range reduction,
// were a third of the ball's mean.
struct NodeCosSin {
  std::array<double, 8> cos{}, sin{};
};
NodeCosSin node_cos_sin(double half) {
  constexpr int kTerms = 10;
  // 1 / ((2k - 1) 2k) and 1 / (2k (2k + 1)), k = 1 .. kTerms.
  constexpr auto ratios = [] {
    std::array<std::array<double, 2>, kTerms> r{};
    for (int k = 1; k <= kTerms; ++k) {
      r[static_cast<std::size_t>(k - 1)] = {1.0 / ((2 * k - 1) * (2 * k)),
                                            1.0 / ((2 * k) * (2 * k + 1))};
    }
    return r;
  }();
  std::array<double, 8> x{}, x2{};
  for (std::size_t j = 0; j < 8; ++j) {
    x[j] = half * kronrod_rule_nodes[j];
    x2[j] = x[j] * x[j];
  }
  NodeCosSin out;
  out.cos.fill(1);
  out.sin.fill(1);
  for (std::size_t k = kTerms; k-- > 0;) {
    for (std::size_t j = 0; j < 8; ++j) {
      out.cos[j] = 1 - x2[j] * ratios[k][0] * out.cos[j];
      out.sin[j] = 1 - x2[j] * ratios[k][1] * out.sin[j];
    }
  }
  for (std::size_t j = 0; j < 8; ++j) out.sin[j] *= x[j];
  return out;
}

// A vector in frame coordinates (a, b, c).
using FrameVector = Eigen::Vector3d;

// A circle P(t) = centre + cos t e1 + sin t e2 in frame coordinates; linear
// functionals of P along it are sinusoids in t.
struct FrameCircle {
  FrameVector centre, e1, e2;
  Sinusoid along(const FrameVector& l, double constant = 0) const {
    return {l.dot(e1), l.dot(e2), l.dot(centre) + constant};
  }
};

struct Ball {
  double R, ap, ae, sigma;
  CutFrame frame;
  double c0, rho;             // stock plane height along N and the rim circle's radius
  FrameVector up;             // the tool axis +z in frame coordinates: z = up.P
  FrameVector across, along;  // unit vectors across (u) and along (v) the projected axis d
  double offset;              // sigma * ae: the previous pass's centre line at b = offset, c = 0
  bool shank_sweep_matters;   // the previous shank's sweep reaches the stock layer

  Ball(double radius, const CutSetup& setup, const CutFrame& f)
      : R(radius), ap(setup.ap), ae(setup.ae), sigma(f.sigma), frame(f) {
    c0 = -(R - ap);
    rho = sqrt0(R * R - c0 * c0);
    up = {frame.feed.z(), frame.side.z(), frame.normal.z()};
    const double d = std::sqrt(up.y() * up.y() + up.z() * up.z());  // > 0 since N_z > 0
    along = {0, up.y() / d, up.z() / d};
    across = {0, up.z() / d, -up.y() / d};
    offset = sigma * ae;
    // The sweep's lowest points are its strip's corners, at c = -R |d_b| / |d|.
    shank_sweep_matters = -R * std::abs(along.y()) < c0;
  }

  double z(const FrameVector& p) const { return up.dot(p); }
  Eigen::Vector3d world(const FrameVector& p) const {
    return p.x() * frame.feed + p.y() * frame.side + p.z() * frame.normal;
  }
  FrameVector from_offset(const FrameVector& p) const { return p - FrameVector(0, offset, 0); }

  bool inside_previous_shank(const FrameVector& p) const {
    if (!shank_sweep_matters) return false;
    const FrameVector q = from_offset(p);
    constexpr double slack = 1e-12;
    return std::abs(across.dot(q)) < R * (1 - slack) && along.dot(q) > slack * R;
  }
  bool engaged(const FrameVector& p) const {
    constexpr double slack = 1e-12;
    const FrameVector q = from_offset(p);
    return p.z() <= c0 + slack * R && p.x() >= -slack * R &&
           q.y() * q.y() + q.z() * q.z() >= R * R * (1 - slack) && !inside_previous_shank(p);
  }

  // Removes from `set` the angles where the circle lies inside the previous shank's sweep.
  void remove_previous_shank(const FrameCircle& circle, AngleSet& set) const {
    if (!shank_sweep_matters || set.empty()) return;
    const FrameVector o(0, offset, 0);
    AngleSet inside = set;
    inside.keep_where(circle.along(across, -across.dot(o)), R);
    inside.keep_where(circle.along(-across, across.dot(o)), R);
    inside.keep_where(circle.along(-along, along.dot(o)), 0);
    set.remove(inside);
  }
};

Extremes extremes_on(const FrameCircle& circle, const AngleSet& set, const Ball& ball) {
  Extremes out;
  const Sinusoid z = circle.along(ball.up);
  for (int i = 0; i < set.size(); ++i) out.add(sinusoid_extremes(z, set[i]));
  return out;
}

// The angles t in [-pi/2, pi/2] with sigma sin t <= k: one interval.
AngleInterval front_half_where(double sigma, double k) {
  if (k >= 1) return {-half_pi, half_pi};
  const double t = std::asin(clamp_unit(k));
  return sigma > 0 ? AngleInterval{-half_pi, t} : AngleInterval{-t, half_pi};
}

// The rim c = c0 (a = rho cos t, b = rho sin t), where (3) reads sigma b <= ae - rho.
Extremes rim_extremes(const Ball& ball) {
  const FrameCircle rim{{0, 0, ball.c0}, {ball.rho, 0, 0}, {0, ball.rho, 0}};
  AngleSet set(front_half_where(ball.sigma, (ball.ae - ball.rho) / ball.rho));
  ball.remove_previous_shank(rim, set);
  return extremes_on(rim, set, ball);
}

// The silhouette a = 0 (b = R sin t, c = -R cos t): (1) reads |t| <= t0, and
// (3) sigma b <= ae/2, i.e. sigma sin t <= ae/2R, which removes the arc
// (t1, pi - t1) mirrored by sigma.
Extremes silhouette_extremes(const Ball& ball) {
  const FrameCircle silhouette{{0, 0, 0}, {0, 0, -ball.R}, {0, ball.R, 0}};
  const double t0 = std::acos(clamp_unit(-ball.c0 / ball.R));
  const double k = ball.ae / (2 * ball.R);
  AngleSet set;
  if (k >= 1) {
    set = AngleSet({-t0, t0});
  } else {
    const double t1 = std::asin(k), s = ball.sigma;
    // For sigma = +1 keep [-t0, min(t0, t1)] and [pi - t1, t0]; mirrored for -1.
    const AngleInterval near{-t0, std::min(t0, t1)}, far{std::numbers::pi - t1, t0};
    set = AngleSet(s > 0 ? near : AngleInterval{-near.hi, -near.lo});
    if (!far.empty()) set.add(s > 0 ? far : AngleInterval{-far.hi, -far.lo});
  }
  ball.remove_previous_shank(silhouette, set);
  return extremes_on(silhouette, set, ball);
}

// The edges |u'| = R of the previous shank's sweep (planes through F and the
// tool axis), on the front half, with v' >= 0; (3) holds there by itself.
Extremes shank_sweep_edge_extremes(const Ball& ball) {
  Extremes out;
  if (!ball.shank_sweep_matters) return out;
  const FrameVector o(0, ball.offset, 0);
  for (const double edge : {-ball.R, ball.R}) {
    const double k = ball.across.dot(o) + edge;  // the plane across.P = k
    if (std::abs(k) >= ball.R) continue;
    const double radius = std::sqrt(ball.R * ball.R - k * k);
    const FrameCircle circle{k * ball.across, {radius, 0, 0}, radius * ball.along};
    AngleSet set({-half_pi, half_pi});
    set.keep_where(circle.along({0, 0, 1}), ball.c0);
    set.keep_where(circle.along(-ball.along, ball.along.dot(o)), 0);
    out.add(extremes_on(circle, set, ball));
  }
  return out;
}

// The previous ball's edge, parametrised by the half-width w in [ae/2, R]:
// a = sqrt(ae (2w - ae)), sigma b = ae - w, c = branch * sqrt(R^2 - w^2).
struct EdgeCurve {
  const Ball& ball;
  double branch;  // -1: lower half of the sphere (c < 0), +1: upper

  double a(double w) const { return sqrt0(ball.ae * (2 * w - ball.ae)); }
  double c(double w) const { return branch * sqrt0(ball.R * ball.R - w * w); }
  double z(double w) const {
    return ball.up.x() * a(w) + ball.sigma * ball.up.y() * (ball.ae - w) + ball.up.z() * c(w);
  }
  double dz(double w) const {
    return ball.up.x() * ball.ae / a(w) - ball.sigma * ball.up.y() -
           branch * ball.up.z() * w / sqrt0(ball.R * ball.R - w * w);
  }
  // dz and d2z together, sharing the square roots (the Newton step needs
  // both at one w; same arithmetic as dz, and as d2z for w <= R).
  std::pair<double, double> dz_d2z(double w) const {
    const double aw = a(w), h = ball.R * ball.R - w * w, root = sqrt0(h);
    const double dz =
        ball.up.x() * ball.ae / aw - ball.sigma * ball.up.y() - branch * ball.up.z() * w / root;
    const double d2z = -ball.up.x() * ball.ae * ball.ae / (aw * aw * aw) -
                       branch * ball.up.z() * ball.R * ball.R / (h * root);
    return {dz, d2z};
  }
};

// Adds z at the stationary point of the edge curve on [lo, hi] where dz is
// monotone and changes sign: Newton's method on dz kept inside the bracket.
void add_monotone_stationary(const EdgeCurve& curve, double lo, double hi, Extremes& out) {
  if (!(hi > lo)) return;
  const double g_lo = curve.dz(lo), g_hi = curve.dz(hi);
  if (std::signbit(g_lo) == std::signbit(g_hi)) return;
  // z is stationary at the root, so an error e in w moves z by O(e^2):
  // 1e-8 R in w is already below double precision in z.
  const double tolerance = 1e-8 * curve.ball.R;
  double w = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const auto [g, dg] = curve.dz_d2z(w);
    if (g == 0) break;
    (std::signbit(g) == std::signbit(g_lo) ? lo : hi) = w;
    if (hi - lo <= tolerance) break;
    const double newton = w - g / dg;
    const bool inside = newton > lo && newton < hi;
    const double next = inside ? newton : 0.5 * (lo + hi);
    const bool converged = inside && std::abs(next - w) <= tolerance;
    w = next;
    if (converged) break;
  }
  out.add(curve.z(w));
}

Extremes edge_piece_extremes(const EdgeCurve& curve, double lo, double hi) {
  Extremes out;
  if (hi < lo) return out;
  out.add(curve.z(lo));
  out.add(curve.z(hi));
  const Ball& ball = curve.ball;
  const double fz = ball.up.x(), nz = ball.up.z();
  if (curve.branch < 0 && fz <= 0) {
    // dz = fz ae/a (rising) - const + nz w/sqrt(R^2-w^2) (rising): monotone.
    add_monotone_stationary(curve, lo, hi, out);
  } else if (curve.branch < 0) {
    // fz > 0: dz falls then rises; its minimum, where d2z = 0, in closed form:
    // R^2 - w^2 = K a^2 with K = (nz R^2 / (fz ae^2))^(2/3).
    const double ae = ball.ae;
    const double K = std::cbrt(std::pow(nz * ball.R * ball.R / (fz * ae * ae), 2));
    const double w_turn = -K * ae + std::sqrt(K * K * ae * ae + K * ae * ae + ball.R * ball.R);
    const double split = std::clamp(w_turn, lo, hi);
    add_monotone_stationary(curve, lo, split, out);
    add_monotone_stationary(curve, split, hi, out);
  } else {
    // Upper branch, only when ap > R: rare; bracket sign changes on a grid.
    constexpr int pieces = 32;
    for (int i = 0; i < pieces; ++i) {
      add_monotone_stationary(curve, lo + (hi - lo) * i / pieces, lo + (hi - lo) * (i + 1) / pieces,
                              out);
    }
  }
  return out;
}

Extremes edge_extremes(const Ball& ball) {
  // On this curve p - o = (-sigma w, c) lies on the circle |p - o| = R, so (4)
  // reduces to v' <= 0: -sigma d_b w + d_c c <= 0, which bounds w at
  // w_v = d_c R / |d| on one branch (sign analysis in the comments below).
  const double db = ball.sigma * ball.along.y(), dc = ball.along.z();
  const double w_v = dc * ball.R;  // along is a unit vector: w_v = R d_c / |d|
  const double w_min = ball.ae / 2;
  double lower_hi = ball.c0 <= 0 ? ball.rho : ball.R;
  double upper_lo = std::max(w_min, ball.rho), upper_hi = ball.c0 > 0 ? ball.R : -1;
  if (ball.shank_sweep_matters) {
    if (db < 0) lower_hi = std::min(lower_hi, w_v);  // lower: -db w <= dc sqrt(R^2 - w^2)
    if (db > 0)
      upper_lo = std::max(upper_lo, w_v);  // upper: dc sqrt(R^2 - w^2) <= db w
    else
      upper_hi = -1;
  }
  Extremes out = edge_piece_extremes({ball, -1}, w_min, lower_hi);
  if (upper_hi > 0) out.add(edge_piece_extremes({ball, +1}, upper_lo, upper_hi));
  return out;
}

// Range of z over the engaged part of the sphere's front half.
Extremes engaged_z_range(const Ball& ball) {
  Extremes out = rim_extremes(ball);
  out.add(silhouette_extremes(ball));
  out.add(edge_extremes(ball));
  out.add(shank_sweep_edge_extremes(ball));
  for (const double pole : {-ball.R, ball.R}) {  // z's only stationary points on the sphere
    if (ball.engaged(pole * ball.up)) out.add(pole);
  }
  return out;
}

double diameter_at_z(const Ball& ball, double z) {
  return z >= 0 ? 2 * ball.R : 2 * sqrt0(ball.R * ball.R - z * z);
}

// --- The rim Gamma: the tool surface in the stock plane c = c0. ---------------
// Its lower part is the circle a^2 + b^2 = rho^2 (where z <= 0), its upper part
// the shank's ellipse |a F_xy + b S0_xy + c0 N_xy| = R (where z >= 0).

struct RimPoint {
  double a, b;
};

// The shank's ellipse in the stock plane, by the angle phi about the tool axis.
struct ShankRim {
  const Ball& ball;
  RimPoint at(double phi) const {
    const Eigen::Vector3d& n = ball.frame.normal;
    const double x = ball.R * std::cos(phi), y = ball.R * std::sin(phi);
    const Eigen::Vector3d p(x, y, (ball.c0 - n.x() * x - n.y() * y) / n.z());
    return {ball.frame.feed.dot(p), ball.frame.side.dot(p)};
  }
  double z(RimPoint p) const { return ball.z({p.a, p.b, ball.c0}); }
  // The angle where b is largest (sign +1) or smallest (-1).
  double extreme_b_angle(double sign) const {
    const Eigen::Vector3d& n = ball.frame.normal;
    const Eigen::Vector3d& s = ball.frame.side;
    const double cx = s.x() - s.z() * n.x() / n.z(), cy = s.y() - s.z() * n.y() / n.z();
    return std::atan2(sign * cy, sign * cx);
  }
  // The two values of a on the ellipse at lateral coordinate b.
  std::array<double, 2> a_at(double b) const {
    const Eigen::Vector3d v = b * ball.frame.side + ball.c0 * ball.frame.normal;
    const Eigen::Vector2d f = ball.frame.feed.head<2>(), w = v.head<2>();
    const double qa = f.squaredNorm(), qb = 2 * f.dot(w), qc = w.squaredNorm() - ball.R * ball.R;
    const double root = sqrt0(qb * qb - 4 * qa * qc);
    return {(-qb - root) / (2 * qa), (-qb + root) / (2 * qa)};
  }
};

struct Rim {
  const Ball& ball;
  bool on_ball_only;  // the whole circle lies at z <= 0

  explicit Rim(const Ball& b)
      : ball(b),
        on_ball_only(
            b.c0 * b.up.z() + b.rho * std::sqrt(b.up.x() * b.up.x() + b.up.y() * b.up.y()) <= 0) {}

  bool circle_point_valid(RimPoint p) const {
    return ball.z({p.a, p.b, ball.c0}) <= 1e-12 * ball.R;
  }

  // The rim point with the smallest (sign -1) or largest (+1) b. Gamma is
  // convex, so if the circle's extreme lies on the ball it is Gamma's; else
  // Gamma's lies on the ellipse or at a junction of circle and ellipse.
  RimPoint extreme(double sign) const {
    const RimPoint circle{0, sign * ball.rho};
    if (on_ball_only || circle_point_valid(circle)) return circle;
    const ShankRim shank{ball};
    RimPoint best = shank.at(shank.extreme_b_angle(sign));
    if (shank.z(best) < 0) best = {0, -sign * HUGE_VAL};  // not on the shank part
    const double A = ball.rho * ball.up.x(), B = ball.rho * ball.up.y(), C = -ball.c0 * ball.up.z();
    const double m = std::sqrt(A * A + B * B);
    if (m > 0 && std::abs(C) <= m) {
      const double t0 = std::atan2(B, A), dt = std::acos(clamp_unit(C / m));
      for (const double t : {t0 - dt, t0 + dt}) {
        const RimPoint junction{ball.rho * std::cos(t), ball.rho * std::sin(t)};
        if (sign * junction.b > sign * best.b) best = junction;
      }
    }
    return best;
  }

  // The points ahead (largest a) and behind (smallest a) at lateral b.
  std::array<RimPoint, 2> at_b(double b) const {
    const double half = sqrt0(ball.rho * ball.rho - b * b);
    if (on_ball_only) return {RimPoint{half, b}, RimPoint{-half, b}};
    double ahead = -HUGE_VAL, behind = HUGE_VAL;
    auto take = [&](double a) {
      ahead = std::max(ahead, a);
      behind = std::min(behind, a);
    };
    for (const double a : {half, -half}) {
      if (std::abs(b) <= ball.rho && circle_point_valid({a, b})) take(a);
    }
    const ShankRim shank{ball};
    for (const double a : shank.a_at(b)) {
      if (shank.z({a, b}) >= -1e-12 * ball.R) take(a);
    }
    return {RimPoint{ahead, b}, RimPoint{behind, b}};
  }
};

CuttingPoint cutting_point(const Ball& ball, RimPoint p) {
  const Eigen::Vector3d position = ball.world({p.a, p.b, ball.c0});
  return {position, 2 * position.head<2>().norm()};
}

CuttingPoints cutting_points(const Ball& ball) {
  const Rim rim(ball);
  const RimPoint p1 = rim.extreme(-1), p2 = rim.extreme(+1);
  CuttingPoints out;
  out.p1 = cutting_point(ball, p1);
  out.p2 = cutting_point(ball, p2);
  // 1' and 1'' at s_min + ae, 2' and 2'' at s_max - ae; past the groove's
  // width they fall onto the opposite tangent point.
  if (p1.b + ball.ae >= p2.b) {
    out.p1a = out.p1b = out.p2;
    out.p2a = out.p2b = out.p1;
  } else {
    const auto ones = rim.at_b(p1.b + ball.ae);
    const auto twos = rim.at_b(p2.b - ball.ae);
    out.p1a = cutting_point(ball, ones[0]);
    out.p1b = cutting_point(ball, ones[1]);
    out.p2a = cutting_point(ball, twos[0]);
    out.p2b = cutting_point(ball, twos[1]);
  }
  out.cut = ball.sigma > 0 ? out.p1 : out.p2;
  return out;
}

// Ball part of the mean: at height c the engaged arcs of the circle of
// radius w(c), a = w cos t, b = w sin t, below the equator; area element
// R dc dt (Archimedes).
struct Slice {
  double area = 0, moment = 0;
};

// The slice at height c. The slices' circles share the phases of b
// (sigma pi/2) and of z: up_across = |up_xy|, z_phase = its angle.
Slice ball_slice(const Ball& ball, double c, double up_across, double z_phase) {
  const double R = ball.R;
  Slice slice;
  const double w = sqrt0(R * R - c * c);
  if (w <= 0) return slice;
  const FrameCircle circle{{0, 0, c}, {w, 0, 0}, {0, w, 0}};
  AngleSet set({-half_pi, half_pi});
  set.keep_where_polar(
      w, [&] { return ball.sigma * half_pi; }, 0, ball.ae - w);
  ball.remove_previous_shank(circle, set);
  const Sinusoid z = circle.along(ball.up);
  set.keep_where_polar(
      w * up_across, [&] { return z_phase; }, z.c, 0);
  const auto diameter = [&](double height) { return 2 * sqrt0(R * R - height * height); };
  for (int i = 0; i < set.size(); ++i) {
    slice.area += R * (set[i].hi - set[i].lo);
    // About the arc's centre m, z(m +- d) = p cos d +- q sin d + z.c, the
    // nodes' cos d and sin d from node_cos_sin: libm's sines and cosines
    // of the nodes were most of the mean's time.
    const double centre = 0.5 * (set[i].lo + set[i].hi);
    const double cos_m = std::cos(centre), sin_m = std::sin(centre);
    const double p = z.a * cos_m + z.b * sin_m, q = z.b * cos_m - z.a * sin_m;
    const double half = 0.5 * (set[i].hi - set[i].lo);
    const NodeCosSin node = node_cos_sin(half);
    const auto pair = [&](std::size_t k, double /*d*/) {
      const double even = p * node.cos[k] + z.c, odd = q * node.sin[k];
      return diameter(even - odd) + diameter(even + odd);
    };
    slice.moment += R * kronrod_rule_by_pairs(diameter(p + z.c), pair, half);
  }
  return slice;
}

// The ball part's area and moment from the same slices, to 1e-7 of their
// size: the mean to well under 1e-6 D, in a bounded number of slices. The
// slices change shape abruptly where an arc appears or vanishes (it grows
// as a square root) and where the circle passes through the tool's tip (r
// has a kink there): the stack is cut at those levels, and each piece
// integrated in theta (integrate_smoothed_pieces), which makes the square
// roots smooth (fewer slices than adaptive bisection took, and closer:
// docs/models.md §2).
std::array<double, 2> ball_part(const Ball& ball, double tolerance) {
  const double R = ball.R;
  const double up_across = std::hypot(ball.up.x(), ball.up.y());
  const double z_phase = std::atan2(ball.up.y(), ball.up.x());
  std::vector<double> cuts{-R * ball.up.z(), R * up_across, -R * up_across};
  if (ball.ae < 2 * R) {
    // Where the previous pass's strip sigma b <= ae - w starts to cut: w = ae / 2.
    const double touch = std::sqrt(R * R - 0.25 * ball.ae * ball.ae);
    cuts.push_back(touch);
    cuts.push_back(-touch);
  }
  return integrate_smoothed_pieces<2>(
      [&](double c) {
        const Slice slice = ball_slice(ball, c, up_across, z_phase);
        return std::array<double, 2>{slice.area, slice.moment};
      },
      breaks_within(std::move(cuts), -R, ball.c0), 1e-7, tolerance, 24);
}

// Shank part (r = R): on the vertical line at angle phi, z runs from 0 up
// to the stock plane and to where the line enters the previous shank's
// sweep, less where it is inside the previous ball's cylinder.
double shank_length(const Ball& ball, const CutFrame& frame, double phi) {
  const double R = ball.R;
  const Eigen::Vector3d& n = frame.normal;
  const Eigen::Vector3d& f = frame.feed;
  const Eigen::Vector3d centre_line = ball.offset * frame.side;
  const Eigen::Vector3d u(std::cos(phi), std::sin(phi), 0);
  if (f.x() * u.x() + f.y() * u.y() < 0) return 0.0;  // trailing side
  double top = (ball.c0 - R * (n.x() * u.x() + n.y() * u.y())) / n.z();
  const Eigen::Vector3d y = R * u - centre_line;  // the line's foot, from the centre line
  if (ball.shank_sweep_matters) {
    const FrameVector q(f.dot(y), frame.side.dot(y), n.dot(y));  // already relative to o
    // v' grows with z at the rate |d| = along.(0, S0_z, N_z) along the line.
    const double rate = ball.along.dot(ball.up);
    if (std::abs(ball.across.dot(q)) < R) top = std::min(top, -ball.along.dot(q) / rate);
  }
  if (top <= 0) return 0.0;
  // |Y + z e_z|^2 - ((Y + z e_z).F)^2 < R^2 is inside the previous cylinder.
  const double qa = 1 - f.z() * f.z(), qb = 2 * (y.z() - y.dot(f) * f.z());
  const double qc = y.squaredNorm() - std::pow(y.dot(f), 2) - R * R;
  const double disc = qb * qb - 4 * qa * qc;
  double length = top;
  if (disc > 0 && qa > 0) {
    const double z1 = (-qb - std::sqrt(disc)) / (2 * qa), z2 = (-qb + std::sqrt(disc)) / (2 * qa);
    length -= std::max(0.0, std::min(z2, top) - std::max(z1, 0.0));
  }
  return length;
}

// The shank part's area, only where the line is on the leading side and
// reaches into the stock.
double shank_area(const Ball& ball, const CutFrame& frame, double tolerance) {
  const double R = ball.R;
  const Eigen::Vector3d& n = frame.normal;
  const Eigen::Vector3d& f = frame.feed;
  AngleSet lines({-std::numbers::pi, std::numbers::pi});
  lines.keep_where({-f.x(), -f.y(), 0}, 0);              // F.u >= 0
  lines.keep_where({R * n.x(), R * n.y(), 0}, ball.c0);  // N.(R u) <= c0 at z = 0
  double area = 0;
  for (int i = 0; i < lines.size(); ++i) {
    area += integrate_capped<1>(
        [&](double phi) { return std::array<double, 1>{R * shank_length(ball, frame, phi)}; },
        lines[i].lo, lines[i].hi, 1e-7, tolerance, 24)[0];
  }
  return area;
}

}  // namespace

void evaluate_ball(double radius, const CutSetup& setup, const CutCheck& check,
                   CuttingPointsWanted points, Engagement& out) {
  const Ball ball(radius, setup, *check.frame);
  if (check.rim_exists && points == CuttingPointsWanted::yes) out.points = cutting_points(ball);
  if (!check.can_engage) {
    out.flags.set(EngagementFlag::nothing_engaged);
    return;
  }
  const Extremes z = engaged_z_range(ball);
  if (z.empty()) {
    out.flags.set(EngagementFlag::nothing_engaged);
    return;
  }
  out.d_max = diameter_at_z(ball, z.max);
  out.d_min = diameter_at_z(ball, z.min);
  if (z.max >= 0) out.flags.set(EngagementFlag::shank_engaged);
}

double ball_mean_diameter(double radius, const CutSetup& setup, const CutFrame& frame) {
  const Ball ball(radius, setup, frame);
  const double R = ball.R;
  const double tolerance = 1e-9 * R * R;
  const auto [ball_area, ball_moment] = ball_part(ball, tolerance);
  const double shank = shank_area(ball, frame, tolerance);
  const double area = ball_area + shank;
  return area > 0 ? (ball_moment + 2 * R * shank) / area : 0;
}

}  // namespace vcpost::geometry
