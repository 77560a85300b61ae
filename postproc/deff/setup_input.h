// The input of the working-diameter evaluation: numbers, vectors, sweep ranges and the
// checks a cutting set-up must pass before the engine sees it. No I/O; every
// failure is an exception whose message the caller prefixes with the
// argument or file:line at fault.
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "geometry/engagement.h"
#include "geometry/tool.h"

namespace vcpost::deff {

// A value that cannot be used is a vcpost::Error whose what() says why,
// without naming the source: E2001 (a bad option), or E2006 from the
// reader of a batch file.

// The part of a set-up a SetupError is about, so the caller can name the
// option (--ap) or the CSV column ('ap') it came from.
enum class SetupField { diameter, ap, ae, normal, feed };

// A set-up that fails its checks (E2001), with the field at fault.
class SetupError : public vcpost::Error {
 public:
  SetupError(SetupField field, const std::string& message)
      : vcpost::Error(Code::E2001, message), field_(field) {}
  SetupField field() const { return field_; }

 private:
  SetupField field_;
};

// |n| may differ from 1 by at most this much; such a normal is rescaled.
inline constexpr double kNormalLengthTolerance = 1e-6;

// A finite decimal number, surrounding blanks allowed ("0.3", " -1e-2 ").
// Throws vcpost::Error (E2001) "'x' is not a number".
double parse_number(std::string_view text);

// Three numbers separated by commas, e.g. "0,0.4226,0.9063".
// Throws vcpost::Error (E2001) naming the expected form.
Eigen::Vector3d parse_vector(std::string_view text, std::string_view names);

// "left" or "right". Throws vcpost::Error (E2001).
geometry::Side parse_side(std::string_view text);

std::string_view to_string(geometry::Side side);

// Checks a set-up and returns it with the normal rescaled to unit length.
// Refuses (SetupError naming the field): ap not in (0, D); ae < 0; any
// non-finite number; a zero normal or |n| off 1 by more than
// kNormalLengthTolerance; n_z <= 0 (undercut: a 3-axis tool cannot reach
// the surface with its end); a zero feed or one parallel to the normal.
geometry::CutSetup checked_setup(const geometry::Tool& tool, geometry::CutSetup setup);

// Tilt of the normal to +z in degrees must lie in (-90, 90): at 90 the
// surface is a vertical wall seen edge-on (n_z = 0, undercut). Throws
// SetupError (the normal's).
void check_tilt(double tilt_deg);

// The parameter a sweep varies, in degrees.
enum class SweepParameter { feed_angle, tilt, azimuth };

std::string_view to_string(SweepParameter parameter);  // "feed-angle", "tilt", "azimuth"
std::string_view csv_name(SweepParameter parameter);   // "feed_angle", "tilt", "azimuth"

struct Sweep {
  SweepParameter parameter = SweepParameter::feed_angle;
  double start = 0, stop = 0, step = 0;  // degrees; step > 0, start <= stop

  // start, start + step, ... up to stop (stop included when it falls on the
  // grid, within a millionth of a step).
  std::vector<double> values() const;
};

// Sweeps are capped so a slip in the step cannot flood the output.
inline constexpr std::size_t kMaxSweepPoints = 100000;

// "feed-angle=0:360:15", "tilt=0:60:5", "azimuth=0:180:10". Throws
// vcpost::Error (E2001) for an unknown parameter, a malformed range, step <= 0,
// stop < start or more than kMaxSweepPoints values.
Sweep parse_sweep(std::string_view text);

double degrees_to_radians(double degrees);
double radians_to_degrees(double radians);

}  // namespace vcpost::deff
