// Every CL file of the shared corpus (../shared/data/cldata, see its
// PROVENANCE.md) is read, or refused with the documented code for a feature
// that cannot be converted soundly; a few records of each producer's files
// are checked against values worked out by hand from the file text.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>

#include "postproc/cldata/cl_reader.h"
#include "postproc/program/arc.h"

namespace vcpost::cldata {
namespace {

namespace fs = std::filesystem;
using namespace vcpost::program;

const fs::path data_dir = fs::path(VCPOST_SHARED_DATA_DIR) / "cldata";

bool is_cl_file(const fs::path& p) {
  const auto ext = p.extension().string();
  return ext == ".apt" || ext == ".cls" || ext == ".clsf" || ext == ".ncl";
}

struct Outcome {
  std::vector<Event> events;
  std::vector<ClCutter> cutters;
  std::vector<ClDiagnostic> warnings;
  std::optional<ClDiagnostic> error;
  std::string error_text;
};

Outcome read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  ClReader reader(in, path.filename().string());
  Outcome o;
  try {
    while (auto e = reader.next()) o.events.push_back(std::move(*e));
  } catch (const ClError& e) {
    o.error = e.diagnostic();
    o.error_text = e.what();
  }
  o.cutters = reader.cutters();
  o.warnings = reader.warnings();
  return o;
}

template <class T>
std::vector<T> only(const std::vector<Event>& events) {
  std::vector<T> out;
  for (const auto& e : events) {
    if (const auto* t = std::get_if<T>(&e)) out.push_back(*t);
  }
  return out;
}

#define SKIP_WITHOUT_DATA()                                                       \
  if (!fs::is_directory(data_dir)) {                                              \
    GTEST_SKIP() << "no CL corpus at " << data_dir << " (../shared/data absent)"; \
  }

TEST(ClRealFiles, EveryFileIsReadOrRefusedWithItsDocumentedCode) {
  SKIP_WITHOUT_DATA();
  // Documented refusals: multi-axis tool axes (E3108), at the first record
  // that needs them.
  const std::map<std::string, std::tuple<Code, unsigned, unsigned>> refused = {
      {"ust_a.cls", {Code::E3108, 11, 32}},
      {"ust_a2.cls", {Code::E3108, 11, 32}},
  };
  int files = 0;
  for (const auto& entry : fs::directory_iterator(data_dir)) {
    if (!is_cl_file(entry.path())) continue;
    ++files;
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    const Outcome o = read_file(entry.path());
    const auto it = refused.find(name);
    if (it == refused.end()) {
      EXPECT_FALSE(o.error) << o.error_text;
      ASSERT_FALSE(o.events.empty());
      EXPECT_TRUE(std::holds_alternative<ProgramEnd>(o.events.back()));
      for (const auto& w : o.warnings) {
        EXPECT_TRUE(w.code == Code::W3150 || w.code == Code::W3153) << format(w, name);
      }
    } else {
      ASSERT_TRUE(o.error) << "expected a refusal";
      EXPECT_EQ(o.error->code, std::get<0>(it->second)) << o.error_text;
      EXPECT_EQ(o.error->line, std::get<1>(it->second)) << o.error_text;
      EXPECT_EQ(o.error->column, std::get<2>(it->second)) << o.error_text;
    }
  }
  EXPECT_GE(files, 10);
}

// boss.apt's last four operations (from line 5551) cut the stock's +X face
// after CSYS/0,0,1.,0,1.,0,0,0,0,1.,0,0, each GOTO with the axis 1.,0,0:
// one WorkingFrame (the four CSYS are the same), and every GOTO of them,
// turned back out of the frame, is where the file writes it (a scan of the
// text, independent of the reader), with the frame's z along the tool.
TEST(ClRealFiles, BossTiltedSetUpIsOneFrameWithTheFilesPoints) {
  SKIP_WITHOUT_DATA();
  const Outcome o = read_file(data_dir / "boss.apt");
  ASSERT_FALSE(o.error) << o.error_text;
  std::vector<WorkingFrame> frames;
  for (const auto& e : o.events)
    if (const auto* f = std::get_if<WorkingFrame>(&e)) frames.push_back(*f);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].source.line, 5551u);
  EXPECT_EQ(frames[0].rotation.col(2), Eigen::Vector3d(1, 0, 0));
  std::map<std::uint32_t, Eigen::Vector3d> written;  // line -> the GOTO's x, y, z
  std::ifstream in(data_dir / "boss.apt", std::ios::binary);
  std::string line;
  for (std::uint32_t n = 1; std::getline(in, line); ++n) {
    if (n < 5551 || line.rfind("GOTO/", 0) != 0) continue;
    Eigen::Vector3d p;
    ASSERT_EQ(std::sscanf(line.c_str(), "GOTO/%lf,%lf,%lf", &p.x(), &p.y(), &p.z()), 3) << line;
    written[n] = p;
  }
  std::size_t compared = 0;
  for (const auto& e : o.events) {
    if (!is_motion(e)) continue;
    const auto at = written.find(source_of(e).line);
    if (at == written.end()) continue;
    Eigen::Vector3d end;
    if (const auto* t = std::get_if<StraightTraverse>(&e))
      end = t->end;
    else if (const auto* f = std::get_if<StraightFeed>(&e))
      end = f->end;
    else
      end = std::get<ArcFeed>(e).end;
    EXPECT_LT((frames[0].to_program(end) - at->second).norm(), 1e-12) << "line " << at->first;
    ++compared;
  }
  EXPECT_GT(compared, 3000u);
}

TEST(ClRealFiles, NxClsfBallFinishingWithNurbs) {
  SKIP_WITHOUT_DATA();
  const Outcome o = read_file(data_dir / "nurbs.clsf");
  ASSERT_FALSE(o.error) << o.error_text;
  ASSERT_EQ(o.cutters.size(), 1u);  // TLDATA/MILL,30.0000,15.0000,75.0000,0,0
  EXPECT_EQ(geometry::to_string(*o.cutters[0].tool), "ball:30");
  const auto traverses = only<StraightTraverse>(o.events);
  ASSERT_FALSE(traverses.empty());
  EXPECT_EQ(traverses[0].end, Eigen::Vector3d(-254.9773, 468.3788, 206.8429));
  EXPECT_EQ(traverses[0].source.line, 9u);
  const auto rates = only<SetFeedRate>(o.events);
  ASSERT_EQ(rates.size(), 1u);  // FEDRAT/MMPM,250 twice: one change
  EXPECT_DOUBLE_EQ(rates[0].rate, 250.0);
  // The first NURBS (line 13) starts at the GOTO of line 12 and ends on its
  // last CNTRL point (line 21); the next GOTO (line 23) is a line from there.
  const auto feeds = only<StraightFeed>(o.events);
  std::size_t first_nurbs = 0;
  while (feeds[first_nurbs].source.line != 13) ++first_nurbs;
  EXPECT_EQ(feeds[first_nurbs].start, Eigen::Vector3d(-254.9774, 466.5681, 206.8891));
  std::size_t last = first_nurbs;
  while (feeds[last + 1].source.line == 13) ++last;
  EXPECT_TRUE(feeds[last].end.isApprox(Eigen::Vector3d(-254.9779, 452.8642, 221.3100), 1e-12));
  EXPECT_EQ(feeds[last + 1].source.line, 23u);
  EXPECT_EQ(feeds[last + 1].end, Eigen::Vector3d(-254.9779, 452.7940, 223.3200));
}

TEST(ClRealFiles, NxClsfContourWithCircles) {
  SKIP_WITHOUT_DATA();
  const Outcome o = read_file(data_dir / "_1_KONTUR_NAR_40_N2.cls");
  ASSERT_FALSE(o.error) << o.error_text;
  EXPECT_EQ(geometry::to_string(*o.cutters.at(0).tool), "bull:40:1");
  const auto arcs = only<ArcFeed>(o.events);
  ASSERT_EQ(arcs.size(), 19u);
  // Line 21 CIRCLE about (0,0,-1), r 277, from (1563.1794,-107.5591) to
  // (1597.8754,-134.3323): counterclockwise by
  // atan2(-231.9996,-151.3446) - atan2(-205.2264,-186.0406) = 9.0744 deg.
  const ArcFeed& a = arcs[1];
  EXPECT_EQ(a.source.line, 22u);
  EXPECT_EQ(a.rotation, 1);
  EXPECT_NEAR(arc_sweep(a) * 180 / std::numbers::pi, 9.0744, 0.0001);
  EXPECT_EQ(a.centre.head<2>(), Eigen::Vector2d(1749.2200, 97.6673));
  for (const ArcFeed& arc : arcs) {
    EXPECT_LT(std::abs(arc_sweep(arc)), std::numbers::pi / 2 + 1e-3) << arc.source.line;
  }
  EXPECT_DOUBLE_EQ(only<SetFeedRate>(o.events).at(0).rate, 621.0);
}

TEST(ClRealFiles, SolidWorksAptPlate) {
  SKIP_WITHOUT_DATA();
  const Outcome o = read_file(data_dir / "basemach.apt");
  ASSERT_FALSE(o.error) << o.error_text;
  ASSERT_EQ(o.cutters.size(), 5u);
  EXPECT_FALSE(o.cutters[0].tool);  // CUTTER/4.,0,2.,1.201721,31.,0,83.: jobber drill
  EXPECT_EQ(geometry::to_string(*o.cutters[1].tool), "flat:5");
  const auto speeds = only<SetSpindleSpeed>(o.events);
  ASSERT_EQ(speeds.size(), 12u);
  EXPECT_DOUBLE_EQ(speeds[0].rpm, 3500);
  EXPECT_DOUBLE_EQ(speeds[1].rpm, 1104);
  EXPECT_EQ(speeds[1].source.line, 42u);
  EXPECT_EQ(only<ArcFeed>(o.events).size(), 369u);
  // Lines 52-54: GOTO/121.,39.25,-2.5, CIRCLE/121.,44.,-2.5,0,0,-1.,
  // GOTO/119.75,39.417424,-2.5: clockwise by 90 - 105.258 = -15.258 deg.
  const auto arcs = only<ArcFeed>(o.events);
  EXPECT_EQ(arcs[0].source.line, 54u);
  EXPECT_EQ(arcs[0].rotation, -1);
  EXPECT_NEAR(arc_sweep(arcs[0]) * 180 / std::numbers::pi, -15.258, 0.001);
  // The drilling cycle (lines 18-36): 16 holes, each fed from z 3 to -10 at
  // 275.59 mm/min.
  const auto feeds = only<StraightFeed>(o.events);
  EXPECT_EQ(feeds[0].start, Eigen::Vector3d(29.06066, 116.93934, 3));
  EXPECT_EQ(feeds[0].end, Eigen::Vector3d(29.06066, 116.93934, -10));
  EXPECT_EQ(feeds[15].end, Eigen::Vector3d(29.06066, 29.06066, -10));
  EXPECT_DOUBLE_EQ(only<SetFeedRate>(o.events).at(0).rate, 275.59);
}

TEST(ClRealFiles, SolidWorksAptBracket) {
  SKIP_WITHOUT_DATA();
  const Outcome o = read_file(data_dir / "Telemecanique-Tilt-Support2.apt");
  ASSERT_FALSE(o.error) << o.error_text;
  EXPECT_DOUBLE_EQ(only<SetSpindleSpeed>(o.events).at(0).rpm, 6556);
  EXPECT_EQ(only<ArcFeed>(o.events).size(), 42u);
  EXPECT_EQ(geometry::to_string(*o.cutters.at(0).tool), "flat:12");
  const auto rates = only<SetFeedRate>(o.events);
  EXPECT_DOUBLE_EQ(rates.at(0).rate, 183.202375);
  EXPECT_EQ(rates.at(0).source.line, 18u);
}

TEST(ClRealFiles, CreoNclInInches) {
  SKIP_WITHOUT_DATA();
  const Outcome gg = read_file(data_dir / "gg.ncl");
  ASSERT_FALSE(gg.error) << gg.error_text;
  ASSERT_EQ(gg.cutters.size(), 1u);  // from the comment `$$-> CUTTER / 0.375000`
  EXPECT_DOUBLE_EQ(gg.cutters[0].diameter(), 9.525);
  EXPECT_DOUBLE_EQ(only<SetSpindleSpeed>(gg.events).at(0).rpm, 2000);
  EXPECT_DOUBLE_EQ(only<SetFeedRate>(gg.events).at(0).rate, 127.0);  // 5 IPM
  EXPECT_EQ(only<ChangeTool>(gg.events).at(0).number, 8);
  const auto traverses = only<StraightTraverse>(gg.events);
  EXPECT_TRUE(traverses.at(0).end.isApprox(Eigen::Vector3d(188.722, 148.59, 95.885), 1e-12));
  // CIRCLE / 7.4550, 5.8500, 1.8000, $ 0,0,1, 0.025 then a three-point GOTO:
  // a full circle in three 120 deg arcs.
  const auto arcs = only<ArcFeed>(gg.events);
  ASSERT_EQ(arcs.size(), 6u);
  double sum = 0;
  for (int i = 0; i < 3; ++i) sum += arc_sweep(arcs[i]);
  EXPECT_NEAR(sum, 2 * std::numbers::pi, 1e-9);
  EXPECT_TRUE(arcs[1].end.isApprox(Eigen::Vector3d(7.4675, 5.8717, 1.8) * 25.4, 1e-12));
  EXPECT_EQ(arcs[1].source.line, 22u);
  EXPECT_EQ(arcs[1].source.column, 8u);

  const Outcome traj = read_file(data_dir / "traj1.ncl");
  ASSERT_FALSE(traj.error) << traj.error_text;
  const auto feeds = only<StraightFeed>(traj.events);
  ASSERT_EQ(feeds.size(), 18u * 3u);
  EXPECT_TRUE(feeds[0].end.isApprox(Eigen::Vector3d(4.6175, 7.6380, 1.9579) * 25.4, 1e-12));
  EXPECT_DOUBLE_EQ(only<SetFeedRate>(traj.events).at(0).rate, 254.0);
}

}  // namespace
}  // namespace vcpost::cldata
