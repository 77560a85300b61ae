// The lossless writer: byte-identical output without changes (every shared
// real program), and S/F patches that change those words only.
#include "postproc/gcode/writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "postproc/gcode/interpreter.h"

namespace vcpost::gcode {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Writer, PatchesOnlyTheWordAndKeepsEverythingElse) {
  const std::string text = "N10 G1 X1 S100 F200 (keep)\r\nn20g1x2s#<a>f[3*4]\r\nG0 X0 ; note\n";
  const std::vector<WordPatch> patches{
      {0, 'S', "12000"}, {0, 'F', "850.5"}, {28, 'S', "9000"}, {48, 'S', "8000"}};
  EXPECT_EQ(patched(text, patches),
            "N10 G1 X1 S12000 F850.5 (keep)\r\nn20g1x2s9000f[3*4]\r\nG0 X0 S8000 ; note\n");
}

TEST(Writer, EmptyPatchListIsByteIdenticalOnSharedPrograms) {
  const fs::path dir = fs::path(VCPOST_SHARED_DATA_DIR) / "gcode";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "shared data not found at " << dir;
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const auto ext = entry.path().extension();
    if (ext == ".md" || ext == ".json") continue;
    const std::string text = read_file(entry.path());
    EXPECT_EQ(patched(text, {}), text) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 5);
}

// Rewriting every S word of a real program to another value: the output
// differs from the input only in those digits, and reads back to the same
// moves with the new speed.
TEST(Writer, RewrittenSpeedReadsBackToTheSameMoves) {
  const fs::path file = fs::path(VCPOST_SHARED_DATA_DIR) / "gcode/3D_Chips.ngc";
  if (!fs::exists(file)) GTEST_SKIP() << "shared data not found: " << file;
  const std::string text = read_file(file);
  auto interpret = [](std::string_view program, std::vector<WordPatch>* patches) {
    Interpreter interpreter(program, rs274ngc_dialect());
    std::vector<program::Event> events, all;
    while (interpreter.next(events)) {
      for (const auto& e : events)
        if (const auto* s = std::get_if<program::SetSpindleSpeed>(&e); s && patches)
          patches->push_back({s->source.offset, 'S', "9000"});
      all.insert(all.end(), events.begin(), events.end());
      events.clear();
    }
    return all;
  };
  std::vector<WordPatch> patches;
  const auto before = interpret(text, &patches);
  ASSERT_EQ(patches.size(), 1u);  // N70S#<rpm>M3
  const std::string out = patched(text, patches);
  // "#<rpm>" (6 bytes) became "9000" (4 bytes).
  EXPECT_EQ(out.size(), text.size() - 2);
  const auto after = interpret(out, nullptr);
  ASSERT_EQ(before.size(), after.size());
  int speeds = 0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    if (const auto* s = std::get_if<program::SetSpindleSpeed>(&after[i])) {
      EXPECT_DOUBLE_EQ(s->rpm, 9000.0);
      EXPECT_DOUBLE_EQ(std::get<program::SetSpindleSpeed>(before[i]).rpm, 1600.0);
      ++speeds;
    } else if (const auto* f = std::get_if<program::StraightFeed>(&after[i])) {
      EXPECT_TRUE(f->end.isApprox(std::get<program::StraightFeed>(before[i]).end, 1e-12));
    }
  }
  EXPECT_EQ(speeds, 1);
}

// Issue 41: a speed on LinuxCNC's analog output 0 (gcode::SpeedForm), each
// form on the line shapes it meets; expected texts written by hand.
TEST(Writer, SpeedOnAnAnalogOutputTakesTheSWordsPlaceOrGoesAfterTheLastWord) {
  const auto speed = [](std::uint64_t offset, std::string value, SpeedForm form, int output = 0) {
    WordPatch patch{offset, 'S', std::move(value)};
    patch.form = form;
    patch.output = output;
    return patch;
  };
  const std::string text =
      "S4000 M3 (start)\n"    // 0: the spindle's start
      "G1 X1 Y2 F100\n"       // 17: a change on a move
      "G1 X2 S5000 Y3 ; s\n"  // 31: the input's S word, mid-line
      "S5100\n"               // 50: alone
      "g1x3s5200\n"           // 56: no blanks
      "G1 X4 M67 E0 Q6000\n"  // 66: posted before
      "G83 X5 Z-1 R1 Q0.5\n"  // 85: a peck's Q: no room
      "G1 X6 M64 P1\n"        // 104: another HAL output code: no room
      "G1 X7 M67 E1 Q3\n"     // 117: output 1 is not the speed's
      "G1 X8 S7000\n";        // 133: output 2 named
  const std::vector<WordPatch> patches{
      speed(0, "6400", SpeedForm::start),      speed(17, "6500", SpeedForm::synced),
      speed(31, "6600", SpeedForm::synced),    {31, 'F', "120"},
      speed(50, "6700", SpeedForm::synced),    speed(56, "6800", SpeedForm::synced),
      speed(66, "6900", SpeedForm::synced),    speed(85, "7000", SpeedForm::synced),
      speed(104, "7100", SpeedForm::synced),   speed(117, "7200", SpeedForm::synced),
      speed(133, "7300", SpeedForm::synced, 2)};
  EXPECT_EQ(patched(text, patches),
            "S6400 M3 M68 E0 Q6400 (start)\n"
            "G1 X1 Y2 F100 M67 E0 Q6500\n"
            "G1 X2 M67 E0 Q6600 Y3 F120 ; s\n"
            "M67 E0 Q6700\n"
            "g1x3M67E0Q6800\n"
            "G1 X4 M67 E0 Q6900\n"
            "G83 X5 Z-1 R1 Q0.5 S7000\n"
            "G1 X6 M64 P1 S7100\n"
            "G1 X7 M67 E1 Q3 S7200\n"
            "G1 X8 M67 E2 Q7300\n");
  // A start on a line posted before keeps its M68 and S word, both set.
  EXPECT_EQ(patched("S1 M3 M68 E0 Q1\n", std::vector{speed(0, "900", SpeedForm::start)}),
            "S900 M3 M68 E0 Q900\n");
  // S0 and plain S patches are untouched by the forms.
  EXPECT_EQ(patched("G1 X1 S100\n", std::vector<WordPatch>{{0, 'S', "0"}}), "G1 X1 S0\n");
}

TEST(Writer, RejectsPatchesThatAreNotLineStarts) {
  const std::string text = "G1 X1\nG1 X2\n";
  const std::vector<WordPatch> bad{{3, 'S', "1"}};
  EXPECT_THROW(patched(text, bad), std::invalid_argument);
  const std::vector<WordPatch> letter{{0, 'X', "1"}};
  EXPECT_THROW(patched(text, letter), std::invalid_argument);
}

}  // namespace
}  // namespace vcpost::gcode
