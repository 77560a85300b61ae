// Seeded random rs274ngc programs read by vcpost and by LinuxCNC's rs274
// (rs274_compare_support.h): both must give the same motion, so that the
// next difference between the readers is found by this test, not by a user
// (issue 42). Each program mixes what real programs and careless users
// write: expressions and functions, named and numbered parameters, arcs in
// the three planes (centre and radius forms, helical, absolute and
// incremental centres), o-word subs with arguments, loops and conditions,
// work offsets (G10 L2, G54-G59, G92), G28/G30 and G53, inch and mm,
// absolute and incremental distances, G5.2/G5.3 NURBS curves. The generator
// is seeded: a failure names the program's seed, and the same seed writes
// the same program.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "tests/postproc/gcode/rs274_compare_support.h"

namespace vcpost::gcode {
namespace {

namespace fs = std::filesystem;
using namespace rs274cmp;  // NOLINT(google-build-using-namespace): this suite's helpers

class ProgramGenerator {
 public:
  // The NURBS curves draw from a stream of their own, so that the programs
  // read before G5.2 was followed stay as they were, curves added between
  // their statements.
  explicit ProgramGenerator(unsigned seed) : random_(seed), nurbs_random_(seed + 7919u) {}

  std::string program() {
    out_.str("");
    inches_ = chance(0.2);
    out_ << (inches_ ? "G20" : "G21") << " G90 G17 G40 G49 G80 G94\n";
    out_ << "F" << (inches_ ? 20 : 500) << "\n#1 = 0\n#<_gv> = 1\n";
    if (chance(0.5)) write_sub();
    const int statements = integer(8, 30);
    for (int k = 0; k < statements; ++k) {
      statement();
      // rs274 2.9 reads G5.2 in the XY plane only.
      if (plane_ == 17 && nurbs_real(0, 1) < 0.15) nurbs();
    }
    straight();
    out_ << "M2\n";
    return out_.str();
  }

 private:
  bool chance(double p) { return std::uniform_real_distribution<double>(0, 1)(random_) < p; }
  int integer(int low, int high) { return std::uniform_int_distribution<int>(low, high)(random_); }
  double real(double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(random_);
  }
  // A length as a program writes it: 4 decimals (mm) or 5 (inch).
  std::string length(double low, double high) {
    const double scale = inches_ ? 1 / 25.4 : 1.0;
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(inches_ ? 5 : 4);
    s << real(low, high) * scale;
    return s.str();
  }

  // A value written as an expression that evaluates to about [low, high].
  std::string expression(double low, double high) {
    const std::string a = length(low, high);
    switch (integer(0, 6)) {
      case 0:
        return "[" + a + "]";
      case 1:
        return "[" + a + " + #1 - #1]";
      case 2:
        return "[" + a + " * COS[0]]";
      case 3:
        return "[ABS[" + a + "] * [" + a + " GE 0] - ABS[" + a + "] * [" + a + " LT 0]]";
      case 4:
        return "[SQRT[" + a + " * " + a + "] * [1 - 2 * [" + a + " LT 0]]]";
      case 5:
        return "[" + a + " / 2 * 2]";
      default:
        return "[#<_gv> * 0 + " + a + "]";
    }
  }

  std::string coordinate(double low, double high) {
    return chance(0.3) ? expression(low, high) : length(low, high);
  }

  void statement() {
    switch (integer(0, 13)) {
      case 0:
      case 1:
      case 2:
        straight();
        break;
      case 3:
      case 4:
        arc();
        break;
      case 5:
        parameters();
        break;
      case 6:
        plane_and_distance();
        break;
      case 7:
        work_offset();
        break;
      case 8:
        home();
        break;
      case 9:
        if (incremental_) {  // G53 is absolute only
          straight();
        } else {
          out_ << "G53 G0 Z" << length(-20, 0) << "\n";
        }
        break;
      case 10:
        loop();
        break;
      case 11:
        condition();
        break;
      case 12:
        if (has_sub_) {
          out_ << "o100 call [" << length(-20, 20) << "] [" << length(-20, 20) << "]\n";
        } else {
          straight();
        }
        break;
      default:
        out_ << "F" << (inches_ ? integer(5, 60) : integer(100, 2000)) << "\n";
        break;
    }
  }

  void straight() {
    out_ << (chance(0.3) ? "G0" : "G1");
    const char* axes = "XYZ";
    bool any = false;
    for (int a = 0; a < 3; ++a) {
      if (chance(0.6) || (a == 2 && !any)) {
        out_ << ' ' << axes[a] << (incremental_ ? coordinate(-10, 10) : coordinate(-50, 50));
        any = true;
      }
    }
    out_ << "\n";
  }

  // A circle through the start: the centre at (I, J) from it in the plane,
  // the end on the circle at another angle (written with 4 or 5 decimals:
  // the radii differ by at most that rounding), or the radius form.
  void arc() {
    const char* first = plane_ == 17 ? "X" : plane_ == 18 ? "Z" : "Y";
    const char* second = plane_ == 17 ? "Y" : plane_ == 18 ? "X" : "Z";
    const char* first_offset = plane_ == 17 ? "I" : plane_ == 18 ? "K" : "J";
    const char* second_offset = plane_ == 17 ? "J" : plane_ == 18 ? "I" : "K";
    const char* axis = plane_ == 17 ? "Z" : plane_ == 18 ? "Y" : "X";
    const double radius = real(1, 20);
    const double start_angle = real(0, 2 * M_PI);
    const double sweep = real(0.2, 5.5);
    const bool clockwise = chance(0.5);
    // Start relative to the centre, end relative to the start.
    const double ci = -radius * std::cos(start_angle), cj = -radius * std::sin(start_angle);
    const double end_angle = start_angle + (clockwise ? -sweep : sweep);
    const double di = ci + radius * std::cos(end_angle), dj = cj + radius * std::sin(end_angle);
    const double scale = inches_ ? 1 / 25.4 : 1.0;
    std::ostringstream w;
    w.setf(std::ios::fixed);
    w.precision(inches_ ? 5 : 4);
    // The end as a displacement: G91 on the arc's block (restored after it)
    // where the program runs absolute, since only the readers know where
    // the tool is.
    out_ << (incremental_ ? "" : "G91 ") << (clockwise ? "G2" : "G3");
    w.str("");
    w << di * scale;
    out_ << ' ' << first << w.str();
    w.str("");
    w << dj * scale;
    out_ << ' ' << second << w.str();
    if (chance(0.2)) {
      w.str("");
      w << real(-3, 3) * scale;
      out_ << ' ' << axis << w.str();
    }
    if (chance(0.25) && sweep < M_PI - 0.1) {
      w.str("");
      w << radius * scale;
      out_ << " R" << w.str();
    } else {
      w.str("");
      w << ci * scale;
      out_ << ' ' << first_offset << w.str();
      w.str("");
      w << cj * scale;
      out_ << ' ' << second_offset << w.str();
    }
    out_ << (incremental_ ? "\n" : "\nG90\n");
  }

  double nurbs_real(double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(nurbs_random_);
  }
  std::string nurbs_number(double value, int decimals) {
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(decimals);
    s << value;
    return s.str();
  }
  std::string nurbs_length(double low, double high) {
    return nurbs_number(nurbs_real(low, high) * (inches_ ? 1 / 25.4 : 1.0), inches_ ? 5 : 4);
  }

  // A G5.2 curve of 2 to 6 points after the tool's position, weights 0.2 to
  // 5, order 3 or an L up to the points' count; sometimes the start's
  // weight from a P alone, a Z word (which rs274 ignores), G5.3 with the
  // next curve's first point. In G91 every point counts from the curve's
  // start.
  void nurbs() {
    const int points = 2 + static_cast<int>(nurbs_real(0, 5));
    const double span = incremental_ ? 10 : 50;
    out_ << "G5.2";
    bool first_line_open = true;  // the G5.2 word's line takes the first point
    if (nurbs_real(0, 1) < 0.3) {
      out_ << " P" << nurbs_number(nurbs_real(0.2, 5), 3) << "\n";
      first_line_open = false;
    }
    const int order = nurbs_real(0, 1) < 0.5 ? 3 : 3 + static_cast<int>(nurbs_real(0, points - 1));
    for (int k = 0; k < points; ++k) {
      out_ << (k == 0 && first_line_open ? " " : "") << "X" << nurbs_length(-span, span) << " Y"
           << nurbs_length(-span, span);
      if (nurbs_real(0, 1) < 0.05) out_ << " Z" << nurbs_length(-span, span);
      out_ << " P" << nurbs_number(nurbs_real(0.2, 5), 3);
      if (k == 0 && order > 3) out_ << " L" << order;
      out_ << "\n";
    }
    if (nurbs_real(0, 1) < 0.1) {
      // G5.3 with axis words: this curve ends, the next opens at its end.
      out_ << "G5.3 X" << nurbs_length(-span, span) << " Y" << nurbs_length(-span, span) << " P1\n";
      out_ << "X" << nurbs_length(-span, span) << " Y" << nurbs_length(-span, span) << " P2\n";
    }
    out_ << "G5.3\n";
  }

  void parameters() {
    switch (integer(0, 3)) {
      case 0:
        out_ << "#1 = " << expression(-5, 5) << "\n";
        break;
      case 1:
        out_ << "#<_gv> = [" << length(-5, 5) << " + 1]\n";
        break;
      case 2:
        out_ << "#2 = [ATAN[" << length(1, 5) << "]/[" << length(1, 5) << "] + SIN[30] + FIX["
             << length(-9, 9) << "] + FUP[" << length(-9, 9) << "] + ROUND[" << length(-9, 9)
             << "] + [7 MOD 3] + [2 ** 3]]\n";
        out_ << "G1 X[#2 / 10]\n";
        break;
      default:
        out_ << "#<x> = " << length(-20, 20) << "\nG1 X#<x> Y[#<x> / 2]\n";
        break;
    }
  }

  void plane_and_distance() {
    if (chance(0.5)) {
      plane_ = 17 + integer(0, 2);
      out_ << "G" << plane_ << "\n";
    } else {
      incremental_ = !incremental_;
      out_ << (incremental_ ? "G91" : "G90") << "\n";
    }
  }

  void work_offset() {
    switch (integer(0, 3)) {
      case 0:
        out_ << "G10 L2 P" << integer(1, 6) << " X" << length(-30, 30) << " Y" << length(-30, 30)
             << " Z" << length(-30, 30) << "\n";
        break;
      case 1:
        out_ << "G" << 54 + integer(0, 5) << "\n";
        break;
      case 2:
        out_ << "G92 X" << length(-20, 20) << " Z" << length(-20, 20) << "\n";
        break;
      default:
        out_ << "G92.1\n";
        break;
    }
  }

  void home() {
    out_ << (chance(0.5) ? "G28" : "G30");
    if (chance(0.5)) out_ << " Z" << (incremental_ ? length(0, 5) : length(10, 30));
    out_ << "\n";
  }

  void loop() {
    const int n = integer(1, 4);
    const int label = next_label_++;
    out_ << "#3 = 0\no" << label << " while [#3 LT " << n << "]\n";
    straight();
    out_ << "#3 = [#3 + 1]\no" << label << " endwhile\n";
  }

  void condition() {
    const int label = next_label_++;
    out_ << "o" << label << " if [#1 GT " << length(-5, 5) << "]\n";
    straight();
    out_ << "o" << label << " else\n";
    straight();
    out_ << "o" << label << " endif\n";
  }

  // A sub with two arguments, moving relative to them in the plane it runs in.
  void write_sub() {
    has_sub_ = true;
    out_ << "o100 sub\n";
    out_ << "G1 X[#1] Y[#2]\n";
    out_ << "G1 X[#1 + 1] Y[#2 - 1]\n";
    out_ << "o100 endsub\n";
  }

  std::mt19937 random_;
  std::mt19937 nurbs_random_;
  std::ostringstream out_;
  bool inches_ = false;
  bool incremental_ = false;
  bool has_sub_ = false;
  int plane_ = 17;
  int next_label_ = 200;
};

TEST(Rs274Random, SeededProgramsReadAsRs274ReadsThem) {
  if (!rs274_available()) GTEST_SKIP() << "rs274 (linuxcnc-uspace) not installed";
  const fs::path dir =
      fs::temp_directory_path() / ("vcpost_rs274_random_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  constexpr unsigned kPrograms = 300;
  int compared = 0;
  int curves = 0;
  for (unsigned seed = 1; seed <= kPrograms; ++seed) {
    ProgramGenerator generator(seed);
    const std::string text = generator.program();
    const fs::path file = dir / ("random_" + std::to_string(seed) + ".ngc");
    std::ofstream(file, std::ios::binary) << text;
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + text);
    compare(file);
    if (::testing::Test::HasFatalFailure()) break;
    ++compared;
    for (std::size_t at = text.find("G5.3"); at != std::string::npos;
         at = text.find("G5.3", at + 1))
      ++curves;
  }
  EXPECT_EQ(compared, static_cast<int>(kPrograms));
  std::printf("%d programs, %d G5.2 curves read alike\n", compared, curves);
  EXPECT_GE(curves, 200);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vcpost::gcode
