// A face's surface evaluated with its derivatives up to order 2, as the
// closest-point search needs it (position, tangents, second derivatives),
// and the principal curvatures made of them. Includes OpenCASCADE: for
// geometry/occt/ only.
#pragma once

#include <BSplSLib_Cache.hxx>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Surface.hxx>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <gp_XYZ.hxx>
#include <vector>

#include "geometry/model.h"

namespace vcpost::occt {

// Index a * stride + b of a row-major grid, in size_t: OpenCASCADE counts in
// int, the product must not be formed in int.
inline std::size_t grid_index(int a, int stride, int b = 0) {
  return static_cast<std::size_t>(a) * static_cast<std::size_t>(stride) +
         static_cast<std::size_t>(b);
}

inline Eigen::Vector3d to_eigen(const gp_XYZ& p) { return {p.X(), p.Y(), p.Z()}; }

// Position and derivatives up to order 2 of a surface at (u,v).
struct SurfacePoint {
  Eigen::Vector3d p, su, sv, suu, svv, suv;
};

// One knot span of a non-rational B-spline surface as a polynomial in
// x = (u - um)/hu, y = (v - vm)/hv about the span's centre (hu, hv: half
// widths): P = sum c[a][b] x^a y^b, the coefficients from the surface's own
// derivatives at the centre (Taylor, exact for a polynomial). Evaluation of
// the point and all derivatives up to order 2 is a nested Horner scheme.
struct PolynomialSpan {
  double um = 0, vm = 0, inv_hu = 1, inv_hv = 1;
  int degree_u = 0, degree_v = 0;
  std::vector<Eigen::Vector3d> c;  // c[a * (degree_v + 1) + b]

  void d2(double u, double v, SurfacePoint& out) const {
    const double x = (u - um) * inv_hu, y = (v - vm) * inv_hv;
    const int nv = degree_v + 1;
    // Horner in x over columns Q_a(y) and their y-derivatives.
    Eigen::Vector3d p0 = Eigen::Vector3d::Zero(), p1 = p0, p2 = p0;  // P, dP/dx, d2P/dx2 / 2
    Eigen::Vector3d y0 = p0, y1 = p0;                                // dP/dy and its x-derivative
    Eigen::Vector3d yy = p0;                                         // d2P/dy2 / 2
    for (int a = degree_u; a >= 0; --a) {
      const Eigen::Vector3d* col = &c[grid_index(a, nv)];
      Eigen::Vector3d q0 = col[degree_v], q1 = Eigen::Vector3d::Zero(),
                      q2 = Eigen::Vector3d::Zero();
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
  explicit SurfaceEval(Handle(Geom_Surface) surface);

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

// Principal curvatures from the fundamental forms, signed convex-positive
// with respect to the oriented normal n (geometry/model.h): the eigenvalues
// of the shape operator W = I^-1 II in closed form (mean and Gaussian
// curvature), the direction of k1 from W's eigenvector.
geometry::PrincipalCurvatures curvature_at(const SurfacePoint& s, const Eigen::Vector3d& n);

}  // namespace vcpost::occt
