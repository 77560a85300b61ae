#include "postproc/samplegen/surfaces.h"

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

namespace vcpost::samplegen {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

std::vector<double> clamped_uniform(double length, int spans, int degree) {
  std::vector<double> k(degree, 0.0);
  for (int i = 0; i <= spans; ++i) k.push_back(length * i / spans);
  k.insert(k.end(), degree, length);
  return k;
}

double greville(const std::vector<double>& knots, int degree, int i) {
  double s = 0;
  for (int k = 1; k <= degree; ++k) s += knots[i + k];
  return s / degree;
}

bool inside(const Eigen::AlignedBox2d& box, const Vector2d& uv, double slack) {
  return uv.x() >= box.min().x() - slack && uv.x() <= box.max().x() + slack &&
         uv.y() >= box.min().y() - slack && uv.y() <= box.max().y() + slack;
}

std::string text(const Vector2d& p) {
  return "(" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ")";
}

}  // namespace

int bspline_basis(const std::vector<double>& t, int p, double x,
                  std::array<std::array<double, 8>, 3>& ders) {
  const int n = static_cast<int>(t.size()) - p - 1;  // number of basis functions
  int span = p;
  while (span + 1 < n && x >= t[span + 1]) ++span;
  // table[k][j]: N_{span-k+j, k}(x) for j = 0..k (the non-zero ones of degree k).
  double table[8][8] = {};
  table[0][0] = 1.0;
  for (int k = 1; k <= p; ++k) {
    for (int j = 0; j <= k; ++j) {
      const int i = span - k + j;  // function index
      double v = 0;
      if (j >= 1) {  // N_{i,k-1} is table[k-1][j-1]
        const double den = t[i + k] - t[i];
        if (den > 0) v += (x - t[i]) / den * table[k - 1][j - 1];
      }
      if (j < k) {  // N_{i+1,k-1} is table[k-1][j]
        const double den = t[i + k + 1] - t[i + 1];
        if (den > 0) v += (t[i + k + 1] - x) / den * table[k - 1][j];
      }
      table[k][j] = v;
    }
  }
  // Derivatives from N'_{i,k} = k (N_{i,k-1}/(t_{i+k}-t_i) - N_{i+1,k-1}/(t_{i+k+1}-t_{i+1})),
  // applied once (first) and twice (second).
  auto lower = [&](int k, int j) {  // N_{span-p+j, k} for k < p, 0 outside the table
    const int jj = j - (p - k);
    return (jj < 0 || jj > k) ? 0.0 : table[k][jj];
  };
  auto coef = [&](int i, int k) {
    const double den = t[i + k] - t[i];
    return den > 0 ? k / den : 0.0;
  };
  for (int j = 0; j <= p; ++j) {
    const int i = span - p + j;
    ders[0][j] = table[p][j];
    ders[1][j] = p >= 1 ? coef(i, p) * lower(p - 1, j) - coef(i + 1, p) * lower(p - 1, j + 1) : 0;
    if (p >= 2) {
      auto d1 = [&](int jj) {  // derivative of N_{span-p+jj, p-1}
        const int ii = span - p + jj;
        return coef(ii, p - 1) * lower(p - 2, jj) - coef(ii + 1, p - 1) * lower(p - 2, jj + 1);
      };
      ders[2][j] = coef(i, p) * d1(j) - coef(i + 1, p) * d1(j + 1);
    } else {
      ders[2][j] = 0;
    }
  }
  return span;
}

WavyBspline::WavyBspline(double length_x, double length_y, int spans_x, int spans_y,
                         double amplitude, double wave_x, double wave_y, double slope) {
  data_.knots_u = clamped_uniform(length_x, spans_x, 3);
  data_.knots_v = clamped_uniform(length_y, spans_y, 3);
  data_.count_u = spans_x + 3;
  data_.count_v = spans_y + 3;
  for (int i = 0; i < data_.count_u; ++i) {
    const double x = greville(data_.knots_u, 3, i);
    for (int j = 0; j < data_.count_v; ++j) {
      const double y = greville(data_.knots_v, 3, j);
      const double z = amplitude * std::sin(2 * std::numbers::pi * x / wave_x) *
                           std::cos(2 * std::numbers::pi * y / wave_y) +
                       slope * x;
      data_.poles.emplace_back(x, y, z);
    }
  }
}

WavyBspline WavyBspline::mould() { return WavyBspline(120, 80, 8, 6, 6, 60, 80, 0.1); }

Eigen::AlignedBox2d WavyBspline::domain() const {
  return {Vector2d(0, 0), Vector2d(data_.knots_u.back(), data_.knots_v.back())};
}

std::array<double, 6> WavyBspline::height(const Vector2d& uv) const {
  std::array<std::array<double, 8>, 3> bu{}, bv{};
  const int su = bspline_basis(data_.knots_u, 3, uv.x(), bu);
  const int sv = bspline_basis(data_.knots_v, 3, uv.y(), bv);
  std::array<double, 6> h{};
  for (int a = 0; a <= 3; ++a) {
    for (int b = 0; b <= 3; ++b) {
      const double z = data_.poles[(su - 3 + a) * data_.count_v + (sv - 3 + b)].z();
      h[0] += z * bu[0][a] * bv[0][b];
      h[1] += z * bu[1][a] * bv[0][b];
      h[2] += z * bu[0][a] * bv[1][b];
      h[3] += z * bu[2][a] * bv[0][b];
      h[4] += z * bu[1][a] * bv[1][b];
      h[5] += z * bu[0][a] * bv[2][b];
    }
  }
  return h;
}

Vector3d WavyBspline::point(const Vector2d& uv) const { return {uv.x(), uv.y(), height(uv)[0]}; }

Vector3d WavyBspline::normal(const Vector2d& uv) const {
  const auto h = height(uv);
  return Vector3d(-h[1], -h[2], 1).normalized();
}

Vector2d WavyBspline::closest(const Vector3d& q, const Vector2d& guess) const {
  Vector2d uv = guess;
  for (int it = 0; it < 50; ++it) {
    const auto h = height(uv);
    const Vector3d s(uv.x(), uv.y(), h[0]), su(1, 0, h[1]), sv(0, 1, h[2]);
    const Vector3d suu(0, 0, h[3]), suv(0, 0, h[4]), svv(0, 0, h[5]);
    const Vector3d d = s - q;
    const Vector2d g(d.dot(su), d.dot(sv));
    Eigen::Matrix2d H;
    H << su.dot(su) + d.dot(suu), su.dot(sv) + d.dot(suv), su.dot(sv) + d.dot(suv),
        sv.dot(sv) + d.dot(svv);
    const Vector2d step = H.ldlt().solve(-g);
    uv += step;
    if (step.norm() < 1e-15 * (1 + uv.norm())) break;
    if (it == 49)
      throw SurfaceError("wavy mould: closest point did not converge near " + text(guess));
  }
  if (!inside(domain(), uv, 0)) {
    throw SurfaceError("wavy mould: the closest point " + text(uv) + " is outside the patch");
  }
  return uv;
}

Vector2d WavyBspline::drop(const Vector2d& xy, double r, const Vector2d& guess) const {
  Vector2d uv = guess;
  for (int it = 0; it < 50; ++it) {
    if (!inside(domain(), uv, 0)) break;
    const auto h = height(uv);
    const Vector2d g(h[1], h[2]);
    const double w = std::sqrt(1 + g.squaredNorm());
    // F(u,v) = (u,v) + r*N_xy - xy with N_xy = -g/w.
    const Vector2d f = uv - r * g / w - xy;
    Eigen::Matrix2d gd;  // columns: dg/du, dg/dv
    gd << h[3], h[4], h[4], h[5];
    Eigen::Matrix2d J = Eigen::Matrix2d::Identity();
    for (int c = 0; c < 2; ++c) {
      const Vector2d dg = gd.col(c);
      J.col(c) -= r * (dg / w - g * g.dot(dg) / (w * w * w));
    }
    const Vector2d step = J.partialPivLu().solve(-f);
    uv += step;
    if (step.norm() < 1e-15 * (1 + uv.norm())) {
      if (!inside(domain(), uv, 0)) break;
      return uv;
    }
  }
  throw SurfaceError("wavy mould: no drop-cutter contact inside the patch for the ball above " +
                     text(xy));
}

Eigen::AlignedBox2d SemiCylinder::domain() const {
  return {Vector2d(0, -std::numbers::pi / 2), Vector2d(length_, std::numbers::pi / 2)};
}

Vector3d SemiCylinder::point(const Vector2d& uv) const {
  return {uv.x(), radius_ * std::sin(uv.y()), radius_ * std::cos(uv.y())};
}

Vector3d SemiCylinder::normal(const Vector2d& uv) const {
  return {0, std::sin(uv.y()), std::cos(uv.y())};
}

Vector2d SemiCylinder::closest(const Vector3d& q, const Vector2d& /*guess*/) const {
  Vector2d uv(q.x(), std::atan2(q.y(), q.z()));
  if (!inside(domain(), uv, 0) || std::hypot(q.y(), q.z()) == 0) {
    throw SurfaceError("semi-cylinder: the closest point of " + std::to_string(q.x()) + ", " +
                       std::to_string(q.y()) + ", " + std::to_string(q.z()) + " is off the patch");
  }
  return uv;
}

Vector2d SemiCylinder::drop(const Vector2d& xy, double r, const Vector2d& /*guess*/) const {
  // The centre is at radius + r from the axis: its y is (radius + r) sin v.
  const double s = xy.y() / (radius_ + r);
  Vector2d uv(xy.x(), std::asin(std::clamp(s, -1.0, 1.0)));
  if (std::abs(s) >= 1 || !inside(domain(), uv, 0)) {
    throw SurfaceError("semi-cylinder: no contact on the patch for the ball above " + text(xy));
  }
  return uv;
}

Eigen::AlignedBox2d Dome::domain() const {
  return {Vector2d(-std::numbers::pi, 0), Vector2d(std::numbers::pi, max_polar_)};
}

Vector3d Dome::point(const Vector2d& uv) const { return radius_ * normal(uv); }

Vector3d Dome::normal(const Vector2d& uv) const {
  return {std::sin(uv.y()) * std::cos(uv.x()), std::sin(uv.y()) * std::sin(uv.x()),
          std::cos(uv.y())};
}

Vector2d Dome::closest(const Vector3d& q, const Vector2d& guess) const {
  const double rho = std::hypot(q.x(), q.y());
  // On the axis any azimuth is right; keep the guess's.
  Vector2d uv(rho > 0 ? std::atan2(q.y(), q.x()) : guess.x(), std::atan2(rho, q.z()));
  if (uv.y() > max_polar_ || q.norm() == 0) {
    throw SurfaceError("dome: the closest point is below the dome's rim");
  }
  return uv;
}

Vector2d Dome::drop(const Vector2d& xy, double r, const Vector2d& guess) const {
  const double rho = xy.norm();
  const double s = rho / (radius_ + r);
  Vector2d uv(rho > 0 ? std::atan2(xy.y(), xy.x()) : guess.x(),
              std::asin(std::clamp(s, -1.0, 1.0)));
  if (s >= 1 || uv.y() > max_polar_) {
    throw SurfaceError("dome: no contact on the dome for the ball above " + text(xy));
  }
  return uv;
}

}  // namespace vcpost::samplegen
