// vcpost's interpreted moves against LinuxCNC's interpreter. How rs274 runs
// standalone here (LinuxCNC 2.9, Debian 12): `rs274 -g FILE < /dev/null`
// prints the canonical calls on stdout; no ini or tool table is needed
// (without -t it starts with an empty tool table, which only changes
// USE_TOOL_LENGTH_OFFSET, not compared). The test skips when rs274 or the
// shared data are absent.
//
// Compared: STRAIGHT_TRAVERSE, STRAIGHT_FEED, ARC_FEED, SET_SPINDLE_SPEED,
// SET_FEED_RATE, in order, every number within 1e-4 in rs274's printed unit
// (mm; after G20 rs274 prints inches with 4 decimals, so vcpost's mm are
// divided by 25.4 there and compared within 1e-4 inch).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "postproc/gcode/interpreter.h"
#include "postproc/program/transcript.h"
#include "tests/postproc/rs274_support.h"

namespace vcpost::gcode {
namespace {

namespace fs = std::filesystem;

struct Call {
  std::string name;
  std::vector<double> args;
  bool inches = false;
};

bool compared(const std::string& name) {
  return name == "STRAIGHT_TRAVERSE" || name == "STRAIGHT_FEED" || name == "ARC_FEED" ||
         name == "SET_SPINDLE_SPEED" || name == "SET_FEED_RATE";
}

// Calls of interest from transcript text (rs274's or vcpost's).
std::vector<Call> parse(const std::string& text) {
  static const std::regex call(R"(([A-Z_]+)\((.*)\))");
  std::vector<Call> calls;
  bool inches = false;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::smatch m;
    if (!std::regex_search(line, m, call)) continue;
    const std::string name = m[1];
    if (name == "USE_LENGTH_UNITS") inches = m[2].str().find("INCHES") != std::string::npos;
    if (!compared(name)) continue;
    Call c{name, {}, inches};
    std::istringstream args(m[2].str());
    std::string a;
    while (std::getline(args, a, ',')) c.args.push_back(std::stod(a));
    calls.push_back(c);
  }
  // rs274 prints F before the G20/G21 of its block: a feed is in the units
  // of the next motion.
  for (std::size_t i = 0; i < calls.size(); ++i) {
    if (calls[i].name != "SET_FEED_RATE") continue;
    for (std::size_t k = i + 1; k < calls.size(); ++k)
      if (calls[k].name != "SET_FEED_RATE" && calls[k].name != "SET_SPINDLE_SPEED") {
        calls[i].inches = calls[k].inches;
        break;
      }
  }
  return calls;
}

std::string run_rs274(const fs::path& file) {
  const std::string command =
      vcpost::testing::rs274_command("-g '" + file.string() + "'") + " < /dev/null 2>&1";
  std::string out;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[65536];
    std::size_t n;
    while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
    pclose(pipe);
  }
  return out;
}

std::string run_vcpost(const fs::path& file, std::string& error) {
  std::ifstream in(file, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Interpreter interpreter(text, rs274ngc_dialect());
  std::vector<program::Event> events;
  std::string out;
  try {
    while (interpreter.next(events)) {
      for (const auto& e : events) program::append_transcript(out, e);
      events.clear();
    }
  } catch (const GcodeError& e) {
    error = format(e.diagnostic(), file.string());
  }
  return out;
}

bool rs274_available() { return std::system("command -v rs274 > /dev/null 2>&1") == 0; }

void compare(const fs::path& file) {
  SCOPED_TRACE(file.string());
  std::string error;
  const auto ours = parse(run_vcpost(file, error));
  ASSERT_EQ(error, "");
  const auto theirs = parse(run_rs274(file));
  ASSERT_GT(theirs.size(), 0u) << "rs274 printed no moves";
  ASSERT_EQ(ours.size(), theirs.size());
  for (std::size_t i = 0; i < ours.size(); ++i) {
    const Call& a = ours[i];
    const Call& b = theirs[i];
    ASSERT_EQ(a.name, b.name) << "call " << i;
    ASSERT_EQ(a.args.size(), b.args.size()) << "call " << i;
    for (std::size_t k = 0; k < a.args.size(); ++k) {
      const bool is_length = a.name != "SET_SPINDLE_SPEED" && !(a.name == "ARC_FEED" && k == 4);
      const double mine = b.inches && is_length ? a.args[k] / 25.4 : a.args[k];
      ASSERT_NEAR(mine, b.args[k], 1e-4) << "call " << i << " (" << a.name << ") argument " << k;
    }
  }
}

TEST(Rs274Compare, OwnTestPrograms) {
  if (!rs274_available()) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "tests/postproc/gcode/programs";
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".ngc") {
      compare(entry.path());
      ++count;
    }
  EXPECT_GE(count, 3);
}

TEST(Rs274Compare, SharedRealPrograms) {
  if (!rs274_available()) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const fs::path dir = fs::path(VCPOST_SHARED_DATA_DIR) / "gcode";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "shared data not found at " << dir;
  // The RS274NGC-compatible programs of PROVENANCE.md (ENSURE_TOOL_LENGTH.EIA
  // is a Mazak macro, not RS274NGC).
  for (const char* name : {"3D_Chips.ngc", "3D_Chips_2006.ngc", "Waterline_OCL.gcode", "bear.nc"}) {
    if (!fs::exists(dir / name)) continue;
    compare(dir / name);
  }
}

}  // namespace
}  // namespace vcpost::gcode
