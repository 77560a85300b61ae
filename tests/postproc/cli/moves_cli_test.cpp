// `vcpost moves` as a user runs it: on every bad-input file it exits non-zero
// (exit code 2) with "<file>:<line>:<col>: error[E....]" on stderr, or exits 0
// with the warning for warning files; a 10 MB line is refused the same way;
// --time prints the programmed time.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "../cli_run_support.h"

namespace {

namespace fs = std::filesystem;

using Outcome = vcpost::testing::CliOutcome;
using vcpost::testing::slurp;

class MovesCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vcpost_moves_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  Outcome run(const std::string& arguments) const {
    return vcpost::testing::run_vcpost("moves " + arguments, dir_);
  }

  fs::path dir_;
};

TEST_F(MovesCli, EveryBadFileGivesItsPositionedDiagnostic) {
  const fs::path bad = fs::path(VCPOST_SOURCE_DIR) / "tests/postproc/bad/gcode";
  static const std::regex expect_re(R"(\(expect ([EW]\d{4}) (\d+):(\d+) ([^)]*)\))");
  static const std::regex dialect_re(R"(\(dialect (\w+)\))");
  int errors = 0, warnings = 0;
  for (const auto& entry : fs::directory_iterator(bad)) {
    SCOPED_TRACE(entry.path().string());
    const std::string text = slurp(entry.path());
    std::smatch expect, dialect;
    ASSERT_TRUE(std::regex_search(text, expect, expect_re));
    // A speed output comes with a machine profile (`post`, `report`), which
    // `moves` does not read.
    if (text.find("(speed output E") != std::string::npos) continue;
    std::string arguments = "'" + entry.path().string() + "'";
    if (std::regex_search(text, dialect, dialect_re)) arguments += " --dialect " + dialect[1].str();
    const Outcome r = run(arguments);
    const bool error = expect[1].str()[0] == 'E';
    const std::string where = entry.path().string() + ":" + expect[2].str() + ":" +
                              expect[3].str() + ": " + (error ? "error[" : "warning[") +
                              expect[1].str() + "]: ";
    EXPECT_NE(r.err.find(where), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(expect[4].str()), std::string::npos) << r.err;
    if (error) {
      EXPECT_EQ(r.exit_code, 2) << r.err;
      ++errors;
    } else {
      EXPECT_EQ(r.exit_code, 0) << r.err;
      ++warnings;
    }
  }
  EXPECT_GE(errors, 35);
  EXPECT_GE(warnings, 3);
}

TEST_F(MovesCli, TenMegabyteLineIsRefusedWithItsPosition) {
  const fs::path file = dir_ / "long_line.ngc";
  {
    std::ofstream out(file, std::ios::binary);
    out << "G0 X1\nG1 X" << std::string(10u << 20, '1') << " F100\nM2\n";
  }
  const Outcome r = run("'" + file.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(file.string() +
                       ":2:1: error[E1006]: line longer than 65536 bytes, the reader's limit"),
            std::string::npos)
      << r.err;
  // The moves before the bad line are printed.
  EXPECT_EQ(r.out, "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n");
}

TEST_F(MovesCli, ProgramTime) {
  const fs::path file = dir_ / "timed.ngc";
  {
    std::ofstream out(file, std::ios::binary);
    // 10 mm rapid at 5000 mm/min = 0.12 s; 10 mm at 600 mm/min = 1 s; dwell 0.5 s.
    out << "G21 G90\nG0 Z10\nG1 Z0 F600\nG4 P0.5\nM2\n";
  }
  const Outcome r = run("--count --time --rapid-rate 5000 '" + file.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("# program time 1.6200 s (rapids at 5000 mm/min)"), std::string::npos)
      << r.out;
}

}  // namespace
