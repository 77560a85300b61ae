#include "geometry/surface_quality.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vcpost::geometry {
namespace {

void require(bool ok, const char* function, const std::string& what) {
  // A value outside the model's range; callers catch it (report/point_row.cpp:
  // no cusp height) or pass checked values.
  if (!ok) throw std::invalid_argument(std::string(function) + ": " + what);
}

void require_radius(const char* function, double radius) {
  require(std::isfinite(radius) && radius > 0, function,
          "tool radius " + std::to_string(radius) + " mm must be > 0");
}

// 0 <= length < 2R: arcs of radius R that far apart still intersect.
void require_spacing(const char* function, const char* name, double length, double radius) {
  require(std::isfinite(length) && length >= 0, function,
          std::string(name) + " " + std::to_string(length) + " mm must be >= 0");
  require(length < 2 * radius, function,
          std::string(name) + " " + std::to_string(length) +
              " mm must be smaller than the ball diameter " + std::to_string(2 * radius));
}

void require_slope(const char* function, double slope) {
  require(std::isfinite(slope) && slope >= 0 && slope < std::numbers::pi / 2, function,
          "slope " + std::to_string(slope) + " rad must lie in [0, pi/2)");
}

// x - sin(x) without the cancellation of the direct difference for small x
// (the roughness of fine stepovers depends on it).
double x_minus_sin_x(double x) {
  if (std::abs(x) >= 1) return x - std::sin(x);
  const double x2 = x * x;
  double term = x * x2 / 6;
  double sum = 0;
  for (int k = 1; k < 30 && std::abs(term) > 1e-18 * std::abs(sum); ++k) {
    sum += term;
    term *= -x2 / ((2 * k + 2) * (2 * k + 3));
  }
  return sum;
}

// R - sqrt(R^2 - c^2) in a form without cancellation for c << R.
double sagitta(double radius, double half_chord) {
  return half_chord * half_chord / (radius + std::sqrt(radius * radius - half_chord * half_chord));
}

}  // namespace

double flat_cusp_height(double radius, double stepover) {
  require_radius("flat_cusp_height", radius);
  require_spacing("flat_cusp_height", "stepover", stepover, radius);
  return sagitta(radius, stepover / 2);
}

InclinedCusp inclined_cusp(double radius, double stepover, double slope, double feed_angle) {
  constexpr const char* fn = "inclined_cusp";
  require_radius(fn, radius);
  require(std::isfinite(stepover) && stepover >= 0, fn, "stepover must be >= 0");
  require_slope(fn, slope);
  require(std::isfinite(feed_angle), fn, "feed angle must be finite");

  const double t = std::tan(slope);
  const double sin_a = std::sin(feed_angle);
  InclinedCusp cusp;
  cusp.alpha3 = std::atan(std::cos(feed_angle) * t);
  cusp.paper_spacing = stepover / std::cos(cusp.alpha3);
  cusp.exact_spacing = stepover * std::sqrt((1 + t * t) / (1 + t * t * sin_a * sin_a));
  require_spacing(fn, "stepover on the surface", cusp.exact_spacing, radius);
  cusp.exact_height = sagitta(radius, cusp.exact_spacing / 2);
  if (cusp.paper_spacing < 2 * radius) cusp.paper_height = sagitta(radius, cusp.paper_spacing / 2);
  return cusp;
}

double curved_cusp_height(double radius, double stepover, double rho, Curvature curvature) {
  constexpr const char* fn = "curved_cusp_height";
  require_radius(fn, radius);
  require(std::isfinite(stepover) && stepover >= 0, fn, "stepover must be >= 0");
  require(std::isfinite(rho) && rho > 0, fn, "curvature radius must be > 0");
  const bool convex = curvature == Curvature::convex;
  require(convex || rho >= radius, fn,
          "a concave radius " + std::to_string(rho) + " mm smaller than the ball radius " +
              std::to_string(radius) + " mm is gouged");
  const double angle = stepover / rho;  // between the contact points, seen from the centre
  require(angle < std::numbers::pi, fn, "stepover must cover less than half the circle");

  const double centre_radius = convex ? rho + radius : rho - radius;
  const double half_distance = centre_radius * std::sin(angle / 2);  // between the centres
  require(half_distance < radius, fn, "the balls of adjacent passes do not overlap");
  // The cusp lies on the bisector at centre_radius*cos(angle/2) -+ sqrt(R^2 - d^2)
  // from the curvature centre (near intersection for convex, far for concave);
  // written as sagitta -+ centre_radius*(1 - cos(angle/2)) to stay exact for large rho.
  const double s = std::sin(angle / 4);
  const double drop = 2 * centre_radius * s * s;
  const double sag = sagitta(radius, half_distance);
  return convex ? sag - drop : sag + drop;
}

Roughness arc_profile_roughness(double radius, double spacing) {
  constexpr const char* fn = "arc_profile_roughness";
  require_radius(fn, radius);
  require_spacing(fn, "spacing", spacing, radius);
  Roughness result;
  if (spacing == 0) return result;

  // One period: z(x) = R - sqrt(R^2 - x^2), |x| <= a, a = R sin(alpha).
  const double a = spacing / 2;
  const double sin_alpha = a / radius;
  const double alpha = std::asin(sin_alpha);
  const double one_minus_cos_alpha = sagitta(radius, a) / radius;
  result.rz = sagitta(radius, a);
  // Mean line: m = (1/2a) * integral of z = R (2 sin - sin cos - alpha) / (2 sin).
  const double mean =
      radius * (sin_alpha * one_minus_cos_alpha - x_minus_sin_x(alpha)) / (2 * sin_alpha);
  // The arc crosses the mean line at x0 = R sin(theta0), 1 - cos(theta0) = m/R;
  // Ra = (2/a) * integral_0^x0 (m - z) = R^2 (2 theta0 - sin(2 theta0)) / (2a).
  const double theta0 = 2 * std::asin(std::sqrt(mean / (2 * radius)));
  result.ra = radius * radius * x_minus_sin_x(2 * theta0) / (2 * a);
  return result;
}

Roughness transverse_roughness(double radius, double stepover) {
  return arc_profile_roughness(radius, stepover);
}

Roughness longitudinal_roughness(double radius, double feed_per_tooth) {
  return arc_profile_roughness(radius, feed_per_tooth);
}

Roughness oblique_roughness(double radius, double stepover, double slope) {
  require_slope("oblique_roughness", slope);
  require(std::isfinite(stepover) && stepover >= 0, "oblique_roughness", "stepover must be >= 0");
  return arc_profile_roughness(radius, stepover / std::cos(slope));
}

double feed_mark_height(double feed_per_tooth, double working_radius, int teeth, MillingMode mode) {
  constexpr const char* fn = "feed_mark_height";
  require(std::isfinite(feed_per_tooth) && feed_per_tooth >= 0, fn, "feed per tooth must be >= 0");
  require(std::isfinite(working_radius) && working_radius > 0, fn, "working radius must be > 0");
  require(teeth >= 1, fn, "the tool needs at least one tooth");
  // Radius of curvature of the trochoidal tooth path at the generating point.
  const double shift = feed_per_tooth * teeth / std::numbers::pi;
  const double path_radius =
      mode == MillingMode::up ? working_radius + shift : working_radius - shift;
  require(path_radius > 0, fn,
          "down milling with fz*z/pi >= working radius: the tooth path has no curvature radius");
  return feed_per_tooth * feed_per_tooth / (8 * path_radius);
}

RunoutBand runout_band(double working_diameter, const Runout& runout) {
  constexpr const char* fn = "runout_band";
  require(std::isfinite(working_diameter) && working_diameter >= 0, fn,
          "working diameter must be >= 0");
  require(std::isfinite(runout.offset) && runout.offset >= 0, fn, "axis offset must be >= 0");
  require(std::isfinite(runout.tilt) && runout.tilt >= 0 && runout.tilt < std::numbers::pi / 2, fn,
          "tilt must lie in [0, pi/2)");
  require(std::isfinite(runout.overhang) && runout.overhang > 0, fn, "overhang must be > 0");
  require(std::isfinite(runout.cut_height) && runout.cut_height >= 0 &&
              runout.cut_height <= runout.overhang,
          fn, "cutting point height must lie in [0, overhang]");

  RunoutBand band;
  band.effective_offset =
      runout.offset + (runout.overhang - runout.cut_height) * std::sin(runout.tilt);
  band.d_min = std::max(0.0, working_diameter - 2 * band.effective_offset);
  band.d_max = working_diameter + 2 * band.effective_offset;
  band.marks_once_per_revolution = band.effective_offset > 0;
  return band;
}

}  // namespace vcpost::geometry
