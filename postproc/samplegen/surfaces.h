// The surfaces of the sample parts, in closed form, so the sample
// generator's truth (CC point and normal for every toolpath point) is exact.
//
// Units: mm and radians. Every surface is one parametric patch S(u,v) over a
// (u,v) box, with a unit normal pointing out of the material (towards the
// tool). The STEP files of the samples hold the same surfaces: the wavy
// mould as the very B-spline defined here (same degree, knots and poles),
// the cylinder and the dome as OpenCASCADE's analytic surfaces.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"

namespace vcpost::samplegen {

// Thrown when a query leaves the patch or Newton's method does not converge
// (the generator was asked for a window the surface cannot serve).
class SurfaceError : public vcpost::Error {
 public:
  explicit SurfaceError(const std::string& message) : vcpost::Error(Code::E8001, message) {}
};

class SampleSurface {
 public:
  virtual ~SampleSurface() = default;
  virtual std::string name() const = 0;
  virtual Eigen::AlignedBox2d domain() const = 0;  // (u,v) box of the patch
  virtual Eigen::Vector3d point(const Eigen::Vector2d& uv) const = 0;
  virtual Eigen::Vector3d normal(const Eigen::Vector2d& uv) const = 0;  // unit, out of the material
  // (u,v) of the point of the patch closest to q. `guess` must be near the
  // answer (the generator passes the intended contact); the answer is the
  // local minimum of |S - q| reached from it, which is the global one for
  // the windows the generator uses (|q - S| < the smallest concave radius).
  // Throws SurfaceError when the minimum is outside the domain.
  virtual Eigen::Vector2d closest(const Eigen::Vector3d& q, const Eigen::Vector2d& guess) const = 0;
  // Drop-cutter: (u,v) of the contact of a ball of radius r whose centre is
  // on the vertical line through xy, resting on the surface from above
  // (S(u,v) + r*N(u,v) has x,y = xy). Throws SurfaceError when that contact
  // is outside the domain.
  virtual Eigen::Vector2d drop(const Eigen::Vector2d& xy, double r,
                               const Eigen::Vector2d& guess) const = 0;
};

// A tensor-product polynomial B-spline graph surface z = h(x,y): clamped
// uniform knots, poles at the Greville abscissae in x and y (so x(u) = u and
// y(v) = v exactly) and pole heights taken from a wave. (u,v) = (x,y).
struct BsplineData {
  int degree_u = 3, degree_v = 3;
  std::vector<double> knots_u, knots_v;  // full knot vectors (with repetition)
  std::vector<Eigen::Vector3d> poles;    // row-major: poles[i * count_v + j]
  int count_u = 0, count_v = 0;
};

class WavyBspline final : public SampleSurface {
 public:
  // Size length_x by length_y mm from the origin, spans_x by spans_y cubic
  // spans; pole heights amplitude*sin(2 pi x/wave_x)*cos(2 pi y/wave_y) +
  // slope*x.
  WavyBspline(double length_x, double length_y, int spans_x, int spans_y, double amplitude,
              double wave_x, double wave_y, double slope);
  // The mould of the samples: 120 x 80 mm, 8 x 6 spans, waves of 60 and 80
  // mm, 6 mm amplitude, 0.1 slope (concave radii > 12 mm: a 12 mm ball fits).
  static WavyBspline mould();

  std::string name() const override { return "wavy-mould"; }
  Eigen::AlignedBox2d domain() const override;
  Eigen::Vector3d point(const Eigen::Vector2d& uv) const override;
  Eigen::Vector3d normal(const Eigen::Vector2d& uv) const override;
  Eigen::Vector2d closest(const Eigen::Vector3d& q, const Eigen::Vector2d& guess) const override;
  Eigen::Vector2d drop(const Eigen::Vector2d& xy, double r,
                       const Eigen::Vector2d& guess) const override;

  const BsplineData& data() const { return data_; }
  // h and its derivatives at (u,v): {h, hu, hv, huu, huv, hvv}.
  std::array<double, 6> height(const Eigen::Vector2d& uv) const;

 private:
  BsplineData data_;
};

// The outside of a cylinder of `radius` about the x axis (z up), the half
// with z >= 0: S(u,v) = (u, radius*sin v, radius*cos v), u in [0, length],
// v in [-pi/2, pi/2] (v = the slope angle of the surface).
class SemiCylinder final : public SampleSurface {
 public:
  SemiCylinder(double radius, double length) : radius_(radius), length_(length) {}
  std::string name() const override { return "semi-cylinder"; }
  Eigen::AlignedBox2d domain() const override;
  Eigen::Vector3d point(const Eigen::Vector2d& uv) const override;
  Eigen::Vector3d normal(const Eigen::Vector2d& uv) const override;
  Eigen::Vector2d closest(const Eigen::Vector3d& q, const Eigen::Vector2d& guess) const override;
  Eigen::Vector2d drop(const Eigen::Vector2d& xy, double r,
                       const Eigen::Vector2d& guess) const override;
  double radius() const { return radius_; }
  double length() const { return length_; }

 private:
  double radius_, length_;
};

// A spherical dome about the z axis, centre at the origin: S(u,v) =
// radius*(sin v cos u, sin v sin u, cos v), u the azimuth in [0, 2 pi],
// v the polar angle in [0, max_polar] (= the wall slope; 80 deg: steep).
class Dome final : public SampleSurface {
 public:
  Dome(double radius, double max_polar) : radius_(radius), max_polar_(max_polar) {}
  std::string name() const override { return "dome"; }
  Eigen::AlignedBox2d domain() const override;
  Eigen::Vector3d point(const Eigen::Vector2d& uv) const override;
  Eigen::Vector3d normal(const Eigen::Vector2d& uv) const override;
  Eigen::Vector2d closest(const Eigen::Vector3d& q, const Eigen::Vector2d& guess) const override;
  Eigen::Vector2d drop(const Eigen::Vector2d& xy, double r,
                       const Eigen::Vector2d& guess) const override;
  double radius() const { return radius_; }
  double max_polar() const { return max_polar_; }

 private:
  double radius_, max_polar_;
};

// Values and first and second derivatives of the degree+1 B-spline basis
// functions that are non-zero at t: ders[d][k] is the d-th derivative of
// N_{span-degree+k}. Returns span (knots[span] <= t < knots[span+1], the
// last non-empty span at the end). REQUIRES knots clamped, t inside.
int bspline_basis(const std::vector<double>& knots, int degree, double t,
                  std::array<std::array<double, 8>, 3>& ders);

}  // namespace vcpost::samplegen
