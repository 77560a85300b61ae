// The post job streams: its output does not depend on the number of
// threads, the points come in path order once, and it tells the caller when
// it is done with the text, in order, up to the end. The G-code written is
// the input with only S words changed whatever the chunking (programs much
// longer than a chunk of samples, with rapids and tool changes between
// chunks).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../dome_program_support.h"
#include "../temp_folder.h"
#include "machines/builtin.h"
#include "postproc/cli/program_text.h"
#include "postproc/post/post_job.h"

namespace vcpost::post {
namespace {

PostSettings settings_with(int threads) {
  PostSettings s;
  s.point.tool = geometry::Tool::ball(2 * testing::dome_ball_radius);
  s.point.ap = 0.3;
  s.point.vc = 150;
  s.threads = threads;
  return s;
}

struct JobRun {
  std::string output;
  PostSummary summary;
  std::vector<std::uint64_t> consumed;
  std::vector<PointRecord> points;
};

JobRun run(const std::string& program, int threads) {
  const auto model = testing::dome();
  JobRun r;
  r.summary = post_program(
      program, "dome.ngc", model, machines::builtin_profile("mazak-3axis"), settings_with(threads),
      [&](std::string_view bytes) { r.output.append(bytes); }, {},
      [&](const pipeline::PathSample&, const pipeline::PointResult&, const PointRecord& p) {
        r.points.push_back(p);
      },
      [&](std::uint64_t offset) { r.consumed.push_back(offset); });
  return r;
}

// A dense raster (about 25 000 samples: a dozen chunks), twice with a tool
// change between.
std::string long_program() {
  const std::string raster = testing::dome_raster(0.5, 0.1, 4000);
  return raster.substr(0, raster.rfind("M30")) + "T2 M6\n" + raster.substr(raster.find('\n') + 1);
}

TEST(PostStream, OutputDoesNotDependOnTheThreads) {
  const std::string program = long_program();
  const JobRun one = run(program, 1);
  const JobRun two = run(program, 2);
  const JobRun four = run(program, 4);
  ASSERT_GT(one.summary.samples, 20000u);
  EXPECT_EQ(one.output, two.output);
  EXPECT_EQ(one.output, four.output);
  EXPECT_EQ(one.summary.s_words, two.summary.s_words);
  EXPECT_EQ(one.summary.touching, two.summary.touching);
  ASSERT_TRUE(one.summary.after && two.summary.after);
  EXPECT_EQ(one.summary.after->mean, two.summary.after->mean);
  EXPECT_EQ(one.summary.after->within_5_percent, four.summary.after->within_5_percent);
  ASSERT_EQ(one.points.size(), two.points.size());
  for (std::size_t i = 0; i < one.points.size(); ++i) {
    EXPECT_EQ(one.points[i].s_after, two.points[i].s_after) << i;
  }
}

TEST(PostStream, PointsComeOnceInPathOrderWithTheirPlannedSpeed) {
  const JobRun r = run(long_program(), 2);
  ASSERT_EQ(r.points.size(), r.summary.samples);
  for (std::size_t i = 1; i < r.points.size(); ++i) {
    ASSERT_GE(r.points[i].time_s, r.points[i - 1].time_s) << i;
    ASSERT_GE(r.points[i].line, r.points[i - 1].line) << i;
  }
  // The S after of a point is the S the output has in effect on its line.
  std::istringstream out(r.output);
  std::vector<double> s_on_line{0};
  double s = 0;
  for (std::string line; std::getline(out, line);) {
    const auto at = line.find('S');
    if (at != std::string::npos) s = std::stod(line.substr(at + 1));
    s_on_line.push_back(s);
  }
  for (const auto& p : r.points) ASSERT_EQ(p.s_after, s_on_line.at(p.line)) << "line " << p.line;
}

TEST(PostStream, TextIsReleasedInOrderUpToTheEnd) {
  const std::string program = long_program();
  const JobRun r = run(program, 2);
  ASSERT_GT(r.consumed.size(), 5u);  // released as it goes, not once at the end
  for (std::size_t i = 1; i < r.consumed.size(); ++i) EXPECT_GT(r.consumed[i], r.consumed[i - 1]);
  EXPECT_EQ(r.consumed.back(), program.size());
  // Every offset but the last is a line start (whole blocks are written).
  for (std::size_t i = 0; i + 1 < r.consumed.size(); ++i) {
    EXPECT_EQ(program[r.consumed[i] - 1], '\n') << r.consumed[i];
  }
}

TEST(ProgramText, MappedFileStaysReadableAfterItsPagesAreReleased) {
  const testing::Folder dir;
  const auto path = dir / "program.nc";
  std::string text;
  for (int i = 0; i < 2'000'000; ++i) text += "G1 X" + std::to_string(i) + "\n";  // ~24 MB
  std::ofstream(path, std::ios::binary) << text;
  {
    cli::ProgramText program(path.string());
    ASSERT_EQ(program.view(), text);
    program.release_before(text.size() / 2);
    EXPECT_EQ(program.view(), text);  // released pages come back from the file
    program.release_before(text.size());
    EXPECT_EQ(program.view().substr(text.size() - 20), text.substr(text.size() - 20));
  }
  std::filesystem::remove(path);
}

TEST(ProgramText, FolderAndMissingFileAreErrors) {
  EXPECT_THROW(cli::ProgramText(std::filesystem::temp_directory_path().string()), std::exception);
  EXPECT_THROW(cli::ProgramText("/nonexistent/vcpost.nc"), std::exception);
}

}  // namespace
}  // namespace vcpost::post
