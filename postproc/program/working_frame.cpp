#include "postproc/program/working_frame.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vcpost::program {

namespace {

// cos and sin of `degrees`, exact at multiples of 90 (so that the common
// tilts, A90 or B-90, turn points without round-off).
std::pair<double, double> cos_sin(double degrees) {
  const double quarter = degrees / 90.0;
  if (quarter == std::round(quarter)) {
    static constexpr double cos_of[] = {1, 0, -1, 0};
    static constexpr double sin_of[] = {0, 1, 0, -1};
    const auto k = static_cast<int>(std::fmod(std::fmod(quarter, 4.0) + 4.0, 4.0));
    return {cos_of[k], sin_of[k]};
  }
  const double radians = degrees * std::numbers::pi / 180.0;
  return {std::cos(radians), std::sin(radians)};
}

}  // namespace

Eigen::Matrix3d turn_about(int axis, double degrees) {
  const auto [c, s] = cos_sin(degrees);
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  r(i, i) = c;
  r(i, j) = -s;
  r(j, i) = s;
  r(j, j) = c;
  return r;
}

Eigen::Matrix3d spatial_angles(double a, double b, double c) {
  return turn_about(2, c) * turn_about(1, b) * turn_about(0, a);
}

Eigen::Matrix3d euler_zxz(double first, double second, double third) {
  return turn_about(2, first) * turn_about(0, second) * turn_about(2, third);
}

std::optional<Eigen::Matrix3d> frame_from_vectors(const Eigen::Vector3d& base,
                                                  const Eigen::Vector3d& normal) {
  const double n = normal.norm();
  if (!(n > 0)) return std::nullopt;
  const Eigen::Vector3d z = normal / n;
  const Eigen::Vector3d x = base - base.dot(z) * z;
  if (!(x.norm() > 1e-9 * std::max(1.0, base.norm()))) return std::nullopt;
  Eigen::Matrix3d r;
  r.col(0) = x.normalized();
  r.col(2) = z;
  r.col(1) = z.cross(r.col(0));
  return r;
}

namespace {

double degrees_of(double y, double x) { return std::atan2(y, x) * 180.0 / std::numbers::pi; }

// Within this of 1, a cosine is taken as 1: the two outer turns share an axis.
constexpr double kGimbal = 1e-12;

}  // namespace

// R = Rz(i) Rx(j) Rz(k): its z column is (sin i sin j, -cos i sin j,
// cos j), its bottom row (sin j sin k, sin j cos k, cos j).
Eigen::Vector3d euler_zxz_of(const Eigen::Matrix3d& r) {
  const double cos_j = std::clamp(r(2, 2), -1.0, 1.0);
  if (std::abs(cos_j) >= 1 - kGimbal) {
    // Rz(i) Rx(0 or 180): r(0,0) = cos i, r(1,0) = sin i.
    return {degrees_of(r(1, 0), r(0, 0)), cos_j > 0 ? 0.0 : 180.0, 0.0};
  }
  return {degrees_of(r(0, 2), -r(1, 2)), std::acos(cos_j) * 180.0 / std::numbers::pi,
          degrees_of(r(2, 0), r(2, 1))};
}

// R = Rz(c) Ry(b) Rx(a): its bottom row (-sin b, cos b sin a, cos b cos a),
// its x column (cos c cos b, sin c cos b, -sin b).
Eigen::Vector3d spatial_angles_of(const Eigen::Matrix3d& r) {
  const double sin_b = std::clamp(-r(2, 0), -1.0, 1.0);
  const double b = std::asin(sin_b) * 180.0 / std::numbers::pi;
  if (std::abs(sin_b) >= 1 - kGimbal) {
    // Rz(c) Ry(+-90): r(0,1) = -sin c, r(1,1) = cos c.
    return {0.0, sin_b > 0 ? 90.0 : -90.0, degrees_of(-r(0, 1), r(1, 1))};
  }
  return {degrees_of(r(2, 1), r(2, 2)), b, degrees_of(r(1, 0), r(0, 0))};
}

}  // namespace vcpost::program
