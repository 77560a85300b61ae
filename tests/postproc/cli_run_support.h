// Runs the built vcpost binary as a user would, for the CLI tests.
#pragma once

#include <filesystem>
#include <string>

namespace vcpost::testing {

struct CliOutcome {
  int exit_code = -1;  // -1 when it did not exit normally
  std::string out;
  std::string err;
};

// The whole file, bytes as they are.
std::string slurp(const std::filesystem::path& path);

// `vcpost ARGUMENTS` (shell words) run in `folder`, with no standard input;
// its standard output and error are captured in out.txt and err.txt there.
// `shell_prefix` runs first in the same shell ("ulimit -s 1024 && ").
CliOutcome run_vcpost(const std::string& arguments, const std::filesystem::path& folder,
                      const std::string& shell_prefix = "");

}  // namespace vcpost::testing
