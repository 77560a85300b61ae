#include "dome_program_support.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace vcpost::testing {

geometry::AnalyticModel dome() {
  geometry::SpherePatch sphere;
  sphere.center = {0, 0, -20};
  sphere.radius = 40;
  sphere.max_polar = 1.4;
  return geometry::AnalyticModel({sphere});
}

namespace {
// Tip height of a tool whose core disc (radius `disc`, `corner` above the
// tip) rests on the dome at (x, y): the disc point nearest the centre is
// max(0, h - disc) off the axis, h = |(x, y)|.
double tip_on_dome(double x, double y, double disc, double corner) {
  const double off = std::max(0.0, std::hypot(x, y) - disc), reach = 40 + corner;
  const double off2 = disc == 0 ? x * x + y * y : off * off;
  return -20 + std::sqrt(reach * reach - off2) - corner;
}

std::string raster(double stepover, double spacing, int spindle, double disc, double corner) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(6);
  out << "%\n(dome raster)\nG21 G90 G17 G94\nT1 M6\nS" << spindle << " M3\nF2000\n";
  bool first = true;
  int pass = 0;
  for (double y = -20; y <= 20 + 1e-9; y += stepover, ++pass) {
    for (int i = 0; i <= static_cast<int>(40 / spacing + 0.5); ++i) {
      const double x = pass % 2 == 0 ? -20 + i * spacing : 20 - i * spacing;
      const double z = tip_on_dome(x, y, disc, corner);
      if (first) {
        out << "G0 X" << x << " Y" << y << " Z" << z + 5 << "\nG1 Z" << z << "\n";
        first = false;
      } else {
        out << "G1 X" << x << " Y" << y << " Z" << z << "\n";
      }
    }
  }
  out << "G0 Z60\nM5\nM30\n%\n";
  return out.str();
}
}  // namespace

std::string dome_raster(double stepover, double spacing, int spindle) {
  return raster(stepover, spacing, spindle, 0, dome_ball_radius);
}

std::string bull_nose_dome_raster(double stepover, double spacing, int spindle, double diameter,
                                  double corner_radius) {
  return raster(stepover, spacing, spindle, diameter / 2 - corner_radius, corner_radius);
}

}  // namespace vcpost::testing
