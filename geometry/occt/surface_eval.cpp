#include "geometry/occt/surface_eval.h"

#include <Geom_RectangularTrimmedSurface.hxx>

namespace vcpost::occt {

using Eigen::Vector2d;
using Eigen::Vector3d;

SurfaceEval::SurfaceEval(Handle(Geom_Surface) surface) : surface_(std::move(surface)) {
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
  const int nu = static_cast<int>(u_knots_.size()) - 1, nv = static_cast<int>(v_knots_.size()) - 1;
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
            span.c[grid_index(a, dv + 1, b)] = d * (std::pow(hu, a) * std::pow(hv, b) / (fa * fb));
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

geometry::PrincipalCurvatures curvature_at(const SurfacePoint& s, const Vector3d& n) {
  const double e = s.su.dot(s.su), f = s.su.dot(s.sv), g = s.sv.dot(s.sv);
  // II with the sign flipped: a surface curving away from n is positive.
  const double l = -s.suu.dot(n), m = -s.suv.dot(n), nn = -s.svv.dot(n);
  geometry::PrincipalCurvatures c;
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

}  // namespace vcpost::occt
