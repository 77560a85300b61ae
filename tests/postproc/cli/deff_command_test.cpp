// `vcpost deff` end to end: runs the built binary and checks stdout, stderr
// and the exit code. Expected numbers come from closed forms written out
// here (MODELS.md section 2), not from the engine.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr double kPi = std::numbers::pi;
double deg(double degrees) { return degrees * kPi / 180; }

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

std::string quote(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A scratch folder per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "vcpost_deff_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name, std::ios::binary) << text;
    return path_ / name;
  }

 private:
  fs::path path_;
};

// Runs `vcpost deff <args>` in `dir` (so relative file names in messages
// are as given), optionally with stdin from a file; captures both streams.
Outcome run_deff(const std::vector<std::string>& args, const fs::path& dir = fs::current_path(),
                 const std::string& stdin_file = "") {
  const TempDir scratch;
  const fs::path err_file = scratch.path() / "stderr.txt";
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on
  // " " + std::string temporaries here.
  std::string command = "cd ";
  command += quote(dir.string());
  command += " && ";
  command += quote(VCPOST_BINARY);
  command += " deff";
  for (const auto& arg : args) {
    command += ' ';
    command += quote(arg);
  }
  command += stdin_file.empty() ? std::string(" </dev/null") : " <" + quote(stdin_file);
  command += " 2>";
  command += quote(err_file.string());
  Outcome run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("popen failed");
  char buffer[4096];
  for (std::size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) run.out.append(buffer, n);
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.err = slurp(err_file);
  return run;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> result;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) result.push_back(line);
  return result;
}

std::vector<std::string> split(const std::string& line, char separator = ',') {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, separator)) cells.push_back(cell);
  if (!line.empty() && line.back() == separator) cells.emplace_back();
  return cells;
}

// The CSV output as rows of column -> cell.
std::vector<std::map<std::string, std::string>> read_csv(const std::string& text) {
  const auto all = lines(text);
  std::vector<std::map<std::string, std::string>> rows;
  if (all.empty()) return rows;
  const auto header = split(all[0]);
  for (std::size_t i = 1; i < all.size(); ++i) {
    const auto cells = split(all[i]);
    EXPECT_EQ(cells.size(), header.size()) << all[i];
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < header.size() && c < cells.size(); ++c) row[header[c]] = cells[c];
    rows.push_back(row);
  }
  return rows;
}

// Horizontal floor, D = 10, ap = 0.3: the rim of the cap has 2r =
// 2 sqrt(ap (D - ap)); with ae = 5 > the groove width the previous pass
// does not reach this pass's cap, and the leading half still holds the rim
// on both sides and the tip (2r = 0).
const double kRimDiameter = 2 * std::sqrt(0.3 * 9.7);  // 3.41174 mm
// Area-weighted mean of 2r = 2R sin(theta) over the cap 0 <= theta <= t0
// (any half of it split through the axis has the same distribution):
// 2R (t0/2 - sin(2 t0)/4) / (1 - cos t0), t0 = acos((R - ap)/R).
const double kCapAngle = std::acos(4.7 / 5);
const double kRimMean =
    10 * (kCapAngle / 2 - std::sin(2 * kCapAngle) / 4) / (1 - std::cos(kCapAngle));

const std::vector<std::string> kHorizontal = {"--tool", "ball:10", "--ap",     "0.3",
                                              "--ae",   "5",       "--normal", "0,0,1",
                                              "--feed", "1,0,0",   "--side",   "left"};

std::vector<std::string> with(std::vector<std::string> base, const std::vector<std::string>& more) {
  base.insert(base.end(), more.begin(), more.end());
  return base;
}

double cell(const std::map<std::string, std::string>& row, const std::string& column) {
  return std::stod(row.at(column));
}

const char* const kResultColumns =
    "d_cut,d_p1,d_p2,d_p1a,d_p1b,d_p2a,d_p2b,d_max,d_min,d_mean,engaged";

TEST(DeffCommand, HorizontalCaseTableShowsRimDiameterAndSpindleSpeed) {
  const Outcome run = run_deff(with(kHorizontal, {"--vc", "120"}));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  // D_max = 2 sqrt(0.3 * 9.7) = 3.4117 mm; n = 1000 * 120 / (pi * 3.41174) = 11195.8 rpm.
  EXPECT_NEAR(kRimDiameter, 3.4117, 5e-5);
  const double rpm = 1000 * 120 / (kPi * kRimDiameter);
  EXPECT_NEAR(rpm, 11196, 0.5);
  bool saw_max = false;
  for (const auto& line : lines(run.out)) {
    std::istringstream words(line);
    std::string label;
    words >> label;
    if (label == "D_max") {
      std::string diameter, vc;
      words >> diameter >> vc;
      EXPECT_EQ(diameter, "3.4117");
      EXPECT_EQ(vc, "120.00");  // the policy max point runs at exactly vc
      saw_max = true;
    }
  }
  EXPECT_TRUE(saw_max) << run.out;
  EXPECT_THAT(run.out, HasSubstr("n = 11196 rpm"));
  EXPECT_THAT(run.out, HasSubstr("down (climb)"));  // previous pass left, M3
}

TEST(DeffCommand, TableShowsAllCuttingPointsAndRadiusColumn) {
  const Outcome run = run_deff(with(kHorizontal, {"--radius"}));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* label : {"D_max", "D_min", "D_mean", "point 1 ", "point 2 ", "point 1'",
                            "point 1''", "point 2'", "point 2''", "cutting point (1)"}) {
    EXPECT_THAT(run.out, HasSubstr(label));
  }
  EXPECT_THAT(run.out, HasSubstr("r [mm]"));
  // The rim radius r = sqrt(0.3 * 9.7) = 1.7059 next to its 2r.
  EXPECT_THAT(run.out, HasSubstr("3.4117  1.7059"));
}

TEST(DeffCommand, JsonHasStableKeysAndTheClosedFormValues) {
  const Outcome run = run_deff(with(kHorizontal, {"--vc", "120", "--json"}));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  std::vector<std::string> keys;
  for (const auto& item : json.items()) keys.push_back(item.key());
  EXPECT_THAT(
      keys, ::testing::UnorderedElementsAre(
                "tool", "diameter", "ap", "ae", "side", "normal", "tilt_deg", "azimuth_deg", "feed",
                "feed_angle_deg", "engaged", "d_max", "d_min", "d_mean", "r_max", "r_min", "r_mean",
                "cut_point", "points", "flags", "spindle", "milling", "speed"));
  EXPECT_EQ(json["tool"], "ball:10");
  EXPECT_EQ(json["side"], "left");
  EXPECT_EQ(json["engaged"], true);
  EXPECT_NEAR(json["d_max"].get<double>(), kRimDiameter, 1e-9);
  EXPECT_NEAR(json["r_max"].get<double>(), kRimDiameter / 2, 1e-9);
  EXPECT_NEAR(json["d_min"].get<double>(), 0, 1e-9);
  EXPECT_NEAR(json["d_mean"].get<double>(), kRimMean, 1e-3);
  EXPECT_TRUE(json["feed_angle_deg"].is_null());
  EXPECT_EQ(json["flags"].size(), 0u);
  EXPECT_EQ(json["cut_point"], "p1");
  EXPECT_EQ(json["milling"], "down");
  EXPECT_EQ(json["spindle"], "cw");

  // S0 = N x F = +y: point 1 is the right groove edge at y = -sqrt(2.91),
  // point 2 the left one, both on the stock plane z = -(R - ap) = -4.7.
  const auto& points = json["points"];
  for (const char* key : {"cut", "p1", "p2", "p1a", "p1b", "p2a", "p2b"}) {
    ASSERT_TRUE(points.contains(key)) << key;
    for (const char* field : {"position", "d", "r", "vc"}) {
      EXPECT_TRUE(points[key].contains(field)) << key << "." << field;
    }
    EXPECT_NEAR(points[key]["d"].get<double>(), kRimDiameter, 1e-9) << key;
    EXPECT_NEAR(points[key]["vc"].get<double>(), 120, 1e-6) << key;
  }
  const double half_width = std::sqrt(2.91);
  EXPECT_NEAR(points["p1"]["position"][1].get<double>(), -half_width, 1e-9);
  EXPECT_NEAR(points["p1"]["position"][2].get<double>(), -4.7, 1e-9);
  EXPECT_NEAR(points["p2"]["position"][1].get<double>(), half_width, 1e-9);
  EXPECT_NEAR(points["cut"]["position"][1].get<double>(), -half_width, 1e-9);

  const auto& speed = json["speed"];
  EXPECT_EQ(speed["policy"], "max");
  EXPECT_NEAR(speed["d_ref"].get<double>(), kRimDiameter, 1e-9);
  EXPECT_NEAR(speed["rpm"].get<double>(), 1000 * 120 / (kPi * kRimDiameter), 1e-6);
  EXPECT_NEAR(speed["vc_nominal"].get<double>(), 120, 0);
  EXPECT_NEAR(speed["vc_max"].get<double>(), 120, 1e-9);
  EXPECT_NEAR(speed["vc_min"].get<double>(), 0, 1e-6);
}

TEST(DeffCommand, JsonWithoutSpeedHasNullSpeedAndNullPointSpeeds) {
  const Outcome run = run_deff(with(kHorizontal, {"--json"}));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_TRUE(json["speed"].is_null());
  EXPECT_TRUE(json["points"]["p1"]["vc"].is_null());
}

TEST(DeffCommand, ZeroWidthOfCutIsValidButEngagesNothing) {
  // ae = 0: the previous pass already took this pass's stock. Not an input
  // error: empty diameters, flags, no spindle speed.
  const Outcome run =
      run_deff({"--tool", "ball:10", "--ap", "0.3", "--ae", "0", "--vc", "120", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["engaged"], false);
  EXPECT_TRUE(json["d_max"].is_null());
  EXPECT_TRUE(json["d_mean"].is_null());
  EXPECT_THAT(json["flags"].get<std::vector<std::string>>(),
              ::testing::IsSupersetOf({"nothing_engaged", "zero_ae"}));
  EXPECT_TRUE(json["speed"]["d_ref"].is_null());
  EXPECT_TRUE(json["speed"]["rpm"].is_null());
  // The rim still exists: its points keep 2 sqrt(ap (D - ap)).
  EXPECT_NEAR(json["points"]["p1"]["d"].get<double>(), kRimDiameter, 1e-9);
}

TEST(DeffCommand, RpmGivesCuttingSpeedsAtThatSpindleSpeed) {
  // The paper's n = 3820 rpm: vc = pi * 2r * n / 1000 at each point.
  const Outcome run = run_deff(with(kHorizontal, {"--rpm", "3820", "--json"}));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_NEAR(json["speed"]["rpm"].get<double>(), 3820, 0);
  EXPECT_TRUE(json["speed"]["vc_nominal"].is_null());
  EXPECT_NEAR(json["speed"]["vc_max"].get<double>(), kPi * kRimDiameter * 3820 / 1000, 1e-9);
}

TEST(DeffCommand, MeanPolicyUsesTheAreaWeightedMean) {
  const Outcome run = run_deff(with(kHorizontal, {"--vc", "120", "--policy", "mean", "--json"}));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_NEAR(json["speed"]["d_ref"].get<double>(), kRimMean, 1e-3);
  // n = 1000 vc / (pi D_mean): a relative error e in D_mean is e in n.
  const double rpm = 1000 * 120 / (kPi * kRimMean);
  EXPECT_NEAR(json["speed"]["rpm"].get<double>(), rpm, rpm * 1e-3 / kRimMean);
}

TEST(DeffCommand, SideAndSpindleDecideMilling) {
  // MODELS.md: M3 with the previous pass on the left is down milling; the
  // opposite side or the opposite spindle direction turns it to up milling.
  const auto milling = [](const std::string& side, const std::string& spindle) {
    const Outcome run = run_deff({"--tool", "ball:10", "--ap", "0.3", "--ae", "0.5", "--side", side,
                                  "--spindle", spindle, "--json"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(run.out)["milling"].get<std::string>();
  };
  EXPECT_EQ(milling("left", "cw"), "down");
  EXPECT_EQ(milling("right", "cw"), "up");
  EXPECT_EQ(milling("left", "ccw"), "up");
  EXPECT_EQ(milling("right", "ccw"), "down");
}

TEST(DeffCommand, AnglesGiveThePapersNormalAndFeed) {
  const Outcome run = run_deff({"--tool", "ball:10", "--ap", "0.3", "--ae", "0.5", "--tilt", "25",
                                "--azimuth", "35", "--feed-angle", "90", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  // N = (sin b cos a, sin b sin a, cos b), b = A_N2 = 25 deg, a = A_N1 = 35 deg.
  const double n[3] = {std::sin(deg(25)) * std::cos(deg(35)), std::sin(deg(25)) * std::sin(deg(35)),
                       std::cos(deg(25))};
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(json["normal"][i].get<double>(), n[i], 1e-12);
  EXPECT_NEAR(json["tilt_deg"].get<double>(), 25, 1e-9);
  EXPECT_NEAR(json["azimuth_deg"].get<double>(), 35, 1e-9);
  // F = (0, 1, 0) projected onto the tangent plane: (0,1,0) - n_y N, normalised.
  double f[3] = {-n[1] * n[0], 1 - n[1] * n[1], -n[1] * n[2]};
  const double length = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(json["feed"][i].get<double>(), f[i] / length, 1e-12);
  EXPECT_NEAR(json["feed_angle_deg"].get<double>(), 90, 0);

  // The same set-up given as vectors must give the same diameters.
  std::ostringstream normal, feed;
  normal.precision(17);
  feed.precision(17);
  normal << n[0] << ',' << n[1] << ',' << n[2];
  feed << "0,1,0";
  const Outcome vectors = run_deff({"--tool", "ball:10", "--ap", "0.3", "--ae", "0.5", "--normal",
                                    normal.str(), "--feed", feed.str(), "--json"});
  ASSERT_EQ(vectors.exit_code, 0) << vectors.err;
  const auto same = nlohmann::json::parse(vectors.out);
  EXPECT_NEAR(same["d_max"].get<double>(), json["d_max"].get<double>(), 1e-9);
  EXPECT_NEAR(same["points"]["p2b"]["d"].get<double>(), json["points"]["p2b"]["d"].get<double>(),
              1e-9);
}

TEST(DeffCommand, UphillOnTiltedSurfaceReachesThePublishedTiltedCutterDiameter) {
  // Feed straight up the slope (normal tilted towards +x, feed angle 180):
  // the leading half holds the cap's farthest point from the axis, 2r =
  // D sin(beta + acos((D - 2 ap)/D)) = 10 sin(45 deg + 19.95 deg) = 9.0593.
  const Outcome run = run_deff({"--tool", "ball:10", "--ap", "0.3", "--ae", "5", "--tilt", "45",
                                "--azimuth", "0", "--feed-angle", "180", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_NEAR(json["d_max"].get<double>(), 10 * std::sin(deg(45) + kCapAngle), 1e-6);
  EXPECT_NEAR(json["d_max"].get<double>(), 9.0593, 5e-5);
}

TEST(DeffCommand, TiltSweepRowsFollowTheTiltedCutterFormula) {
  const Outcome run = run_deff({"--tool", "ball:10", "--ap", "0.3", "--ae", "5", "--azimuth", "0",
                                "--feed-angle", "180", "--sweep", "tilt=0:60:5"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  const auto all = lines(run.out);
  ASSERT_EQ(all.size(), 14u);  // header + 0, 5, ..., 60
  EXPECT_EQ(all[0], std::string("tilt,") + kResultColumns);
  const auto rows = read_csv(run.out);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double tilt = 5.0 * static_cast<double>(i);
    EXPECT_NEAR(cell(rows[i], "tilt"), tilt, 0);
    // Printed with 4 decimals: within half a unit of the last digit.
    EXPECT_NEAR(cell(rows[i], "d_max"), 10 * std::sin(deg(tilt) + kCapAngle), 5.01e-5) << tilt;
    EXPECT_EQ(rows[i].at("engaged"), "1");
  }
  EXPECT_EQ(rows[9].at("d_max"), "9.0593");  // tilt 45
}

TEST(DeffCommand, FeedAngleSweepIncludesStopAndKeepsTheHorizontalRim) {
  const Outcome run =
      run_deff({"--tool", "ball:10", "--ap", "0.3", "--ae", "5", "--sweep", "feed-angle=0:360:15"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto rows = read_csv(run.out);
  ASSERT_EQ(rows.size(), 25u);  // 0, 15, ..., 360
  EXPECT_EQ(rows.front().at("feed_angle"), "0");
  EXPECT_EQ(rows.back().at("feed_angle"), "360");
  for (const auto& row : rows) {
    // On a horizontal floor every feed direction sees the same groove.
    EXPECT_EQ(row.at("d_max"), "3.4117");
    EXPECT_EQ(row.at("d_cut"), "3.4117");
    EXPECT_EQ(row.at("d_min"), "0.0000");
  }
}

TEST(DeffCommand, SweepStopOffTheGridIsNotIncluded) {
  const Outcome run =
      run_deff({"--tool", "ball:10", "--ap", "0.3", "--ae", "5", "--sweep", "azimuth=0:10:3"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto rows = read_csv(run.out);
  ASSERT_EQ(rows.size(), 4u);  // 0, 3, 6, 9
  EXPECT_EQ(rows.back().at("azimuth"), "9");
}

TEST(DeffCommand, FeedAngleSweepReproducesThePapersFigure8Range) {
  // D = 10, tilt 25, azimuth 35, ap = 1: over all feed directions r at
  // points 1 and 2 spans 1.03 .. 4.41 mm (MODELS.md; paper's Fig. 8).
  const Outcome run = run_deff({"--tool", "ball:10", "--ap", "1", "--ae", "1", "--tilt", "25",
                                "--azimuth", "35", "--radius", "--sweep", "feed-angle=0:360:0.5"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto rows = read_csv(run.out);
  ASSERT_EQ(rows.size(), 721u);
  double low = 1e9, high = 0;
  for (const auto& row : rows) {
    for (const char* column : {"r_p1", "r_p2"}) {
      low = std::min(low, cell(row, column));
      high = std::max(high, cell(row, column));
    }
    // Both rounded to 4 decimals: 2 * 0.5e-4 + 0.5e-4 apart at most.
    EXPECT_NEAR(cell(row, "r_max") * 2, cell(row, "d_max"), 1.5e-4 + 1e-12);
  }
  EXPECT_NEAR(low, 1.03, 0.01);
  EXPECT_NEAR(high, 4.41, 0.01);
}

const char* const kBatchHeader = "name,side,ap,d,ae,nx,ny,nz,fx,fy,fz";

TEST(DeffCommand, BatchCopiesRowsAndAppendsResultColumns) {
  const TempDir dir;
  // Columns out of order, an extra quoted column, CRLF line ends and a
  // blank line: all allowed.
  dir.write("cases.csv", std::string(kBatchHeader) +
                             "\r\n\"floor, wide\",left,0.3,10,5,0,0,1,1,0,0\r\n\r\n"
                             "floor-no-ae,right,0.3,10,0,0,0,1,0,2,0\r\n");
  const Outcome run = run_deff({"--batch", "cases.csv"}, dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  const auto all = lines(run.out);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0], std::string(kBatchHeader) + "," + kResultColumns);
  EXPECT_THAT(all[1], StartsWith("\"floor, wide\",left,0.3,10,5,0,0,1,1,0,0,"));
  const auto results =
      split(all[1].substr(std::string("\"floor, wide\",left,0.3,10,5,0,0,1,1,0,0,").size()));
  ASSERT_EQ(results.size(), 11u);
  // d_cut .. d_p2b are rim points: 2 sqrt(0.3 * 9.7).
  for (std::size_t i = 0; i < 7; ++i) EXPECT_EQ(results[i], "3.4117") << i;
  EXPECT_EQ(results[7], "3.4117");  // d_max
  EXPECT_EQ(results[8], "0.0000");  // d_min: the tip
  EXPECT_NEAR(std::stod(results[9]), kRimMean, 1e-3);
  EXPECT_EQ(results[10], "1");

  // ae = 0: the previous pass took everything, the rim points still exist.
  const auto empty = split(all[2]);
  ASSERT_EQ(empty.size(), 22u);
  EXPECT_EQ(empty[11], "3.4117");  // d_cut
  EXPECT_EQ(empty[18], "");        // d_max
  EXPECT_EQ(empty[19], "");        // d_min
  EXPECT_EQ(empty[20], "");        // d_mean
  EXPECT_EQ(empty[21], "0");       // engaged
}

TEST(DeffCommand, BatchToolColumnsSelectBullNoseAndFlat) {
  const TempDir dir;
  dir.write("tools.csv",
            "tool,rc,d,ap,ae,nx,ny,nz,fx,fy,fz,side\n"
            "bull,2,10,0.3,5,0,0,1,1,0,0,left\n"
            "flat,,10,0.3,5,0,0,1,1,0,0,left\n"
            ",,10,0.3,5,0,0,1,1,0,0,left\n");
  const Outcome run = run_deff({"--batch", "tools.csv"}, dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto rows = read_csv(run.out);
  ASSERT_EQ(rows.size(), 3u);
  // Bull-nose on a horizontal floor, ap < rc: rim 2 (R0 + sqrt(ap (2 rc - ap))),
  // R0 = R - rc = 3 (MODELS.md): 8.1071 mm at both groove edges.
  const double bull_rim = 2 * (3 + std::sqrt(0.3 * (4 - 0.3)));
  EXPECT_NEAR(cell(rows[0], "d_p1"), bull_rim, 5.01e-5);
  EXPECT_NEAR(cell(rows[0], "d_p2"), bull_rim, 5.01e-5);
  EXPECT_NEAR(cell(rows[0], "d_max"), bull_rim, 5.01e-5);
  // Flat end mill: the periphery cuts with the full D.
  EXPECT_EQ(rows[1].at("d_max"), "10.0000");
  EXPECT_EQ(rows[1].at("d_cut"), "10.0000");
  // An empty tool cell is a ball.
  EXPECT_EQ(rows[2].at("d_max"), "3.4117");
}

TEST(DeffCommand, BatchFromStdinMatchesBatchFromFile) {
  const TempDir dir;
  const fs::path file =
      dir.write("cases.csv", std::string(kBatchHeader) + "\nfloor,left,0.3,10,5,0,0,1,1,0,0\n");
  const Outcome from_file = run_deff({"--batch", "cases.csv", "--radius"}, dir.path());
  const Outcome from_stdin = run_deff({"--batch", "-", "--radius"}, dir.path(), file.string());
  ASSERT_EQ(from_file.exit_code, 0) << from_file.err;
  ASSERT_EQ(from_stdin.exit_code, 0) << from_stdin.err;
  EXPECT_EQ(from_file.out, from_stdin.out);
  const auto rows = read_csv(from_file.out);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].at("r_max"), "1.7059");
}

TEST(DeffCommand, SampleCasesRun) {
  const fs::path sample = fs::path(VCPOST_SOURCE_DIR) / "samples" / "deff_cases.csv";
  const Outcome run = run_deff({"--batch", sample.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto input = lines(slurp(sample));
  const auto output = lines(run.out);
  ASSERT_EQ(output.size(), input.size());
  for (std::size_t i = 1; i < input.size(); ++i) EXPECT_THAT(output[i], StartsWith(input[i] + ","));
  const auto rows = read_csv(run.out);
  // The horizontal rows: rim 2 sqrt(ap (D - ap)) at ap = 0.3 and at ap = 1 (6.0000).
  EXPECT_EQ(rows.front().at("d_cut"), "3.4117");
  EXPECT_EQ(rows.back().at("d_cut"), "6.0000");
  for (const auto& row : rows) EXPECT_EQ(row.at("engaged"), "1") << row.at("case");
}

// Every refused input: exit 2, nothing on stdout, one line on stderr that
// starts with the argument or file:line at fault.
struct BadInput {
  std::vector<std::string> args;
  std::string blame;      // what the message must start with after "vcpost: error: "
  std::string says = "";  // and a phrase it must hold
};

void PrintTo(const BadInput& bad, std::ostream* out) {
  for (const auto& arg : bad.args) *out << arg << ' ';
}

class DeffBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(DeffBadInput, ExitsTwoWithOneLineNamingTheArgument) {
  const TempDir dir;
  dir.write("cases.csv", "d,ap,ae,nx,ny,nz,fx,fy,fz,side\n10,0.3,5,0,0,1,1,0,0,left\n");
  const Outcome run = run_deff(GetParam().args, dir.path());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  ASSERT_EQ(lines(run.err).size(), 1u) << run.err;
  EXPECT_THAT(run.err, StartsWith("vcpost: error: " + GetParam().blame)) << run.err;
  EXPECT_THAT(run.err, HasSubstr(GetParam().says));
}

std::vector<std::string> base(const std::vector<std::string>& more) {
  return with({"--tool", "ball:10", "--ap", "0.3", "--ae", "0.5"}, more);
}

INSTANTIATE_TEST_SUITE_P(
    Arguments, DeffBadInput,
    ::testing::Values(
        BadInput{{"--tool", "ball:-10", "--ap", "0.3", "--ae", "0.5"}, "--tool:", "> 0"},
        BadInput{{"--tool", "ball:0", "--ap", "0.3", "--ae", "0.5"}, "--tool:", "> 0"},
        BadInput{
            {"--tool", "ball:1e300", "--ap", "0.3", "--ae", "0.5"}, "--tool:", "at most 5000 mm"},
        BadInput{{"--tool", "drill:10", "--ap", "0.3", "--ae", "0.5"}, "--tool:", "unknown"},
        BadInput{{"--tool", "ball:10", "--ap", "10.5", "--ae", "0.5"}, "--ap:", "reaches the tool"},
        // ap = D, which the help once allowed, gave no diameters (issue 42).
        BadInput{{"--tool", "ball:10", "--ap", "10", "--ae", "0.5"}, "--ap:", "give ap below D"},
        BadInput{{"--tool", "ball:10", "--ap", "-0.3", "--ae", "0.5"}, "--ap:", "> 0"},
        BadInput{{"--tool", "ball:10", "--ap", "x", "--ae", "0.5"}, "--ap:", "not a number"},
        BadInput{{"--tool", "ball:10", "--ap", "0.3", "--ae", "-1"}, "--ae:", ">= 0"},
        BadInput{base({"--normal", "0,0,0"}), "--normal:", "zero"},
        BadInput{base({"--normal", "0,0,1.01"}), "--normal:", "unit vector"},
        BadInput{base({"--normal", "0,0,1.000002"}), "--normal:", "unit vector"},
        BadInput{base({"--normal", "1,0,0"}), "--normal:", "undercut"},
        BadInput{base({"--normal", "0.6,0,-0.8"}), "--normal:", "undercut"},
        BadInput{base({"--normal", "0,1"}), "--normal:", "three numbers"},
        BadInput{base({"--feed", "0,0,2"}), "--feed:", "parallel"},
        BadInput{base({"--feed", "0,0,0"}), "--feed:", "zero"},
        BadInput{base({"--tilt", "90"}), "--tilt:", "(-90, 90)"},
        BadInput{base({"--side", "up"}), "--side:", "left or right"},
        BadInput{base({"--vc", "-5"}), "--vc:", "> 0"},
        BadInput{base({"--vc", "100", "--policy", "fastest"}), "--policy:", "max, tangent"},
        BadInput{base({"--spindle", "m3"}), "--spindle:", "cw or ccw"},
        BadInput{base({"--sweep", "tilt=0:90:5"}), "--sweep: tilt = 90:", "(-90, 90)"},
        BadInput{base({"--sweep", "speed=0:9:1"}), "--sweep:", "unknown parameter"},
        BadInput{base({"--sweep", "tilt=0:60:0"}), "--sweep:", "step"},
        BadInput{{"--ap", "0.3", "--ae", "0.5"}, "--tool:", "required"}),
    [](const auto& test_case) { return "Case" + std::to_string(test_case.index); });

INSTANTIATE_TEST_SUITE_P(
    Conflicts, DeffBadInput,
    ::testing::Values(
        BadInput{base({"--normal", "0,0,1", "--tilt", "5"}), "--normal:", "--tilt"},
        BadInput{base({"--normal", "0,0,1", "--azimuth", "5"}), "--normal:", "--azimuth"},
        BadInput{base({"--feed", "1,0,0", "--feed-angle", "5"}), "--feed:", "--feed-angle"},
        BadInput{base({"--vc", "120", "--rpm", "3820"}), "--vc:", "--rpm"},
        BadInput{base({"--sweep", "tilt=0:5:1", "--batch", "cases.csv"}), "--sweep:", "--batch"},
        BadInput{base({"--sweep", "tilt=0:5:1", "--tilt", "3"}), "--sweep:", "--tilt"},
        BadInput{base({"--sweep", "feed-angle=0:5:1", "--feed", "1,0,0"}), "--sweep:", "--feed"},
        BadInput{base({"--sweep", "tilt=0:5:1", "--json"}), "--json:", "--sweep"},
        BadInput{{"--batch", "cases.csv", "--ap", "0.3"}, "--ap:", "--batch"},
        BadInput{base({"--policy", "mean"}), "--policy:", "--vc"}),
    [](const auto& test_case) { return "Case" + std::to_string(test_case.index); });

// A batch file whose problem is on the line named in `blame`.
struct BadFile {
  std::string text;
  std::string blame;
  std::string says;
};

void PrintTo(const BadFile& bad, std::ostream* out) { *out << bad.text; }

class DeffBadBatch : public ::testing::TestWithParam<BadFile> {};

TEST_P(DeffBadBatch, ExitsTwoWithFileAndLineAndPrintsNothing) {
  const TempDir dir;
  dir.write("bad.csv", GetParam().text);
  const Outcome run = run_deff({"--batch", "bad.csv"}, dir.path());
  EXPECT_EQ(run.exit_code, 2);
  // A file is checked whole before anything is printed.
  EXPECT_EQ(run.out, "");
  ASSERT_EQ(lines(run.err).size(), 1u) << run.err;
  EXPECT_THAT(run.err, StartsWith("vcpost: error: " + GetParam().blame)) << run.err;
  EXPECT_THAT(run.err, HasSubstr(GetParam().says)) << run.err;
}

const std::string kHeader = "d,ap,ae,nx,ny,nz,fx,fy,fz,side\n";
const std::string kGoodRow = "10,0.3,0.5,0,0,1,1,0,0,left\n";

INSTANTIATE_TEST_SUITE_P(
    Rows, DeffBadBatch,
    ::testing::Values(
        BadFile{kHeader + kGoodRow + "10,x,0.5,0,0,1,1,0,0,left\n",
                "bad.csv:3: column 'ap': 'x' is not a number", ""},
        BadFile{"d,ap,ae,nx,ny,nz,fx,fy,side\n" + kGoodRow, "bad.csv:1: missing column 'fz'", ""},
        BadFile{kHeader + kGoodRow + "10,0.3,0.5,0,0,1,1,0\n", "bad.csv:3:", "found 8"},
        BadFile{kHeader + kGoodRow + "0,0.3,0.5,0,0,1,1,0,0,left\n",
                "bad.csv:3: column 'd':", "> 0"},
        BadFile{kHeader + kGoodRow + "-10,0.3,0.5,0,0,1,1,0,0,left\n",
                "bad.csv:3: column 'd':", "> 0"},
        BadFile{kHeader + kGoodRow + "10,11,0.5,0,0,1,1,0,0,left\n",
                "bad.csv:3: column 'ap':", "reaches the tool"},
        BadFile{kHeader + kGoodRow + "10,0.3,0.5,0,0,0.5,1,0,0,left\n",
                "bad.csv:3: columns 'nx,ny,nz':", "unit vector"},
        BadFile{kHeader + kGoodRow + "10,0.3,0.5,0,0,0,1,0,0,left\n",
                "bad.csv:3: columns 'nx,ny,nz':", "zero"},
        BadFile{kHeader + kGoodRow + "10,0.3,0.5,0,-1,0,1,0,0,left\n",
                "bad.csv:3: columns 'nx,ny,nz':", "undercut"},
        BadFile{kHeader + kGoodRow + "10,0.3,0.5,0,0,1,0,0,1,left\n",
                "bad.csv:3: columns 'fx,fy,fz':", "parallel"},
        BadFile{kHeader + kGoodRow + "10,0.3,0.5,0,0,1,1,0,0,up\n",
                "bad.csv:3: column 'side':", "left or right"},
        BadFile{"d,ap,ae,nx,ny,nz,fx,fy,fz,side,tool\n10,0.3,0.5,0,0,1,1,0,0,left,ball\n"
                "10,0.3,0.5,0,0,1,1,0,0,left,drill\n",
                "bad.csv:3: column 'tool':", "unknown tool 'drill'"},
        BadFile{"d,ap,ae,nx,ny,nz,fx,fy,fz,side,tool,rc\n10,0.3,0.5,0,0,1,1,0,0,left,ball,\n"
                "10,0.3,0.5,0,0,1,1,0,0,left,bull,\n",
                "bad.csv:3: column 'rc':", "corner radius"},
        BadFile{kHeader + kGoodRow + "\"10,0.3,0.5,0,0,1,1,0,0,left\n",
                "bad.csv:3:", "unterminated"},
        BadFile{"d,ap,ap,nx,ny,nz,fx,fy,fz,side\n", "bad.csv:1: column 'ap' appears twice", ""},
        BadFile{"", "bad.csv: empty input", ""}),
    [](const auto& test_case) { return "Case" + std::to_string(test_case.index); });

TEST(DeffCommand, MissingBatchFileIsAnInputError) {
  const TempDir dir;
  const Outcome run = run_deff({"--batch", "nowhere.csv"}, dir.path());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.out, "");
  EXPECT_EQ(run.err, "vcpost: error: --batch: cannot open 'nowhere.csv' for reading\n");
}

TEST(DeffCommand, BadRowOnStdinStopsTheStreamAfterTheRowsBeforeIt) {
  // stdin cannot be read twice: rows stream out, and a bad row ends the run
  // with exit 2 after the good rows before it (README documents this).
  const TempDir dir;
  const fs::path file =
      dir.write("bad.csv", kHeader + kGoodRow + "10,0.3,0.5,0,0,1,1,0,0,sideways\n");
  const Outcome run = run_deff({"--batch", "-"}, dir.path(), file.string());
  EXPECT_EQ(run.exit_code, 2);
  const auto out = lines(run.out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_THAT(out[1], StartsWith("10,0.3,0.5,0,0,1,1,0,0,left,"));
  EXPECT_EQ(run.err,
            "vcpost: error: <stdin>:3: column 'side': 'sideways' is not a side "
            "(expected left or right)\n");
}

TEST(DeffCommand, NormalWithinToleranceOfUnitLengthIsAccepted) {
  const Outcome run = run_deff(base({"--normal", "0,0,1.0000005", "--json"}));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  EXPECT_NEAR(json["normal"][2].get<double>(), 1, 1e-15);  // rescaled to unit length
}

TEST(DeffCommand, HelpTeachesUnitsDefaultsAndExamples) {
  const Outcome run = run_deff({"--help"});
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_THAT(run.out, HasSubstr("--sweep feed-angle=0:360:15"));
  EXPECT_THAT(run.out, HasSubstr("--tilt 25 --azimuth 35"));
  EXPECT_THAT(run.out, HasSubstr("m/min"));
  EXPECT_THAT(run.out, HasSubstr("(default max)"));
  EXPECT_THAT(run.out, HasSubstr("(default left)"));
}

}  // namespace
