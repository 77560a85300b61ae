#include "revolved_sampler_support.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

namespace vcpost::testing {
namespace {

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

// Golden-section minimum value of a unimodal function on [lo, hi].
double golden_min(const std::function<double(double)>& f, double lo, double hi) {
  const double ratio = 0.5 * (std::sqrt(5.0) - 1);
  double a = lo, b = hi;
  double x1 = b - ratio * (b - a), x2 = a + ratio * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < 90; ++i) {
    if (f1 <= f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - ratio * (b - a), f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + ratio * (b - a), f2 = f(x2);
    }
  }
  return std::min({f1, f2, f(lo), f(hi)});
}

enum class Piece { face, corner, shank };

struct Surface {
  double radius, corner, flat;  // R, rc, R0
  double shank_height;          // no shank point above this is in the stock

  // Parameters: face (rho, theta), corner (psi, theta), shank (z, theta).
  Vector3d point(Piece piece, double u, double theta) const {
    const double c = std::cos(theta), s = std::sin(theta);
    switch (piece) {
      case Piece::face:
        return {u * c, u * s, -corner};
      case Piece::corner: {
        const double rho = flat + corner * std::sin(u);
        return {rho * c, rho * s, -corner * std::cos(u)};
      }
      case Piece::shank:
        return {radius * c, radius * s, u};
    }
    return Vector3d::Zero();
  }
  Vector3d normal(Piece piece, double u, double theta) const {
    const double c = std::cos(theta), s = std::sin(theta);
    switch (piece) {
      case Piece::face:
        return {0, 0, -1};
      case Piece::corner:
        return {std::sin(u) * c, std::sin(u) * s, -std::cos(u)};
      case Piece::shank:
        return {c, s, 0};
    }
    return Vector3d::Zero();
  }
  // Area of a du x dtheta cell at u.
  double area(Piece piece, double u) const {
    switch (piece) {
      case Piece::face:
        return u;
      case Piece::corner:
        return corner * (flat + corner * std::sin(u));
      case Piece::shank:
        return radius;
    }
    return 0;
  }
  double u_max(Piece piece) const {
    switch (piece) {
      case Piece::face:
        return flat;
      case Piece::corner:
        return kPi / 2;
      case Piece::shank:
        return shank_height;
    }
    return 0;
  }
};

}  // namespace

bool inside_sweep(double diameter, double corner_radius, const Vector3d& p, const Vector3d& offset,
                  const Vector3d& feed) {
  const double radius = diameter / 2, flat = radius - corner_radius;
  const Vector3d base = p - offset;
  const double horizontal = std::hypot(feed.x(), feed.y());
  const double reach = (base.norm() + radius) / horizontal + 1;
  const auto at = [&](double t) { return Vector3d(base - t * feed); };
  if (corner_radius == 0) {
    // Depth inside the solid {rho < R, z > 0}: concave along the line.
    const auto shallowness = [&](double t) {
      const Vector3d x = at(t);
      return -std::min(radius - std::hypot(x.x(), x.y()), x.z());
    };
    return -golden_min(shallowness, -reach, reach) > 1e-10 * radius;
  }
  // Distance to the core {rho <= R0, z >= 0} below rc: inside the bull-nose.
  const auto distance = [&](double t) {
    const Vector3d x = at(t);
    return std::hypot(std::max(0.0, std::hypot(x.x(), x.y()) - flat), std::min(0.0, x.z()));
  };
  return golden_min(distance, -reach, reach) < corner_radius - 1e-10 * radius;
}

RevolvedSample sample_revolved(double diameter, double corner_radius, double ap, double ae,
                               const Vector3d& normal_in, const Vector3d& feed_in,
                               bool previous_on_left, int resolution) {
  const Vector3d n = normal_in.normalized();
  const Vector3d f = (feed_in - feed_in.dot(n) * n).normalized();
  const Vector3d s0 = n.cross(f);
  const Vector3d offset = (previous_on_left ? ae : -ae) * s0;
  const double radius = diameter / 2, flat = radius - corner_radius;
  // The lowest tool point along N: the rim of the core pushed by rc along -N.
  const double c_min = -flat * std::hypot(n.x(), n.y()) - corner_radius;
  const double c0 = c_min + ap;
  const Surface surface{radius, corner_radius, flat,
                        std::max(0.0, (c0 + radius * std::hypot(n.x(), n.y())) / n.z())};

  RevolvedSample out;
  out.c0 = c0;
  const auto engaged = [&](Piece piece, double u, double theta) {
    const Vector3d p = surface.point(piece, u, theta);
    if (n.dot(p) > c0 + 1e-12) return false;
    // Leading within round-off: a level feed's face is seen edge-on (the
    // engine's kEdgeOn), whatever sign F_z's 1e-17 of renormalising takes.
    if (surface.normal(piece, u, theta).dot(f) < -1e-12) return false;
    return !inside_sweep(diameter, corner_radius, p, offset, f);
  };

  std::vector<Piece> pieces{Piece::face, Piece::shank};
  if (corner_radius > 0) pieces.push_back(Piece::corner);
  const int n_theta = 4 * resolution, n_u = resolution;
  double sum_weight = 0, sum_diameter = 0;
  struct Best {
    double r;
    Piece piece;
    double u, theta;
  };
  Best lowest{std::numeric_limits<double>::infinity(), Piece::face, 0, 0};
  Best highest{-1, Piece::face, 0, 0};
  const auto consider = [&](Piece piece, double u, double theta) {
    const Vector3d p = surface.point(piece, u, theta);
    const double r = std::hypot(p.x(), p.y());
    if (r < lowest.r) lowest = {r, piece, u, theta};
    if (r > highest.r) highest = {r, piece, u, theta};
    if (piece == Piece::shank && p.z() > 1e-9) out.shank = true;
  };
  for (const Piece piece : pieces) {
    const double du = surface.u_max(piece) / n_u, dtheta = 2 * kPi / n_theta;
    if (!(du > 0)) continue;
    const double extent = piece == Piece::corner ? corner_radius * du
                          : piece == Piece::face ? du
                                                 : du;
    out.spacing = std::max({out.spacing, extent, (piece == Piece::face ? flat : radius) * dtheta});
    // Cell corners for the extremes (they reach the pieces' edges), cell
    // centres for the area-weighted mean.
    for (int i = 0; i <= n_u; ++i) {
      for (int j = 0; j < n_theta; ++j) {
        const double u = i * du, theta = j * dtheta;
        if (engaged(piece, u, theta)) {
          out.any = true;
          consider(piece, u, theta);
        }
        if (i == n_u) continue;
        const double uc = u + du / 2, tc = theta + dtheta / 2;
        if (!engaged(piece, uc, tc)) continue;
        const Vector3d p = surface.point(piece, uc, tc);
        const double weight = surface.area(piece, uc) * du * dtheta;
        sum_weight += weight;
        sum_diameter += weight * 2 * std::hypot(p.x(), p.y());
      }
    }
  }
  if (!out.any) return out;
  // Zoom on the extremes: finer grids around the best point, same piece.
  for (Best* best : {&lowest, &highest}) {
    double half_u = surface.u_max(best->piece) / n_u, half_theta = 2 * kPi / n_theta;
    for (int round = 0; round < 5; ++round) {
      const Best centre = *best;
      for (int i = -10; i <= 10; ++i) {
        for (int j = -10; j <= 10; ++j) {
          const double u = std::clamp(centre.u + half_u * i / 10, 0.0, surface.u_max(centre.piece));
          const double theta = centre.theta + half_theta * j / 10;
          if (!engaged(centre.piece, u, theta)) continue;
          const Vector3d p = surface.point(centre.piece, u, theta);
          const double r = std::hypot(p.x(), p.y());
          if (best == &lowest ? r < best->r : r > best->r) *best = {r, centre.piece, u, theta};
        }
      }
      half_u /= 5;
      half_theta /= 5;
    }
  }
  out.p_min = surface.point(lowest.piece, lowest.u, lowest.theta);
  out.p_max = surface.point(highest.piece, highest.u, highest.theta);
  out.d_min = 2 * lowest.r;
  out.d_max = 2 * highest.r;
  out.d_mean = sum_weight > 0 ? sum_diameter / sum_weight : 0;
  return out;
}

double mean_by_circles(double diameter, double corner_radius, double ap, double ae,
                       const Vector3d& normal_in, const Vector3d& feed_in, bool previous_on_left,
                       int circles, int cells) {
  const Vector3d n = normal_in.normalized();
  const Vector3d f = (feed_in - feed_in.dot(n) * n).normalized();
  const Vector3d offset = (previous_on_left ? ae : -ae) * n.cross(f);
  const double radius = diameter / 2, flat = radius - corner_radius;
  const double c0 = -flat * std::hypot(n.x(), n.y()) - corner_radius + ap;
  const Surface surface{radius, corner_radius, flat,
                        std::max(0.0, (c0 + radius * std::hypot(n.x(), n.y())) / n.z())};
  const auto engaged = [&](Piece piece, double u, double theta) {
    const Vector3d p = surface.point(piece, u, theta);
    if (n.dot(p) > c0) return false;
    if (surface.normal(piece, u, theta).dot(f) < -1e-12) return false;
    return !inside_sweep(diameter, corner_radius, p, offset, f);
  };
  double area = 0, moment = 0;
  for (const Piece piece : {Piece::face, Piece::corner, Piece::shank}) {
    if (piece == Piece::corner && corner_radius == 0) continue;
    const double du = surface.u_max(piece) / circles;
    if (!(du > 0)) continue;
    for (int i = 0; i < circles; ++i) {
      const double u = (i + 0.5) * du;
      const double r = std::hypot(surface.point(piece, u, 0).x(), surface.point(piece, u, 0).y());
      const double dtheta = 2 * kPi / cells;
      double length = 0;
      bool before = engaged(piece, u, 0);
      for (int j = 0; j < cells; ++j) {
        const double lo = j * dtheta, hi = lo + dtheta;
        const bool after = engaged(piece, u, hi);
        if (before && after) length += dtheta;
        if (before != after) {
          double a = lo, b = hi;  // engaged(a) == before
          while (b - a > 1e-12) {
            const double m = 0.5 * (a + b);
            (engaged(piece, u, m) == before ? a : b) = m;
          }
          length += before ? a - lo : hi - a;
        }
        before = after;
      }
      const double weight = surface.area(piece, u) * du * length;
      area += weight;
      moment += weight * 2 * r;
    }
  }
  return area > 0 ? moment / area : 0;
}

}  // namespace vcpost::testing
