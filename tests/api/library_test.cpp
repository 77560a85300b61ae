// The public library libvcpost (include/vcpost/), linked as a program of
// its own links it: the shared library, through its public headers only.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <optional>
#include <string>

#include "vcpost/post.h"
#include "vcpost/version.h"

namespace {

namespace api = vcpost::api;
namespace fs = std::filesystem;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

fs::path samples() { return fs::path(VCPOST_SOURCE_DIR) / "samples"; }

// `vcpost ARGUMENTS` in a fresh folder; its standard output.
std::string run_vcpost(const std::string& arguments, int& exit_code) {
  const fs::path folder =
      fs::temp_directory_path() / ("vcpost_library_test_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const std::string command = "cd '" + folder.string() + "' && '" + VCPOST_BINARY + "' " +
                              arguments + " > out.txt 2> /dev/null < /dev/null";
  const int status = std::system(command.c_str());
  exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::string out = slurp(folder / "out.txt");
  fs::remove_all(folder);
  return out;
}

TEST(Library, PostsAProgramByteForByteAsTheCommandDoes) {
  const fs::path program = samples() / "wavy_raster_a0_ae2.nc";
  const fs::path model = samples() / "wavy.step";
  int exit_code = -1;
  const std::string expected =
      run_vcpost("post '" + program.string() + "' --model '" + model.string() +
                     "' --tool ball:10 --vc 120 --ap 0.3 --machine mazak-3axis -q -o -",
                 exit_code);
  ASSERT_EQ(exit_code, 0);
  ASSERT_FALSE(expected.empty());

  api::PostOptions options;
  options.tool = "ball:10";
  options.vc = 120;
  options.ap = 0.3;
  options.keep_points = true;
  const api::PostResult result =
      api::post(slurp(program), program.string(), api::Model::load(model.string()),
                api::MachineProfile::load("mazak-3axis"), options);
  EXPECT_EQ(result.program, expected);
  EXPECT_EQ(result.summary.kind, "gcode");
  EXPECT_GT(result.summary.s_words, 0u);
  EXPECT_EQ(result.points.size(), result.summary.points);
  EXPECT_EQ(result.summary.touching + result.summary.lifted + result.summary.gouging +
                result.summary.missed,
            result.summary.points);
  ASSERT_TRUE(result.summary.vc_after.has_value());
  // The plan keeps vc at or under nominal (120 m/min) wherever it can.
  EXPECT_LE(result.summary.vc_after->mean, 120.0 + 1e-9);
}

TEST(Library, WorkingDiameterOfThePapersCase) {
  // `vcpost deff --tool ball:10 --ap 0.3 --ae 0.5 --tilt 25 --azimuth 35
  // --feed-angle 90 --side left` (README): D_max 4.6113, D_min 0.8805,
  // D_mean 2.4999 mm, printed to 1e-4.
  const double tilt = 25 * std::numbers::pi / 180, azimuth = 35 * std::numbers::pi / 180;
  api::CutSetup setup;
  setup.ap = 0.3;
  setup.ae = 0.5;
  setup.normal = {std::sin(tilt) * std::cos(azimuth), std::sin(tilt) * std::sin(azimuth),
                  std::cos(tilt)};
  setup.feed = {0, 1, 0};  // feed angle 90 deg, projected onto the tangent plane by the engine
  setup.side = api::Side::left;
  const api::Tool tool = api::parse_tool("ball:10");
  EXPECT_EQ(tool.kind, api::ToolKind::ball);
  EXPECT_EQ(tool.corner_radius, 5.0);
  EXPECT_EQ(api::to_string(tool), "ball:10");
  const api::WorkingDiameter d = api::working_diameter(tool, setup);
  EXPECT_TRUE(d.engaged);
  ASSERT_TRUE(d.d_max && d.d_min && d.d_cut);
  EXPECT_NEAR(*d.d_max, 4.6113, 5e-5);
  EXPECT_NEAR(*d.d_min, 0.8805, 5e-5);
  EXPECT_NEAR(*d.d_cut, 2.2796, 5e-5);  // point 1: the previous pass is on the left
  EXPECT_TRUE(d.flags.empty());
  const auto mean = api::mean_working_diameter(tool, setup);
  ASSERT_TRUE(mean);
  EXPECT_NEAR(*mean, 2.4999, 1e-3);
  EXPECT_NEAR(api::spindle_speed_for(120, *d.d_max), 120000 / (std::numbers::pi * 4.6113), 0.1);
}

TEST(Library, DegenerateSetUpsAreFlaggedNotThrown) {
  api::CutSetup setup;
  setup.ap = 0.3;
  setup.ae = 0;
  const api::WorkingDiameter d = api::working_diameter(api::parse_tool("ball:10"), setup);
  EXPECT_FALSE(d.engaged);
  EXPECT_EQ(d.flags, (std::vector<std::string>{"nothing_engaged", "zero_ae"}));
}

TEST(Library, FailuresLeaveAsOneErrorTypeWithCodeAndPosition) {
  try {
    api::MachineProfile::load("no-such-machine");
    FAIL() << "an unknown profile loaded";
  } catch (const api::Error& e) {
    EXPECT_EQ(e.code(), "E5009");
    EXPECT_EQ(e.severity(), api::Severity::error);
  }
  try {
    // n_max_rpm on line 3, column 1: a string where a number is due.
    api::MachineProfile::from_toml("[machine]\nname = \"x\"\n[spindle]\nn_max_rpm = \"fast\"\n",
                                   "mine.toml");
    FAIL() << "a bad profile loaded";
  } catch (const api::Error& e) {
    EXPECT_EQ(e.file(), "mine.toml");
    EXPECT_EQ(e.code().substr(0, 2), "E5");
    EXPECT_GT(e.line(), 0u);
    EXPECT_NE(std::string(e.what()).find(e.message()), std::string::npos);
  }
  EXPECT_THROW(api::parse_tool("cone:10"), api::Error);
  api::PostOptions options;  // vc and ap missing
  EXPECT_THROW(api::post("G1 X1\n", "p.nc", api::Model::load((samples() / "wavy.step").string()),
                         api::MachineProfile::load("generic"), options),
               api::Error);
}

TEST(Library, AProgramWithAnErrorNamesItsLineAndCode) {
  api::PostOptions options;
  options.tool = "ball:10";
  options.vc = 120;
  options.ap = 0.3;
  try {
    api::post("G21 G90\nG1 X0 Y0 Z0 F1000\nG7.3 X1\n", "bad.nc",
              api::Model::load((samples() / "wavy.step").string()),
              api::MachineProfile::load("generic"), options);
    FAIL() << "an unknown G code posted";
  } catch (const api::Error& e) {
    EXPECT_EQ(e.file(), "bad.nc");
    EXPECT_EQ(e.line(), 3u);
    EXPECT_GT(e.column(), 0u);
    EXPECT_EQ(e.code().size(), 5u);
  }
}

// A refusal found while timing the path (feed per revolution with the
// spindle stopped) reaches the API as the command line words it: the code,
// the place in the program, the message alone, and the table's hint.
TEST(Library, ATimingRefusalCarriesCodePlaceMessageAndHint) {
  api::PostOptions options;
  options.tool = "ball:10";
  options.vc = 120;
  options.ap = 0.3;
  try {
    api::post("G21 G95 F0.1\nG1 X10\nM2\n", "g95.ngc",
              api::Model::load((samples() / "wavy.step").string()),
              api::MachineProfile::load("generic"), options);
    FAIL() << "a feed per revolution with the spindle stopped posted";
  } catch (const api::Error& e) {
    EXPECT_EQ(e.code(), "E6103");
    EXPECT_EQ(e.file(), "g95.ngc");
    EXPECT_EQ(e.line(), 2u);
    EXPECT_EQ(e.column(), 1u);
    EXPECT_EQ(std::string(e.what()), "g95.ngc:2:1: error[E6103]: " + e.message());
    EXPECT_EQ(e.message().find("error["), std::string::npos) << e.message();
    EXPECT_FALSE(e.hint().empty());
  }
}

// The error of a post of one line with the tool `tool` (which must fail).
std::optional<api::Error> post_error_with_tool(const std::string& tool) {
  api::PostOptions options;
  options.tool = tool;
  options.vc = 120;
  options.ap = 0.3;
  try {
    api::post("G1 X1\n", "p.nc", api::Model::load((samples() / "wavy.step").string()),
              api::MachineProfile::load("generic"), options);
  } catch (const api::Error& e) {
    return e;
  }
  return std::nullopt;
}

// An error that carries no place (a bad --tool) leaves with its code and
// hint, its whole text as the message and no file, line or column.
TEST(Library, AnErrorWithoutAPlaceKeepsItsWholeTextAsTheMessage) {
  const auto error = post_error_with_tool("cone:10");
  ASSERT_TRUE(error) << "an unknown tool kind posted";
  {
    const api::Error& e = *error;
    EXPECT_EQ(e.code(), "E1601");
    EXPECT_EQ(std::string(e.what()),
              "--tool 'cone:10': unknown shape 'cone' (expected ball:D, bull:D:rc, flat:D, drill:D "
              "or other, optionally after T<n>=)");
    EXPECT_EQ(e.message(), e.what());
    EXPECT_EQ(e.file(), "");
    EXPECT_EQ(e.line(), 0u);
    EXPECT_EQ(e.column(), 0u);
    EXPECT_FALSE(e.hint().empty());
  }
}

// The place and code come from the error, never from its text: a user's
// text worded like a diagnostic is not read as one.
TEST(Library, TextWordedLikeADiagnosticIsNotReadForAPlace) {
  try {
    api::parse_tool("x:7: error[E1201]: y");
    FAIL() << "an unknown tool kind parsed";
  } catch (const api::Error& e) {
    EXPECT_EQ(e.code(), "");
    EXPECT_EQ(e.message(), e.what());
    EXPECT_EQ(e.file(), "");
    EXPECT_EQ(e.line(), 0u);
  }
  const auto error = post_error_with_tool("x:7: error[E1201]: y");
  ASSERT_TRUE(error) << "an unknown tool kind posted";
  {
    const api::Error& e = *error;
    EXPECT_EQ(e.code(), "E1601");
    EXPECT_EQ(e.message(), e.what());
    EXPECT_EQ(e.file(), "");
    EXPECT_EQ(e.line(), 0u);
  }
}

TEST(Library, OneVersionForTheLibraryAndTheCommand) {
  EXPECT_STREQ(api::version(), VCPOST_VERSION);
  const std::string line = api::version_line();
  EXPECT_EQ(line.rfind(std::string("vcpost ") + VCPOST_VERSION, 0), 0u) << line;
  int exit_code = -1;
  EXPECT_EQ(run_vcpost("--version", exit_code), line + "\n");
  EXPECT_EQ(exit_code, 0);
}

}  // namespace

namespace {

// A D10 ball along X over a level face with 0.5 mm of stock on it: the
// library's stock options give ap 0.5 at every point, and the program the
// command writes with the same options.
TEST(Library, InProcessStockGivesApPerPointAsTheCommandDoes) {
  const fs::path folder =
      fs::temp_directory_path() / ("vcpost_library_stock_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  std::ofstream(folder / "face.stl")
      << "solid f\nfacet normal 0 0 1\nouter loop\nvertex -40 -40 0\nvertex 40 -40 0\n"
         "vertex 40 40 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex -40 -40 0\n"
         "vertex 40 40 0\nvertex -40 40 0\nendloop\nendfacet\nendsolid f\n";
  const std::string program =
      "G21 G90 G17\nT1 M6\nS8000 M3\nG0 X-10 Y0 Z5\nG1 Z0 F1000\nG1 X10\nG1 Y1\nG1 X-10\n"
      "G0 Z5\nM5\nM30\n";
  std::ofstream(folder / "p.ngc") << program;
  int exit_code = -1;
  const std::string expected = run_vcpost(
      "post '" + (folder / "p.ngc").string() + "' --model '" + (folder / "face.stl").string() +
          "' --tool ball:10 --vc 120 --ap 0.3 --stock-box=-20,-20,-5,20,20,0.5 --stock-cell 0.1 "
          "-q -o -",
      exit_code);
  ASSERT_EQ(exit_code, 0);
  api::PostOptions options;
  options.tool = "ball:10";
  options.vc = 120;
  options.ap = 0.3;
  options.keep_points = true;
  options.stock_box = std::array<double, 6>{-20, -20, -5, 20, 20, 0.5};
  options.stock_cell_mm = 0.1;
  const api::PostResult result =
      api::post(program, "p.ngc", api::Model::load((folder / "face.stl").string()),
                api::MachineProfile::load("generic"), options);
  fs::remove_all(folder);
  EXPECT_EQ(result.program, expected);
  ASSERT_TRUE(result.summary.stock.has_value());
  EXPECT_EQ(result.summary.stock->source, "--stock-box");
  EXPECT_GT(result.summary.stock->points_stock, 20u);
  EXPECT_NEAR(result.summary.stock->ap_max_mm, 0.5, 1e-3);
  std::size_t from_stock = 0;
  for (const api::PostPoint& p : result.points) {
    if (!p.ap || !p.ap_from_stock) continue;
    EXPECT_NEAR(*p.ap, 0.5, 1e-3) << p.line;
    ++from_stock;
  }
  EXPECT_EQ(from_stock, result.summary.stock->points_stock);
}

}  // namespace
