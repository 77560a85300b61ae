#include "tests/postproc/gcode/rs274_compare_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "postproc/gcode/interpreter.h"
#include "postproc/program/transcript.h"
#include "tests/postproc/rs274_support.h"

namespace vcpost::gcode::rs274cmp {

namespace fs = std::filesystem;

namespace {

struct Call {
  std::string name;
  std::vector<double> args;
  bool inches = false;
};

// Marks straight moves that end exactly where the last move ended (as
// printed: rs274's bare "G0" blocks, cycle moves to the level the tool is at).
struct Marked {
  Call call;
  bool null = false;
  // How far offset changes since the last NURBS_FEED moved where the tool
  // stands in the program's frame (rs274 prints no NURBS end point).
  std::vector<double> shift_since_nurbs = {0.0, 0.0, 0.0};
};
// rs274 prints positions in the program's frame: a change of the G92 or
// G5x offset (SET_G92_OFFSET, SET_G5X_OFFSET, dropped here) moves where the
// tool stands in it, so that G28's move to the intermediate point where
// the tool already is stays a null move after a G92.
std::vector<Marked> mark_null_moves(std::vector<Call> calls) {
  std::vector<Marked> marked;
  std::vector<double> at = {0.0, 0.0, 0.0};
  std::vector<double> g92 = {0.0, 0.0, 0.0}, g5x = {0.0, 0.0, 0.0};
  std::vector<double> shift = {0.0, 0.0, 0.0};
  int plane = 17;
  for (auto& c : calls) {
    if (c.name == "SELECT_PLANE") {
      plane = static_cast<int>(c.args[0]);
      continue;
    }
    if (c.name == "SET_G92_OFFSET" || c.name == "SET_G5X_OFFSET") {
      auto& offset = c.name == "SET_G92_OFFSET" ? g92 : g5x;
      const std::size_t first = c.name == "SET_G92_OFFSET" ? 0 : 1;  // G5X: the system's index
      for (std::size_t k = 0; k < 3 && first + k < c.args.size(); ++k) {
        at[k] -= c.args[first + k] - offset[k];
        shift[k] -= c.args[first + k] - offset[k];
        offset[k] = c.args[first + k];
      }
      continue;
    }
    bool null = false;
    if (c.name == "STRAIGHT_TRAVERSE" || c.name == "STRAIGHT_FEED") {
      // Within the rounding of the printed numbers (4 decimals) an offset
      // change adds to them.
      null = std::abs(c.args[0] - at[0]) < 2e-4 && std::abs(c.args[1] - at[1]) < 2e-4 &&
             std::abs(c.args[2] - at[2]) < 2e-4;
      at = {c.args[0], c.args[1], c.args[2]};
    } else if (c.name == "NURBS_FEED") {
      at = {std::nan(""), 0.0, 0.0};  // rs274 prints no end point
      shift = {0.0, 0.0, 0.0};
    } else if (c.name == "ARC_FEED") {
      // ARC_FEED(first end, second end, ..., axis end): XY, ZX or YZ.
      const double first = c.args[0], second = c.args[1], axis = c.args[5];
      at = plane == 18   ? std::vector<double>{second, axis, first}
           : plane == 19 ? std::vector<double>{axis, first, second}
                         : std::vector<double>{first, second, axis};
    }
    marked.push_back(Marked{std::move(c), null, shift});
  }
  return marked;
}

bool compared(const std::string& name) {
  return name == "STRAIGHT_TRAVERSE" || name == "STRAIGHT_FEED" || name == "ARC_FEED" ||
         name == "NURBS_FEED" || name == "SET_SPINDLE_SPEED" || name == "SET_FEED_RATE" ||
         name == "SET_G92_OFFSET" || name == "SET_G5X_OFFSET" || name == "SELECT_PLANE";
}

// Calls of interest from transcript text (rs274's or vcpost's).
std::vector<Call> parse(const std::string& text) {
  static const std::regex call(R"(([A-Z_][A-Z0-9_]*)\((.*)\))");
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
    // SELECT_PLANE(CANON_PLANE_XZ): its G code (17, 18, 19) as the one number.
    if (name == "SELECT_PLANE") {
      const std::string plane = m[2].str();
      c.args.push_back(plane.ends_with("XZ") ? 18 : plane.ends_with("YZ") ? 19 : 17);
    } else if (name != "NURBS_FEED")  // NURBS_FEED(4, ...): the control points' count only
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

// vcpost's `end` (mm) as a move like `theirs`, in theirs' frame.
Call moved_by(const Call& end, const Marked& theirs) {
  Call c{theirs.call.name, end.args, false};
  const double unit = theirs.call.inches ? 25.4 : 1.0;
  for (std::size_t k = 0; k < 3 && k < c.args.size(); ++k)
    c.args[k] += theirs.shift_since_nurbs[k] * unit;
  return c;
}

bool same_call(const Call& a, const Call& b) {
  if (a.name != b.name || a.args.size() != b.args.size()) return false;
  for (std::size_t k = 0; k < a.args.size(); ++k) {
    const bool is_length = a.name != "SET_SPINDLE_SPEED" && !(a.name == "ARC_FEED" && k == 4);
    const double mine = b.inches && is_length ? a.args[k] / 25.4 : a.args[k];
    if (std::abs(mine - b.args[k]) > 1e-4) return false;
  }
  return true;
}

}  // namespace

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

std::string rs274_error(const std::string& transcript) {
  std::istringstream in(transcript);
  std::string line;
  static const std::regex call(R"(^\s*\d+ N)");
  while (std::getline(in, line)) {
    if (line.empty() || line == "executing" || std::regex_search(line, call)) continue;
    // Read to its end, motion complete (rs274 prints the last line after
    // it): vcpost warns (W1305) there.
    if (line == "File ended with no percent sign or program end") return "";
    return line;
  }
  return "";
}

std::string run_vcpost(const fs::path& file, std::string& error, const Dialect& dialect) {
  std::ifstream in(file, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Interpreter interpreter(text, dialect);
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
  const auto ours = mark_null_moves(parse(run_vcpost(file, error)));
  ASSERT_EQ(error, "");
  const std::string transcript = run_rs274(file);
  ASSERT_EQ(rs274_error(transcript), "");
  const auto theirs = mark_null_moves(parse(transcript));
  ASSERT_GT(theirs.size(), 0u) << "rs274 printed no moves";
  std::size_t i = 0, j = 0;
  // Where vcpost's last NURBS ended (its last chord), until the next move.
  std::optional<Call> curve_end;
  while (i < ours.size() || j < theirs.size()) {
    if (i < ours.size() && j < theirs.size() && same_call(ours[i].call, theirs[j].call)) {
      // (A move ends the tool's stay at the curve's end; F and S do not.)
      const std::string& name = ours[i].call.name;
      if (name.starts_with("STRAIGHT_") || name == "ARC_FEED") curve_end.reset();
      ++i;
      ++j;
    } else if (j < theirs.size() && curve_end && theirs[j].call.name.starts_with("STRAIGHT_") &&
               same_call(moved_by(*curve_end, theirs[j]), theirs[j].call)) {
      // rs274 prints no end point for a NURBS, so it cannot tell a move of
      // its to where the tool already is (G28's to the intermediate point
      // without axis words) from a real one: a move exactly to where
      // vcpost's curve ended (in the frame of the move), which vcpost
      // leaves out as no motion.
      ++j;
    } else if (j < theirs.size() && theirs[j].call.name == "NURBS_FEED" && i < ours.size() &&
               ours[i].call.name == "STRAIGHT_FEED") {
      // A spline: vcpost's chords (splines_test.cpp and nurbs_test.cpp
      // check their geometry) up to the call that matches rs274's next
      // (G5.3 with axis words ends one NURBS and opens the next at once:
      // two NURBS_FEED in a row).
      while (j < theirs.size() && theirs[j].call.name == "NURBS_FEED") ++j;
      while (i < ours.size() && ours[i].call.name == "STRAIGHT_FEED" &&
             !(j < theirs.size() && same_call(ours[i].call, theirs[j].call))) {
        curve_end = ours[i].call;
        ++i;
      }
    } else if (j < theirs.size() && theirs[j].null) {
      ++j;
    } else if (i < ours.size() && ours[i].null) {
      ++i;
    } else {
      auto text = [](const std::vector<Marked>& v, std::size_t n) {
        if (n >= v.size()) return std::string("(end)");
        std::string t = v[n].call.name + "(";
        for (double x : v[n].call.args) t += std::to_string(x) + ",";
        return t + ")";
      };
      FAIL() << "call " << i << " of vcpost " << text(ours, i) << " vs call " << j << " of rs274 "
             << text(theirs, j);
    }
  }
}

}  // namespace vcpost::gcode::rs274cmp
