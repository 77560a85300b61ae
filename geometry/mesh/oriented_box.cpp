#include "geometry/mesh/oriented_box.h"

#include <Eigen/Eigenvalues>
#include <cstring>

namespace vcpost::mesh {

void project_arrays(const double* xs, const double* ys, const double* zs, std::size_t n,
                    const Eigen::Matrix3d& axes, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  using D2 = double __attribute__((vector_size(16)));
  const auto load = [](const double* a) {
    D2 v;
    std::memcpy(&v, a, sizeof v);
    return v;
  };
  const auto splat = [](double x) { return D2{x, x}; };  // x in both lanes
  const D2 a00 = splat(axes(0, 0)), a01 = splat(axes(0, 1)), a02 = splat(axes(0, 2));
  const D2 a10 = splat(axes(1, 0)), a11 = splat(axes(1, 1)), a12 = splat(axes(1, 2));
  const D2 a20 = splat(axes(2, 0)), a21 = splat(axes(2, 1)), a22 = splat(axes(2, 2));
  constexpr double inf = std::numeric_limits<double>::infinity();
  D2 l0 = splat(inf), l1 = l0, l2 = l0;
  D2 h0 = splat(-inf), h1 = h0, h2 = h0;
  // q < l ? q : l lane by lane is std::min(l, q) (minpd on x86-64).
  const auto two = [&](D2 x, D2 y, D2 z) {
    const D2 q0 = (a00 * x + a01 * y) + a02 * z;
    const D2 q1 = (a10 * x + a11 * y) + a12 * z;
    const D2 q2 = a20 * x + (a21 * y + a22 * z);
    l0 = q0 < l0 ? q0 : l0;
    l1 = q1 < l1 ? q1 : l1;
    l2 = q2 < l2 ? q2 : l2;
    h0 = q0 > h0 ? q0 : h0;
    h1 = q1 > h1 ? q1 : h1;
    h2 = q2 > h2 ? q2 : h2;
  };
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) two(load(xs + i), load(ys + i), load(zs + i));
  if (i < n) two(splat(xs[i]), splat(ys[i]), splat(zs[i]));  // an odd last corner in both lanes
  lo = {std::min(l0[0], l0[1]), std::min(l1[0], l1[1]), std::min(l2[0], l2[1])};
  hi = {std::max(h0[0], h0[1]), std::max(h1[0], h1[1]), std::max(h2[0], h2[1])};
  if ((lo.array() != 0).all() && (hi.array() != 0).all()) return;
  const auto in_order = [&](auto& f) {
    for (std::size_t k = 0; k < n; ++k) f(xs[k], ys[k], zs[k]);
  };
  project(in_order, axes, lo, hi);
}

Eigen::Matrix3d principal_frame(const CornerSpread& spread) {
  // The closed-form solver: a third of the iterative one's time (which was
  // a quarter of the build). Its vectors may be off orthogonal where two
  // eigenvalues nearly meet, so the frame is made orthonormal again (the
  // boxes hold the corners whatever the axes; the query's bounds need
  // them orthonormal): the smallest one kept, the normal of a flat patch.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(spread.scatter);
  const Eigen::Matrix3d& v = solver.eigenvectors();
  Eigen::Vector3d a0 = v.col(0);
  if (!(a0.norm() > 0.5)) a0 = Eigen::Vector3d::UnitZ();
  a0.normalize();
  Eigen::Vector3d a2 = v.col(2) - v.col(2).dot(a0) * a0;
  a2 = a2.norm() > 0.5 ? Eigen::Vector3d(a2.normalized()) : a0.unitOrthogonal();
  Eigen::Matrix3d principal;
  principal.row(0) = a0;
  principal.row(1) = a2.cross(a0);
  principal.row(2) = a2;
  return principal;
}

}  // namespace vcpost::mesh
