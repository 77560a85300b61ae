// The shared hyperMILL programs (../shared/data/corpus/heidenhain): each
// reads to its end, and the end point of every L and C block equals an
// independent reading of its coordinates: a scan of the text by a regular
// expression that keeps the last X, Y and Z written plus the datum shift
// of CYCL DEF 7 at the time (these programs write absolute coordinates; in
// a tilted working plane the events are the frame's coordinates plus that
// shift, docs/tilted-frames.md). Tolerance 1e-9 mm: both read the same
// decimals.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <string>

#include "postproc/heidenhain/interpreter.h"

namespace vcpost::heidenhain {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// line -> X, Y, Z after the block, for the L and C blocks with literal
// coordinates; an axis a M91/M92 block names is unknown (machine
// coordinates) until the text writes it again.
std::map<std::uint32_t, std::array<std::optional<double>, 3>> scan(const std::string& text) {
  static const std::regex block(R"(^\d+ (L|C) (.*)$)");
  static const std::regex word(R"(\b([XYZ])([-+]?[0-9]*\.?[0-9]+)\b)");
  static const std::regex unreadable(R"(\b(I[XYZ]|[XYZ][-+]?Q))");
  static const std::regex datum(R"(^\d+ CYCL DEF 7\.[123] ([XYZ])([-+]?[0-9]*\.?[0-9]+))");
  static const std::regex plane(R"(^\d+ (PLANE|CYCL DEF 19\.1) )");
  std::map<std::uint32_t, std::array<std::optional<double>, 3>> out;
  std::array<std::optional<double>, 3> at{0.0, 0.0, 0.0};
  std::array<double, 3> shift{0.0, 0.0, 0.0};
  std::istringstream in(text);
  std::string line;
  std::uint32_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::smatch m;
    if (std::regex_search(line, m, datum)) {
      shift[static_cast<std::size_t>(m[1].str()[0] - 'X')] = std::stod(m[2].str());
      continue;
    }
    if (std::regex_search(line, plane)) {
      // The tool's tip stays on the part through a tilt: in the new frame's
      // coordinates it is somewhere the text does not say.
      at = {std::nullopt, std::nullopt, std::nullopt};
      continue;
    }
    if (!std::regex_match(line, m, block)) continue;
    std::string words = m[2].str();
    words = words.substr(0, words.find(';'));
    const bool machine =
        words.find("M91") != std::string::npos || words.find("M92") != std::string::npos;
    if (std::regex_search(words, unreadable)) return out;  // the scan stops where it cannot follow
    bool any = false;
    for (std::sregex_iterator w(words.begin(), words.end(), word), e; w != e; ++w) {
      const auto k = static_cast<std::size_t>((*w)[1].str()[0] - 'X');
      if (machine)
        at[k].reset();
      else
        at[k] = std::stod((*w)[2].str()) + shift[k];
      any = true;
    }
    if (any && !machine) out[number] = at;
  }
  return out;
}

TEST(KlartextSharedPrograms, ReadAndEndPointsMatchTheText) {
  const fs::path dir = fs::path(VCPOST_SHARED_DATA_DIR) / "corpus/heidenhain";
  if (!fs::exists(dir)) GTEST_SKIP() << "shared data absent: " << dir;
  int programs = 0, read = 0, compared = 0, tilted = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.path().extension() != ".h") continue;
    SCOPED_TRACE(entry.path().filename().string());
    ++programs;
    const std::string text = read_file(entry.path());
    const auto expected = scan(text);
    Interpreter interpreter(text);
    std::vector<program::Event> events;
    std::map<std::uint32_t, Eigen::Vector3d> first_end;  // the first motion of each line
    bool refused = false;
    try {
      while (interpreter.next(events)) {
        for (const auto& e : events) {
          if (const auto* f = std::get_if<program::WorkingFrame>(&e)) {
            // The five tilt to the part's X faces: SPA90 SPC-/+90, z = -/+X.
            if (!f->is_identity()) {
              ++tilted;
              EXPECT_NEAR(std::abs(f->rotation(0, 2)), 1.0, 1e-15);
            }
          }
          if (!program::is_motion(e)) continue;
          const auto line = program::source_of(e).line;
          Eigen::Vector3d end;
          if (const auto* t = std::get_if<program::StraightTraverse>(&e))
            end = t->end;
          else if (const auto* f = std::get_if<program::StraightFeed>(&e))
            end = f->end;
          else
            end = std::get<program::ArcFeed>(e).end;
          first_end.try_emplace(line, end);
        }
        events.clear();
      }
      ++read;
    } catch (const KlartextError& e) {
      ADD_FAILURE() << e.what();
      refused = true;
    }
    for (const auto& [line, xyz] : expected) {
      const auto it = first_end.find(line);
      if (it == first_end.end()) {
        // Only blocks after a refusal, or never run (subprograms not called), lack a move.
        EXPECT_TRUE(refused || line > interpreter.block().line) << "no move for line " << line;
        continue;
      }
      for (std::size_t a = 0; a < 3; ++a) {
        if (!xyz[a]) continue;
        EXPECT_NEAR(it->second[static_cast<Eigen::Index>(a)], *xyz[a], 1e-9) << "line " << line;
        ++compared;
      }
    }
  }
  EXPECT_EQ(programs, 27);
  EXPECT_EQ(read, 27);
  EXPECT_EQ(tilted, 9);  // B5, B6, B8, B10 and B16 tilt the plane (PLANE SPATIAL SPA90)
  EXPECT_GT(compared, 90000);
}

}  // namespace
}  // namespace vcpost::heidenhain
