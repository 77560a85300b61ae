#include "postproc/deff/setup_input.h"

#include <Eigen/Geometry>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>

#include "core/text.h"

namespace vcpost::deff {
namespace {

std::string format_number(double value) {
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

}  // namespace

double parse_number(std::string_view text) {
  std::string_view body = trim(text, kBlanks);
  // from_chars refuses a leading '+', which people do write.
  if (body.size() > 1 && body.front() == '+') body.remove_prefix(1);
  const std::optional<double> value = finite_number(body);
  if (!value) throw vcpost::Error(Code::E2001, "'" + std::string(text) + "' is not a number");
  return *value;
}

Eigen::Vector3d parse_vector(std::string_view text, std::string_view names) {
  Eigen::Vector3d vector;
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = text.find(',', start);
    const bool last = i == 2;
    if (last != (comma == std::string_view::npos)) {
      throw vcpost::Error(Code::E2001, "expected three numbers " + std::string(names) + ", got '" +
                                           std::string(text) + "'");
    }
    const std::string_view part = text.substr(start, last ? text.npos : comma - start);
    try {
      vector[i] = parse_number(part);
    } catch (const vcpost::Error&) {
      throw vcpost::Error(Code::E2001, "expected three numbers " + std::string(names) + ", got '" +
                                           std::string(text) + "' ('" + std::string(part) +
                                           "' is not a number)");
    }
    start = comma + 1;
  }
  return vector;
}

geometry::Side parse_side(std::string_view text) {
  const std::string_view body = trim(text, kBlanks);
  if (body == "left") return geometry::Side::left;
  if (body == "right") return geometry::Side::right;
  throw vcpost::Error(Code::E2001,
                      "'" + std::string(text) + "' is not a side (expected left or right)");
}

std::string_view to_string(geometry::Side side) {
  return side == geometry::Side::left ? "left" : "right";
}

geometry::CutSetup checked_setup(const geometry::Tool& tool, geometry::CutSetup setup) {
  if (!(tool.diameter > 0) || !std::isfinite(tool.diameter)) {
    throw SetupError(SetupField::diameter,
                     "diameter must be > 0 mm, got " + format_number(tool.diameter));
  }
  if (!(setup.ap > 0)) {
    throw SetupError(SetupField::ap, "depth of cut must be > 0 mm, got " + format_number(setup.ap));
  }
  if (setup.ap >= tool.diameter) {
    // The engine then flags ap_exceeds_d and gives no diameters: the whole
    // end of the tool is in the stock and the shank cuts too.
    throw SetupError(SetupField::ap, "depth of cut " + format_number(setup.ap) +
                                         " mm reaches the tool diameter " +
                                         format_number(tool.diameter) +
                                         " mm: the shank would cut too; give ap below D");
  }
  if (!(setup.ae >= 0)) {
    throw SetupError(SetupField::ae,
                     "width of cut must be >= 0 mm, got " + format_number(setup.ae));
  }

  const double length = setup.normal.norm();
  if (!setup.normal.allFinite() || length == 0) {
    throw SetupError(SetupField::normal,
                     "the normal is a zero vector; give the unit surface normal");
  }
  if (std::abs(length - 1) > kNormalLengthTolerance) {
    throw SetupError(SetupField::normal, "the normal must be a unit vector, its length is " +
                                             format_number(length) + " (accepted: 1 +- 1e-6)");
  }
  setup.normal /= length;
  if (setup.normal.z() <= 0) {
    throw SetupError(SetupField::normal,
                     "n_z = " + format_number(setup.normal.z()) +
                         " <= 0: undercut, the surface faces sideways or down and a 3-axis "
                         "tool cannot reach it with its end");
  }

  const double feed_length = setup.feed.norm();
  if (!setup.feed.allFinite() || feed_length == 0) {
    throw SetupError(SetupField::feed, "the feed direction is a zero vector");
  }
  // sin of the angle between F and N: below this F has no usable direction
  // in the tangent plane.
  if (setup.feed.cross(setup.normal).norm() <= 1e-9 * feed_length) {
    throw SetupError(SetupField::feed,
                     "the feed direction is parallel to the normal, it has no component in "
                     "the surface");
  }
  return setup;
}

void check_tilt(double tilt_deg) {
  if (!(std::abs(tilt_deg) < 90)) {
    throw SetupError(SetupField::normal,
                     "tilt must lie in (-90, 90) degrees, got " + format_number(tilt_deg) +
                         " (at 90 and beyond the surface is a wall or an undercut)");
  }
}

std::string_view to_string(SweepParameter parameter) {
  switch (parameter) {
    case SweepParameter::feed_angle:
      return "feed-angle";
    case SweepParameter::tilt:
      return "tilt";
    case SweepParameter::azimuth:
      return "azimuth";
  }
  return "?";
}

std::string_view csv_name(SweepParameter parameter) {
  switch (parameter) {
    case SweepParameter::feed_angle:
      return "feed_angle";
    case SweepParameter::tilt:
      return "tilt";
    case SweepParameter::azimuth:
      return "azimuth";
  }
  return "?";
}

std::vector<double> Sweep::values() const {
  // Count the grid points first so a step of 0.1 does not lose the stop
  // value to rounding.
  const double span = (stop - start) / step;
  const auto count = static_cast<std::size_t>(std::floor(span + 1e-6)) + 1;
  std::vector<double> result;
  result.reserve(count);
  for (std::size_t i = 0; i < count; ++i) result.push_back(start + static_cast<double>(i) * step);
  return result;
}

Sweep parse_sweep(std::string_view text) {
  const std::string form =
      "expected NAME=START:STOP:STEP with NAME feed-angle, tilt or azimuth "
      "(degrees), e.g. feed-angle=0:360:15";
  const std::size_t equals = text.find('=');
  if (equals == std::string_view::npos) {
    throw vcpost::Error(Code::E2001, "'" + std::string(text) + "': " + form);
  }
  const std::string_view name = trim(text.substr(0, equals), kBlanks);
  Sweep sweep;
  if (name == "feed-angle" || name == "feed_angle") {
    sweep.parameter = SweepParameter::feed_angle;
  } else if (name == "tilt") {
    sweep.parameter = SweepParameter::tilt;
  } else if (name == "azimuth") {
    sweep.parameter = SweepParameter::azimuth;
  } else {
    throw vcpost::Error(Code::E2001, "unknown parameter '" + std::string(name) + "': " + form);
  }

  const std::string_view range = text.substr(equals + 1);
  const std::size_t colon1 = range.find(':');
  const std::size_t colon2 =
      colon1 == std::string_view::npos ? colon1 : range.find(':', colon1 + 1);
  if (colon2 == std::string_view::npos || range.find(':', colon2 + 1) != std::string_view::npos) {
    throw vcpost::Error(Code::E2001, "'" + std::string(text) + "': " + form);
  }
  try {
    sweep.start = parse_number(range.substr(0, colon1));
    sweep.stop = parse_number(range.substr(colon1 + 1, colon2 - colon1 - 1));
    sweep.step = parse_number(range.substr(colon2 + 1));
  } catch (const vcpost::Error& e) {
    throw vcpost::Error(Code::E2001, "'" + std::string(text) + "': " + e.what() + "; " + form);
  }
  if (!(sweep.step > 0)) {
    throw vcpost::Error(Code::E2001, "'" + std::string(text) + "': the step must be > 0");
  }
  if (sweep.stop < sweep.start) {
    throw vcpost::Error(Code::E2001,
                        "'" + std::string(text) + "': the stop must not be below the start");
  }
  if ((sweep.stop - sweep.start) / sweep.step >= static_cast<double>(kMaxSweepPoints)) {
    throw vcpost::Error(Code::E2001, "'" + std::string(text) + "': more than " +
                                         std::to_string(kMaxSweepPoints) +
                                         " values; use a larger step");
  }
  return sweep;
}

double degrees_to_radians(double degrees) { return degrees * std::numbers::pi / 180; }
double radians_to_degrees(double radians) { return radians * 180 / std::numbers::pi; }

}  // namespace vcpost::deff
