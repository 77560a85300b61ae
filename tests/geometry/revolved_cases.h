// The random set-ups the bull-nose and flat tests draw (one generator, so
// the engine's tests and the reference comparison see the same cases for
// the same seed).
#pragma once

#include <Eigen/Core>
#include <numbers>
#include <random>

#include "geometry/engagement.h"

namespace vcpost::geometry {

struct RandomCase {
  double diameter, corner, ap, ae;  // corner = 0: the flat end mill
  Eigen::Vector3d normal, feed;
  Side side;
};

// D 4..20 mm, rc 10..90 % of R, ap and ae from 1 % and 2 % of D, surface
// tilt up to 80 deg, any azimuth, feed direction and side.
inline RandomCase random_case(std::mt19937& random, bool flat) {
  constexpr double kPi = std::numbers::pi;
  std::uniform_real_distribution<double> unit(0, 1);
  RandomCase c;
  c.diameter = 4 + 16 * unit(random);
  const double radius = c.diameter / 2;
  c.corner = flat ? 0 : radius * (0.1 + 0.8 * unit(random));
  c.ap = c.diameter * (0.01 + 0.5 * unit(random) * unit(random));
  c.ae = c.diameter * (0.02 + 1.1 * unit(random));
  c.normal = normal_from_angles(80 * kPi / 180 * unit(random), 2 * kPi * unit(random));
  c.feed = feed_from_angle(2 * kPi * unit(random), c.normal);
  c.side = unit(random) < 0.5 ? Side::left : Side::right;
  return c;
}

inline Tool tool_of(const RandomCase& c) {
  return c.corner > 0 ? Tool::bull_nose(c.diameter, c.corner) : Tool::flat(c.diameter);
}

inline CutSetup setup_of(const RandomCase& c) { return {c.ap, c.ae, c.normal, c.feed, c.side}; }

}  // namespace vcpost::geometry
