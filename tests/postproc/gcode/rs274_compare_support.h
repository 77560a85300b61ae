// vcpost's reading of a program against LinuxCNC's rs274, for the tests
// that compare them (rs274_compare_test.cpp, rs274_hostile_test.cpp,
// rs274_random_test.cpp). How rs274 runs standalone here (LinuxCNC 2.9,
// Debian 12): `rs274 -g FILE < /dev/null` prints the canonical calls on
// stdout; no ini or tool table is needed (without -t it starts with an
// empty tool table, which only changes USE_TOOL_LENGTH_OFFSET, not
// compared).
//
// Compared: STRAIGHT_TRAVERSE, STRAIGHT_FEED, ARC_FEED, SET_SPINDLE_SPEED,
// SET_FEED_RATE, in order, every number within 1e-4 in rs274's printed unit
// (mm; after G20 rs274 prints inches with 4 decimals, so vcpost's mm are
// divided by 25.4 there and compared within 1e-4 inch). A straight move
// that ends where the tool already is (rs274 prints one for a bare "G0" or
// "G1" block) is no motion and is dropped on both sides.
#pragma once

#include <filesystem>
#include <string>

#include "postproc/gcode/dialect.h"

namespace vcpost::gcode::rs274cmp {

bool rs274_available();
// rs274's transcript of `file` (its canonical calls and its error, if any).
std::string run_rs274(const std::filesystem::path& file);
// rs274's error message, or "" when it read the program to its end.
std::string rs274_error(const std::string& transcript);
// vcpost's transcript of `file`; its error, formatted, in `error`.
std::string run_vcpost(const std::filesystem::path& file, std::string& error,
                       const Dialect& dialect = rs274ngc_dialect());
// Both read `file` to its end with the same motion (gtest failures if not).
void compare(const std::filesystem::path& file);

}  // namespace vcpost::gcode::rs274cmp
