// Output side of `vcpost deff`: one evaluation of the working-diameter
// engine, the spindle speed for a nominal cutting speed, and their three
// renderings (aligned text table, JSON, CSV cells). Writes only to the
// streams it is given.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>

#include "geometry/diameter_policy.h"
#include "geometry/engagement.h"
#include "geometry/tool.h"

namespace vcpost::cli::deff {

struct Evaluation {
  geometry::Engagement engagement;
  std::optional<double> d_mean;  // mm; empty when nothing is engaged
};

// Runs the engine. REQUIRES: setup passed checked_setup (deff_input.h).
// Throws what the engine throws (std::logic_error for a tool kind it does
// not handle yet).
Evaluation evaluate(const geometry::Tool& tool, const geometry::CutSetup& setup);

using geometry::DiameterPolicy;  // which diameter sets the spindle speed

struct SpeedRequest {
  DiameterPolicy policy = DiameterPolicy::max;
  std::optional<double> vc;   // nominal cutting speed, m/min, > 0
  std::optional<double> rpm;  // given spindle speed, 1/min, > 0
};

struct Speed {
  DiameterPolicy policy = DiameterPolicy::max;
  std::optional<double> d_ref;       // mm; empty when the policy's point does not exist
  std::optional<double> vc_nominal;  // m/min, as requested
  // The spindle speed the cutting speeds are given at: the request's rpm, or
  // the one that gives vc_nominal at d_ref; empty when d_ref is missing or 0
  // (n unbounded).
  std::optional<double> rpm;
  std::optional<double> vc_at(std::optional<double> diameter) const;
};

Speed plan_speed(const Evaluation& evaluation, const SpeedRequest& request);

// What the user asked for, to echo with the results.
struct Description {
  geometry::Tool tool;
  geometry::CutSetup setup;
  geometry::SpindleDirection spindle = geometry::SpindleDirection::clockwise;
  std::optional<double> feed_angle_deg;  // when the feed was given as an angle
};

// Human-readable report: set-up, an aligned table of D_max, D_min, D_mean
// and the cutting points (position, 2r, r with `radius`, vc with a speed),
// flags, milling mode and spindle speed.
void write_table(std::ostream& out, const Description& description, const Evaluation& evaluation,
                 const std::optional<Speed>& speed, bool radius);

// Machine-readable report; keys documented in README.md ("vcpost deff").
nlohmann::ordered_json to_json(const Description& description, const Evaluation& evaluation,
                               const std::optional<Speed>& speed);

// The result columns shared by --sweep and --batch:
// d_cut,d_p1,d_p2,d_p1a,d_p1b,d_p2a,d_p2b,d_max,d_min,d_mean,engaged and,
// with `radius`, r_cut ... r_mean after them. Cells: mm with 4 decimals,
// empty where a point does not exist; engaged 0 or 1.
std::string csv_header(bool radius);
std::string csv_cells(const Evaluation& evaluation, bool radius);

}  // namespace vcpost::cli::deff
