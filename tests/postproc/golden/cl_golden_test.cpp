// Whole-program golden cases of CL -> G-code (tests/golden/README.md): each
// case holds a CL file of its own or names one of ../shared/data (skipped
// when that folder is absent); it is posted for every shipped
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

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "machines/builtin.h"
#include "postproc/cldata/cl_reader.h"
#include "postproc/output/event_writer.h"
#include "postproc/post/post_job.h"
#include "postproc/program/transcript.h"
#include "postproc/verify/verify.h"
#include "tests/postproc/cldata/cl_support.h"
#include "tests/postproc/golden/golden_support.h"

namespace vcpost {
namespace {

namespace fs = std::filesystem;

const fs::path golden_dir = fs::path(VCPOST_SOURCE_DIR) / "tests/golden";
const fs::path shared_dir = fs::path(VCPOST_SHARED_DATA_DIR);
using golden::read;
using golden::stored_program;
using golden::trimmed;

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
    const auto writer_of_profile = output::make_event_writer(out, profile);
    output::EventWriter& writer = *writer_of_profile;
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

// The first word of a line that grbl 1.1 refuses, empty when none: its
// gcode.c takes G0-G3, G4, G10, G17-G21, G28/G30(.1), G38.2-G38.5, G40,
// G43.1, G49, G53-G59, G61, G80, G90/G91(.1), G92(.1), G93/G94; M0-M5,
// M8, M9 (M7 only when built with it), M30; the letters F I J K L N P R S T
// X Y Z; comments in ( ). No '%' line (error 1: expected command letter).
std::string grbl_refusal(std::string_view line) {
  static const std::vector<double> g_codes = {
      0,  1,  2,  3,  4,  10, 17, 18, 19, 20, 21,   28,   30,   40,   49,   53,   54,   55,   56,
      57, 58, 59, 61, 80, 90, 91, 92, 93, 94, 28.1, 30.1, 38.2, 38.3, 38.4, 38.5, 43.1, 91.1, 92.1};
  static const std::vector<double> m_codes = {0, 1, 2, 3, 4, 5, 8, 9, 30};
  std::size_t i = 0;
  while (i < line.size()) {
    const char c = line[i];
    if (c == ' ' || c == '\r') {
      ++i;
    } else if (c == '(') {
      const std::size_t close = line.find(')', i);
      if (close == std::string_view::npos) return std::string(line.substr(i));
      i = close + 1;
    } else {
      std::size_t end = i + 1;
      while (end < line.size() && (std::isdigit(static_cast<unsigned char>(line[end])) ||
                                   line[end] == '.' || line[end] == '-'))
        ++end;
      const std::string word(line.substr(i, end - i));
      if (std::string("FGIJKLMNPRSTXYZ").find(c) == std::string::npos || end == i + 1) return word;
      const double value = std::stod(word.substr(1));
      const auto& codes = c == 'G' ? g_codes : m_codes;
      if ((c == 'G' || c == 'M') && std::none_of(codes.begin(), codes.end(), [&](double v) {
            return std::abs(v - value) < 1e-9;
          }))
        return word;
      i = end;
    }
  }
  return "";
}

TEST(GoldenCl, GrblRefusalFindsWhatGrblRefuses) {
  EXPECT_EQ(grbl_refusal("G43 H2 G0 X1. Y2."), "G43");
  EXPECT_EQ(grbl_refusal("T2 M6"), "M6");
  EXPECT_EQ(grbl_refusal("M7"), "M7");
  EXPECT_EQ(grbl_refusal("%"), "%");
  EXPECT_EQ(grbl_refusal("G81 X1. Y1. Z-1. R1."), "G81");
  EXPECT_EQ(grbl_refusal("(TOOL CHANGE: LOAD T2) T2 M0"), "");
  EXPECT_EQ(grbl_refusal("G21 G17 G40 G49 G80 G90 G94"), "");
  EXPECT_EQ(grbl_refusal("G1 X-1.5 Y2. Z-0.25 F1200 S9000 M3"), "");
}

TEST(GoldenCl, EveryCaseEqualsItsStoredResultVerifiesAndRunsInRs274) {
  const bool update = golden::updating();
  int cases = 0, written = 0, skipped = 0;
  for (const auto& entry : fs::directory_iterator(golden_dir)) {
    // A case's CL file is its own (input.cls), or the file of ../shared/data
    // that `input` names, read where it lies.
    const fs::path own = entry.path() / "input.cls";
    const bool has_own = fs::exists(own);
    if (!entry.is_directory() || (!has_own && !fs::exists(entry.path() / "input"))) continue;
    const std::string input = has_own ? "input.cls" : trimmed(read(entry.path() / "input"));
    if (!has_own && !fs::is_directory(shared_dir)) {
      ++skipped;
      continue;
    }
    const fs::path cl_path = has_own ? own : shared_dir / input;
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
      const bool klartext = profile.output_format() == machines::OutputFormat::heidenhain;
      const fs::path program_file = entry.path() / (profile_name + (klartext ? ".h" : ".nc"));
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
      // Klartext is read back by the Klartext reader: the same motion.
      const auto options = post::cl_output_verify_options(profile);
      const verify::Result v = klartext ? verify::verify_cl_klartext(text, p.program, options, name)
                                        : verify::verify_cl(text, p.program, options, name);
      EXPECT_TRUE(v.ok()) << (v.violations.empty() ? ""
                                                   : verify::format(v.violations[0], "output"));
      EXPECT_TRUE(v.changes.empty()) << "S/F values differ from the CL's";
      if (profile_name == "grbl") {  // every line in the words grbl takes
        std::istringstream lines(p.program);
        std::size_t number = 0;
        for (std::string line; std::getline(lines, line);) {
          ++number;
          EXPECT_EQ(grbl_refusal(line), "") << "line " << number << ": " << line;
        }
      }
      if (profile_name == "linuxcnc-3axis" && cldata::testing::have_rs274()) {
        expect_rs274_motion(p, entry.path().filename().string());
      }
    }
  }
  if (skipped > 0)
    std::printf("%d golden CL cases skipped: no shared data at %s\n", skipped, shared_dir.c_str());
  EXPECT_GE(cases, 3);
  EXPECT_GT(written, 0);
}

}  // namespace
}  // namespace vcpost
