// Whole-program golden cases of CL -> G-code (tests/golden/README.md): each
// case names a CL file of ../shared/data; it is posted for every shipped
// profile and the result (exit status, diagnostic, program) must equal the
// stored one byte for byte. Every program that is written must also pass
// `vcpost verify` against its CL data, and the linuxcnc-3axis program must
// move in rs274 as the CL data do (cycles compared as rs274 reads the
// expanded moves).
//
// VCPOST_GOLDEN_UPDATE=1 rewrites the expected files from what vcpost
// writes now (review the diff before committing it).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "machines/builtin.h"
#include "postproc/cldata/cl_reader.h"
#include "postproc/output/gcode_writer.h"
#include "postproc/post/post_job.h"
#include "postproc/program/transcript.h"
#include "postproc/verify/verify.h"
#include "tests/postproc/cldata/cl_support.h"

namespace vcpost {
namespace {

namespace fs = std::filesystem;

const fs::path golden_dir = fs::path(VCPOST_SOURCE_DIR) / "tests/golden";
const fs::path shared_dir = fs::path(VCPOST_SHARED_DATA_DIR);
constexpr std::size_t whole_program_lines = 150;  // longer programs: digest, head and tail
constexpr std::size_t head_tail_lines = 25;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

// FNV-1a, 64 bits: a stable digest with no dependency.
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

// The stored form of a program: whole when short, else its size, digest,
// first and last lines.
std::string stored_program(const std::string& program) {
  const auto lines = lines_of(program);
  if (lines.size() <= whole_program_lines) return program;
  std::string out = "lines " + std::to_string(lines.size()) + " bytes " +
                    std::to_string(program.size()) + " fnv1a64 " + digest(program) + "\n";
  out += "-- head\n";
  for (std::size_t i = 0; i < head_tail_lines; ++i) out += lines[i];
  out += "-- tail\n";
  for (std::size_t i = lines.size() - head_tail_lines; i < lines.size(); ++i) out += lines[i];
  return out;
}

struct Posted {
  int exit_code = 0;    // as `vcpost` would end: 0 written, 2 refused input
  std::string message;  // the diagnostic of a refusal
  std::string program;  // empty when refused
  std::vector<std::string> warnings;
  std::string cl_transcript;
};

Posted post_cl(const std::string& text, const std::string& name,
               const machines::MachineProfile& profile) {
  Posted p;
  std::istringstream in(text);
  std::ostringstream out;
  try {
    cldata::ClReader reader(in, name);
    output::GcodeWriter writer(out, output::format_for(profile));
    while (auto e = reader.next()) {
      writer.write(*e);
      program::append_transcript(p.cl_transcript, *e);
    }
    writer.finish();
    for (const auto& w : reader.warnings()) p.warnings.push_back(cldata::format(w, name));
    p.program = out.str();
  } catch (const cldata::ClError& e) {
    p.exit_code = 2;
    p.message = e.what();
  } catch (const output::OutputError& e) {
    p.exit_code = 2;
    p.message = e.what();
  }
  return p;
}

std::string result_text(const Posted& p) {
  std::string out = "exit " + std::to_string(p.exit_code) + "\n";
  if (!p.message.empty()) out += "error " + p.message + "\n";
  for (const auto& w : p.warnings) out += "warning " + w + "\n";
  return out;
}

// rs274's motion of the written program vs the CL events, call by call.
void expect_rs274_motion(const Posted& p, const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("vcpost_golden_" + std::to_string(getpid()) + "_" + name);
  fs::create_directories(dir);
  const fs::path nc = dir / "program.ngc";
  std::ofstream(nc, std::ios::binary) << p.program;
  const auto rs274 = cldata::testing::run_rs274(nc.string());
  fs::remove_all(dir);
  ASSERT_TRUE(rs274);
  std::vector<cldata::testing::Call> got;
  for (auto& c : cldata::testing::motion_calls(*rs274)) {
    // rs274's own calls of the program start and end (G94, M30), and the
    // speeds and feeds S and F: only the motion is compared here.
    if (c.name == "SET_FEED_RATE" || c.name == "SET_SPINDLE_SPEED") continue;
    got.push_back(std::move(c));
  }
  std::vector<cldata::testing::Call> want;
  for (auto& c : cldata::testing::motion_calls(p.cl_transcript)) {
    if (c.name == "SET_FEED_RATE" || c.name == "SET_SPINDLE_SPEED") continue;
    want.push_back(std::move(c));
  }
  ASSERT_EQ(want.size(), got.size()) << "rs274 output:\n" << rs274->substr(0, 2000);
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(want[i].name, got[i].name) << "call " << i;
    ASSERT_EQ(want[i].args.size(), got[i].args.size()) << "call " << i;
    for (std::size_t k = 0; k < want[i].args.size(); ++k) {
      ASSERT_NEAR(want[i].args[k], got[i].args[k], 1e-4 + 1e-9)
          << "call " << i << " " << want[i].name << " argument " << k;
    }
  }
}

TEST(GoldenCl, EveryCaseEqualsItsStoredResultVerifiesAndRunsInRs274) {
  if (!fs::is_directory(shared_dir)) GTEST_SKIP() << "no shared data at " << shared_dir;
  const bool update = std::getenv("VCPOST_GOLDEN_UPDATE") != nullptr;
  int cases = 0, written = 0;
  for (const auto& entry : fs::directory_iterator(golden_dir)) {
    if (!entry.is_directory() || !fs::exists(entry.path() / "input")) continue;
    const std::string input = trimmed(read(entry.path() / "input"));
    const fs::path cl_path = shared_dir / input;
    const std::string name = cl_path.filename().string();
    SCOPED_TRACE(entry.path().filename().string() + " (" + input + ")");
    ASSERT_TRUE(fs::exists(cl_path)) << cl_path;
    const std::string text = read(cl_path);
    ++cases;
    for (const auto& builtin : machines::builtin_profiles()) {
      const std::string profile_name(builtin.name);
      SCOPED_TRACE(profile_name);
      const machines::MachineProfile profile = machines::builtin_profile(profile_name);
      const Posted p = post_cl(text, name, profile);
      const fs::path result_file = entry.path() / (profile_name + ".result");
      const fs::path program_file = entry.path() / (profile_name + ".nc");
      const std::string result = result_text(p);
      const std::string program = p.program.empty() ? "" : stored_program(p.program);
      if (update) {
        std::ofstream(result_file, std::ios::binary) << result;
        if (program.empty())
          fs::remove(program_file);
        else
          std::ofstream(program_file, std::ios::binary) << program;
      }
      EXPECT_EQ(read(result_file), result);
      EXPECT_EQ(fs::exists(program_file) ? read(program_file) : "", program);
      if (p.exit_code != 0) continue;
      ++written;
      verify::Options options;
      options.dialect = post::output_dialect_of(profile);
      options.output_decimals = profile.output().decimals;
      options.output_feed_decimals = profile.output().feed_decimals;
      options.cutter_compensation = profile.output().cutter_compensation;
      const verify::Result v = verify::verify_cl(text, p.program, options, name);
      EXPECT_TRUE(v.ok()) << (v.violations.empty() ? ""
                                                   : verify::format(v.violations[0], "output"));
      EXPECT_TRUE(v.changes.empty()) << "S/F values differ from the CL's";
      if (profile_name == "linuxcnc-3axis" && cldata::testing::have_rs274()) {
        expect_rs274_motion(p, entry.path().filename().string());
      }
    }
  }
  EXPECT_GE(cases, 14);
  EXPECT_GT(written, 0);
}

}  // namespace
}  // namespace vcpost
