#include "dome_program_support.h"

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

std::string dome_raster(double stepover, double spacing, int spindle) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(6);
  out << "%\n(dome raster)\nG21 G90 G17 G94\nT1 M6\nS" << spindle << " M3\nF2000\n";
  bool first = true;
  int pass = 0;
  for (double y = -20; y <= 20 + 1e-9; y += stepover, ++pass) {
    for (int i = 0; i <= static_cast<int>(40 / spacing + 0.5); ++i) {
      const double x = pass % 2 == 0 ? -20 + i * spacing : 20 - i * spacing;
      const double z = -20 + std::sqrt(45.0 * 45.0 - x * x - y * y) - dome_ball_radius;
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

}  // namespace vcpost::testing
