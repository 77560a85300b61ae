#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "postproc/program/transcript.h"
#include "tests/postproc/cldata/cl_support.h"
#include "tests/postproc/rs274_support.h"

namespace vcpost::cldata::testing {

std::vector<program::Event> read_events(const std::string& text, ClReadOptions options) {
  std::istringstream in(text);
  ClReader reader(in, "test.cl", options);
  std::vector<program::Event> events;
  while (auto e = reader.next()) events.push_back(std::move(*e));
  return events;
}

std::vector<Call> motion_calls(const std::string& transcript) {
  static const char* names[] = {"STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED",
                                "SET_SPINDLE_SPEED", "SET_FEED_RATE"};
  std::vector<Call> calls;
  std::istringstream in(transcript);
  std::string line;
  while (std::getline(in, line)) {
    for (const char* name : names) {
      const std::string key = std::string(name) + "(";
      const auto at = line.find(key);
      if (at == std::string::npos) continue;
      if (at > 0 && line[at - 1] != ' ') continue;
      Call c;
      c.name = name;
      std::string args = line.substr(at + key.size());
      args = args.substr(0, args.find(')'));
      std::istringstream a(args);
      std::string item;
      while (std::getline(a, item, ',')) c.args.push_back(std::strtod(item.c_str(), nullptr));
      calls.push_back(std::move(c));
      break;
    }
  }
  return calls;
}

bool have_rs274() { return access("/usr/bin/rs274", X_OK) == 0; }

std::optional<std::string> run_rs274(const std::string& path, double diameter_inch) {
  if (!have_rs274()) return std::nullopt;
  // Tools 1..99 of length 0: rs274 refuses tools missing from its table,
  // and G43 must not shift the comparison (nor G41/G42 with D).
  const std::string table = path + ".tbl";
  {
    std::ofstream t(table);
    for (int i = 1; i <= 99; ++i) t << 'T' << i << " P" << i << " Z0 D" << diameter_inch << '\n';
  }
  // In the program's own folder, with no terminal: rs274 keeps its parameter
  // file in the working folder, which parallel tests would otherwise share.
  const std::string folder = std::filesystem::path(path).parent_path().string();
  const std::string command =
      "cd '" + (folder.empty() ? std::string(".") : folder) + "' && " +
      vcpost::testing::rs274_command("-t '" + table + "' -g '" + path + "'") + " < /dev/null 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return std::nullopt;
  std::string out;
  char buffer[4096];
  std::size_t n = 0;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  pclose(pipe);
  return out;
}

std::string write_gcode(const std::string& cl, const output::Format& format) {
  std::ostringstream out;
  output::GcodeWriter writer(out, format);
  for (const auto& e : read_events(cl)) writer.write(e);
  writer.finish();
  return out.str();
}

verify::Result verify_written(const std::string& cl, const std::string& text, bool fanuc) {
  verify::Options options;
  options.dialect = fanuc ? gcode::fanuc_dialect() : gcode::rs274ngc_dialect();
  return verify::verify_cl(cl, text, options, "test.cl");
}

std::string first_violation(const verify::Result& result) {
  return result.violations.empty() ? "" : verify::format(result.violations[0], "output");
}

std::vector<Call> moves_only(const std::string& transcript) {
  std::vector<Call> moves;
  for (auto& c : motion_calls(transcript))
    if (c.name != "SET_FEED_RATE" && c.name != "SET_SPINDLE_SPEED") moves.push_back(std::move(c));
  return moves;
}

std::vector<Call> cl_moves(const std::string& cl) {
  std::string transcript;
  for (const auto& e : read_events(cl)) program::append_transcript(transcript, e);
  return moves_only(transcript);
}

void expect_same_moves(const std::vector<Call>& want, const std::vector<Call>& got) {
  ASSERT_EQ(want.size(), got.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(want[i].name, got[i].name) << "call " << i;
    for (std::size_t k = 0; k < want[i].args.size(); ++k)
      ASSERT_NEAR(want[i].args[k], got[i].args.at(k), 1e-4 + 1e-9) << "call " << i << " arg " << k;
  }
}

}  // namespace vcpost::cldata::testing
