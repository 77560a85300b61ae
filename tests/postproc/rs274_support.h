// LinuxCNC's rs274 as a reference reader of G-code, for tests.
#pragma once

#include <filesystem>
#include <string>

namespace vcpost::testing {

// The shell command running rs274 with `arguments`, one rs274 at a time on
// the machine: LinuxCNC's rs274 dies of a bus error now and then when two
// run at once (seen with 8 in parallel: half died), as ctest -j does.
std::string rs274_command(const std::string& arguments);

// Writes `text` to dir/name and returns rs274's canonical transcript of it
// without the sequence numbers and the spindle-speed and feed-rate calls:
// the motion, which a rewrite of S and F must not change. Runs in `dir`
// (rs274 keeps its parameter file in the working folder). Empty when rs274
// fails or is missing.
std::string rs274_motion(const std::filesystem::path& dir, const std::string& name,
                         const std::string& text);

}  // namespace vcpost::testing
