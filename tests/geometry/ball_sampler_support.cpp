#include "ball_sampler_support.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace vcpost::testing {

SampledEngagement sample_ball(double diameter, double ap, double ae, const Eigen::Vector3d& normal,
                              const Eigen::Vector3d& feed, bool previous_on_left, int resolution) {
  const double R = diameter / 2, pi = std::numbers::pi;
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d f = (feed - feed.dot(n) * n).normalized();
  const Eigen::Vector3d left = n.cross(f).normalized();
  const Eigen::Vector3d axis_point = (previous_on_left ? ae : -ae) * left;
  const double stock = -(R - ap);

  // The previous pass's tool is its ball plus the shank above the ball's
  // centre: p is inside its sweep if it is within R of the centre line, or
  // above some centre O + tF that is within R of it horizontally.
  auto outside_previous = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - axis_point;
    if ((d - d.dot(f) * f).norm() < R) return false;
    const double fxy2 = f.x() * f.x() + f.y() * f.y();
    const double dxy2 = d.x() * d.x() + d.y() * d.y();
    if (fxy2 < 1e-300) return !(dxy2 <= R * R && d.z() >= -INFINITY);
    const double mid = (d.x() * f.x() + d.y() * f.y()) / fxy2;  // closest t horizontally
    const double gap2 = dxy2 - mid * mid * fxy2;
    if (gap2 > R * R) return true;
    const double half = std::sqrt((R * R - gap2) / fxy2);
    const double lowest_centre = std::min((mid - half) * f.z(), (mid + half) * f.z());
    return d.z() < lowest_centre;
  };

  SampledEngagement out;
  double d_lo = INFINITY, d_hi = -INFINITY, weight_sum = 0, moment = 0;
  auto take = [&](const Eigen::Vector3d& p, double weight) {
    const double d = 2 * std::hypot(p.x(), p.y());
    d_lo = std::min(d_lo, d);
    d_hi = std::max(d_hi, d);
    weight_sum += weight;
    moment += weight * d;
  };

  // Ball: polar angle alpha from -N up to the stock rim, azimuth theta
  // about N, in a basis that has nothing to do with F.
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  const double alpha_max = std::acos(std::clamp((R - ap) / R, -1.0, 1.0));
  const int n_alpha = resolution, n_theta = 2 * resolution;
  const double d_alpha = alpha_max / n_alpha, d_theta = 2 * pi / n_theta;
  for (int i = 0; i < n_alpha; ++i) {
    const double alpha = (i + 0.5) * d_alpha;
    for (int j = 0; j < n_theta; ++j) {
      const double theta = (j + 0.5) * d_theta;
      const Eigen::Vector3d p =
          R *
          (std::sin(alpha) * (std::cos(theta) * e1 + std::sin(theta) * e2) - std::cos(alpha) * n);
      if (p.z() > 0 || n.dot(p) > stock || f.dot(p) < 0 || !outside_previous(p)) continue;
      take(p, R * R * std::sin(alpha) * d_alpha * d_theta);
    }
  }
  // Shank: the cylinder r = R above the equator, up to the stock plane's top.
  const double nxy = std::hypot(n.x(), n.y());
  const double z_top = (stock + R * nxy) / n.z();
  double shank_step = 0;
  if (z_top > 0) {
    const int n_phi = 2 * resolution, n_z = resolution;
    const double d_phi = 2 * pi / n_phi, d_z = z_top / n_z;
    shank_step = std::max(R * d_phi, d_z);
    for (int i = 0; i < n_phi; ++i) {
      const double phi = (i + 0.5) * d_phi;
      const Eigen::Vector3d outward(std::cos(phi), std::sin(phi), 0);
      for (int j = 0; j < n_z; ++j) {
        const Eigen::Vector3d p = R * outward + Eigen::Vector3d(0, 0, (j + 0.5) * d_z);
        if (n.dot(p) > stock || f.dot(outward) < 0 || !outside_previous(p)) continue;
        out.shank = true;
        take(p, R * d_phi * d_z);
      }
    }
  }
  out.any = weight_sum > 0;
  if (out.any) {
    out.d_max = d_hi;
    out.d_min = d_lo;
    out.d_mean = moment / weight_sum;
  }
  out.spacing = std::max({R * d_alpha, R * d_theta, shank_step});

  // Rim: the ball circle where it lies below the equator, the shank's
  // ellipse (by its angle about the axis) where above.
  const double rim = std::sqrt(std::max(0.0, R * R - stock * stock));
  double s_lo = INFINITY, s_hi = -INFINITY;
  auto rim_candidate = [&](const Eigen::Vector3d& p) {
    const double s = left.dot(p);
    if (s < s_lo) {
      s_lo = s;
      out.p1 = p;
    }
    if (s > s_hi) {
      s_hi = s;
      out.p2 = p;
    }
  };
  const int n_rim = 200 * resolution;
  for (int k = 0; k < n_rim; ++k) {
    const double t = 2 * pi * k / n_rim;
    const Eigen::Vector3d on_ball = stock * n + rim * (std::cos(t) * e1 + std::sin(t) * e2);
    if (on_ball.z() <= 0) rim_candidate(on_ball);
    const Eigen::Vector3d xy(R * std::cos(t), R * std::sin(t), 0);
    const double z = (stock - n.dot(xy)) / n.z();
    if (z >= 0) rim_candidate(xy + Eigen::Vector3d(0, 0, z));
  }
  return out;
}

}  // namespace vcpost::testing
