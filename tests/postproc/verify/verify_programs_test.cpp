// verify on real programs: every shared G-code program and the samples,
// posted with the library, verify with exactly as many changes as the post
// summary counts S and F words; the CL samples posted to G-code verify
// against their CL data; shared CL programs (with arcs) written by the
// Mazak writer verify, and moving one end point or arc centre by 0.001 mm
// fails while 0.0001 mm passes (default tolerance 0.0005 mm); the verdict
// on a sample agrees with LinuxCNC's rs274 when it is installed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "../dome_program_support.h"
#include "../rs274_support.h"
#include "geometry/analytic_surfaces.h"
#include "geometry/occt/brep_model.h"
#include "machines/builtin.h"
#include "postproc/cldata/cl_reader.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/output/gcode_writer.h"
#include "postproc/post/post_job.h"
#include "postproc/verify/lexer.h"
#include "postproc/verify/verify.h"
#include "tests/sanitizers.h"

namespace vcpost::verify {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

struct Posted {
  std::string output;
  post::PostSummary summary;
};

Posted post_with(const std::string& input, const std::string& name,
                 const geometry::SurfaceModel& model, const machines::MachineProfile& profile,
                 const post::PostSettings& settings) {
  Posted p;
  p.summary = post::post_program(input, name, model, profile, settings,
                                 [&](std::string_view bytes) { p.output.append(bytes); });
  return p;
}

// A plane under the program's lowest feed move, as wide as its feed moves:
// the tool touches it wherever the program cuts deepest.
geometry::AnalyticModel floor_under(const std::string& program, const gcode::Dialect& dialect) {
  gcode::Interpreter interpreter(program, dialect);
  std::vector<program::Event> events;
  Eigen::AlignedBox3d box;
  while (interpreter.next(events)) {
    for (const auto& e : events) {
      if (const auto* f = std::get_if<program::StraightFeed>(&e)) box.extend(f->end);
      if (const auto* a = std::get_if<program::ArcFeed>(&e)) box.extend(a->end);
    }
    events.clear();
  }
  geometry::PlanePatch plane;
  plane.origin = {0, 0, box.min().z()};
  plane.u_min = box.min().x() - 10;
  plane.u_max = box.max().x() + 10;
  plane.v_min = box.min().y() - 10;
  plane.v_max = box.max().y() + 10;
  return geometry::AnalyticModel({plane});
}

void expect_verified_gcode(const std::string& input, const Posted& p,
                           const gcode::Dialect& dialect) {
  Options options;
  options.dialect = dialect;
  const Result r = verify_gcode(input, p.output, options);
  EXPECT_TRUE(r.ok()) << (r.violations.empty() ? "" : format(r.violations[0], "output"));
  // The post counts every word it writes; a word of the input rewritten
  // with the value it had is no change. So the changes equal the post's
  // count up to the input's words that kept their bytes (counted here
  // with the lexer, independently of the comparison).
  std::uint64_t kept[2] = {0, 0};
  std::vector<Token> tokens;
  for (const auto& line : split_lines(input)) {
    tokenize(line.text, tokens);
    for (const auto& t : tokens)
      if (t.is_sf()) ++kept[t.letter() == 'S' ? 0 : 1];
  }
  for (const auto& c : r.changes)
    if (!c.added) --kept[c.letter == 'S' ? 0 : 1];
  EXPECT_LE(r.s_changes, p.summary.s_words);
  EXPECT_GE(r.s_changes + kept[0], p.summary.s_words);
  EXPECT_LE(r.f_changes, p.summary.f_words);
  EXPECT_GE(r.f_changes + kept[1], p.summary.f_words);
  EXPECT_EQ(r.motions, p.summary.motion_events);
  std::printf(
      "  %llu S and %llu F words changed (post: %llu S, %llu F written; input words "
      "kept: %llu S, %llu F), %llu motions compared\n",
      static_cast<unsigned long long>(r.s_changes), static_cast<unsigned long long>(r.f_changes),
      static_cast<unsigned long long>(p.summary.s_words),
      static_cast<unsigned long long>(p.summary.f_words), static_cast<unsigned long long>(kept[0]),
      static_cast<unsigned long long>(kept[1]), static_cast<unsigned long long>(r.motions));
}

TEST(VerifyPrograms, SharedGcodeProgramsPostedVerify) {
  const fs::path dir = fs::path(VCPOST_SHARED_DATA_DIR) / "gcode";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "no shared data at " << dir;
  int posted = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".md" || ext == ".json") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const bool eia = ext == ".EIA" || ext == ".eia";
    const auto profile = machines::builtin_profile(eia ? "mazak-3axis" : "generic");
    const std::string input = read(entry.path());
    post::PostSettings settings;
    settings.point.tool = geometry::Tool::ball(6);
    settings.point.vc = 120;
    settings.point.ap = 0.3;
    std::optional<Posted> p;
    try {
      p = post_with(input, entry.path().filename().string(),
                    floor_under(input, post::dialect_of(profile)), profile, settings);
    } catch (const std::exception& e) {
      // A program the post refuses (a macro program that reads machine
      // state) cannot be posted; it must still verify against itself, or
      // be refused by verify as an input error in the same way.
      std::printf("%s: not posted (%s)\n", entry.path().filename().string().c_str(), e.what());
      try {
        Options options;
        options.dialect = post::dialect_of(profile);
        const Result r = verify_gcode(input, input, options);
        EXPECT_TRUE(r.ok());
        EXPECT_TRUE(r.changes.empty());
      } catch (const vcpost::Error& error) {
        std::printf("  verify refuses it too: %s\n", error.what());
      }
      continue;
    }
    std::printf("%s:\n", entry.path().filename().string().c_str());
    EXPECT_GT(p->summary.s_words, 0u);
    expect_verified_gcode(input, *p, post::dialect_of(profile));
    ++posted;
  }
  EXPECT_GE(posted, 4);
}

TEST(VerifyPrograms, DomeRasterPostedWithFeedCouplingVerifies) {
  const std::string input = testing::dome_raster(1.0, 0.5, 8000);
  const auto profile = machines::builtin_profile("mazak-3axis");
  post::PostSettings settings;
  settings.point.tool = geometry::Tool::ball(2 * testing::dome_ball_radius);
  settings.point.vc = 120;
  settings.point.ap = 0.3;
  settings.adjust_feed = true;
  settings.dialect = gcode::rs274ngc_dialect();
  const Posted p = post_with(input, "dome.ngc", testing::dome(), profile, settings);
  EXPECT_GT(p.summary.s_words, 10u);
  EXPECT_GT(p.summary.f_words, 10u);
  expect_verified_gcode(input, p, gcode::rs274ngc_dialect());
}

struct Sample {
  std::string program, model;
  double diameter, vc, ap;
};

Sample sample_for(const std::string& program) {
  if (program.rfind("wavy", 0) == 0) return {program, "wavy.step", 10, 120, 0.3};
  if (program.rfind("cylinder", 0) == 0) return {program, "cylinder.step", 12, 150, 0.2};
  return {program, "dome.step", 10, 120, 0.3};
}

// Every sample program with `extension` posted for mazak-3axis, by name.
std::vector<std::pair<std::string, Posted>> post_samples_now(const std::string& extension) {
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "samples";
  const auto profile = machines::builtin_profile("mazak-3axis");
  std::vector<std::pair<std::string, Posted>> out;
  std::map<std::string, occt::BrepModel> models;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != extension) continue;
    const Sample s = sample_for(entry.path().filename().string());
    if (!models.contains(s.model))
      models.emplace(s.model, occt::BrepModel::load_step(dir / s.model));
    post::PostSettings settings;
    settings.point.tool = geometry::Tool::ball(s.diameter);
    settings.point.vc = s.vc;
    settings.point.ap = s.ap;
    settings.dialect = gcode::rs274ngc_dialect();
    out.emplace_back(
        s.program, post_with(read(entry.path()), s.program, models.at(s.model), profile, settings));
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return out;
}

// Posted once per test program run (posting is the slow part).
const std::vector<std::pair<std::string, Posted>>& post_samples(const std::string& extension) {
  static std::map<std::string, std::vector<std::pair<std::string, Posted>>> cache;
  if (!cache.contains(extension)) cache.emplace(extension, post_samples_now(extension));
  return cache.at(extension);
}

TEST(VerifyPrograms, GcodeSamplesPostedVerify) {
  const auto& posted = post_samples(".nc");
  ASSERT_GE(posted.size(), 10u);
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "samples";
  for (const auto& [name, p] : posted) {
    SCOPED_TRACE(name);
    std::printf("%s:\n", name.c_str());
    EXPECT_GT(p.summary.s_words, 0u);
    expect_verified_gcode(read(dir / name), p, gcode::rs274ngc_dialect());
  }
}

std::pair<std::string, std::uint32_t> moved(const std::string& output, const std::string& axis,
                                            int nth, double delta);

using testing::rs274_motion;

// The verdict agrees with an independent reader: LinuxCNC's rs274 reads the
// same motion from a sample and its posted program (verify passes), and
// another motion once one coordinate digit of a feed block changed (verify
// fails there).
TEST(VerifyPrograms, VerdictAgreesWithLinuxcncRs274) {
  if (std::system("command -v rs274 >/dev/null 2>&1") != 0) GTEST_SKIP() << "rs274 not installed";
  const auto& posted = post_samples(".nc");
  ASSERT_FALSE(posted.empty());
  const auto& [name, p] = posted.front();
  const fs::path dir =
      fs::temp_directory_path() / ("vcpost_verify_rs274_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string input = read(fs::path(VCPOST_SOURCE_DIR) / "samples" / name);
  const std::string a = rs274_motion(dir, "in.ngc", input);
  EXPECT_GT(std::count(a.begin(), a.end(), '\n'), 500);
  EXPECT_TRUE(verify_gcode(input, p.output, Options{}).ok());
  EXPECT_EQ(rs274_motion(dir, "out.ngc", p.output), a);
  const auto [changed, line] = moved(p.output, "X", 3, 0.001);
  ASSERT_GT(line, 0u);
  const Result r = verify_gcode(input, changed, Options{});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.violations[0].code, Code::E7103);
  EXPECT_EQ(r.violations[0].line, line);
  EXPECT_NE(rs274_motion(dir, "changed.ngc", changed), a);
  fs::remove_all(dir);
}

Options mazak_options() {
  Options o;
  o.dialect = gcode::mazak_dialect();
  o.output_decimals = machines::builtin_profile("mazak-3axis").output().decimals;
  o.output_feed_decimals = machines::builtin_profile("mazak-3axis").output().feed_decimals;
  return o;
}

TEST(VerifyPrograms, ClSamplesPostedVerify) {
  const auto& posted = post_samples(".cls");
  ASSERT_GE(posted.size(), 10u);
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "samples";
  for (const auto& [name, p] : posted) {
    SCOPED_TRACE(name);
    const Result r = verify_cl(read(dir / name), p.output, mazak_options(), name);
    EXPECT_TRUE(r.ok()) << (r.violations.empty() ? "" : format(r.violations[0], "output"));
    EXPECT_EQ(r.motions, p.summary.motion_events);
    EXPECT_GT(r.s_changes, 0u);
    EXPECT_DOUBLE_EQ(r.tolerance_mm, 0.0005);
    std::printf("%s: %llu motions, %llu S and %llu F words changed\n", name.c_str(),
                static_cast<unsigned long long>(r.motions),
                static_cast<unsigned long long>(r.s_changes),
                static_cast<unsigned long long>(r.f_changes));
  }
}

// True when `line` holds the word `code` (G1, not G17 or G1.5).
bool has_code(const std::string& line, const std::string& code) {
  return std::regex_search(line, std::regex("(^|[^0-9.])" + code + "([^0-9.]|$)"));
}

// The output with the value of `axis` in the `nth` feed block (G1 modal;
// for I: the nth arc block) holding that axis moved by `delta` mm, written
// back with 4 decimals; and that block's line.
std::pair<std::string, std::uint32_t> moved(const std::string& output, const std::string& axis,
                                            int nth, double delta) {
  std::istringstream in(output);
  std::string line, out;
  std::uint32_t number = 0, hit = 0;
  const std::regex word(axis + "(-?[0-9]+\\.[0-9]+)");
  int seen = 0;
  bool feed = false;
  while (std::getline(in, line)) {
    ++number;
    const bool arc = has_code(line, "G2") || has_code(line, "G3");
    if (has_code(line, "G1")) feed = true;
    if (has_code(line, "G0") || arc) feed = false;
    const bool wanted = axis == "I" ? arc : feed;
    std::smatch m;
    if (!hit && wanted && std::regex_search(line, m, word) && ++seen == nth) {
      char value[64];
      std::snprintf(value, sizeof value, "%.4f", std::stod(m[1].str()) + delta);
      line = m.prefix().str() + axis + value + m.suffix().str();
      hit = number;
    }
    out += line + '\n';
  }
  return {out, hit};
}

TEST(VerifyPrograms, ClEndPointMovedByAMicronFailsByATenthPasses) {
  const auto& posted = post_samples(".cls");
  ASSERT_FALSE(posted.empty());
  const auto& [name, p] = posted.front();
  const std::string cl = read(fs::path(VCPOST_SOURCE_DIR) / "samples" / name);
  // The 5th feed block with an X word: X and the next blocks' X (modal)
  // move; the first violation is at the moved block.
  const auto [far, line] = moved(p.output, "X", 5, 0.001);
  ASSERT_GT(line, 0u);
  const Result bad = verify_cl(cl, far, mazak_options(), name);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.violations[0].code, Code::E7132);
  EXPECT_EQ(bad.violations[0].line, line);
  EXPECT_NE(bad.violations[0].message.find("0.0010 mm"), std::string::npos)
      << bad.violations[0].message;
  const auto [near, line2] = moved(p.output, "X", 5, 0.0001);
  EXPECT_EQ(line2, line);
  const Result good = verify_cl(cl, near, mazak_options(), name);
  EXPECT_TRUE(good.ok()) << (good.violations.empty() ? "" : format(good.violations[0], "out"));
  // A tighter tolerance than the output's grid is raised to half a step.
  Options tight = mazak_options();
  tight.tolerance_mm = 0.00001;
  EXPECT_DOUBLE_EQ(verify_cl(cl, p.output, tight, name).tolerance_mm, 0.00005);
  EXPECT_TRUE(verify_cl(cl, p.output, tight, name).ok());
}

TEST(VerifyPrograms, ClRapidWrittenAsFeedAndMissingMotionAreCaught) {
  const auto& posted = post_samples(".cls");
  ASSERT_FALSE(posted.empty());
  const auto& [name, p] = posted.front();
  const std::string cl = read(fs::path(VCPOST_SOURCE_DIR) / "samples" / name);
  // The first G0 block as G1: motion kind differs at that line.
  const auto g0 = p.output.find("\nG0 ");
  ASSERT_NE(g0, std::string::npos);
  std::string as_feed = p.output;
  as_feed[g0 + 2] = '1';
  const auto g0_line = static_cast<std::uint32_t>(
      std::count(p.output.begin(), p.output.begin() + static_cast<std::ptrdiff_t>(g0) + 1, '\n') +
      1);
  const Result r = verify_cl(cl, as_feed, mazak_options(), name);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.violations[0].code, Code::E7133);
  EXPECT_EQ(r.violations[0].line, g0_line);
  // The final retract (the last G0 block) removed: where the CL data
  // retract, the output stops the spindle.
  const auto last = p.output.rfind("\nG0 ");
  ASSERT_NE(last, std::string::npos);
  const auto next = p.output.find('\n', last + 1);
  const std::string shorter = p.output.substr(0, last) + p.output.substr(next);
  const auto last_line = static_cast<std::uint32_t>(
      std::count(p.output.begin(), p.output.begin() + static_cast<std::ptrdiff_t>(last) + 1, '\n') +
      1);
  const Result r2 = verify_cl(cl, shorter, mazak_options(), name);
  ASSERT_EQ(r2.violation_count, 1u);
  EXPECT_EQ(r2.violations[0].code, Code::E7131);
  EXPECT_EQ(r2.violations[0].line, last_line);  // the M5 block moved up into its place
}

// Shared CL programs written to G-code with the S and F they have: no
// change, every motion matches, arcs included; an arc centre moved by
// 0.001 mm is caught.
TEST(VerifyPrograms, SharedClProgramsWrittenByTheGcodeWriterVerify) {
  const fs::path dir = fs::path(VCPOST_SHARED_DATA_DIR) / "cldata";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "no shared data at " << dir;
  int with_arcs = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".md" || ext == ".stl" || ext == ".STL") continue;
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    const std::string cl = read(entry.path());
    std::ostringstream out;
    std::uint64_t arcs = 0;
    try {
      std::istringstream in(cl);
      cldata::ClReader reader(in, name);
      output::GcodeWriter writer(out, output::Format{});
      while (auto e = reader.next()) {
        arcs += std::holds_alternative<program::ArcFeed>(*e);
        writer.write(*e);
      }
      writer.finish();
    } catch (const std::exception& e) {
      std::printf("%s: not written (%s)\n", name.c_str(), e.what());
      continue;
    }
    Options options = mazak_options();
    options.output_feed_decimals = output::Format{}.feed_decimals;
    options.setups = true;  // Format{} writes a tilted frame as a set-up (boss.apt)
    const Result r = verify_cl(cl, out.str(), options, name);
    EXPECT_TRUE(r.ok()) << (r.violations.empty() ? "" : format(r.violations[0], "output"));
    EXPECT_TRUE(r.changes.empty());
    std::printf("%s: %llu motions (%llu arcs) match\n", name.c_str(),
                static_cast<unsigned long long>(r.motions), static_cast<unsigned long long>(arcs));
    if (arcs == 0) continue;
    ++with_arcs;
    if (vcpost::testing::kSanitized) continue;  // two more verifies of each program, as above
    // I of the first arc block by 0.001 mm: E7134 there; by 0.0001 mm: passes.
    const auto [far, line] = moved(out.str(), "I", 1, 0.001);
    ASSERT_GT(line, 0u);
    const Result bad = verify_cl(cl, far, options, name);
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.violations[0].code, Code::E7134) << format(bad.violations[0], "out");
    EXPECT_EQ(bad.violations[0].line, line);
    const auto [near, line2] = moved(out.str(), "I", 1, 0.0001);
    const Result good = verify_cl(cl, near, options, name);
    EXPECT_TRUE(good.ok()) << (good.violations.empty() ? "" : format(good.violations[0], "out"));
  }
  EXPECT_GE(with_arcs, 1);
}

}  // namespace
}  // namespace vcpost::verify
