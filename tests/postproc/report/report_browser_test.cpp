// The HTML report in a real browser: Debian's chromium, headless, opens
// the page written by `vcpost report` for the wavy sample from a file URL
// (offline: no network is needed or allowed), with a fresh profile. The
// page must log nothing to the console (no errors, no warnings), its own
// check must find ink on all five plots and Chart.js loaded from the
// inlined copy, and a screenshot is saved as a test artefact under the
// build folder (test-artefacts/report/report.png). Skips without chromium.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
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
  const fs::path dom = dir / "dom.html", log = dir / "chromium.log";
  ASSERT_EQ(shell(chromium(profile / "a") + " --virtual-time-budget=10000 --dump-dom file://" +
                  page.string() + " >" + dom.string() + " 2>" + log.string()),
            0)
      << slurp(log);

  // Every console message the page caused (Chromium logs them all as CONSOLE).
  std::istringstream lines(slurp(log));
  std::string line;
  while (std::getline(lines, line)) {
    EXPECT_EQ(line.find(":CONSOLE"), std::string::npos) << line;
  }

  // The page's own check, written into #selfcheck after drawing.
  const std::string text = slurp(dom);
  const std::string open = "<pre id=\"selfcheck\">";
  const auto begin = text.find(open);
  ASSERT_NE(begin, std::string::npos) << "no #selfcheck in the DOM";
  const auto end = text.find("</pre>", begin);
  const auto check =
      nlohmann::json::parse(text.substr(begin + open.size(), end - begin - open.size()));
  EXPECT_EQ(check["chart"], "3.9.1") << check.dump();
  EXPECT_TRUE(check["errors"].empty()) << check.dump();
  EXPECT_EQ(check["drawn"], check["canvases"]) << check.dump();
  EXPECT_EQ(check["drawn"].size(), 5u) << check.dump();
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

}  // namespace
