#include "cli_run_support.h"

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iterator>

namespace vcpost::testing {

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

CliOutcome run_vcpost(const std::string& arguments, const std::filesystem::path& folder,
                      const std::string& shell_prefix) {
  const std::string command = "cd '" + folder.string() + "' && " + shell_prefix + "'" +
                              VCPOST_BINARY + "' " + arguments +
                              " > out.txt 2> err.txt < /dev/null";
  const int status = std::system(command.c_str());
  CliOutcome r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(folder / "out.txt");
  r.err = slurp(folder / "err.txt");
  return r;
}

}  // namespace vcpost::testing
