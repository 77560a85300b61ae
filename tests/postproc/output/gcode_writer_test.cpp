// CL data -> Mazak-like G-code: the format, and the motions rs274 reads back
// from the written program compared with the CL events.
#include "postproc/output/gcode_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "postproc/cldata/cl_reader.h"
#include "postproc/gcode/dialect.h"
#include "postproc/program/transcript.h"
#include "postproc/verify/verify.h"
#include "tests/postproc/cldata/cl_support.h"

namespace vcpost::output {
namespace {

namespace fs = std::filesystem;
using namespace vcpost::program;
using cldata::testing::Call;
using cldata::testing::motion_calls;
using cldata::testing::read_events;

std::string write_program(const std::vector<Event>& events, const Format& format) {
  std::ostringstream out;
  GcodeWriter writer(out, format);
  for (const auto& e : events) writer.write(e);
  writer.finish();
  return out.str();
}

TEST(GcodeWriter, SmallProgramInTheDefaultFormat) {
  const auto events = read_events(
      "PARTNO/BRACKET (A)\nLOADTL/3\nCOOLNT/FLOOD\nSPINDL/6556.4,RPM,CLW\nRAPID\n"
      "GOTO/-4.360504,-10.464015,25.\nRAPID\nGOTO/-4.360504,-10.464015,2.5\n"
      "FEDRAT/183.202375,MMPM\nGOTO/-4.360504,-10.464015,-6.\nGOTO/5,-10.464015,-6.\n"
      "CIRCLE/5,-5,-6,0,0,1,5.464015\nGOTO/10.464015,-5,-6\nSPINDL/OFF\nFINI\n");
  Format format;
  format.title = "bracket";
  const std::string expected =
      "%\n"
      "O1000(bracket)\n"
      "G21 G17 G40 G49 G80 G90 G94\n"
      "G54\n"
      "(PARTNO BRACKET [A])\n"
      "T3 M6\n"
      "M8\n"
      "S6556 M3\n"
      "G43 H3 G0 X-4.3605 Y-10.464 Z25.\n"
      "Z2.5\n"
      "G1 Z-6. F183.2\n"
      "X5.\n"
      "G3 X10.464 Y-5. I0. J5.464\n"
      "M5\n"
      "M30\n"
      "%\n";
  EXPECT_EQ(write_program(events, format), expected);
}

// A CL `$$` comment record is a comment of the program, where it stands.
TEST(GcodeWriter, ClCommentRecordsAreComments) {
  const auto events = read_events("$$ centerline data (NX)\nLOADTL/1\nGOTO/1,2,3\nFINI\n");
  Format format;
  format.program_number.reset();
  EXPECT_EQ(write_program(events, format),
            "%\n"
            "G21 G17 G40 G49 G80 G90 G94\n"
            "G54\n"
            "(centerline data [NX])\n"
            "T1 M6\n"
            "G43 H1\n"
            "G1 X1. Y2. Z3.\n"
            "M30\n"
            "%\n");
}

TEST(GcodeWriter, HighSpeedModeGeometryCompensationAndLineNumbers) {
  const auto events =
      read_events("LOADTL/1\nSPINDL/12000\nFEDRAT/1000\nGOTO/1,2,3\nDELAY/0.5\nFINI\n");
  Format format;
  format.high_speed_mode = true;
  format.geometry_compensation = true;
  format.line_numbers = true;
  format.percent_lines = false;
  format.program_number = 42;
  format.end_of_line.assign(2, '\r');  // CRLF (GCC 12 warns falsely on = "\r\n")
  format.end_of_line[1] = '\n';
  const std::string expected =
      "O42\r\n"
      "N10 G21 G17 G40 G49 G80 G90 G94\r\n"
      "N20 G54\r\n"
      "N30 G61.1\r\n"
      "N40 T1 M6\r\n"
      "N50 G05 P2\r\n"
      "N60 S12000 M3\r\n"
      "N70 G43 H1\r\n"
      "N80 G1 X1. Y2. Z3. F1000.\r\n"
      "N90 G4 X0.5\r\n"
      "N100 G05 P0\r\n"
      "N110 G64\r\n"
      "N120 M30\r\n";
  EXPECT_EQ(write_program(events, format), expected);
}

// The tool change as the profile says: a move up before it (G28 / G53),
// M6 or by hand (M5, a comment, T M0), with or without G43; the coolant
// codes of the profile. Expected programs written out by hand.
constexpr const char* kTwoTools =
    "LOADTL/1\nSPINDL/1000\nCOOLNT/MIST\nFEDRAT/500\nGOTO/1,2,3\nLOADTL/2\nSPINDL/2000\nGOTO/"
    "4,5,6\n"
    "COOLNT/OFF\nFINI\n";

TEST(GcodeWriter, ToolChangeWithTheMoveUpBeforeIt) {
  Format format;  // Mazak-like: O1000, '%'
  format.home_before_tool_change = machines::ToolChangeHome::g28;
  EXPECT_EQ(write_program(read_events(kTwoTools), format),
            "%\n"
            "O1000\n"
            "G21 G17 G40 G49 G80 G90 G94\n"
            "G54\n"
            "G91 G28 Z0.\n"
            "G90\n"
            "T1 M6\n"
            "S1000 M3\n"
            "M7\n"
            "G43 H1\n"
            "G1 X1. Y2. Z3. F500.\n"
            "G91 G28 Z0.\n"
            "G90\n"
            "T2 M6\n"
            "S2000 M3\n"
            "G43 H2\n"
            "G1 X4. Y5. Z6.\n"
            "M9\n"
            "M30\n"
            "%\n");
  format.home_before_tool_change = machines::ToolChangeHome::g53;
  const std::string g53 = write_program(read_events(kTwoTools), format);
  EXPECT_NE(g53.find("G1 X1. Y2. Z3. F500.\nG53 G0 Z0.\nT2 M6\n"), std::string::npos) << g53;
}

TEST(GcodeWriter, ToolChangeByHandWithoutG43AndPercent) {
  Format format;
  format.program_number.reset();
  format.percent_lines = false;
  format.manual_tool_change = true;
  format.tool_length_offset = false;
  format.coolant_mist = "M8";
  EXPECT_EQ(write_program(read_events(kTwoTools), format),
            "G21 G17 G40 G49 G80 G90 G94\n"
            "G54\n"
            "(TOOL CHANGE: LOAD T1, THEN CYCLE START)\n"
            "T1 M0\n"
            "S1000 M3\n"
            "M8\n"
            "G1 X1. Y2. Z3. F500.\n"
            "M5\n"
            "(TOOL CHANGE: LOAD T2, THEN CYCLE START)\n"
            "T2 M0\n"
            "S2000 M3\n"
            "G1 X4. Y5. Z6.\n"
            "M9\n"
            "M30\n");
}

// verify takes the move up right before a tool change, and the change by
// hand, as the CL's tool change; a move up elsewhere, or one that moves X
// or Y, is a difference.
TEST(GcodeWriter, VerifyTakesTheMoveUpAndTheChangeByHand) {
  Format format;
  format.home_before_tool_change = machines::ToolChangeHome::g28;
  const std::string homed = write_program(read_events(kTwoTools), format);
  verify::Options options;
  options.dialect = gcode::mazak_dialect();
  verify::Result v = verify::verify_cl(kTwoTools, homed, options, "two.cl");
  EXPECT_TRUE(v.ok()) << cldata::testing::first_violation(v);

  std::string stray = homed;  // a move up before a motion, not a tool change
  stray.replace(stray.find("G1 X4."), 0, "G91 G28 Z0.\nG90\n");
  EXPECT_FALSE(verify::verify_cl(kTwoTools, stray, options, "two.cl").ok());
  std::string sideways = homed;  // the move up also moves X
  sideways.replace(sideways.find("G91 G28 Z0.\nG90\nT2"), 11, "G91 G28 X0. Z0.");
  EXPECT_FALSE(verify::verify_cl(kTwoTools, sideways, options, "two.cl").ok());

  format = Format{};
  format.manual_tool_change = true;
  const std::string by_hand = write_program(read_events(kTwoTools), format);
  options.manual_tool_change = true;
  v = verify::verify_cl(kTwoTools, by_hand, options, "two.cl");
  EXPECT_TRUE(v.ok()) << cldata::testing::first_violation(v);
  EXPECT_TRUE(v.changes.empty());
  std::string no_stop = by_hand;  // the spindle still turns at the change
  no_stop.erase(no_stop.find("M5\n(TOOL"), 3);
  EXPECT_FALSE(verify::verify_cl(kTwoTools, no_stop, options, "two.cl").ok());
  std::string other_tool = by_hand;
  other_tool.replace(other_tool.find("T2 M0"), 2, "T3");
  EXPECT_FALSE(verify::verify_cl(kTwoTools, other_tool, options, "two.cl").ok());
}

TEST(GcodeWriter, ArcPlanesAndRefusals) {
  ArcFeed xz;
  xz.start = {5, 0, 0};
  xz.end = {0, 0, 5};
  xz.centre = {0, 0, 0};
  xz.plane = Plane::xz;
  xz.rotation = -1;
  std::ostringstream out;
  GcodeWriter writer(out, Format{});
  writer.write(xz);
  EXPECT_NE(out.str().find("G18 G2 X0. Y0. Z5. I-5. K0."), std::string::npos) << out.str();
  xz.rotation = 2;
  try {
    writer.write(xz);
    FAIL();
  } catch (const OutputError& e) {
    EXPECT_EQ(e.code(), Code::E3201);
  }
  EXPECT_THROW(writer.write(SetFeedRate{10, FeedMode::inverse_time, {}}), OutputError);
}

// --- rs274 comparison --------------------------------------------------------

const fs::path data_dir = fs::path(VCPOST_SHARED_DATA_DIR) / "cldata";

// The CL events as transcript calls; rs274's own SET_FEED_RATE(0) of the
// program start and end (G94, M30) are not in CL data.
void compare(const std::vector<Call>& cl, const std::vector<Call>& gcode, const Format& f) {
  const double position_tol = 1e-4 + 1e-9;
  const double feed_tol = 0.5 * std::pow(10.0, -f.feed_decimals) + 1e-9;
  ASSERT_EQ(cl.size(), gcode.size());
  for (std::size_t i = 0; i < cl.size(); ++i) {
    SCOPED_TRACE("call " + std::to_string(i) + " " + cl[i].name);
    ASSERT_EQ(cl[i].name, gcode[i].name);
    ASSERT_EQ(cl[i].args.size(), gcode[i].args.size());
    const double tol = cl[i].name == "SET_FEED_RATE"       ? feed_tol
                       : cl[i].name == "SET_SPINDLE_SPEED" ? 0.5 + 1e-9
                                                           : position_tol;
    for (std::size_t k = 0; k < cl[i].args.size(); ++k) {
      ASSERT_NEAR(cl[i].args[k], gcode[i].args[k], tol) << "argument " << k;
    }
  }
}

TEST(GcodeWriter, Rs274ReadsTheSameMotionsAsTheClData) {
  if (!cldata::testing::have_rs274()) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  if (!fs::is_directory(data_dir)) GTEST_SKIP() << "no CL corpus at " << data_dir;
  Format format;
  format.geometry_compensation = true;  // G61.1: rs274 takes it; G05 P2 it does not
  format.line_numbers = true;
  format.dwell = DwellWord::p_seconds;
  const fs::path tmp = fs::temp_directory_path() / ("vcpost_cl_rs274_" + std::to_string(getpid()));
  fs::create_directories(tmp);
  int compared = 0;
  for (const char* name : {"gg.ncl", "traj1.ncl", "_1_KONTUR_NAR_40_N2.cls", "nurbs.clsf",
                           "basemach.apt", "Telemecanique-Tilt-Support2.apt"}) {
    SCOPED_TRACE(name);
    std::ifstream in(data_dir / name, std::ios::binary);
    cldata::ClReader reader(in, name);
    std::string transcript;
    const fs::path nc = tmp / (std::string(name) + ".nc");
    {
      std::ofstream out(nc, std::ios::binary);
      GcodeWriter writer(out, format);
      while (auto e = reader.next()) {
        append_transcript(transcript, *e);
        writer.write(*e);
      }
      writer.finish();
    }
    const auto rs274 = cldata::testing::run_rs274(nc.string());
    ASSERT_TRUE(rs274);
    std::vector<Call> gcode_calls;
    for (auto& c : motion_calls(*rs274)) {
      if (c.name == "SET_FEED_RATE" && c.args.at(0) == 0.0) continue;
      gcode_calls.push_back(std::move(c));
    }
    const auto cl_calls = motion_calls(transcript);
    EXPECT_GT(cl_calls.size(), 10u);
    compare(cl_calls, gcode_calls, format);
    ++compared;
  }
  fs::remove_all(tmp);
  EXPECT_EQ(compared, 6);
}

}  // namespace
}  // namespace vcpost::output
