// D_max and D_min of a bull-nose or flat end mill: the extremes of r over
// the engaged zone's boundary curves (revolved_groove.h describes them).
#include "geometry/revolved_groove.h"

namespace vcpost::geometry::revolved {

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

// Those polynomials on one arc of the silhouette's parameter, their roots
// added where they lie on their piece.
class Groove::ShiftedArc {
  enum class Piece { face, corner, shank };

  const ArcForm<2>& s() const { return forms_.sin(); }

  // Whether p lies on the piece, within round-off: beyond the face's rim
  // its plane stays within 1e-9 R of the corner for sqrt(2e-9 R rc), so the
  // surface test alone took the plane's root there for the corner's (D_min
  // 5.3e-8 mm off, D 10, rc 2).
  bool on(Piece piece, const Vector3d& p) const {
    const double slack = 1e-12 * g_.radius_;
    switch (piece) {
      case Piece::face:
        return length_of(p.x(), p.y()) <= g_.flat_radius_ + slack;
      case Piece::corner:
        return length_of(p.x(), p.y()) >= g_.flat_radius_ - slack && p.z() <= slack;
      case Piece::shank:
        return p.z() >= -slack;
    }
    return false;
  }

  // The point, from the silhouette normal's angle given by its cosine and sine.
  std::optional<Vector3d> meridian_point_at(double cos_phi, double sin_phi) const {
    const Vector3d u = cos_phi * g_.side_ + sin_phi * g_.normal_;
    const double length = length_of(u.x(), u.y());
    if (!(length > 0)) return std::nullopt;
    const Vector3d x = (r0_ / length) * Vector3d(u.x(), u.y(), 0) + rc_ * u + ae_ * g_.side_;
    const double across = g_.feed_.x() * u.y() - g_.feed_.y() * u.x();
    if (across == 0) return std::nullopt;
    return x - (x.x() * u.y() - x.y() * u.x()) / across * g_.feed_;
  }

  // What form_roots calls a root tau of a piece's polynomial with: its
  // point added where it lies on that piece and on the tool as a leading
  // point.
  auto adds_on(Piece piece) const {
    return [this, piece](double tau) {
      const auto [cos_phi, sin_phi] = forms_.cos_sin_at(tau);
      const auto p = meridian_point_at(cos_phi, sin_phi);
      if (p && on(piece, *p) && std::abs(g_.outside_by(*p)) <= 1e-9 * g_.radius_ &&
          g_.leads(g_.surface_normal(*p)))
        out_.add(*p);
    };
  }

 public:
  ShiftedArc(const Groove& groove, double lo, double hi, RadiusExtremes& out)
      : g_(groove),
        out_(out),
        forms_(lo, hi, groove.cos_sin(0.5 * (lo + hi))),
        ez_(groove.side_.z()),
        nz_(groove.normal_.z()),
        fz_(groove.feed_.z()),
        en_(groove.side_.x() * groove.normal_.y() - groove.side_.y() * groove.normal_.x()),
        fe_(groove.feed_.x() * groove.side_.y() - groove.feed_.y() * groove.side_.x()),
        fn_(groove.feed_.x() * groove.normal_.y() - groove.feed_.y() * groove.normal_.x()),
        r0_(groove.flat_radius_),
        rc_(groove.corner_),
        ae_(groove.ae_),
        shank_(groove.c0_ + groove.radius_ * groove.rim_tilt_ > -1e-9 * groove.radius_),
        uphill_(!groove.edge_on_ && fz_ > 0),
        d_(forms_.linear(fe_, fn_, 0)),
        v_(forms_.linear(ez_, nz_, 0)),
        d2_(d_ * d_),
        m_low_(m_lower_bound()) {}

  // The face, where it leads.
  void face() const {
    if (!g_.face_leads()) return;
    form_roots(forms_.sum(forms_.linear(rc_ * ez_, rc_ * nz_, rc_ + ae_ * ez_) * d_,
                          (-ae_ * en_ * fz_) * s()),
               adds_on(Piece::face));
  }

  void corner() const {
    if (!(rc_ > 0)) return;
    form_roots(forms_.sum((ae_ * en_ * en_) * (s() * s()), forms_.linear(2 * rc_, 0, ae_) * d2_),
               adds_on(Piece::corner));
  }

  // The corner across the axis (lambda <= -R0) and the shank (lambda =
  // R, and -R where M <= -(R + R0) L may hold): M D and L^2 built only
  // where one of them may hold a point.
  void across_axis_and_shank() const {
    const bool across_possible = rc_ > 0 && r0_ > 0 && !ruled_out(2 * r0_);
    if (!shank_ && !across_possible) return;
    const ArcForm<4> l2 = forms_.sum(forms_.one() * forms_.one(), (-1.0) * (v_ * v_));
    const ArcForm<6> md = forms_.sum(
        forms_.sum(rc_ * l2, forms_.linear(ae_ * (1 - ez_ * ez_), -ae_ * ez_ * nz_, 0)) * d_,
        (ae_ * en_ * fz_) * (s() * v_));
    if (across_possible && may_cross(md, 2 * r0_)) {
      const ArcForm<6> g =
          forms_.sum(forms_.linear(2 * rc_ * ae_, 0, ae_ * ae_ + 4 * r0_ * r0_) * d2_,
                     (ae_ * ae_ * en_ * en_) * (s() * s()));
      form_roots(forms_.sum(g * g * l2, (-16 * r0_ * r0_) * (md * md * d2_)),
                 adds_on(Piece::corner));
    }
    if (!shank_) return;
    if (rc_ > 0)
      form_roots(forms_.sum(md * md, (-rc_ * rc_) * (l2 * d2_)), adds_on(Piece::shank));
    else
      form_roots(md, adds_on(Piece::shank));
    const double across = g_.radius_ + r0_;
    if (!ruled_out(across) && may_cross(md, across))
      form_roots(forms_.sum(md * md, (-across * across) * (l2 * d2_)), adds_on(Piece::shank));
  }

 private:
  // Whether M <= -k L can hold on the arc (lambda <= R0 - k): L >=
  // |F_z| (v^2 <= e_z^2 + N_z^2 = 1 - F_z^2), so not where M > -k |F_z|
  // on the whole arc. First by a bound: where D keeps its sign (its ends'
  // signs agree: an arc < pi then holds no zero of D, and one of pi
  // has ends of opposite signs), M = rc L^2 + ae (c - e_z v) + ae A F_z
  // s v / D >= -ae (1 + |A F_z| / min |D|), |D| least at an end; this
  // decides most finishing set-ups' arcs, for which building M D's form
  // took a fifth of the evaluation. Else by the form (may_cross).
  // (D's form at the arc's ends is D (1 + W^2) = D times one's end coefficient.)
  double m_lower_bound() const {
    const double d_lo = d_.a[0], d_hi = d_.a[2];
    const double least_d = std::min(std::abs(d_lo), std::abs(d_hi)) / forms_.one().a[0];
    const bool d_keeps_sign = (d_lo > 0 && d_hi > 0) || (d_lo < 0 && d_hi < 0);
    return d_keeps_sign ? -ae_ * (1 + std::abs(en_ * fz_) / least_d) : -kInf;
  }
  // Ruled out without the form: uphill, or by the bound.
  bool ruled_out(double k) const { return uphill_ || m_low_ > -k * std::abs(fz_); }
  // By the form: not where D keeps its sign and M D + k |F_z| D has that
  // sign on the whole arc.
  bool may_cross(const ArcForm<6>& md, double k) const {
    const ArcForm<6> bound =
        forms_.sum(md, (k * std::abs(fz_)) * (d_ * forms_.one() * forms_.one()));
    const auto all = [](const auto& form, bool positive) {
      return std::all_of(form.a.begin(), form.a.end(),
                         [positive](double x) { return positive ? x > 0 : x < 0; });
    };
    const bool positive = d_.a[0] > 0;
    return !(all(d_, positive) && all(bound, positive));
  }

  const Groove& g_;
  RadiusExtremes& out_;
  const ArcForms forms_;
  // e_z, N_z, F_z, and A, B and C above.
  const double ez_, nz_, fz_, en_, fe_, fn_;
  const double r0_, rc_, ae_;
  // Whether the shank can hold a point of the groove (c <= c0 there).
  const bool shank_;
  // Going uphill (F_z > 0) no point across the axis (x_xy = lambda d,
  // lambda < 0) leads: with U_z = v <= 0 on the lower boundary, U_xy.F_xy =
  // -v F_z, there the corner's normal n = -cos(theta) d + sin(theta) z
  // (theta in [-pi/2, 0]) has n.F = F_z (cos(theta) v / L + sin(theta)) <= 0
  // and the shank's, -d, has n.F = v F_z / L <= 0.
  const bool uphill_;
  const ArcForm<2> d_, v_;  // D and v = U_z
  const ArcForm<4> d2_;
  const double m_low_;  // M >= m_low_ on the arc (see m_lower_bound)
};

// The shifted silhouette's extremes, arc by arc (the method above).
void Groove::shifted_silhouette_extremes(double phi_top, double phi_star,
                                         RadiusExtremes& out) const {
  if (corner_ == 0 && !edge_on_) {
    flat_shifted_rim_extremes(std::min(phi_top, phi_star), std::max(phi_top, phi_star), out);
    return;
  }
  const double lo = std::min(phi_top, phi_star), hi = std::max(phi_top, phi_star);
  if (!(hi > lo)) return;
  // Arcs of at most pi (the left boundary spans no more): W <= tan(pi / 4) = 1.
  const int arcs = std::max(1, static_cast<int>(std::ceil((hi - lo) / kPi)));
  for (int arc = 0; arc < arcs; ++arc) {
    const double arc_lo = lo + (hi - lo) * arc / arcs, arc_hi = lo + (hi - lo) * (arc + 1) / arcs;
    const ShiftedArc piece(*this, arc_lo, arc_hi, out);
    piece.face();
    piece.corner();
    piece.across_axis_and_shank();
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

}  // namespace vcpost::geometry::revolved
