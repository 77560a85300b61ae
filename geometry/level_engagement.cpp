// Engagement of a bull-nose or flat end mill fed level (see
// level_engagement.h). With F level, N and e lie in the vertical plane
// across F, spanned by m (horizontal, across F) and z, and the volume a
// tool sweeps along F is a prism over its section by that plane, the
// profile |m| <= rho(z): rho = R0 + sqrt(rc^2 - z^2) on the corner (-rc <
// z < 0), R on the shank. So a point of the tool's side at height z and
// lateral position m is engaged (docs/models.md, conditions 1-3) iff N_m m +
// N_z z <= c0, (m - ae e_m, z - ae e_z) is not strictly inside the
// profile, and the point lies on the front half of its horizontal circle,
// where F.n >= 0. Each circle of radius rho thus keeps the front arcs over
// an interval of m less an open one, rho (asin(m2 / rho) - asin(m1 /
// rho)) long, all at r = rho: the area and the moment of 2r are integrals
// along the profile (rc dpsi on the corner, dz on the shank) of closed
// forms, smooth between the heights where two of the kept set's bounds
// cross (circles and lines of the (m, z) plane, met in closed form). The
// end face, edge-on, is added in its own plane.
#include "geometry/level_engagement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>
#include <vector>

#include "geometry/quadrature.h"

namespace vcpost::geometry {
namespace {

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Point {
  double m, z;
};

// A bound of the kept sets in the (m, z) plane over heights [lo, hi]: the
// circle |(m, z) - centre| = radius on the side `side` of its centre (+1:
// m >= centre.m), or, with radius 0, the line a m + b z = c ((a, b) unit).
struct Bound {
  double lo = -kInf, hi = kInf;
  Point centre{0, 0};
  double radius = 0, side = 0;
  double a = 0, b = 0, c = 0;

  bool holds(const Point& p) const {
    constexpr double kSlack = 1e-9;  // mm: a crossing kept too many cuts a piece, no harm
    if (!(p.z >= lo - kSlack && p.z <= hi + kSlack)) return false;
    return radius == 0 || (p.m - centre.m) * side >= -kSlack;
  }
};

// A few bounds, kept on the stack.
struct Bounds {
  std::array<Bound, 9> items;
  std::size_t size = 0;
  void add(const Bound& k) { items[size++] = k; }
};

Bound line(double a, double b, double c, double lo) {
  const double length = std::sqrt(a * a + b * b);
  Bound k;
  k.lo = lo;
  k.a = a / length;
  k.b = b / length;
  k.c = c / length;
  return k;
}

// At most two points of the (m, z) plane.
struct Points {
  std::array<Point, 2> items;
  int size = 0;
  void add(const Point& p) { items[size++] = p; }
};

// The points common to two bounds' whole circles or lines.
Points meet(const Bound& x, const Bound& y) {
  Points out;
  if (x.radius == 0 && y.radius == 0) {
    const double det = x.a * y.b - y.a * x.b;
    if (std::abs(det) > 1e-12)
      out.add({(x.c * y.b - y.c * x.b) / det, (x.a * y.c - y.a * x.c) / det});
    return out;
  }
  if (x.radius == 0 || y.radius == 0) {
    const Bound& l = x.radius == 0 ? x : y;
    const Bound& k = x.radius == 0 ? y : x;
    // The line's points p0 + t d, p0 = c (a, b), d = (-b, a).
    const double wm = l.c * l.a - k.centre.m, wz = l.c * l.b - k.centre.z;
    const double along = -wm * l.b + wz * l.a;
    // A tangent point may come out a hair off the circle: kept, as a cut.
    const double disc = along * along - (wm * wm + wz * wz - k.radius * k.radius);
    if (disc < -1e-12 * k.radius * k.radius) return out;
    const double root = std::sqrt(std::max(0.0, disc));
    for (const double t : {-along - root, -along + root})
      out.add({l.c * l.a - t * l.b, l.c * l.b + t * l.a});
    return out;
  }
  const double dm = y.centre.m - x.centre.m, dz = y.centre.z - x.centre.z;
  const double d = std::sqrt(dm * dm + dz * dz);
  if (!(d > 0) || d > x.radius + y.radius || d < std::abs(x.radius - y.radius)) return out;
  const double along = (x.radius * x.radius - y.radius * y.radius + d * d) / (2 * d);
  const double off = std::sqrt(std::max(0.0, x.radius * x.radius - along * along));
  const Point base{x.centre.m + along * dm / d, x.centre.z + along * dz / d};
  out.add({base.m - off * dz / d, base.z + off * dm / d});
  out.add({base.m + off * dz / d, base.z - off * dm / d});
  return out;
}

// The points where two bounds cross: met, then within both's heights and sides.
Points crossings(const Bound& x, const Bound& y) {
  const Points met = meet(x, y);
  Points out;
  for (int i = 0; i < met.size; ++i)
    if (x.holds(met.items[i]) && y.holds(met.items[i])) out.add(met.items[i]);
  return out;
}

class LevelZone {
 public:
  explicit LevelZone(const LevelCut& cut)
      : r0_(cut.flat_radius), rc_(cut.corner), radius_(r0_ + rc_), c0_(cut.stock_level) {
    const double length = std::sqrt(cut.feed.x() * cut.feed.x() + cut.feed.y() * cut.feed.y());
    const Vector3d across(-cut.feed.y() / length, cut.feed.x() / length, 0);
    normal_ = {cut.normal.dot(across), cut.normal.z()};
    shift_ = {cut.ae * cut.side.dot(across), cut.ae * cut.side.z()};
    across_ = across;
    along_ = {cut.feed.x() / length, cut.feed.y() / length, 0};
    ae_ = cut.ae;
  }

  // The tool point at lateral position m, height z, v along the feed.
  Vector3d point(double m, double z, double v = 0) const {
    return m * across_ + v * along_ + z * Vector3d::UnitZ();
  }

  // The profile's sides shifted by `offset`: its corner's circles (none
  // for the flat mill) and its shank's lines.
  void add_profile(const Point& offset, Bounds& bounds) const {
    for (const double side : {-1.0, 1.0}) {
      if (rc_ > 0) {
        Bound k;
        k.lo = offset.z - rc_;
        k.hi = offset.z;
        k.centre = {offset.m + side * r0_, offset.z};
        k.radius = rc_;
        k.side = side;
        bounds.add(k);
      }
      bounds.add(line(1, 0, offset.m + side * radius_, offset.z));
    }
  }

  Bound stock_line() const { return line(normal_.m, normal_.z, c0_, -kInf); }

  // See LevelRim. In (m, z) the stock line N_m m + N_z z = c0 runs along
  // s = N_z m - N_m z, and it leaves the profile at the rim's s extremes:
  // there the rim's tangent is along F, at v = 0.
  LevelRim rim() const {
    const Bound stock = stock_line();
    Point low{0, 0}, high{0, 0};
    double s_low = kInf, s_high = -kInf;
    const auto consider = [&](const Point& p) {
      const double s = stock.b * p.m - stock.a * p.z;
      if (s < s_low) std::tie(low, s_low) = std::pair{p, s};
      if (s > s_high) std::tie(high, s_high) = std::pair{p, s};
    };
    Bounds sides;
    add_profile({0, 0}, sides);
    for (std::size_t i = 0; i < sides.size; ++i) {
      const Points crossing = crossings(stock, sides.items[i]);
      for (int k = 0; k < crossing.size; ++k) consider(crossing.items[k]);
    }
    // The end face's chord.
    if (normal_.m != 0) {
      const double m = (c0_ + normal_.z * rc_) / normal_.m;
      if (std::abs(m) <= r0_) consider({m, -rc_});
    }
    LevelRim out{point(low.m, low.z), point(high.m, high.z), std::nullopt, std::nullopt};
    if (!(ae_ > 0 && s_low + ae_ < s_high)) return out;
    // The fibre at (m, z) crosses its circle at v = +-sqrt(rho^2 - m^2).
    const auto fibre = [&](const Point& from, double ds) {
      const double m = from.m + ds * stock.b, z = from.z - ds * stock.a;
      const double rho = radius_at(z);
      const double v = std::sqrt(std::max(0.0, rho * rho - m * m));
      return std::pair{point(m, z, v), point(m, z, -v)};
    };
    out.beside_low = fibre(low, ae_);
    out.beside_high = fibre(high, -ae_);
    return out;
  }

  // The profile's half-width at height z (negative below the end face).
  double half_width(double z) const {
    if (z >= 0) return radius_;
    if (!(z > -rc_)) return -1;
    return r0_ + std::sqrt(rc_ * rc_ - z * z);
  }

  // The profile's half-width at height z on the tool (R0 at its face).
  double radius_at(double z) const { return std::max(half_width(z), r0_); }

  // The lateral positions m kept at height z within |m| <= half (the
  // circle's there; the face's chords at z = -rc): in the stock, less
  // |m - ae e_m| < removed, what the previous tool removes at that height
  // (none when removed <= 0). Two intervals, either perhaps empty.
  using Intervals = std::array<std::pair<double, double>, 2>;
  Intervals kept(double half, double z, double removed) const {
    double lo = -half, hi = half;
    const double reach = c0_ - normal_.z * z;
    if (normal_.m > 0) hi = std::min(hi, reach / normal_.m);
    if (normal_.m < 0) lo = std::max(lo, reach / normal_.m);
    if (normal_.m == 0 && reach < 0) return {};
    if (!(removed > 0)) return {{{lo, hi}, {0, 0}}};
    return {{{lo, std::min(hi, shift_.m - removed)}, {std::max(lo, shift_.m + removed), hi}}};
  }
  Intervals kept_on_circle(double rho, double z) const {
    return kept(rho, z, half_width(z - shift_.z));
  }
  Intervals kept_on_face() const {
    return kept(r0_, -rc_, shift_.z < 0 ? half_width(-rc_ - shift_.z) : -1);
  }

  // The angle round the axis kept on the circle of radius rho at height z.
  double kept_angle(double rho, double z) const {
    if (!(rho > 0)) return 0;
    double angle = 0;
    for (const auto& [a, b] : kept_on_circle(rho, z)) {
      if (b > a)
        angle +=
            std::asin(std::clamp(b / rho, -1.0, 1.0)) - std::asin(std::clamp(a / rho, -1.0, 1.0));
    }
    return angle;
  }

  // The heights where the kept sets change form: the pieces' ends and the
  // crossings of any two bounds (the profile's, the shifted profile's, the
  // stock line).
  std::vector<double> breaks() const {
    Bounds bounds;
    add_profile({0, 0}, bounds);
    add_profile(shift_, bounds);
    bounds.add(stock_line());
    std::vector<double> zs{-rc_, 0.0, shift_.z - rc_, shift_.z};
    zs.reserve(40);
    for (std::size_t i = 0; i < bounds.size; ++i) {
      for (std::size_t j = i + 1; j < bounds.size; ++j) {
        const Points crossing = crossings(bounds.items[i], bounds.items[j]);
        for (int k = 0; k < crossing.size; ++k) zs.push_back(crossing.items[k].z);
      }
    }
    return zs;
  }

  // The highest level any kept set reaches: above max(0, ae e_z) both
  // profiles are the shank's, and the strips the shifted one leaves go up
  // to the stock line.
  double top() const {
    const double above = std::max(0.0, shift_.z);
    double top = above;
    const auto reach = [&](double m) { return (c0_ - normal_.m * m) / normal_.z; };
    for (const auto& [lo, hi] : {std::pair{-radius_, std::min(radius_, shift_.m - radius_)},
                                 std::pair{std::max(-radius_, shift_.m + radius_), radius_}}) {
      if (hi > lo) top = std::max({top, reach(lo), reach(hi)});
    }
    // And never above the stock line's highest point on the shank.
    return std::min(top, reach(normal_.m > 0 ? -radius_ : radius_));
  }

  std::array<double, 2> sides() const {
    constexpr double kRelative = 1e-9;
    constexpr int kPanels = 8;
    const double absolute = 1e-14 * radius_ * radius_ * radius_;
    std::vector<double> zs = breaks();
    std::array<double, 2> sum{0, 0};
    const auto add = [&](const std::array<double, 2>& part) {
      sum[0] += part[0];
      sum[1] += part[1];
    };
    if (rc_ > 0) {
      // The corner by its meridian angle psi: z = -rc cos psi, rho = R0 + rc sin psi.
      std::vector<double> psis;
      for (const double z : zs)
        if (z > -rc_ && z < 0) psis.push_back(std::acos(-z / rc_));
      add(integrate_smoothed_pieces<2>(
          [&](double psi) {
            const double rho = r0_ + rc_ * std::sin(psi);
            const double area = rc_ * rho * kept_angle(rho, -rc_ * std::cos(psi));
            return std::array<double, 2>{area, 2 * rho * area};
          },
          breaks_within(psis, 0, kPi / 2), kRelative, absolute, kPanels));
    }
    const double z_top = top();
    if (z_top > 0) {
      add(integrate_smoothed_pieces<2>(
          [&](double z) {
            const double area = radius_ * kept_angle(radius_, z);
            return std::array<double, 2>{area, 2 * radius_ * area};
          },
          breaks_within(zs, 0, z_top), kRelative, absolute, kPanels));
    }
    return sum;
  }

  // The least and greatest r and the greatest z of the engaged points.
  // On the sides r = rho(z) grows with z: the lowest and the highest
  // heights whose circles keep something. A kept set is empty or not all
  // along a stretch between two breaks (its bounds cross only there), so
  // the stretch's middle tells. A face's chord reaches the rim (r = R0),
  // and comes nearest the axis at v = 0.
  RadiusExtremes extremes(bool face_leads) const {
    const double slack = 1e-12 * radius_;
    const auto any = [slack](const Intervals& set) {
      return set[0].second - set[0].first > slack || set[1].second - set[1].first > slack;
    };
    RadiusExtremes out;
    const std::vector<double> zs = breaks_within(breaks(), -rc_, std::max(0.0, top()));
    for (std::size_t k = 0; k + 1 < zs.size(); ++k) {
      const double middle = 0.5 * (zs[k] + zs[k + 1]);
      if (!(zs[k + 1] > zs[k]) || !any(kept_on_circle(radius_at(middle), middle))) continue;
      out.r_min = std::min(out.r_min, radius_at(zs[k]));
      out.r_max = radius_at(zs[k + 1]);
      out.z_max = zs[k + 1];
    }
    if (const Intervals face = kept_on_face(); face_leads && r0_ > 0 && any(face)) {
      for (const auto& [a, b] : face) {
        if (!(b - a > slack)) continue;
        out.r_min =
            std::min(out.r_min, a <= 0 && b >= 0 ? 0.0 : std::min(std::abs(a), std::abs(b)));
        out.r_max = std::max(out.r_max, r0_);
        out.z_max = std::max(out.z_max, -rc_);
      }
    }
    return out;
  }

  // The end face at z = -rc, seen edge-on: docs/models.md's "non-negative
  // component along F" counts it as leading. On it both the stock's test
  // and the previous pass's depend only on m: N_m m - N_z rc <= c0, and the
  // previous tool removes |m - ae e_m| < its half-width at this height
  // (only where its face runs higher: its face's plane is no inside).
  // Over a strip of m the chord |v| <= w = sqrt(R0^2 - m^2) gives the area
  // 2 w and the moment of 2r = 2 sqrt(m^2 + v^2): 2 w R0 + 2 m^2 ln((R0 +
  // w) / |m|).
  std::array<double, 2> face() const {
    const double r0 = r0_;
    // The area of the chords over [a, b]: the integral of 2 sqrt(R0^2 - m^2).
    const auto area_to = [r0](double m) {
      return m * std::sqrt(std::max(0.0, r0 * r0 - m * m)) + r0 * r0 * std::asin(m / r0);
    };
    std::array<double, 2> sum{0, 0};
    for (const auto& [a, b] : kept_on_face()) {
      if (!(b > a)) continue;
      sum[0] += area_to(b) - area_to(a);
      // By quadrature: smooth but for m^2 ln|m| at 0 and the square roots
      // at +-R0, which the pieces' ends absorb.
      sum[1] += integrate_smoothed_pieces<1>(
          [r0](double m) {
            const double w = std::sqrt(std::max(0.0, r0 * r0 - m * m));
            const double log_term = m != 0 ? m * m * std::log((r0 + w) / std::abs(m)) : 0.0;
            return std::array<double, 1>{2 * w * r0 + 2 * log_term};
          },
          breaks_within({0.0}, a, b), 1e-10, 1e-14 * r0 * r0 * r0, 8)[0];
    }
    return sum;
  }

 private:
  double r0_, rc_, radius_, c0_;
  Vector3d across_, along_;  // m's direction, F's level direction
  double ae_ = 0;
  Point normal_{0, 0};  // N in (m, z)
  Point shift_{0, 0};   // ae e in (m, z): the previous tool's offset
};

}  // namespace

LevelRim level_rim(const LevelCut& cut) { return LevelZone(cut).rim(); }

RadiusExtremes level_extremes(const LevelCut& cut) {
  return LevelZone(cut).extremes(cut.face_leads);
}

std::array<double, 2> level_area_and_moment(const LevelCut& cut) {
  const LevelZone zone(cut);
  std::array<double, 2> sum = zone.sides();
  if (cut.face_leads && cut.flat_radius > 0) {
    const auto face = zone.face();
    sum[0] += face[0];
    sum[1] += face[1];
  }
  return sum;
}

}  // namespace vcpost::geometry
