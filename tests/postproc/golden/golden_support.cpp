#include "tests/postproc/golden/golden_support.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace vcpost::golden {

namespace {
constexpr std::size_t kWholeProgramLines = 150;
constexpr std::size_t kHeadTailLines = 25;
}  // namespace

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

std::string digest(std::string_view text) {
  std::uint64_t h = 1469598103934665603ull;
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(h));
  return buffer;
}

std::vector<std::string_view> lines_of(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = text.find('\n', at);
    const std::size_t stop = end == std::string_view::npos ? text.size() : end + 1;
    lines.push_back(text.substr(at, stop - at));
    at = stop;
  }
  return lines;
}

std::string stored_program(const std::string& program) {
  const auto lines = lines_of(program);
  if (lines.size() <= kWholeProgramLines) return program;
  std::string out = "lines " + std::to_string(lines.size()) + " bytes " +
                    std::to_string(program.size()) + " fnv1a64 " + digest(program) + "\n";
  out += "-- head\n";
  for (std::size_t i = 0; i < kHeadTailLines; ++i) out += lines[i];
  out += "-- tail\n";
  for (std::size_t i = lines.size() - kHeadTailLines; i < lines.size(); ++i) out += lines[i];
  return out;
}

bool updating() { return std::getenv("VCPOST_GOLDEN_UPDATE") != nullptr; }

}  // namespace vcpost::golden
