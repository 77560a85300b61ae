// The mean of 2r over the engaged zone of a bull-nose or flat end mill:
// the flat mill's circle by circle, the bull-nose's round the zone's
// boundary (Green's theorem), either's along the profile when fed level.
#include "geometry/revolved_groove.h"

namespace vcpost::geometry::revolved {

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
// see kNearlyEdgeOn; feeds just off the threshold need the 16, a piece's
// front points racing round the face's rim). Accuracy and times against
// the area's double quadrature: docs/models.md §2.
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
    // side (each cut piece a ratio of 4 of the spike's tail), so the
    // quadrature does not chase it.
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
    // tighter than the area, for nothing).
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

}  // namespace vcpost::geometry::revolved
