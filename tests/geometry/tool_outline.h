// Test support: a revolved tool's outline seen along a direction, from the
// tool's support function by convex duality (independent of the engine's
// silhouette): the tool (its end the core disc grown by rc, under the
// shank's cylinder of radius R) is convex with support function h(v) =
// max(R0 |v_xy| + rc |v|, R |v_xy|) where v_z <= 0 (infinite upwards), so
// the lowest c = n.P over its points P (the frame's origin at the core
// disc's centre) with e.P = b is c(b) = max over t of (t b - h(t e - n)),
// a concave maximum found by golden sections. e, n: orthonormal, normal to
// the direction seen along.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "geometry/tool.h"

namespace vcpost::testing {

struct ToolOutline {
  geometry::Tool tool;
  Eigen::Vector3d e, n;

  double support(const Eigen::Vector3d& v) const {
    const double flat = std::hypot(v.x(), v.y());
    return std::max(tool.flat_radius() * flat + tool.corner_radius * v.norm(),
                    tool.radius() * flat);
  }

  double lowest(double b) const {
    // t e_z - n_z <= 0 keeps h finite.
    double lo = -1e3, hi = e.z() > 0 ? n.z() / e.z() : 1e3;
    if (e.z() < 0) lo = std::max(lo, n.z() / e.z());
    const auto f = [&](double t) { return t * b - support(t * e - n); };
    const double golden = (std::sqrt(5.0) - 1) / 2;
    double a = hi - golden * (hi - lo), c = lo + golden * (hi - lo);
    double fa = f(a), fc = f(c);
    for (int i = 0; i < 200 && hi - lo > 1e-13; ++i) {
      if (fa < fc) {  // the maximum lies in [a, hi]
        lo = a;
        a = c;
        fa = fc;
        c = lo + golden * (hi - lo);
        fc = f(c);
      } else {
        hi = c;
        c = a;
        fc = fa;
        a = hi - golden * (hi - lo);
        fa = f(a);
      }
    }
    return f(0.5 * (lo + hi));
  }
};

}  // namespace vcpost::testing
