// Helpers for the CL data tests: read a CL text into events, and the
// canonical-transcript calls that rs274 and vcpost are compared on.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "postproc/cldata/cl_reader.h"
#include "postproc/output/gcode_writer.h"
#include "postproc/program/events.h"
#include "postproc/verify/verify.h"

namespace vcpost::cldata::testing {

// All events of `text` (throws ClError like the reader).
std::vector<program::Event> read_events(const std::string& text, ClReadOptions options = {});

// One canonical call: its name and numeric arguments.
struct Call {
  std::string name;
  std::vector<double> args;
};

// Parses the calls named STRAIGHT_TRAVERSE, STRAIGHT_FEED, ARC_FEED,
// SET_SPINDLE_SPEED, SET_FEED_RATE out of transcript lines (rs274's
// "   12 N..... NAME(args)" or vcpost's "NAME(args)").
std::vector<Call> motion_calls(const std::string& transcript);

// stdout of `rs274 -g file`, or nullopt when rs274 cannot be run. Its tool
// table holds tools 1..99 of length 0 and diameter `diameter_inch` (rs274
// reads the table in inches): 0 by default, as the D register of a CL
// path's cutter compensation holds only the wear (gcode_writer.h).
std::optional<std::string> run_rs274(const std::string& path, double diameter_inch = 0.0);

bool have_rs274();

// The G-code the writer makes of CL text `cl` in `format`.
std::string write_gcode(const std::string& cl, const output::Format& format);

// vcpost verify's proof that `text` holds the CL motions of `cl`, read in
// the Fanuc dialect or rs274ngc's; and its first violation in words ("" if
// none), for a failure message.
verify::Result verify_written(const std::string& cl, const std::string& text, bool fanuc);
std::string first_violation(const verify::Result& result);

// The motion calls of a transcript (no SET_FEED_RATE, SET_SPINDLE_SPEED),
// and of CL text through vcpost's own reader.
std::vector<Call> moves_only(const std::string& transcript);
std::vector<Call> cl_moves(const std::string& cl);
// Fails the test (gtest) unless `got` lists the calls of `want`, every
// number within 1e-4 (rs274's printed precision).
void expect_same_moves(const std::vector<Call>& want, const std::vector<Call>& got);

}  // namespace vcpost::cldata::testing
