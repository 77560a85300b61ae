#include "geometry/occt/brep_model.h"

#include <BRepBndLib.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <BSplSLib_Cache.hxx>
#include <Bnd_Box.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Curve.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_Surface.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "geometry/occt/box_tree.h"
#include "geometry/occt/shape_model.h"

namespace vcpost::occt {

using Eigen::Vector2d;
using Eigen::Vector3d;
using geometry::ContactHint;
using geometry::ContactType;
using geometry::ModelContact;
using geometry::PrincipalCurvatures;

namespace {

// Index a * stride + b of a row-major grid, in size_t: OpenCASCADE counts in
// int, the product must not be formed in int.
std::size_t grid_index(int a, int stride, int b = 0) {
  return static_cast<std::size_t>(a) * static_cast<std::size_t>(stride) +
         static_cast<std::size_t>(b);
}

Vector3d to_eigen(const gp_XYZ& p) { return {p.X(), p.Y(), p.Z()}; }

// Position and derivatives up to order 2 of a surface at (u,v).
struct SurfacePoint {
  Vector3d p, su, sv, suu, svv, suv;
};

// One knot span of a non-rational B-spline surface as a polynomial in
// x = (u - um)/hu, y = (v - vm)/hv about the span's centre (hu, hv: half
// widths): P = sum c[a][b] x^a y^b, the coefficients from the surface's own
// derivatives at the centre (Taylor, exact for a polynomial). Evaluation of
// the point and all derivatives up to order 2 is a nested Horner scheme.
struct PolynomialSpan {
  double um = 0, vm = 0, inv_hu = 1, inv_hv = 1;
  int degree_u = 0, degree_v = 0;
  std::vector<Vector3d> c;  // c[a * (degree_v + 1) + b]

  void d2(double u, double v, SurfacePoint& out) const {
    const double x = (u - um) * inv_hu, y = (v - vm) * inv_hv;
    const int nv = degree_v + 1;
    // Horner in x over columns Q_a(y) and their y-derivatives.
    Vector3d p0 = Vector3d::Zero(), p1 = p0, p2 = p0;  // P, dP/dx, d2P/dx2 / 2
    Vector3d y0 = p0, y1 = p0;                         // dP/dy and its x-derivative
    Vector3d yy = p0;                                  // d2P/dy2 / 2
    for (int a = degree_u; a >= 0; --a) {
      const Vector3d* col = &c[grid_index(a, nv)];
      Vector3d q0 = col[degree_v], q1 = Vector3d::Zero(), q2 = Vector3d::Zero();
      for (int b = degree_v - 1; b >= 0; --b) {
        q2 = q2 * y + q1;
        q1 = q1 * y + q0;
        q0 = q0 * y + col[b];
      }
      p2 = p2 * x + p1;
      p1 = p1 * x + p0;
      p0 = p0 * x + q0;
      y1 = y1 * x + y0;
      y0 = y0 * x + q1;
      yy = yy * x + q2;
    }
    out.p = p0;
    out.su = p1 * inv_hu;
    out.sv = y0 * inv_hv;
    out.suu = 2 * inv_hu * inv_hu * p2;
    out.svv = 2 * inv_hv * inv_hv * yy;
    out.suv = inv_hu * inv_hv * y1;
  }
};

// Evaluates a face's surface. Non-rational B-spline surfaces get one
// PolynomialSpan per knot span, rational ones one prebuilt BSplSLib_Cache
// (local power basis) per span: evaluation is then a polynomial, several
// times faster than Geom_BSplineSurface::D2, and nothing is rebuilt at
// query time, so evaluation stays const and thread-safe.
class SurfaceEval {
 public:
  explicit SurfaceEval(Handle(Geom_Surface) surface) : surface_(std::move(surface)) {
    Handle(Geom_Surface) basis = surface_;
    while (auto trimmed = Handle(Geom_RectangularTrimmedSurface)::DownCast(basis)) {
      basis = trimmed->BasisSurface();
    }
    bspline_ = Handle(Geom_BSplineSurface)::DownCast(basis);
    if (bspline_.IsNull()) return;
    const auto& uk = bspline_->UKnots();
    const auto& vk = bspline_->VKnots();
    for (int i = uk.Lower(); i <= uk.Upper(); ++i) u_knots_.push_back(uk(i));
    for (int i = vk.Lower(); i <= vk.Upper(); ++i) v_knots_.push_back(vk(i));
    const int nu = static_cast<int>(u_knots_.size()) - 1,
              nv = static_cast<int>(v_knots_.size()) - 1;
    const bool rational = bspline_->IsURational() || bspline_->IsVRational();
    if (!rational) {
      const int du = bspline_->UDegree(), dv = bspline_->VDegree();
      spans_.reserve(grid_index(nu, nv));
      for (int i = 0; i < nu; ++i) {
        for (int j = 0; j < nv; ++j) {
          PolynomialSpan span;
          span.degree_u = du;
          span.degree_v = dv;
          span.um = (u_knots_[i] + u_knots_[i + 1]) / 2;
          span.vm = (v_knots_[j] + v_knots_[j + 1]) / 2;
          const double hu = (u_knots_[i + 1] - u_knots_[i]) / 2;
          const double hv = (v_knots_[j + 1] - v_knots_[j]) / 2;
          span.inv_hu = 1 / hu;
          span.inv_hv = 1 / hv;
          span.c.resize(grid_index(du + 1, dv + 1));
          double fa = 1;  // a!
          for (int a = 0; a <= du; ++a) {
            if (a > 0) fa *= a;
            double fb = 1;  // b!
            for (int b = 0; b <= dv; ++b) {
              if (b > 0) fb *= b;
              const Vector3d d = a + b == 0 ? to_eigen(bspline_->Value(span.um, span.vm).XYZ())
                                            : to_eigen(bspline_->DN(span.um, span.vm, a, b).XYZ());
              span.c[grid_index(a, dv + 1, b)] =
                  d * (std::pow(hu, a) * std::pow(hv, b) / (fa * fb));
            }
          }
          spans_.push_back(std::move(span));
        }
      }
      return;
    }
    const auto& flat_u = bspline_->UKnotSequence();
    const auto& flat_v = bspline_->VKnotSequence();
    caches_.reserve(grid_index(nu, nv));
    for (int i = 0; i < nu; ++i) {
      for (int j = 0; j < nv; ++j) {
        Handle(BSplSLib_Cache) cache = new BSplSLib_Cache(
            bspline_->UDegree(), bspline_->IsUPeriodic(), flat_u, bspline_->VDegree(),
            bspline_->IsVPeriodic(), flat_v, bspline_->Weights());
        cache->BuildCache((u_knots_[i] + u_knots_[i + 1]) / 2, (v_knots_[j] + v_knots_[j + 1]) / 2,
                          flat_u, flat_v, bspline_->Poles(), bspline_->Weights());
        caches_.push_back(cache);
      }
    }
  }

  SurfacePoint d2(double u, double v) const {
    if (bspline_.IsNull()) {
      gp_Pnt p;
      gp_Vec su, sv, suu, svv, suv;
      surface_->D2(u, v, p, su, sv, suu, svv, suv);
      return {to_eigen(p.XYZ()),   to_eigen(su.XYZ()),  to_eigen(sv.XYZ()),
              to_eigen(suu.XYZ()), to_eigen(svv.XYZ()), to_eigen(suv.XYZ())};
    }
    if (bspline_->IsUPeriodic()) u = wrap(u, u_knots_.front(), u_knots_.back());
    if (bspline_->IsVPeriodic()) v = wrap(v, v_knots_.front(), v_knots_.back());
    const std::size_t i = span(u_knots_, u), j = span(v_knots_, v);
    const std::size_t k = i * (v_knots_.size() - 1) + j;
    if (!spans_.empty()) {
      SurfacePoint out;
      spans_[k].d2(u, v, out);
      return out;
    }
    gp_Pnt p;
    gp_Vec su, sv, suu, svv, suv;
    caches_[k]->D2(u, v, p, su, sv, suu, svv, suv);
    return {to_eigen(p.XYZ()),   to_eigen(su.XYZ()),  to_eigen(sv.XYZ()),
            to_eigen(suu.XYZ()), to_eigen(svv.XYZ()), to_eigen(suv.XYZ())};
  }

 private:
  static double wrap(double x, double lo, double hi) {
    const double period = hi - lo;
    x = lo + std::fmod(x - lo, period);
    return x < lo ? x + period : x;
  }
  static std::size_t span(const std::vector<double>& knots, double x) {
    const auto it = std::upper_bound(knots.begin(), knots.end(), x);
    const std::ptrdiff_t i = (it - knots.begin()) - 1;
    return static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(i, 0, std::ssize(knots) - 2));
  }

  Handle(Geom_Surface) surface_;
  Handle(Geom_BSplineSurface) bspline_;
  std::vector<double> u_knots_, v_knots_;
  std::vector<PolynomialSpan> spans_;           // non-rational
  std::vector<Handle(BSplSLib_Cache)> caches_;  // rational
};

struct EdgeData {
  Handle(Geom_Curve) curve;
  bool closed = false;  // starts and ends at one vertex (a full circle): its ends are no corner
  double t0 = 0, t1 = 0;
  std::vector<double> ts;  // samples for the start of Newton's method
  std::vector<Vector3d> points;
  Eigen::AlignedBox3d box;  // of the samples, grown by the chord error bound
};

struct FaceEdge {
  int edge = 0;
  Handle(Geom2d_Curve) pcurve;
};

enum class Trim : std::uint8_t { outside, inside, boundary };

struct FaceData {
  FaceData(TopoDS_Face f, SurfaceEval e) : face(std::move(f)), eval(std::move(e)) {}
  TopoDS_Face face;
  SurfaceEval eval;
  bool reversed = false;
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  double u_period = 0, v_period = 0;        // > 0 when the surface is periodic in that direction
  bool u_closed = false, v_closed = false;  // the face spans the whole period: no bound there
  bool natural = false;                     // the trim is the whole (u,v) box
  static constexpr int kGrid = 32;
  std::vector<Trim> cells;                     // kGrid x kGrid classification of the (u,v) box
  std::vector<std::array<Vector2d, 2>> loops;  // segments of the trim polygon in (u,v)
  double polygon_error = 0;                    // largest chord error of those segments, in (u,v)
  // Where the grid says "boundary": the segments whose v range meets each
  // grid row (the crossing count of a ray along +u needs no others) and the
  // segments within one cell of each cell (the only ones that can be
  // within the chord-error band of a point in it). local_lists is false
  // when the band is wider than a cell; then every segment is read.
  bool local_lists = false;
  std::vector<std::uint32_t> row_start, row_segments;
  std::vector<std::uint32_t> cell_start, cell_segments;
  std::vector<std::array<Vector3d, 3>> triangles;
  std::vector<std::array<Vector2d, 3>> triangle_uv;
  BoxTree tree;
  std::vector<FaceEdge> edges;
  double slack = 0;  // bound on the tessellation's distance from the face, mm
  Eigen::AlignedBox3d box;
};

// Closest point of triangle abc to p, as barycentric weights (wa, wb, wc).
Eigen::Vector3d closest_on_triangle(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                                    const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = d1 / (d1 - d3);
    return {1 - t, t, 0};
  }
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    return {1 - t, 0, t};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - t, t};
  }
  const double inv = 1 / (va + vb + vc);
  return {1 - (vb + vc) * inv, vb * inv, vc * inv};
}

// Even-odd crossing test of a point against the trim polygon.
bool inside_polygon(const std::vector<std::array<Vector2d, 2>>& segments, const Vector2d& q) {
  bool inside = false;
  for (const auto& [a, b] : segments) {
    if ((a.y() > q.y()) != (b.y() > q.y())) {
      const double x = a.x() + (q.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (x > q.x()) inside = !inside;
    }
  }
  return inside;
}

// Principal curvatures from the fundamental forms, signed convex-positive
// with respect to the oriented normal n (geometry/model.h): the eigenvalues
// of the shape operator W = I^-1 II in closed form (mean and Gaussian
// curvature), the direction of k1 from W's eigenvector.
PrincipalCurvatures curvature_at(const SurfacePoint& s, const Vector3d& n) {
  const double e = s.su.dot(s.su), f = s.su.dot(s.sv), g = s.sv.dot(s.sv);
  // II with the sign flipped: a surface curving away from n is positive.
  const double l = -s.suu.dot(n), m = -s.suv.dot(n), nn = -s.svv.dot(n);
  PrincipalCurvatures c;
  const double det = e * g - f * f;
  if (!(det > 0)) return c;
  const double w00 = (g * l - f * m) / det, w01 = (g * m - f * nn) / det;
  const double w10 = (e * m - f * l) / det, w11 = (e * nn - f * m) / det;
  const double mean = (w00 + w11) / 2, gauss = (l * nn - m * m) / det;
  const double root = std::sqrt(std::max(mean * mean - gauss, 0.0));
  c.k1 = mean + root;
  c.k2 = mean - root;
  // (W - k1) x = 0: either row gives x; take the better conditioned one.
  const Vector2d a(w01, c.k1 - w00), b(c.k1 - w11, w10);
  const Vector2d x = a.squaredNorm() >= b.squaredNorm() ? a : b;
  Vector3d d1 = x.squaredNorm() > 1e-30 * (1 + c.k1 * c.k1) ? Vector3d(x.x() * s.su + x.y() * s.sv)
                                                            : s.su;  // umbilic: any direction
  d1 -= d1.dot(n) * n;
  if (d1.norm() > 0) c.d1 = d1.normalized();
  c.d2 = n.cross(c.d1);
  return c;
}

struct Local {
  Vector2d uv;
  SurfacePoint s;
  bool on_box_bound = false;
};

}  // namespace

struct BrepModel::Impl {
  std::vector<FaceData> faces;
  std::vector<EdgeData> edges;
  BoxTree face_tree;
  double max_slack = 0;
  StepInfo info;
  Eigen::AlignedBox3d bounds;

  // Brings (u,v) into the face's box: periodic directions wrap to the
  // period centred on the box, then every direction clamps.
  Vector2d into_box(const FaceData& f, Vector2d uv, bool& clamped) const {
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

  static bool at_bound(const FaceData& f, const Vector2d& uv) {
    return (!f.u_closed && (uv.x() <= f.u0 || uv.x() >= f.u1)) ||
           (!f.v_closed && (uv.y() <= f.v0 || uv.y() >= f.v1));
  }

  // Newton's method for the closest point of the face's surface, inside
  // its (u,v) box; a variable on the box bound with the gradient pointing
  // out stays fixed. Empty when it does not converge.
  std::optional<Local> newton(const FaceData& f, const Vector3d& p, Vector2d uv) const {
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

  Trim classify(const FaceData& f, const Vector2d& uv) const {
    if (f.natural) return Trim::inside;
    const int gx = std::clamp(static_cast<int>((uv.x() - f.u0) / (f.u1 - f.u0) * FaceData::kGrid),
                              0, FaceData::kGrid - 1);
    const int gy = std::clamp(static_cast<int>((uv.y() - f.v0) / (f.v1 - f.v0) * FaceData::kGrid),
                              0, FaceData::kGrid - 1);
    const Trim cell = f.cells[grid_index(gx, FaceData::kGrid, gy)];
    if (cell != Trim::boundary) return cell;
    // The polygon decides unless the point is within its chord error of it.
    bool inside = false;
    double nearest = std::numeric_limits<double>::infinity();
    const auto cross = [&](const std::array<Vector2d, 2>& segment) {
      const auto& [a, b] = segment;
      if ((a.y() > uv.y()) != (b.y() > uv.y())) {
        const double x = a.x() + (uv.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
        if (x > uv.x()) inside = !inside;
      }
    };
    const auto near = [&](const std::array<Vector2d, 2>& segment) {
      const auto& [a, b] = segment;
      const Vector2d ab = b - a;
      const double t = std::clamp((uv - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
      nearest = std::min(nearest, (a + t * ab - uv).squaredNorm());
    };
    if (f.local_lists) {
      const auto row = static_cast<std::size_t>(gy);
      for (std::uint32_t i = f.row_start[row]; i < f.row_start[row + 1]; ++i) {
        cross(f.loops[f.row_segments[i]]);
      }
      const auto at = grid_index(gx, FaceData::kGrid, gy);
      for (std::uint32_t i = f.cell_start[at]; i < f.cell_start[at + 1]; ++i) {
        near(f.loops[f.cell_segments[i]]);
      }
    } else {
      for (const auto& segment : f.loops) {
        cross(segment);
        near(segment);
      }
    }
    const double band = 2 * f.polygon_error + 1e-9 * std::max(f.u1 - f.u0, f.v1 - f.v0);
    if (nearest > band * band) return inside ? Trim::inside : Trim::outside;
    // Near the boundary the polygon is not exact: classify on the pcurves.
    const double tol = 1e-9 * std::max(f.u1 - f.u0, f.v1 - f.v0);
    BRepClass_FaceClassifier classifier(f.face, gp_Pnt2d(uv.x(), uv.y()), tol);
    const TopAbs_State state = classifier.State();
    return state == TopAbs_IN ? Trim::inside : state == TopAbs_OUT ? Trim::outside : Trim::boundary;
  }

  // curvature: whether to fill ModelContact::curvature (only reports read it).
  ModelContact make_contact(int face, const Vector3d& p, const Vector2d& uv, const SurfacePoint& s,
                            ContactType type, const Vector3d& point, bool curvature) const {
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

  // Closest point of the face's boundary edges (seams and degenerate edges
  // excluded), nearer than `bound`.
  std::optional<ModelContact> on_edges(int face, const Vector3d& p, double bound,
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

  // The exact closest point of one face from a start (u,v): Newton on the
  // surface, then the trim; outside it, the face's edges.
  std::optional<ModelContact> refine(int face, const Vector3d& p, const Vector2d& start,
                                     double bound, bool curvature) const {
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

  // A contact inside a face; where the parametrisation is singular (a
  // pole: first fundamental form degenerate) normal and curvatures come
  // from a point a hair inside the (u,v) box.
  ModelContact face_contact(int face, const Vector3d& p, const Vector2d& uv, const SurfacePoint& s,
                            bool curvature) const {
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

  // Nearest tessellation triangle of a face within `bound`: its distance
  // and the (u,v) of its closest point.
  std::optional<std::pair<double, Vector2d>> nearest_triangle(const FaceData& f, const Vector3d& p,
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
        best =
            std::make_pair(std::sqrt(d), Vector2d(w.x() * uv[0] + w.y() * uv[1] + w.z() * uv[2]));
      }
      return best_sq;
    });
    return best;
  }

  std::optional<ModelContact> query(const Vector3d& p, double max_distance,
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
};

namespace {

// The trim polygon (f.loops, f.polygon_error) and the face's edges
// (f.edges); returns the number of wires.
int add_trims(FaceData& f, const TopoDS_Face& face, const TopTools_IndexedMapOfShape& edge_map) {
  int wires = 0;
  for (TopExp_Explorer w(face, TopAbs_WIRE); w.More(); w.Next()) ++wires;
  for (TopExp_Explorer x(face, TopAbs_EDGE); x.More(); x.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(x.Current());
    double a = 0, b = 0;
    Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(edge, face, a, b);
    if (pcurve.IsNull()) continue;
    // A straight pcurve is one segment; others start as 16 and are halved
    // where the curve's midpoint is off the chord by more than 1e-7 of the
    // face's (u,v) span: a tight polygon leaves only a thin band around the
    // trim for the (slow) exact classifier.
    Handle(Geom2d_Curve) basis = pcurve;
    while (auto trimmed = Handle(Geom2d_TrimmedCurve)::DownCast(basis))
      basis = trimmed->BasisCurve();
    const auto at = [&](double t) {
      const gp_Pnt2d q = pcurve->Value(t);
      return Vector2d(q.X(), q.Y());
    };
    if (basis->IsKind(STANDARD_TYPE(Geom2d_Line))) {
      f.loops.push_back({at(a), at(b)});
    } else {
      const double tolerance = 1e-7 * std::max(f.u1 - f.u0, f.v1 - f.v0);
      constexpr int kStart = 16, kMaxDepth = 10;
      struct Piece {
        double t0, t1;
        Vector2d p0, p1;
        int depth;
      };
      std::vector<Piece> pending;
      for (int i = kStart - 1; i >= 0; --i) {
        const double t0 = a + (b - a) * i / kStart, t1 = a + (b - a) * (i + 1) / kStart;
        pending.push_back({t0, t1, at(t0), at(t1), 0});
      }
      while (!pending.empty()) {
        const Piece piece = pending.back();
        pending.pop_back();
        const double tm = (piece.t0 + piece.t1) / 2;
        const Vector2d pm = at(tm);
        const double error = (pm - (piece.p0 + piece.p1) / 2).norm();
        if (error > tolerance && piece.depth < kMaxDepth) {
          pending.push_back({tm, piece.t1, pm, piece.p1, piece.depth + 1});
          pending.push_back({piece.t0, tm, piece.p0, pm, piece.depth + 1});
        } else {
          f.loops.push_back({piece.p0, piece.p1});
          f.polygon_error = std::max(f.polygon_error, error);
        }
      }
    }
    if (BRep_Tool::Degenerated(edge) || BRep_Tool::IsClosed(edge, face)) continue;
    const int index = edge_map.FindIndex(edge) - 1;
    if (index >= 0) f.edges.push_back({index, pcurve});
  }
  return wires;
}

// Whether the trim is the (u,v) box (f.natural); else the grid of cells
// inside, outside or on the trim, and the segments near each row and cell.
void classify_trim(FaceData& f, int wires) {
  const double span_u = f.u1 - f.u0, span_v = f.v1 - f.v0;
  const double eps = 1e-9 * std::max(span_u, span_v);
  const auto on_box = [&](const Vector2d& q) {
    return std::abs(q.x() - f.u0) < eps || std::abs(q.x() - f.u1) < eps ||
           std::abs(q.y() - f.v0) < eps || std::abs(q.y() - f.v1) < eps;
  };
  f.natural = wires == 1 && std::all_of(f.loops.begin(), f.loops.end(), [&](const auto& s) {
                return on_box(s[0]) && on_box(s[1]);
              });
  if (!f.natural) {
    constexpr int g = FaceData::kGrid;
    std::vector<bool> touched(g * g, false);
    const auto cell_of = [&](double x, double lo, double span) {
      return std::clamp(static_cast<int>((x - lo) / span * g), 0, g - 1);
    };
    for (const auto& [a, b] : f.loops) {
      // Cells within one cell of a segment's box are boundary cells.
      const int x0 = cell_of(std::min(a.x(), b.x()), f.u0, span_u) - 1;
      const int x1 = cell_of(std::max(a.x(), b.x()), f.u0, span_u) + 1;
      const int y0 = cell_of(std::min(a.y(), b.y()), f.v0, span_v) - 1;
      const int y1 = cell_of(std::max(a.y(), b.y()), f.v0, span_v) + 1;
      for (int x = std::max(x0, 0); x <= std::min(x1, g - 1); ++x) {
        for (int y = std::max(y0, 0); y <= std::min(y1, g - 1); ++y) touched[x * g + y] = true;
      }
    }
    // Row and cell lists (CSR), each segment listed one row or cell beyond
    // its box so rounding at the grid lines loses none.
    std::vector<std::vector<std::uint32_t>> rows(g), cells(g * g);
    for (std::size_t i = 0; i < f.loops.size(); ++i) {
      const auto& [a, b] = f.loops[i];
      const int x0 = cell_of(std::min(a.x(), b.x()), f.u0, span_u) - 1;
      const int x1 = cell_of(std::max(a.x(), b.x()), f.u0, span_u) + 1;
      const int y0 = cell_of(std::min(a.y(), b.y()), f.v0, span_v) - 1;
      const int y1 = cell_of(std::max(a.y(), b.y()), f.v0, span_v) + 1;
      for (int y = std::max(y0, 0); y <= std::min(y1, g - 1); ++y) {
        rows[static_cast<std::size_t>(y)].push_back(static_cast<std::uint32_t>(i));
        for (int x = std::max(x0, 0); x <= std::min(x1, g - 1); ++x) {
          cells[grid_index(x, g, y)].push_back(static_cast<std::uint32_t>(i));
        }
      }
    }
    const auto flatten = [](const std::vector<std::vector<std::uint32_t>>& lists,
                            std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& flat) {
      start.assign(1, 0);
      for (const auto& list : lists) {
        flat.insert(flat.end(), list.begin(), list.end());
        start.push_back(static_cast<std::uint32_t>(flat.size()));
      }
    };
    flatten(rows, f.row_start, f.row_segments);
    flatten(cells, f.cell_start, f.cell_segments);
    const double band = 2 * f.polygon_error + 1e-9 * std::max(span_u, span_v);
    f.local_lists = band < std::min(span_u, span_v) / g;
    f.cells.resize(g * g);
    for (int x = 0; x < g; ++x) {
      for (int y = 0; y < g; ++y) {
        const Vector2d centre(f.u0 + (x + 0.5) * span_u / g, f.v0 + (y + 0.5) * span_v / g);
        f.cells[x * g + y] = touched[x * g + y]                ? Trim::boundary
                             : inside_polygon(f.loops, centre) ? Trim::inside
                                                               : Trim::outside;
      }
    }
  }
}

// Tessellation (with (u,v) at the nodes) or, without one, a (u,v) grid;
// f.slack bounds the surface's distance from the triangles.
void tessellate(FaceData& f, const TopoDS_Face& face) {
  const double span_u = f.u1 - f.u0, span_v = f.v1 - f.v0;
  TopLoc_Location location;
  const Handle(Poly_Triangulation) mesh = BRep_Tool::Triangulation(face, location);
  if (!mesh.IsNull() && mesh->HasUVNodes() && mesh->NbTriangles() > 0) {
    const gp_Trsf trsf = location.Transformation();
    for (int t = 1; t <= mesh->NbTriangles(); ++t) {
      int n[3];
      mesh->Triangle(t).Get(n[0], n[1], n[2]);
      std::array<Vector3d, 3> tri;
      std::array<Vector2d, 3> uv;
      for (int k = 0; k < 3; ++k) {
        tri[k] = to_eigen(mesh->Node(n[k]).Transformed(trsf).XYZ());
        const gp_Pnt2d q = mesh->UVNode(n[k]);
        uv[k] = {q.X(), q.Y()};
      }
      f.triangles.push_back(tri);
      f.triangle_uv.push_back(uv);
    }
    // The triangulation's own Deflection() is not a bound we can use, so
    // measure how far the surface at each triangle's (u,v) centre and edge
    // midpoints lies from the triangle.
    double chord = 0;
    for (std::size_t t = 0; t < f.triangles.size(); ++t) {
      const auto& tri = f.triangles[t];
      const auto& uv = f.triangle_uv[t];
      const auto gap = [&](const Vector2d& q) {
        const Vector3d x = f.eval.d2(q.x(), q.y()).p;
        const Vector3d w = closest_on_triangle(x, tri[0], tri[1], tri[2]);
        chord = std::max(chord, (w.x() * tri[0] + w.y() * tri[1] + w.z() * tri[2] - x).norm());
      };
      gap((uv[0] + uv[1] + uv[2]) / 3);
      for (int k = 0; k < 3; ++k) gap((uv[k] + uv[(k + 1) % 3]) / 2);
    }
    f.slack = 2 * chord + 1e-6;
  } else {
    constexpr int g = 24;
    std::vector<Vector3d> grid;
    for (int i = 0; i <= g; ++i) {
      for (int j = 0; j <= g; ++j) {
        grid.push_back(f.eval.d2(f.u0 + span_u * i / g, f.v0 + span_v * j / g).p);
      }
    }
    double chord = 0;
    for (int i = 0; i < g; ++i) {
      for (int j = 0; j < g; ++j) {
        const auto at = [&](int a, int b) { return grid_index(a, g + 1, b); };
        const auto uv = [&](int a, int b) {
          return Vector2d(f.u0 + span_u * a / g, f.v0 + span_v * b / g);
        };
        f.triangles.push_back({grid[at(i, j)], grid[at(i + 1, j)], grid[at(i + 1, j + 1)]});
        f.triangle_uv.push_back({uv(i, j), uv(i + 1, j), uv(i + 1, j + 1)});
        f.triangles.push_back({grid[at(i, j)], grid[at(i + 1, j + 1)], grid[at(i, j + 1)]});
        f.triangle_uv.push_back({uv(i, j), uv(i + 1, j + 1), uv(i, j + 1)});
        const Vector3d mid =
            f.eval.d2(f.u0 + span_u * (i + 0.5) / g, f.v0 + span_v * (j + 0.5) / g).p;
        chord = std::max(chord, (mid - (grid[at(i, j)] + grid[at(i + 1, j + 1)]) / 2).norm());
      }
    }
    f.slack = 4 * chord + 1e-6;
  }
}

// The box tree over the triangles and the face's box grown by the slack.
void build_box_tree(FaceData& f) {
  std::vector<Eigen::AlignedBox3d> boxes;
  boxes.reserve(f.triangles.size());
  for (const auto& tri : f.triangles) {
    Eigen::AlignedBox3d b(tri[0]);
    b.extend(tri[1]);
    b.extend(tri[2]);
    boxes.push_back(b);
    f.box.extend(b);
  }
  f.tree = BoxTree(boxes);
  const Vector3d grow = Vector3d::Constant(f.slack);
  f.box = Eigen::AlignedBox3d(f.box.min() - grow, f.box.max() + grow);
}

// Flips f.reversed where the face's area-weighted mean normal points down.
void orient_up_normal(FaceData& f) {
  // Area-weighted mean of the oriented normal over the tessellation.
  double up = 0;
  for (std::size_t t = 0; t < f.triangles.size(); ++t) {
    const auto& tri = f.triangles[t];
    const auto& uv = f.triangle_uv[t];
    const Vector2d c = (uv[0] + uv[1] + uv[2]) / 3;
    const SurfacePoint sp = f.eval.d2(c.x(), c.y());
    const Vector3d n = sp.su.cross(sp.sv);
    const double area = (tri[1] - tri[0]).cross(tri[2] - tri[0]).norm();
    if (n.norm() > 0) up += area * n.z() / n.norm();
  }
  if ((f.reversed ? -up : up) < 0) f.reversed = !f.reversed;
}

void add_face(BrepModel::Impl& model, const TopoDS_Face& face,
              const TopTools_IndexedMapOfShape& edge_map, bool orient_up) {
  Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
  if (surface.IsNull()) return;
  FaceData f(face, SurfaceEval(surface));
  f.reversed = face.Orientation() == TopAbs_REVERSED;
  BRepTools::UVBounds(face, f.u0, f.u1, f.v0, f.v1);
  if (surface->IsUPeriodic()) f.u_period = surface->UPeriod();
  if (surface->IsVPeriodic()) f.v_period = surface->VPeriod();
  const int wires = add_trims(f, face, edge_map);
  const double span_u = f.u1 - f.u0, span_v = f.v1 - f.v0;
  if (!(span_u > 0 && span_v > 0)) return;
  f.u_closed = f.u_period > 0 && span_u >= f.u_period * (1 - 1e-9);
  f.v_closed = f.v_period > 0 && span_v >= f.v_period * (1 - 1e-9);
  classify_trim(f, wires);
  tessellate(f, face);
  build_box_tree(f);
  if (orient_up) orient_up_normal(f);
  model.faces.push_back(std::move(f));
}

void add_edges(BrepModel::Impl& model, const TopTools_IndexedMapOfShape& edge_map) {
  model.edges.resize(static_cast<std::size_t>(edge_map.Extent()));
  for (int i = 1; i <= edge_map.Extent(); ++i) {
    const TopoDS_Edge& edge = TopoDS::Edge(edge_map(i));
    EdgeData& e = model.edges[static_cast<std::size_t>(i - 1)];
    if (BRep_Tool::Degenerated(edge)) continue;
    e.curve = BRep_Tool::Curve(edge, e.t0, e.t1);
    if (e.curve.IsNull()) continue;
    TopoDS_Vertex first, last;
    TopExp::Vertices(edge, first, last);
    e.closed = !first.IsNull() && first.IsSame(last);
    constexpr int kSamples = 64;
    double chord = 0;
    for (int k = 0; k <= kSamples; ++k) {
      const double t = e.t0 + (e.t1 - e.t0) * k / kSamples;
      e.ts.push_back(t);
      e.points.push_back(to_eigen(e.curve->Value(t).XYZ()));
      e.box.extend(e.points.back());
      if (k > 0) {
        const Vector3d mid = to_eigen(e.curve->Value(t - (e.t1 - e.t0) / kSamples / 2).XYZ());
        chord = std::max(chord, (mid - (e.points[k - 1] + e.points[k]) / 2).norm());
      }
    }
    const Vector3d grow = Vector3d::Constant(4 * chord + 1e-6);
    e.box = Eigen::AlignedBox3d(e.box.min() - grow, e.box.max() + grow);
  }
}

}  // namespace

std::string_view code_of(ModelErrorCode code) {
  switch (code) {
    case ModelErrorCode::file_missing:
      return "E4101";
    case ModelErrorCode::file_unreadable:
      return "E4102";
    case ModelErrorCode::file_empty:
      return "E4103";
    case ModelErrorCode::not_step:
      return "E4104";
    case ModelErrorCode::no_faces:
      return "E4105";
    case ModelErrorCode::kernel_failure:
      return "E4106";
    case ModelErrorCode::bad_values:
      return "E4107";
  }
  return "E9999";  // unreachable: every enumerator is above
}

ModelError::ModelError(ModelErrorCode code, const std::string& path, const std::string& message)
    : vcpost::Error(code_of(code), path + ": error[" + std::string(code_of(code)) + "]: " + message,
                    {path, 0, 0}),
      code_(code) {}

BrepModel model_from_shape(const TopoDS_Shape& shape, const BrepOptions& options,
                           const std::string& source, const std::string& length_unit) {
  auto impl = std::make_unique<BrepModel::Impl>();
  impl->info.length_unit = length_unit;
  try {
    TopTools_IndexedMapOfShape face_map, edge_map;
    TopExp::MapShapes(shape, TopAbs_FACE, face_map);
    TopExp::MapShapes(shape, TopAbs_EDGE, edge_map);
    if (face_map.Extent() == 0) {
      throw ModelError(ModelErrorCode::no_faces, source,
                       "the model holds no faces (points, curves or an empty assembly only); "
                       "export the finished surfaces or the solid");
    }
    Bnd_Box box;
    BRepBndLib::Add(shape, box);
    if (!box.IsVoid()) {
      // Checked before meshing: a pole at 1E300 would mesh for hours.
      double x0, y0, z0, x1, y1, z1;
      box.Get(x0, y0, z0, x1, y1, z1);
      const double reach = std::max(
          {std::abs(x0), std::abs(y0), std::abs(z0), std::abs(x1), std::abs(y1), std::abs(z1)});
      if (!(reach <= kMaxModelReachMm)) {
        std::ostringstream text;
        text << "the model reaches " << reach << " mm from the origin; parts within "
             << kMaxModelReachMm << " mm (100 m) of it are read (a stray point or a wrong unit?)";
        throw ModelError(ModelErrorCode::bad_values, source, text.str());
      }
    }
    double deflection = options.deflection;
    if (deflection <= 0) {
      const double diagonal = box.IsVoid() ? 100 : std::sqrt(box.SquareExtent());
      // Over 4 m of diagonal the chord grows with the model, so the number
      // of triangles (the meshing effort) stays bounded.
      deflection = std::max(std::clamp(diagonal / 1000, 0.002, 0.2), diagonal / 20000);
    }
    BRepMesh_IncrementalMesh mesher(shape, deflection, false, 0.2, false);
    TopTools_IndexedMapOfShape solids;
    TopExp::MapShapes(shape, TopAbs_SOLID, solids);
    const bool orient_up = options.orient_open_faces_up && solids.Extent() == 0;
    add_edges(*impl, edge_map);
    for (int i = 1; i <= face_map.Extent(); ++i) {
      add_face(*impl, TopoDS::Face(face_map(i)), edge_map, orient_up);
    }
    if (impl->faces.empty()) {
      throw ModelError(ModelErrorCode::no_faces, source, "no face of the model has a surface");
    }
    std::vector<Eigen::AlignedBox3d> boxes;
    for (const FaceData& f : impl->faces) {
      boxes.push_back(f.box);
      impl->bounds.extend(f.box);
      impl->max_slack = std::max(impl->max_slack, f.slack);
      impl->info.triangles += static_cast<int>(f.triangles.size());
    }
    impl->face_tree = BoxTree(boxes);
    impl->info.faces = static_cast<int>(impl->faces.size());
    impl->info.deflection = deflection;
  } catch (const Standard_Failure& failure) {
    throw ModelError(
        ModelErrorCode::kernel_failure, source,
        std::string("OpenCASCADE failed while indexing the model: ") + failure.GetMessageString());
  }
  return BrepModel(std::move(impl));
}

BrepModel::BrepModel(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
BrepModel::BrepModel(BrepModel&&) noexcept = default;
BrepModel& BrepModel::operator=(BrepModel&&) noexcept = default;
BrepModel::~BrepModel() = default;

std::optional<ModelContact> BrepModel::closest_point(const Eigen::Vector3d& point,
                                                     double max_distance, ContactHint* hint) const {
  return impl_->query(point, max_distance, hint);
}

Eigen::AlignedBox3d BrepModel::bounds() const { return impl_->bounds; }
int BrepModel::face_count() const { return static_cast<int>(impl_->faces.size()); }
const StepInfo& BrepModel::info() const { return impl_->info; }

}  // namespace vcpost::occt
