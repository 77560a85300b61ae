// The in-process stock's bad input (tests/postproc/bad/stock): each file's
// first line (a Klartext file's second) says the code it must give and the command-line options
// that go with it ("expect E4720: --stock-from-program"); the options are parsed as `vcpost post`
// parses them and the file is posted against a level face: an error's code must be the one thrown,
// a warning's must be in the stock's summary.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <regex>
#include <string>

#include "geometry/analytic_surfaces.h"
#include "machines/builtin.h"
#include "postproc/cli/post_options.h"
#include "postproc/post/post_job.h"
#include "tests/postproc/cli_run_support.h"

namespace vcpost::testing {
namespace {

namespace fs = std::filesystem;

// The code of what posting `file` with `options` throws, or the warnings' codes.
std::string outcome(const fs::path& file, const std::string& options) {
  cli::PostArguments args;
  CLI::App app;
  cli::add_job_options(app, args);
  const std::string machine = file.extension() == ".H" ? "heidenhain-tnc640" : "mazak-3axis";
  const bool own_machine = options.find("--machine") != std::string::npos;
  const std::string line = "'" + file.string() + "' --model face --vc 150 --ap 0.3 " +
                           (own_machine ? "" : "--machine " + machine + " ") +
                           (options.find("--tool") == std::string::npos ? "--tool ball:10 " : "") +
                           options;
  try {
    app.parse(line, false);
    const post::PostSettings settings = cli::settings_from(args);
    geometry::PlanePatch plane;
    plane.u_min = plane.v_min = -40;
    plane.u_max = plane.v_max = 40;
    const geometry::AnalyticModel face({plane});
    const std::string text = slurp(file);
    const post::PostSummary summary =
        post::post_program(text, file.filename().string(), face,
                           machines::builtin_profile(args.machine), settings, {});
    std::string codes;
    if (summary.stock)
      for (const std::string& w : summary.stock->warnings) codes += w.substr(0, 5) + " ";
    return codes;
  } catch (const vcpost::Error& e) {
    return std::string(e.id());
  }
}

TEST(StockBadInput, EachFileGivesItsCode) {
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "tests/postproc/bad/stock";
  std::size_t files = 0;
  static const std::regex expect(R"(expect ([EW]\d{4}): ([^)\n]*))");
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string text = slurp(entry.path());
    std::smatch m;  // on the first line (Klartext: the second, after BEGIN PGM)
    ASSERT_TRUE(std::regex_search(text, m, expect)) << entry.path();
    const std::string code = m[1].str();
    const std::string got = outcome(entry.path(), m[2].str());
    if (code[0] == 'E') {
      EXPECT_EQ(got, code) << entry.path().filename();
    } else {
      EXPECT_NE(got.find(code), std::string::npos) << entry.path().filename() << ": " << got;
    }
    ++files;
  }
  EXPECT_EQ(files, 8u);
}

}  // namespace
}  // namespace vcpost::testing
