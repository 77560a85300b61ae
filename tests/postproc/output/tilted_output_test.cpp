// Tilted working planes written from CL data (output.tilted_plane): the
// G68.2 and PLANE SPATIAL blocks of a frame worked out by hand, and for a
// compound tilt each way read back by vcpost's own readers: every point
// must lie where the CL puts it on the part (G68.2, PLANE SPATIAL: R p + t
// of the frame read; setup: the frame's own coordinates R^T (p - t)).
// Tolerance 5e-4 mm: half a step of the 4-decimal output plus the angles'
// rounding to 0.0001 deg (1.7e-4 mm at 100 mm).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "postproc/gcode/dialect.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/heidenhain/interpreter.h"
#include "postproc/output/event_writer.h"
#include "postproc/output/gcode_writer.h"
#include "postproc/output/klartext_writer.h"
#include "postproc/program/working_frame.h"
#include "postproc/verify/verify.h"
#include "tests/postproc/cldata/cl_support.h"

namespace vcpost::output {
namespace {

using cldata::testing::read_events;
using machines::TiltedPlane;
using program::Event;
using program::WorkingFrame;

constexpr double kTolerance = 5e-4;

std::string gcode_of(const std::string& cl, TiltedPlane tilted, int decimals = 4) {
  Format format;
  format.tilted_plane = tilted;
  format.decimals = decimals;
  format.program_number.reset();
  std::ostringstream out;
  GcodeWriter writer(out, format);
  for (const auto& e : read_events(cl)) writer.write(e);
  writer.finish();
  return out.str();
}

std::string klartext_of(const std::string& cl, TiltedPlane tilted) {
  KlartextFormat format;
  format.tilted_plane = tilted;
  std::ostringstream out;
  KlartextWriter writer(out, format);
  for (const auto& e : read_events(cl)) writer.write(e);
  writer.finish();
  return out.str();
}

// The motions' ends: as given (in their frame) and on the part (R p + t).
struct Ends {
  std::vector<Eigen::Vector3d> given, on_part;
};

void collect(const std::vector<Event>& events, WorkingFrame& frame, Ends& ends) {
  for (const auto& e : events) {
    if (const auto* f = std::get_if<WorkingFrame>(&e)) frame = *f;
    if (!program::is_motion(e)) continue;
    const Eigen::Vector3d end = std::holds_alternative<program::StraightTraverse>(e)
                                    ? std::get<program::StraightTraverse>(e).end
                                : std::holds_alternative<program::StraightFeed>(e)
                                    ? std::get<program::StraightFeed>(e).end
                                    : std::get<program::ArcFeed>(e).end;
    ends.given.push_back(end);
    ends.on_part.push_back(frame.to_program(end));
  }
}

Ends cl_ends(const std::string& cl) {
  Ends ends;
  WorkingFrame frame;
  collect(read_events(cl), frame, ends);
  return ends;
}

Ends gcode_ends(const std::string& text, gcode::Dialect dialect) {
  gcode::Interpreter interpreter(text, dialect);
  Ends ends;
  WorkingFrame frame;
  std::vector<Event> events;
  while (interpreter.next(events)) {
    collect(events, frame, ends);
    events.clear();
  }
  return ends;
}

Ends klartext_ends(const std::string& text) {
  heidenhain::Interpreter interpreter(text);
  Ends ends;
  WorkingFrame frame;
  std::vector<Event> events;
  while (interpreter.next(events)) {
    collect(events, frame, ends);
    events.clear();
  }
  return ends;
}

void expect_same(const std::vector<Eigen::Vector3d>& want,
                 const std::vector<Eigen::Vector3d>& got) {
  ASSERT_EQ(want.size(), got.size());
  for (std::size_t i = 0; i < want.size(); ++i)
    EXPECT_LT((want[i] - got[i]).cwiseAbs().maxCoeff(), kTolerance)
        << "motion " << i << ": " << got[i].transpose() << " vs " << want[i].transpose();
}

// A CL program that tilts to `r` about `t` (CSYS row by row), its points and
// tool axes in the base frame as SolidWorks CAM writes them, then back.
std::string tilted_cl(const Eigen::Matrix3d& r, const Eigen::Vector3d& t) {
  std::string cl = "LOADTL/1\nSPINDL/5000,RPM,CLW\nRAPID\nGOTO/0,0,100\nCSYS/";
  char buffer[64];
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      std::snprintf(buffer, sizeof buffer, "%.12f,", r(row, col));
      cl += buffer;
    }
    std::snprintf(buffer, sizeof buffer, "%.6f%s", t[row], row < 2 ? "," : "\n");
    cl += buffer;
  }
  const Eigen::Vector3d z = r.col(2);
  // Points of the frame (x, y, height above its plane) placed on the part.
  const double frame_points[][3] = {{0, 0, 60},     {10, 5, 2},     {10, 5, -1}, {40, 5, -1},
                                    {40, 25, -1.5}, {10, 25, -1.5}, {10, 25, 30}};
  for (int k = 0; k < 7; ++k) {
    const Eigen::Vector3d p =
        r * Eigen::Vector3d(frame_points[k][0], frame_points[k][1], frame_points[k][2]) + t;
    if (k == 0 || k == 1 || k == 6) cl += "RAPID\n";
    if (k == 2) cl += "FEDRAT/800,MMPM\n";
    std::snprintf(buffer, sizeof buffer, "GOTO/%.6f,%.6f,%.6f,", p.x(), p.y(), p.z());
    cl += buffer;
    std::snprintf(buffer, sizeof buffer, "%.12f,%.12f,%.12f\n", z.x(), z.y(), z.z());
    cl += buffer;
  }
  cl += "CSYS/1,0,0,0,0,1,0,0,0,0,1,0\nRAPID\nGOTO/0,0,100\nSPINDL/OFF\nFINI\n";
  return cl;
}

// boss.apt's frame (z = +X, x = +Y) moved to (10, 20, 30): x = (0,1,0), y =
// (0,0,1), z = (1,0,0) is Rz(90) Rx(90) Rz(0) (Euler Z-X'-Z'' 90, 90, 0)
// and Rz(90) Ry(0) Rx(90) (SPA90 SPB0 SPC90, as the shop's DMU programs
// write the +X face). Klartext writes c + R^T t: R^T (10, 20, 30) = (20,
// 30, 10) added to the frame's points.
TEST(TiltedOutput, TheBossFrameByHand) {
  const std::string cl =
      "LOADTL/1\nSPINDL/5000,RPM,CLW\nCSYS/0,0,1.,10,1.,0,0,20,0,1.,0,30\nRAPID\n"
      "GOTO/130.,24.,-20.,1.,0,0\nFEDRAT/500,MMPM\nGOTO/100.,24.,-20.,1.,0,0\n"
      "CSYS/1.,0,0,0,0,1.,0,0,0,0,1.,0\nRAPID\nGOTO/0,0,100\nFINI\n";
  const std::string g = gcode_of(cl, TiltedPlane::g68_2);
  EXPECT_NE(g.find("M3\nG68.2 X10. Y20. Z30. I90. J90. K0.\nG53.1\nG43 H1 G0 X4. Y-50. Z120.\n"
                   "G1 Z90. F500.\nG69\nG0 X0. Y0. Z100.\n"),
            std::string::npos)
      << g;
  const std::string k = klartext_of(cl, TiltedPlane::plane_spatial);
  EXPECT_NE(k.find("PLANE SPATIAL SPA+90 SPB+0 SPC+90 STAY\n4 L A+Q120 C+Q122 R0 FMAX\n"
                   "5 L X+24 Y-20 Z+130 R0 FMAX\n6 L Z+100 F500\n7 PLANE RESET STAY\n"
                   "8 L X+0 Y+0 Z+100 R0 FMAX\n"),
            std::string::npos)
      << k;
  const std::string s = gcode_of(cl, TiltedPlane::setup);
  EXPECT_NE(s.find("M5\n(SET-UP 2: CLAMP THE PART WITH ITS DIRECTION [1, 0, 0] UP THE SPINDLE [+Z] "
                   "AND ITS [0, 1, 0] ALONG +X, SET G55 ON ITS POINT [10, 20, 30], THEN CYCLE "
                   "START)\nM0\nG55\nM3\nG43 H1 G0 X4. Y-50. Z120.\n"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("(SET-UP 1: CLAMP THE PART AS AT THE START [ITS +Z UP, ITS +X ALONG +X], SET "
                   "G54 ON ITS POINT [0, 0, 0], THEN CYCLE START)\nM0\nG54\nM3\n"),
            std::string::npos)
      << s;
}

TEST(TiltedOutput, ACompoundTiltReadsBackWhereTheClPutsIt) {
  for (const auto& angles : {Eigen::Vector3d(30, 40, -50), Eigen::Vector3d(0, 90, 0),
                             Eigen::Vector3d(-120, 135, 10), Eigen::Vector3d(90, 90, 90)}) {
    SCOPED_TRACE(angles.transpose());
    const Eigen::Matrix3d r = program::euler_zxz(angles.x(), angles.y(), angles.z());
    const Eigen::Vector3d t(12.5, -7.25, 3);
    const std::string cl = tilted_cl(r, t);
    const Ends want = cl_ends(cl);
    expect_same(want.on_part,
                gcode_ends(gcode_of(cl, TiltedPlane::g68_2), gcode::fanuc_dialect()).on_part);
    expect_same(want.on_part, klartext_ends(klartext_of(cl, TiltedPlane::plane_spatial)).on_part);
    // A set-up: the points in the frame's own coordinates, no frame read.
    const Ends setup = gcode_ends(gcode_of(cl, TiltedPlane::setup), gcode::rs274ngc_dialect());
    expect_same(want.given, setup.given);
    expect_same(setup.given, setup.on_part);
    // And vcpost verify holds each way (the G-code as the fanuc reader
    // reads it, the set-up as rs274ngc).
    verify::Options options;
    options.dialect = gcode::fanuc_dialect();
    EXPECT_EQ(cldata::testing::first_violation(
                  verify::verify_cl(cl, gcode_of(cl, TiltedPlane::g68_2), options, "t.cl")),
              "");
    EXPECT_EQ(cldata::testing::first_violation(verify::verify_cl_klartext(
                  cl, klartext_of(cl, TiltedPlane::plane_spatial), options, "t.cl")),
              "");
    options.dialect = gcode::rs274ngc_dialect();
    options.setups = true;
    EXPECT_EQ(cldata::testing::first_violation(
                  verify::verify_cl(cl, gcode_of(cl, TiltedPlane::setup), options, "t.cl")),
              "");
  }
}

// A frame turned by 1 degree more than the CL's is named (E7143), once.
TEST(TiltedOutput, VerifyNamesAnotherFrame) {
  const Eigen::Matrix3d r = program::euler_zxz(30, 40, -50);
  const std::string cl = tilted_cl(r, Eigen::Vector3d::Zero());
  std::string g = gcode_of(cl, TiltedPlane::g68_2);
  const auto at = g.find(" J40.");
  ASSERT_NE(at, std::string::npos) << g;
  g.replace(at, 5, " J41.");
  verify::Options options;
  options.dialect = gcode::fanuc_dialect();
  const verify::Result result = verify::verify_cl(cl, g, options, "t.cl");
  ASSERT_FALSE(result.violations.empty());
  EXPECT_EQ(result.violations.front().code, vcpost::Code::E7143);
  const auto frames =
      std::count_if(result.violations.begin(), result.violations.end(),
                    [](const verify::Violation& v) { return v.code == vcpost::Code::E7143; });
  EXPECT_EQ(frames, 1);
}

// Six frames take G54..G59; a seventh has no work offset left (E3205).
TEST(TiltedOutput, SetUpsBeyondG59AreRefused) {
  std::string cl = "LOADTL/1\n";
  for (int k = 1; k <= 6; ++k) {
    const Eigen::Matrix3d r = program::turn_about(0, 10.0 * k);
    char buffer[200];
    std::snprintf(buffer, sizeof buffer,
                  "CSYS/1,0,0,0,0,%.12f,%.12f,0,0,%.12f,%.12f,0\nRAPID\nGOTO/0,%.12f,%.12f,%.12f,"
                  "%.12f,%.12f\n",
                  r(1, 1), r(1, 2), r(2, 1), r(2, 2), 50 * r(1, 2), 50 * r(2, 2), 0.0, r(1, 2),
                  r(2, 2));
    cl += buffer;
  }
  cl += "FINI\n";
  try {
    gcode_of(cl, TiltedPlane::setup);
    FAIL() << "no error";
  } catch (const OutputError& e) {
    EXPECT_EQ(e.code(), Code::E3205);
    EXPECT_NE(std::string(e.what()).find("set-up 7 needs work offset G60"), std::string::npos)
        << e.what();
  }
  // Five tilted frames (set-ups 2..6) fit: G55..G59.
  const std::string five = cl.substr(0, cl.rfind("CSYS")) + "FINI\n";
  const std::string g = gcode_of(five, TiltedPlane::setup);
  EXPECT_NE(g.find("\nG59\n"), std::string::npos);
}

// The bad-input files of the writers (tests/postproc/bad/output): each CL
// file's first line says what posting it for the profile named gives.
TEST(TiltedOutput, BadFilesGiveTheirDiagnostic) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "tests/postproc/bad/output";
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".cl") continue;
    ++files;
    SCOPED_TRACE(entry.path().filename().string());
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    const std::string all = text.str();
    const std::string prefix = "$$ expect: ";
    ASSERT_EQ(all.rfind(prefix, 0), 0u);
    const std::string expected = all.substr(prefix.size(), all.find('\n') - prefix.size());
    try {
      gcode_of(all, TiltedPlane::setup);
      ADD_FAILURE() << "no error";
    } catch (const OutputError& e) {
      EXPECT_EQ(std::string(e.what()), expected);
    }
  }
  EXPECT_GE(files, 1);
}

// The angles read back: euler_zxz_of and spatial_angles_of give angles
// whose rotation is the one given (1e-12), also where the outer turns share
// an axis.
TEST(TiltedOutput, AnglesOfARotation) {
  for (int ia = 0; ia < 10; ++ia) {
    for (int ib = 0; ib <= 8; ++ib) {
      for (int ic = 0; ic < 7; ++ic) {
        const double a = -170 + 37 * ia, b = 22.5 * ib, c = -180 + 53 * ic;
        const Eigen::Matrix3d r = program::euler_zxz(a, b, c);
        const Eigen::Vector3d e = program::euler_zxz_of(r);
        EXPECT_LT((program::euler_zxz(e.x(), e.y(), e.z()) - r).cwiseAbs().maxCoeff(), 1e-12)
            << a << " " << b << " " << c;
        const Eigen::Vector3d s = program::spatial_angles_of(r);
        EXPECT_LT((program::spatial_angles(s.x(), s.y(), s.z()) - r).cwiseAbs().maxCoeff(), 1e-12)
            << a << " " << b << " " << c;
      }
    }
  }
  const Eigen::Vector3d gimbal = program::spatial_angles_of(program::spatial_angles(30, 90, 20));
  EXPECT_NEAR(gimbal.y(), 90, 1e-12);
  EXPECT_EQ(gimbal.x(), 0.0);
}

}  // namespace
}  // namespace vcpost::output

namespace vcpost::verify {
namespace {

// G-code in, G-code out: the tilt blocks are the input's (a post changes
// only S and F); an output whose G68.2 or CYCLE800 turns by one degree more
// is named: a changed word (E7103) or event (E7121); verify's lexer takes
// a Sinumerik call's ( ) as a comment, so CYCLE800's changed argument is
// named as a changed comment (E7107).
TEST(TiltedVerify, AnotherTiltInTheOutputIsNamed) {
  const std::string fanuc =
      "G21 G90 G17\nS5000 M3\nG0 X0 Y0 Z100.\nG68.2 X10. Y0 Z0 I0 J30. K0\nG53.1\n"
      "G0 X5. Y5. Z20.\nG1 Z0 F500\nG69\nM30\n";
  const std::string sinumerik =
      "G71 G90 G17\nS5000 M3\nG0 X0 Y0 Z100\nCYCLE800(1,\"TC1\",0,57,10,0,0,30,0,0,0,0,0,1)\n"
      "G0 X5 Y5 Z20\nG1 Z0 F500\nCYCLE800()\nM30\n";
  struct Case {
    std::string text, from, to;
    gcode::Dialect dialect;
  };
  for (const Case& c :
       {Case{fanuc, "J30.", "J31.", gcode::fanuc_dialect()},
        Case{sinumerik, "57,10,0,0,30", "57,10,0,0,31", gcode::sinumerik_dialect()}}) {
    SCOPED_TRACE(c.text);
    Options options;
    options.dialect = c.dialect;
    std::string faster = c.text;
    faster.replace(faster.find("S5000"), 5, "S5200");
    EXPECT_TRUE(verify_gcode(c.text, faster, options).ok());
    std::string turned = c.text;
    turned.replace(turned.find(c.from), c.from.size(), c.to);
    const Result r = verify_gcode(c.text, turned, options);
    ASSERT_FALSE(r.ok());
    const bool named = std::any_of(r.violations.begin(), r.violations.end(), [](const auto& v) {
      return v.code == Code::E7121 || v.code == Code::E7103 || v.code == Code::E7107;
    });
    EXPECT_TRUE(named) << format(r.violations.front(), "out");
  }
}

}  // namespace
}  // namespace vcpost::verify
