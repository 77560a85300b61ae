// The closest point of a B-rep model: candidate faces from the box trees
// over the tessellation, Newton's method on each face's exact surface,
// the trim, and the face's edges where the foot point lies outside it.
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/occt/brep_faces.h"

namespace vcpost::occt {

using Eigen::Vector2d;
using Eigen::Vector3d;
using geometry::ContactHint;
using geometry::ContactType;
using geometry::ModelContact;

Vector2d BrepModel::Impl::into_box(const FaceData& f, Vector2d uv, bool& clamped) const {
  if (f.u_period > 0) {
    const double mid = (f.u0 + f.u1) / 2;
    uv.x() -= f.u_period * std::round((uv.x() - mid) / f.u_period);
  }
  if (f.v_period > 0) {
    const double mid = (f.v0 + f.v1) / 2;
    uv.y() -= f.v_period * std::round((uv.y() - mid) / f.v_period);
  }
  Vector2d c(f.u_closed ? uv.x() : std::clamp(uv.x(), f.u0, f.u1),
             f.v_closed ? uv.y() : std::clamp(uv.y(), f.v0, f.v1));
  clamped = c != uv;
  return c;
}

bool BrepModel::Impl::at_bound(const FaceData& f, const Vector2d& uv) {
  return (!f.u_closed && (uv.x() <= f.u0 || uv.x() >= f.u1)) ||
         (!f.v_closed && (uv.y() <= f.v0 || uv.y() >= f.v1));
}

std::optional<Local> BrepModel::Impl::newton(const FaceData& f, const Vector3d& p,
                                             Vector2d uv) const {
  bool clamped = false;
  uv = into_box(f, uv, clamped);
  SurfacePoint s = f.eval.d2(uv.x(), uv.y());
  double value = (s.p - p).squaredNorm();
  const double scale = 1 + p.cwiseAbs().maxCoeff();
  for (int iteration = 0; iteration < 40; ++iteration) {
    const Vector3d r = s.p - p;
    const Vector2d g(s.su.dot(r), s.sv.dot(r));
    Eigen::Matrix2d h;
    h << s.su.dot(s.su) + s.suu.dot(r), s.su.dot(s.sv) + s.suv.dot(r),
        s.su.dot(s.sv) + s.suv.dot(r), s.sv.dot(s.sv) + s.svv.dot(r);
    const bool fix_u =
        !f.u_closed && ((uv.x() <= f.u0 && g.x() > 0) || (uv.x() >= f.u1 && g.x() < 0));
    const bool fix_v =
        !f.v_closed && ((uv.y() <= f.v0 && g.y() > 0) || (uv.y() >= f.v1 && g.y() < 0));
    // Tangential residual in mm along the free directions.
    const double ru = fix_u ? 0 : std::abs(g.x()) / std::max(s.su.norm(), 1e-300);
    const double rv = fix_v ? 0 : std::abs(g.y()) / std::max(s.sv.norm(), 1e-300);
    if (std::max(ru, rv) < 1e-12 * scale) {
      return Local{uv, s, fix_u || fix_v || at_bound(f, uv)};
    }
    Vector2d step = Vector2d::Zero();
    if (fix_u && fix_v) return Local{uv, s, true};
    if (fix_u || fix_v) {
      const int k = fix_u ? 1 : 0;
      double hk = h(k, k);
      const Vector3d& t = fix_u ? s.sv : s.su;
      if (hk <= 0) hk = t.squaredNorm();
      step[k] = -g[k] / hk;
    } else {
      if (h(0, 0) <= 0 || h.determinant() <= 0) {
        h << s.su.dot(s.su), s.su.dot(s.sv), s.su.dot(s.sv), s.sv.dot(s.sv);  // Gauss-Newton
      }
      step = -h.ldlt().solve(g);
      if (!step.allFinite()) return std::nullopt;
    }
    // Backtrack until the squared distance does not grow. Within ~1e-8
    // of the minimum the squared distance no longer tells (its change is
    // below its rounding), so a full step that shrinks the gradient is
    // taken too: that is where Newton's method converges quadratically.
    bool improved = false;
    const double gradient = g.squaredNorm();
    for (int halving = 0; halving < 30; ++halving) {
      Vector2d trial = into_box(f, uv + step, clamped);
      SurfacePoint st = f.eval.d2(trial.x(), trial.y());
      const Vector3d rt = st.p - p;
      const double trial_value = rt.squaredNorm();
      const bool flat = halving == 0 && (st.p - s.p).squaredNorm() < 1e-12 * value &&
                        Vector2d(st.su.dot(rt), st.sv.dot(rt)).squaredNorm() < gradient;
      if (trial_value <= value * (1 + 1e-15) + 1e-300 || flat) {
        const double moved = (st.p - s.p).norm();
        uv = trial;
        s = st;
        value = trial_value;
        improved = true;
        if (moved < 1e-13 * scale) {
          return Local{uv, s, at_bound(f, uv)};
        }
        break;
      }
      step /= 2;
    }
    if (!improved) return Local{uv, s, at_bound(f, uv)};
  }
  return std::nullopt;
}

ModelContact BrepModel::Impl::make_contact(int face, const Vector3d& p, const Vector2d& uv,
                                           const SurfacePoint& s, ContactType type,
                                           const Vector3d& point, bool curvature) const {
  const FaceData& f = faces[static_cast<std::size_t>(face)];
  ModelContact c;
  c.point = point;
  Vector3d n = s.su.cross(s.sv);
  const double length = n.norm();
  n = length > 0 ? Vector3d(n / length) : Vector3d((p - point).normalized());
  if (f.reversed) n = -n;
  c.normal = n;
  c.distance = (p - point).norm();
  if (curvature) c.curvature = curvature_at(s, n);
  c.face = face;
  c.uv = uv;
  c.type = type;
  return c;
}

std::optional<ModelContact> BrepModel::Impl::on_edges(int face, const Vector3d& p, double bound,
                                                      bool curvature) const {
  const FaceData& f = faces[static_cast<std::size_t>(face)];
  double best = bound;
  const FaceEdge* best_edge = nullptr;
  double best_t = 0;
  Vector3d best_point;
  for (const FaceEdge& fe : f.edges) {
    const EdgeData& e = edges[static_cast<std::size_t>(fe.edge)];
    if (e.box.exteriorDistance(p) >= best) continue;
    std::size_t nearest = 0;
    double nearest_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < e.points.size(); ++i) {
      const double d = (e.points[i] - p).squaredNorm();
      if (d < nearest_d) {
        nearest_d = d;
        nearest = i;
      }
    }
    double t = e.ts[nearest];
    gp_Pnt c;
    gp_Vec c1, c2;
    for (int iteration = 0; iteration < 30; ++iteration) {
      e.curve->D2(t, c, c1, c2);
      const Vector3d r = to_eigen(c.XYZ()) - p, d1 = to_eigen(c1.XYZ()), d2 = to_eigen(c2.XYZ());
      const double g = d1.dot(r);
      double h = d2.dot(r) + d1.squaredNorm();
      if (h <= 0) h = d1.squaredNorm();
      if (h <= 0) break;
      const double next = std::clamp(t - g / h, e.t0, e.t1);
      const double moved = std::abs(next - t) * d1.norm();
      t = next;
      if (moved < 1e-13 * (1 + p.cwiseAbs().maxCoeff())) break;
    }
    const Vector3d point = to_eigen(e.curve->Value(t).XYZ());
    const double d = (point - p).norm();
    if (d < best) {
      best = d;
      best_edge = &fe;
      best_t = t;
      best_point = point;
    }
  }
  if (!best_edge) return std::nullopt;
  const EdgeData& e = edges[static_cast<std::size_t>(best_edge->edge)];
  const gp_Pnt2d uv2 = best_edge->pcurve->Value(best_t);
  const Vector2d uv(uv2.X(), uv2.Y());
  const SurfacePoint s = f.eval.d2(uv.x(), uv.y());
  const ContactType type =
      (!e.closed && (best_t <= e.t0 || best_t >= e.t1)) ? ContactType::vertex : ContactType::edge;
  return make_contact(face, p, uv, s, type, best_point, curvature);
}

std::optional<ModelContact> BrepModel::Impl::refine(int face, const Vector3d& p,
                                                    const Vector2d& start, double bound,
                                                    bool curvature) const {
  const FaceData& f = faces[static_cast<std::size_t>(face)];
  const std::optional<Local> local = newton(f, p, start);
  if (!local) return std::nullopt;
  const double d = (local->s.p - p).norm();
  if (!local->on_box_bound) {
    if (classify(f, local->uv) == Trim::inside) {
      if (d >= bound) return std::nullopt;
      return face_contact(face, p, local->uv, local->s, curvature);
    }
    return on_edges(face, p, bound, curvature);
  }
  // On the (u,v) box of an untrimmed face: the box is the face's border,
  // so this is the local minimum over the face; no nearer than the bound
  // means nothing to gain here (as inside: local minima are trusted).
  if (f.natural && d >= bound) return std::nullopt;
  // On the (u,v) box: usually an edge, but a pole (degenerate edge) or a
  // seam is no edge of ours, and there the surface point is the answer.
  // It must be a true foot point (p - S along the normal), not a point
  // where the box merely stopped Newton's method.
  std::optional<ModelContact> edge = on_edges(face, p, bound, curvature);
  const bool on_face = f.natural || classify(f, local->uv) != Trim::outside;
  if (on_face && d < bound && (!edge || d < edge->distance - 1e-9)) {
    ModelContact c = face_contact(face, p, local->uv, local->s, curvature);
    if ((p - c.point).cross(c.normal).norm() <= 1e-7 * std::max(1.0, d)) return c;
  }
  return edge;
}

ModelContact BrepModel::Impl::face_contact(int face, const Vector3d& p, const Vector2d& uv,
                                           const SurfacePoint& s, bool curvature) const {
  const FaceData& f = faces[static_cast<std::size_t>(face)];
  const double area = s.su.cross(s.sv).norm();
  if (area > 1e-10 * std::max(1.0, s.su.squaredNorm() + s.sv.squaredNorm())) {
    return make_contact(face, p, uv, s, ContactType::face, s.p, curvature);
  }
  const Vector2d centre((f.u0 + f.u1) / 2, (f.v0 + f.v1) / 2);
  const Vector2d nudged = uv + 1e-9 * (centre - uv);
  return make_contact(face, p, uv, f.eval.d2(nudged.x(), nudged.y()), ContactType::face, s.p,
                      curvature);
}

std::optional<std::pair<double, Vector2d>> BrepModel::Impl::nearest_triangle(const FaceData& f,
                                                                             const Vector3d& p,
                                                                             double bound) const {
  double best_sq = bound * bound;
  std::optional<std::pair<double, Vector2d>> best;
  f.tree.search(p, best_sq, [&](std::int32_t t, double) {
    const auto& tri = f.triangles[static_cast<std::size_t>(t)];
    const Vector3d w = closest_on_triangle(p, tri[0], tri[1], tri[2]);
    const Vector3d q = w.x() * tri[0] + w.y() * tri[1] + w.z() * tri[2];
    const double d = (q - p).squaredNorm();
    if (d < best_sq) {
      best_sq = d;
      const auto& uv = f.triangle_uv[static_cast<std::size_t>(t)];
      best = std::make_pair(std::sqrt(d), Vector2d(w.x() * uv[0] + w.y() * uv[1] + w.z() * uv[2]));
    }
    return best_sq;
  });
  return best;
}

std::optional<ModelContact> BrepModel::Impl::query(const Vector3d& p, double max_distance,
                                                   ContactHint* hint) const {
  std::optional<ModelContact> best;
  double bound = max_distance;
  int done = -1;
  const bool curvature = !hint || hint->curvature;
  if (hint && hint->face >= 0 && hint->face < static_cast<int>(faces.size()) &&
      (p - hint->query).norm() <= max_distance) {
    best = refine(hint->face, p, hint->uv, std::numeric_limits<double>::infinity(), curvature);
    if (best && best->distance > bound) best.reset();
    // A failed warm start leaves the face to the global search below.
    if (best) {
      bound = best->distance;
      done = hint->face;
    }
  }
  if (hint) ++(done >= 0 && best ? hint->warm_queries : hint->cold_queries);
  // Every other face whose tessellation comes within the bound (plus the
  // tessellation's own error) may hold a nearer point.
  const double reach = bound + max_slack;
  face_tree.search(p, reach * reach, [&](std::int32_t index, double) {
    if (index != done) {
      const FaceData& f = faces[static_cast<std::size_t>(index)];
      const auto tri = nearest_triangle(f, p, bound + f.slack);
      if (tri) {
        auto c = refine(index, p, tri->second, bound, curvature);
        if (c && c->distance < bound) {
          best = c;
          bound = c->distance;
        }
      }
    }
    const double r = bound + max_slack;
    return r * r;
  });
  if (hint && best) {
    hint->face = best->face;
    hint->uv = best->uv;
    hint->query = p;
  }
  return best;
}

}  // namespace vcpost::occt
