// The engaged zone of a ball mill, in the frame (a, b, c) = (F.P, S0.P, N.P)
// of cut_frame.h, is the part of the sphere |P| = R with
//   (1) c <= c0 = -(R - ap)                  inside the stock layer,
//   (2) a >= 0                               on the leading side,
//   (3) sigma*b <= ae - w(c), w = sqrt(R^2 - c^2)
// where (3) says P lies outside the cylinder of radius R that the previous
// pass's ball swept about the line through sigma*ae*S0 along F: at height c
// both the tool's circle and that cylinder's section have half-width w(c).
// On the sphere r^2 = R^2 - z^2, so the extremes of r are those of z, a
// linear function: they lie on the zone's boundary (the rim c = c0, the
// silhouette a = 0 and the previous pass's edge where (3) holds with '=')
// or at the poles. The first two are circles (sinusoids, closed form), the
// third a one-parameter curve whose stationary points are found by
// bracketed root finding on pieces where z' is monotone.
// Above the equator (z > 0) the tool is its shank, r = R.
#include "geometry/ball_engagement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "geometry/quadrature.h"
#include "geometry/roots.h"
#include "geometry/sinusoid.h"

namespace vcpost::geometry {
namespace {

constexpr double half_pi = std::numbers::pi / 2;

double clamp_unit(double x) { return std::clamp(x, -1.0, 1.0); }
double sqrt0(double x) { return std::sqrt(std::max(0.0, x)); }

struct Ball {
  double R, ap, ae, sigma;
  CutFrame frame;
  double c0, rho;   // stock plane height along N and the rim circle's radius
  double fz, sz, nz;  // the tool axis +z in the frame: z = a fz + b sz + c nz

  Ball(double radius, const CutSetup& setup, const CutFrame& f)
      : R(radius), ap(setup.ap), ae(setup.ae), sigma(f.sigma), frame(f) {
    c0 = -(R - ap);
    rho = sqrt0(R * R - c0 * c0);
    fz = frame.feed.z();
    sz = frame.side.z();
    nz = frame.normal.z();
  }

  double z(double a, double b, double c) const { return a * fz + b * sz + c * nz; }
  Eigen::Vector3d point(double a, double b, double c) const {
    return a * frame.feed + b * frame.side + c * frame.normal;
  }
  bool engaged(double a, double b, double c) const {
    constexpr double slack = 1e-12;
    return c <= c0 + slack * R && a >= -slack * R &&
           sigma * b <= ae - sqrt0(R * R - c * c) + slack * R;
  }
};

// z over the rim circle a = rho cos t, b = rho sin t, c = c0, where (2) and (3) hold.
Extremes rim_extremes(const Ball& ball) {
  const double k = (ball.ae - ball.rho) / ball.rho;  // (3): sigma sin t <= k
  AngleInterval range{-half_pi, half_pi};
  if (k < 1) {
    const double t = std::asin(clamp_unit(k));
    range = ball.sigma > 0 ? AngleInterval{-half_pi, t} : AngleInterval{-t, half_pi};
  }
  return sinusoid_extremes({ball.rho * ball.fz, ball.rho * ball.sz, ball.c0 * ball.nz}, range);
}

// z over the silhouette a = 0: b = R sin t, c = -R cos t, |t| <= t0 from (1),
// where (3) reduces to sigma sin t <= ae / 2R.
Extremes silhouette_extremes(const Ball& ball) {
  const double t0 = std::acos(clamp_unit((ball.R - ball.ap) / ball.R));
  const Sinusoid z{-ball.R * ball.nz, ball.R * ball.sz, 0};
  const double k = ball.ae / (2 * ball.R);
  if (k >= 1) return sinusoid_extremes(z, {-t0, t0});
  const double t = std::asin(k);  // sigma sin > k on (t, pi - t) mirrored by sigma
  Extremes out;
  if (ball.sigma > 0) {
    out.add(sinusoid_extremes(z, {-t0, std::min(t0, t)}));
    out.add(sinusoid_extremes(z, {std::numbers::pi - t, t0}));
  } else {
    out.add(sinusoid_extremes(z, {std::max(-t0, -t), t0}));
    out.add(sinusoid_extremes(z, {-t0, -(std::numbers::pi - t)}));
  }
  return out;
}

// The previous pass's edge, parametrised by the half-width w in [ae/2, R]:
// a = sqrt(ae (2w - ae)), sigma b = ae - w, c = -+sqrt(R^2 - w^2).
struct EdgeCurve {
  const Ball& ball;
  double branch;  // -1: lower half of the sphere (c < 0), +1: upper

  double a(double w) const { return sqrt0(ball.ae * (2 * w - ball.ae)); }
  double c(double w) const { return branch * sqrt0(ball.R * ball.R - w * w); }
  double z(double w) const {
    return ball.fz * a(w) + ball.sigma * ball.sz * (ball.ae - w) + ball.nz * c(w);
  }
  double dz(double w) const {
    return ball.fz * ball.ae / a(w) - ball.sigma * ball.sz -
           branch * ball.nz * w / sqrt0(ball.R * ball.R - w * w);
  }
};

// Adds z at the stationary points of the edge curve on [lo, hi], where dz is
// monotone (or known to change sign at most once).
void add_monotone_stationary(const EdgeCurve& curve, double lo, double hi, Extremes& out) {
  const double g_lo = curve.dz(lo), g_hi = curve.dz(hi);
  if (!(hi > lo) || std::signbit(g_lo) == std::signbit(g_hi)) return;
  const double w =
      bracketed_root([&](double x) { return curve.dz(x); }, lo, hi, g_lo, g_hi, 1e-13 * curve.ball.R);
  out.add(curve.z(w));
}

Extremes edge_piece_extremes(const EdgeCurve& curve, double lo, double hi) {
  Extremes out;
  if (hi < lo) return out;
  out.add(curve.z(lo));
  out.add(curve.z(hi));
  if (hi == lo) return out;
  const Ball& ball = curve.ball;
  if (curve.branch < 0 && ball.fz <= 0) {
    // dz = fz ae/a (rising) - const + nz w/sqrt(R^2-w^2) (rising): monotone.
    add_monotone_stationary(curve, lo, hi, out);
  } else if (curve.branch < 0) {
    // fz > 0: dz falls then rises; its minimum, where d2z = 0, in closed form:
    // (R^2 - w^2) = K a^2 with K = (nz R^2 / (fz ae^2))^(2/3).
    const double K = std::cbrt(std::pow(ball.nz * ball.R * ball.R / (ball.fz * ball.ae * ball.ae), 2));
    const double ae = ball.ae;
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
  Extremes out;
  const double w_min = ball.ae / 2;
  if (ball.c0 <= 0) {
    out.add(edge_piece_extremes({ball, -1}, w_min, ball.rho));
  } else {
    out.add(edge_piece_extremes({ball, -1}, w_min, ball.R));
    out.add(edge_piece_extremes({ball, +1}, std::max(w_min, ball.rho), ball.R));
  }
  return out;
}

// Range of z over the engaged part of the whole sphere.
Extremes engaged_z_range(const Ball& ball) {
  Extremes out = rim_extremes(ball);
  out.add(silhouette_extremes(ball));
  out.add(edge_extremes(ball));
  for (const double pole : {-ball.R, ball.R}) {  // z's only stationary points on the sphere
    if (ball.engaged(pole * ball.fz, pole * ball.sz, pole * ball.nz)) out.add(pole);
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

// The shank ellipse at angle phi around the tool axis.
struct ShankRim {
  const Ball& ball;
  RimPoint at(double phi) const {
    const Eigen::Vector3d& n = ball.frame.normal;
    const double x = ball.R * std::cos(phi), y = ball.R * std::sin(phi);
    const double zz = (ball.c0 - n.x() * x - n.y() * y) / n.z();
    const Eigen::Vector3d p(x, y, zz);
    return {ball.frame.feed.dot(p), ball.frame.side.dot(p)};
  }
  double z(RimPoint p) const { return ball.z(p.a, p.b, ball.c0); }
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
      : ball(b), on_ball_only(b.c0 * b.nz + b.rho * std::hypot(b.fz, b.sz) <= 0) {}

  bool circle_point_valid(RimPoint p) const { return ball.z(p.a, p.b, ball.c0) <= 1e-12 * ball.R; }

  // The rim point with the smallest (sign -1) or largest (+1) b.
  RimPoint extreme(double sign) const {
    const RimPoint circle{0, sign * ball.rho};
    if (on_ball_only || circle_point_valid(circle)) return circle;
    const ShankRim shank{ball};
    RimPoint best = shank.at(shank.extreme_b_angle(sign));
    if (shank.z(best) < 0) best = {0, -sign * INFINITY};  // not on the shank part
    // The junctions of circle and ellipse (z = 0 on the circle).
    const double A = ball.rho * ball.fz, B = ball.rho * ball.sz, C = -ball.c0 * ball.nz;
    const double m = std::hypot(A, B);
    if (m > 0 && std::abs(C) <= m) {
      const double t0 = std::atan2(B, A), dt = std::acos(clamp_unit(C / m));
      for (const double t : {t0 - dt, t0 + dt}) {
        const RimPoint j{ball.rho * std::cos(t), ball.rho * std::sin(t)};
        if (sign * j.b > sign * best.b) best = j;
      }
    }
    return best;
  }

  // The points ahead (largest a) and behind (smallest a) at lateral b.
  std::array<RimPoint, 2> at_b(double b) const {
    const double half = sqrt0(ball.rho * ball.rho - b * b);
    if (on_ball_only) return {RimPoint{half, b}, RimPoint{-half, b}};
    double ahead = -INFINITY, behind = INFINITY;
    const ShankRim shank{ball};
    for (const double a : {half, -half}) {
      if (std::abs(b) <= ball.rho && circle_point_valid({a, b})) {
        ahead = std::max(ahead, a);
        behind = std::min(behind, a);
      }
    }
    for (const double a : shank.a_at(b)) {
      if (shank.z({a, b}) >= -1e-12 * ball.R) {
        ahead = std::max(ahead, a);
        behind = std::min(behind, a);
      }
    }
    return {RimPoint{ahead, b}, RimPoint{behind, b}};
  }
};

CuttingPoint cutting_point(const Ball& ball, RimPoint p) {
  const Eigen::Vector3d position = ball.point(p.a, p.b, ball.c0);
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

}  // namespace

void evaluate_ball(double radius, const CutSetup& setup, const CutCheck& check, Engagement& out) {
  const Ball ball(radius, setup, *check.frame);
  if (check.rim_exists) out.points = cutting_points(ball);
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

  // Ball part: at height c the engaged arc of the circle of radius w(c),
  // a = w cos t, b = w sin t; area element R dc dt (Archimedes).
  auto ball_slice = [&](double c, double& area, double& moment) {
    const double w = sqrt0(R * R - c * c);
    area = moment = 0;
    if (w <= 0) return;
    AngleInterval range{-half_pi, half_pi};
    const double k = (ball.ae - w) / w;
    if (k < 1) {
      const double t = std::asin(clamp_unit(k));
      range = ball.sigma > 0 ? AngleInterval{-half_pi, t} : AngleInterval{-t, half_pi};
    }
    // Split where z crosses 0 so each piece is all ball (2r < D) or all shank-side.
    const Sinusoid zt{w * ball.fz, w * ball.sz, c * ball.nz};
    std::array<double, 4> cuts{range.lo, range.hi, range.lo, range.lo};
    int count = 2;
    const double m = std::hypot(zt.a, zt.b);
    if (m > 0 && std::abs(zt.c) < m) {
      const double t0 = std::atan2(zt.b, zt.a), dt = std::acos(clamp_unit(-zt.c / m));
      for (const double t : {t0 - dt, t0 + dt}) {
        const double inside = wrap_from(t, range.lo);
        if (inside < range.hi) cuts[static_cast<std::size_t>(count++)] = inside;
      }
    }
    std::sort(cuts.begin(), cuts.begin() + count);
    for (int i = 0; i + 1 < count; ++i) {
      const double lo = cuts[static_cast<std::size_t>(i)], hi = cuts[static_cast<std::size_t>(i + 1)];
      if (zt(0.5 * (lo + hi)) > 0) continue;  // above the equator: not ball surface
      area += R * (hi - lo);
      moment += R * kronrod_rule(
                        [&](double t) { return 2 * sqrt0(R * R - std::pow(zt(t), 2)); }, lo, hi);
    }
  };
  const auto ball_area = integrate_adaptive(
      [&](double c) { double a, m; ball_slice(c, a, m); return a; }, -R, ball.c0, tolerance);
  const auto ball_moment = integrate_adaptive(
      [&](double c) { double a, m; ball_slice(c, a, m); return m; }, -R, ball.c0, tolerance);

  // Shank part (r = R): on the vertical line at angle phi, z runs from 0 up
  // to the stock plane, less where it is inside the previous pass's cylinder.
  const Eigen::Vector3d& n = frame.normal;
  const Eigen::Vector3d& f = frame.feed;
  const Eigen::Vector3d offset = ball.sigma * ball.ae * frame.side;
  auto shank_length = [&](double phi) {
    const Eigen::Vector3d u(std::cos(phi), std::sin(phi), 0);
    if (f.x() * u.x() + f.y() * u.y() < 0) return 0.0;  // trailing side
    const double top = (ball.c0 - R * (n.x() * u.x() + n.y() * u.y())) / n.z();
    if (top <= 0) return 0.0;
    // |Y + z e_z|^2 - ((Y + z e_z).F)^2 < R^2 is inside the previous cylinder.
    const Eigen::Vector3d y = R * u - offset;
    const double qa = 1 - f.z() * f.z(), qb = 2 * (y.z() - y.dot(f) * f.z());
    const double qc = y.squaredNorm() - std::pow(y.dot(f), 2) - R * R;
    const double disc = qb * qb - 4 * qa * qc;
    double length = top;
    if (disc > 0 && qa > 0) {
      const double z1 = (-qb - std::sqrt(disc)) / (2 * qa), z2 = (-qb + std::sqrt(disc)) / (2 * qa);
      length -= std::max(0.0, std::min(z2, top) - std::max(z1, 0.0));
    }
    return length;
  };
  const double shank_area =
      integrate_adaptive([&](double phi) { return R * shank_length(phi); }, -std::numbers::pi,
                         std::numbers::pi, tolerance);
  const double area = ball_area + shank_area;
  return area > 0 ? (ball_moment + 2 * R * shank_area) / area : 0;
}

}  // namespace vcpost::geometry
