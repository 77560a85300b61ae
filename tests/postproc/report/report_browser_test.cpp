// The HTML report in a real browser: Debian's chromium, headless, opens
// the page written by `vcpost report` for the wavy sample from a file URL
// (offline: no network is needed or allowed), with a fresh profile. The
// page must log nothing to the console (no errors, no warnings), its own
// check must find ink on all five plots and Chart.js loaded from the
// inlined copy, and a screenshot is saved as a test artefact under the
// build folder (test-artefacts/report/report.png). A two-tool program's
// page draws a mark per tool section on its time axis. Without a model
// the page says so and leaves out the cusp map. Skips without chromium.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../cli_run_support.h"

namespace {

namespace fs = std::filesystem;

using vcpost::testing::slurp;

int shell(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// build/<name>/postproc/cli/vcpost -> build/<name>/test-artefacts/report
fs::path artefact_dir() {
  return fs::path(VCPOST_BINARY).parent_path().parent_path().parent_path() / "test-artefacts" /
         "report";
}

std::string chromium(const fs::path& profile) {
  return "chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
         "--disable-background-networking --disable-component-update --disable-sync "
         "--hide-scrollbars --enable-logging=stderr --v=0 --user-data-dir=" +
         profile.string();
}

// Opens `page` headless, expects no console message, and returns the page's
// own check (written into #selfcheck after drawing) and the DOM.
struct Drawn {
  nlohmann::json check;
  std::string dom;
};
Drawn open_page(const fs::path& page, const fs::path& profile, std::size_t plots = 5) {
  const fs::path dir = page.parent_path();
  const fs::path dom = dir / (page.stem().string() + ".dom.html");
  const fs::path log = dir / (page.stem().string() + ".chromium.log");
  Drawn out;
  EXPECT_EQ(shell(chromium(profile) + " --virtual-time-budget=10000 --dump-dom file://" +
                  page.string() + " >" + dom.string() + " 2>" + log.string()),
            0)
      << slurp(log);
  // Every console message the page caused (Chromium logs them all as CONSOLE).
  std::istringstream lines(slurp(log));
  std::string line;
  while (std::getline(lines, line)) {
    EXPECT_EQ(line.find(":CONSOLE"), std::string::npos) << line;
  }
  out.dom = slurp(dom);
  const std::string open = "<pre id=\"selfcheck\">";
  const auto begin = out.dom.find(open);
  EXPECT_NE(begin, std::string::npos) << "no #selfcheck in the DOM";
  if (begin == std::string::npos) return out;
  const auto end = out.dom.find("</pre>", begin);
  out.check = nlohmann::json::parse(out.dom.substr(begin + open.size(), end - begin - open.size()));
  EXPECT_EQ(out.check["chart"], "3.9.1") << out.check.dump();
  EXPECT_TRUE(out.check["errors"].empty()) << out.check.dump();
  EXPECT_EQ(out.check["drawn"], out.check["canvases"]) << out.check.dump();
  EXPECT_EQ(out.check["drawn"].size(), plots) << out.check.dump();
  return out;
}

TEST(ReportBrowser, PageDrawsEveryPlotWithoutConsoleMessages) {
  if (shell("command -v chromium >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  }
  const fs::path dir = artefact_dir();
  fs::create_directories(dir);
  const fs::path page = dir / "report.html";
  const std::string samples = std::string(VCPOST_SOURCE_DIR) + "/samples/";
  ASSERT_EQ(
      shell(std::string(VCPOST_BINARY) + " report " + samples + "wavy_raster_a0_ae2.nc --model " +
            samples + "wavy.step --tool ball:10 --vc 120 --ap 0.3 --machine mazak-3axis -q -o " +
            page.string()),
      0);

  const fs::path profile =
      fs::temp_directory_path() / ("vcpost_chromium_" + std::to_string(::getpid()));
  fs::remove_all(profile);
  const Drawn drawn = open_page(page, profile / "a");
  const std::string& text = drawn.dom;
  EXPECT_TRUE(drawn.check["marks"].empty()) << drawn.check.dump();  // one section: no marks
  // The worst-regions table names NC lines (the wavy sample's slew-limited turns).
  EXPECT_NE(text.find("<th class=\"l\">NC lines</th>"), std::string::npos);

  const fs::path shot = dir / "report.png";
  fs::remove(shot);
  ASSERT_EQ(shell(chromium(profile / "b") +
                  " --window-size=1400,2400 --virtual-time-budget=10000 --screenshot=" +
                  shot.string() + " file://" + page.string() + " >/dev/null 2>&1"),
            0);
  // A blank 1400 x 2400 PNG is a few kB; plots, maps and tables make far more.
  ASSERT_TRUE(fs::exists(shot));
  EXPECT_GT(fs::file_size(shot), 100000u);
  fs::remove_all(profile);
  std::cout << "screenshot: " << shot.string() << '\n';
}

// A program of two tool sections (the dome raster cut by T1 then T2, both
// balls, both posted): the vc plot draws a mark where each section's
// evaluated points start, at 0 and at T1's cutting time, half the whole
// cutting time as the two sections cut the same raster at the same feed.
TEST(ReportBrowser, PageMarksTheToolSectionsOnItsTimeAxis) {
  if (shell("command -v chromium >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  }
  const fs::path dir = artefact_dir();
  fs::create_directories(dir);
  const std::string samples = std::string(VCPOST_SOURCE_DIR) + "/samples/";
  const std::string sample = slurp(samples + "dome_raster_a0_ae3.nc");
  const std::size_t begin = sample.find("G0 Z50.000000\n");
  const std::size_t end = sample.find("M5\n");
  ASSERT_NE(begin, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  const std::string moves = sample.substr(begin, end - begin);
  const fs::path program = dir / "two_tools.nc", page = dir / "two_tools.html";
  std::ofstream(program, std::ios::binary) << "%\nG21 G90 G17 G94 G40\nT1 M6\nS4800 M3\n"
                                           << moves << "M5\nT2 M6\nS4800 M3\n"
                                           << moves << "M5\nM30\n%\n";
  const fs::path json = dir / "two_tools.json";
  ASSERT_EQ(shell(std::string(VCPOST_BINARY) + " report " + program.string() + " --model " +
                  samples + "dome.step --tool ball:10 --vc 120 --ap 0.3 --machine mazak-3axis " +
                  "-q -o " + page.string() + " -o " + json.string()),
            0);
  const auto report = nlohmann::json::parse(slurp(json));
  const double cutting = report["time_s"]["cutting"].get<double>();
  ASSERT_GT(cutting, 0);

  const fs::path profile =
      fs::temp_directory_path() / ("vcpost_chromium_marks_" + std::to_string(::getpid()));
  fs::remove_all(profile);
  const Drawn drawn = open_page(page, profile);
  fs::remove_all(profile);
  const auto& marks = drawn.check["marks"];
  ASSERT_EQ(marks.size(), 2u) << drawn.check.dump();
  EXPECT_EQ(marks[0]["label"], "T1 ball (posted)");
  EXPECT_EQ(marks[1]["label"], "T2 ball (posted)");
  EXPECT_DOUBLE_EQ(marks[0]["x"].get<double>(), 0.0);
  EXPECT_NEAR(marks[1]["x"].get<double>(), cutting / 2, 1e-9 * cutting);
}

// Without a model (issue 39): the four plots that need no model drawn,
// the cusp map and its cards left out (not drawn empty), and the summary
// saying plainly that there is no gouge check and no cusp map, and how
// the normals were found.
TEST(ReportBrowser, PageWithoutAModelSaysSoAndLeavesOutTheCuspMap) {
  if (shell("command -v chromium >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  }
  const fs::path dir = artefact_dir();
  fs::create_directories(dir);
  const fs::path page = dir / "no_model.html";
  const std::string samples = std::string(VCPOST_SOURCE_DIR) + "/samples/";
  ASSERT_EQ(shell(std::string(VCPOST_BINARY) + " report " + samples +
                  "wavy_raster_a0_ae2.nc --tool ball:10 --vc 120 --ap 0.3 --machine mazak-3axis "
                  "-q -o " +
                  page.string()),
            0);
  const fs::path profile =
      fs::temp_directory_path() / ("vcpost_chromium_no_model_" + std::to_string(::getpid()));
  fs::remove_all(profile);
  const Drawn drawn = open_page(page, profile, 4);
  fs::remove_all(profile);
  EXPECT_EQ(drawn.check["canvases"],
            nlohmann::json::array({"vcplot", "histplot", "splot", "devmap"}));
  const std::string& dom = drawn.dom;
  EXPECT_EQ(dom.find("id=\"cuspmap\""), std::string::npos);
  // The cards as drawn (the page's script names them too).
  EXPECT_EQ(dom.find("\"k\">Cusp height<"), std::string::npos);
  EXPECT_EQ(dom.find("\"k\">Ra / Rz"), std::string::npos);
  EXPECT_EQ(dom.find("\"k\">No contact / gouge<"), std::string::npos);
  EXPECT_NE(dom.find("\"v\">no gouge check, no cusp map"), std::string::npos);
  EXPECT_NE(dom.find("\"k\">Normals from the toolpath<"), std::string::npos);
  EXPECT_NE(dom.find(">no model: normals from the toolpath"), std::string::npos);
  EXPECT_NE(dom.find("id=\"devmap\""), std::string::npos);
}

}  // namespace
