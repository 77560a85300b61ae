// The lower surface of a cutter above its tip, as the stock sees it: the
// height h(r) of the tool's underside at radial distance r in [0, R] from
// its axis. Above the underside every tool is solid up to infinity (the
// shank): a Z-map only sees the lowest point over each cell.
#pragma once

#include <algorithm>
#include <cmath>

#include "geometry/stock/height_field.h"

namespace vcpost::geometry::stock {

enum class ProfileKind { ball, torus, flat, cone };

struct CutterProfile {
  ProfileKind kind = ProfileKind::flat;
  double radius = 0;         // R
  double flat_radius = 0;    // R0 = R - rc (torus)
  double corner_radius = 0;  // rc (torus and ball)
  double cone_slope = 0;     // dh/dr of a drill point: cot(angle / 2)

  // Throws vcpost::Error E4706 for a diameter that is not positive and
  // finite, a corner radius outside (0, R] for a bull-nose, or a point
  // angle outside (0, 180) degrees.
  static CutterProfile of(const Cutter& cutter);

  double height(double r) const {
    switch (kind) {
      case ProfileKind::ball:
        return radius - std::sqrt(std::max(0.0, radius * radius - r * r));
      case ProfileKind::torus: {
        const double d = r - flat_radius;
        return d <= 0 ? 0.0
                      : corner_radius -
                            std::sqrt(std::max(0.0, corner_radius * corner_radius - d * d));
      }
      case ProfileKind::flat:
        return 0.0;
      case ProfileKind::cone:
        return cone_slope * r;
    }
    return 0.0;
  }
};

}  // namespace vcpost::geometry::stock
