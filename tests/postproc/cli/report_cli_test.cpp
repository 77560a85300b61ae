// `vcpost report` and `vcpost post --report` on the shipped wavy sample:
// every format by its file name, the same numbers in the JSON as in the
// job's own summary, one CSV row per point, the program unchanged by a
// report, and clear errors (exit 2) for formats it does not know.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

namespace {

namespace fs = std::filesystem;

const std::string kSamples = std::string(VCPOST_SOURCE_DIR) + "/samples/";

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

int run(const std::string& arguments) {
  const std::string command = std::string(VCPOST_BINARY) + " " + arguments;
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class ReportCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vcpost_report_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string job() const {
    return kSamples + "wavy_raster_a0_ae2.nc --model " + kSamples +
           "wavy.step --tool ball:10 --vc 120 --ap 0.3 --machine mazak-3axis -q";
  }
  fs::path dir_;
};

TEST_F(ReportCli, ReportWritesEveryFormatByItsName) {
  const fs::path json = dir_ / "r.json", csv = dir_ / "r.csv", html = dir_ / "r.html";
  const fs::path job_summary = dir_ / "job.json";
  ASSERT_EQ(run("report " + job() + " -o " + json.string() + " -o " + csv.string() + " -o " +
                html.string() + " --summary-json " + job_summary.string() + " 2>" +
                (dir_ / "err").string()),
            0)
      << read(dir_ / "err");
  const auto j = nlohmann::json::parse(read(json));
  const auto s = nlohmann::json::parse(read(job_summary));
  // The report and the job count the same points and cutting time.
  EXPECT_EQ(j["points"]["total"], s["points"]["total"]);
  EXPECT_EQ(j["points"]["gouging"], s["points"]["gouging"]);
  EXPECT_NEAR(j["time_s"]["cutting"].get<double>(), s["time_s"]["cutting"].get<double>(), 1e-9);
  EXPECT_NEAR(j["after"]["within_10_percent"].get<double>(),
              s["after"]["within_10_percent"].get<double>(), 1e-3);
  EXPECT_NEAR(j["before"]["vc"]["mean"].get<double>(), s["before"]["vc"]["mean"].get<double>(),
              1e-3);
  // A dry run counts the S words the rewrite would write.
  EXPECT_GT(j["words_written"]["s"].get<int>(), 0);
  EXPECT_EQ(j["words_written"]["s"], s["words_written"]["s"]);
  EXPECT_EQ(j["profile"]["n_max_rpm"].get<double>(), 12000);

  const std::string rows = read(csv);
  EXPECT_EQ(
      rows.rfind("line,x,y,z,cc_x,cc_y,cc_z,n_x,n_y,n_z,f_x,f_y,f_z,ae,d_ref,d_max,d_min,d_cut,"
                 "s_before,s_after,vc_before,vc_after,dev_pct,flags",
                 0),
      0u);
  EXPECT_EQ(static_cast<std::uint64_t>(std::count(rows.begin(), rows.end(), '\n')),
            j["points"]["total"].get<std::uint64_t>() + 1);
  // The job computes the cutting points only for a report that takes its
  // points: every engaged row (d_max, column 15 from 0) has its d_cut (17).
  std::istringstream lines(rows);
  std::string line;
  std::getline(lines, line);  // the header
  int engaged = 0;
  while (std::getline(lines, line)) {
    std::vector<std::string> cells;
    std::istringstream fields(line);
    for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
    ASSERT_GT(cells.size(), 17u) << line;
    if (cells[15].empty()) continue;
    ++engaged;
    EXPECT_FALSE(cells[17].empty()) << line;
  }
  EXPECT_GT(engaged, 0);

  const std::string page = read(html);
  EXPECT_NE(page.find("Chart.js v3"), std::string::npos);  // the installed library, inlined
  EXPECT_EQ(page.find(" src="), std::string::npos);
  EXPECT_LT(page.size(), 3u << 20);
}

TEST_F(ReportCli, PostWritesTheReportBesideTheSameProgram) {
  const fs::path plain = dir_ / "plain.nc", with = dir_ / "with.nc", report = dir_ / "with.json";
  ASSERT_EQ(run("post " + job() + " -o " + plain.string()), 0);
  ASSERT_EQ(run("post " + job() + " -o " + with.string() + " --report " + report.string()), 0);
  EXPECT_EQ(read(plain), read(with));
  const auto j = nlohmann::json::parse(read(report));
  EXPECT_GT(j["after"]["within_10_percent"].get<double>(),
            j["before"]["within_10_percent"].get<double>());
}

TEST_F(ReportCli, UnknownFormatIsAnInputErrorAndWritesNothing) {
  const fs::path out = dir_ / "r.txt";
  EXPECT_EQ(run("report " + job() + " -o " + out.string() + " 2>" + (dir_ / "err").string()), 2);
  EXPECT_NE(read(dir_ / "err").find(".json, .csv or .html"), std::string::npos)
      << read(dir_ / "err");
  EXPECT_FALSE(fs::exists(out));
  const fs::path program = dir_ / "p.nc";
  EXPECT_EQ(run("post " + job() + " -o " + program.string() + " --report " +
                (dir_ / "r.pdf").string() + " 2>/dev/null"),
            2);
  EXPECT_FALSE(fs::exists(program));
}

TEST_F(ReportCli, DashPrintsTheJsonSummary) {
  ASSERT_EQ(run("report " + job() + " -o - >" + (dir_ / "out").string()), 0);
  const auto j = nlohmann::json::parse(read(dir_ / "out"));
  EXPECT_EQ(j["schema"], "vcpost-report/2");
}

}  // namespace
