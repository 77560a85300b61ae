// The APT CL driver (see fuzz/finding.h for the contract of drivers).
#pragma once

#include <sstream>
#include <string>
#include <string_view>

#include "fuzz/event_checks.h"
#include "postproc/cldata/cl_reader.h"
#include "postproc/program/timing.h"

namespace vcpost::fuzz {

// Reads APT CL text to the end and times every event.
inline std::string run_cldata(std::string_view text) {
  std::istringstream in{std::string(text)};
  cldata::ClReader reader(in, "fuzz.cl");
  program::PathClock clock;
  try {
    while (auto event = reader.next()) {
      check_finite(*event);
      clock.advance(*event);
    }
  } catch (const cldata::ClError& e) {
    return std::string(e.id());
  } catch (const program::TimingError&) {
    return "timing";
  }
  return "ok";
}

}  // namespace vcpost::fuzz
