#include "rs274_support.h"

#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>

namespace vcpost::testing {

std::string rs274_command(const std::string& arguments) {
  return "flock /tmp/vcpost-rs274.lock rs274 " + arguments;
}

std::string rs274_motion(const std::filesystem::path& dir, const std::string& name,
                         const std::string& text) {
  std::ofstream(dir / name, std::ios::binary) << text;
  const std::string command = "cd '" + dir.string() + "' && " +
                              rs274_command("-g '" + (dir / name).string() + "'") +
                              " < /dev/null 2>&1";
  std::string lines, result;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[65536];
    std::size_t n;
    while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) lines.append(buffer, n);
    pclose(pipe);
  }
  std::istringstream in(lines);
  std::string line;
  static const std::regex call(R"([A-Z_]+\(.*)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (!std::regex_search(line, m, call)) continue;
    const std::string rest = m[0];
    if (rest.starts_with("SET_SPINDLE_SPEED") || rest.starts_with("SET_FEED_RATE")) continue;
    result += rest + "\n";
  }
  return result;
}

}  // namespace vcpost::testing
