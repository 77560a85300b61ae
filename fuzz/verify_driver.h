// The verify driver (see fuzz/finding.h for the contract of drivers).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "fuzz/finding.h"
#include "postproc/gcode/diagnostics.h"
#include "postproc/gcode/dialect.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/gcode/writer.h"
#include "postproc/verify/verify.h"

namespace vcpost::fuzz {

// The line that splits one fuzz input into the program given to `post`
// and the program `post` wrote.
inline constexpr std::string_view kVerifySeparator = "\n%%vcpost-output%%\n";

// Whether `text` runs to its end (or to a reader's error) within the
// fuzzing budget: 10,000 loop iterations and 200,000 blocks. A longer run
// is a legal program (a loop of a million turns) that verify would read
// twice more, too slow to fuzz under the sanitizers: not a finding.
inline bool within_budget(std::string_view text, const gcode::Dialect& dialect) {
  gcode::InterpreterLimits limits;
  limits.max_loop_iterations = 10'000;
  gcode::Interpreter interpreter(text, dialect, limits);
  std::vector<program::Event> events;
  try {
    for (std::uint64_t blocks = 0; interpreter.next(events); ++blocks) {
      events.clear();
      if (blocks > 200'000) return false;
    }
  } catch (const gcode::GcodeError& e) {
    return e.diagnostic().code != vcpost::Code::E1307 &&
           e.diagnostic().code != vcpost::Code::E1309 &&
           e.diagnostic().code != vcpost::Code::E1308 && e.diagnostic().code != vcpost::Code::E1304;
  }
  return true;
}

// verify's documented refusal of an input that does not read: the G-code
// (E1...) or CL (E3...) reader's error, passed on as a vcpost::Error.
inline bool reader_refusal(const vcpost::Error& e) {
  return e.id().starts_with("E1") || e.id().starts_with("E3");
}

// With the separator: verifies the two halves as G-code and as CL in /
// G-code out; any Result or a documented reader refusal is fine. Without it:
// the output is the input with an S word patched into (at most 64 of) the
// blocks with events the interpreter read, as `post` writes it, and that must
// verify (a false alarm of verify is a finding).
inline std::string run_verify(std::string_view data) {
  verify::Options options;
  options.max_violations = 16;
  const std::size_t split = data.find(kVerifySeparator);
  if (split != std::string_view::npos) {
    const std::string_view input = data.substr(0, split);
    const std::string_view output = data.substr(split + kVerifySeparator.size());
    if (!within_budget(input, options.dialect) || !within_budget(output, options.dialect)) {
      return "budget";
    }
    std::string outcome;
    try {
      outcome = verify::verify_gcode(input, output, options).ok() ? "gcode:ok" : "gcode:differs";
    } catch (const vcpost::Error& e) {
      if (!reader_refusal(e)) throw;
      outcome = "gcode:input";
    }
    try {
      outcome += verify::verify_cl(input, output, options).ok() ? " cl:ok" : " cl:differs";
    } catch (const vcpost::Error& e) {
      if (!reader_refusal(e)) throw;
      outcome += " cl:input";
    }
    return outcome;
  }
  if (!within_budget(data, gcode::rs274ngc_dialect())) return "budget";
  gcode::Interpreter interpreter(data, gcode::rs274ngc_dialect());
  std::vector<program::Event> events;
  std::vector<std::uint64_t> offsets;
  try {
    while (interpreter.next(events)) {
      // Only blocks with events get an S from `post` (not o-word lines,
      // '%' or skipped '/' lines).
      if (!events.empty() && offsets.size() < 64) offsets.push_back(interpreter.block().offset);
      events.clear();
    }
  } catch (const gcode::GcodeError&) {
    return "input";  // verify refuses such an input too (checked below)
  }
  std::sort(offsets.begin(), offsets.end());
  offsets.erase(std::unique(offsets.begin(), offsets.end()), offsets.end());
  std::vector<gcode::WordPatch> patches;
  for (auto offset : offsets) patches.push_back({offset, 'S', "1234"});
  const std::string output = gcode::patched(data, patches);
  verify::Result result;
  try {
    result = verify::verify_gcode(data, output, options);
  } catch (const vcpost::Error& e) {
    throw FuzzFinding(std::string("verify refused an input the interpreter reads: ") + e.what());
  }
  if (!result.ok()) {
    throw FuzzFinding("verify rejected a program patched only in S: " +
                      verify::format(result.violations.front(), "output"));
  }
  return "ok";
}

}  // namespace vcpost::fuzz
