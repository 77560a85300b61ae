// What the fuzz targets do with one input, shared by the libFuzzer targets
// (fuzz/*_fuzz.cpp) and the regression tests that replay saved findings
// through the ordinary build (tests/*/fuzz_regressions_test.cpp).
// Header-only, so that both builds compile the same code.
//
// Contract of every driver: it returns the outcome of reading the input,
// "ok" or the stable code of the documented error the reader threw
// ("E1201", "E3103", "E5001", or "timing" for program::TimingError).
// Anything else is a finding and escapes: an exception of another type,
// FuzzFinding for a broken invariant, a crash or a sanitizer report.
#pragma once

#include <stdexcept>

namespace vcpost::fuzz {

// A broken invariant (not a documented error): always a finding.
class FuzzFinding : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

}  // namespace vcpost::fuzz
