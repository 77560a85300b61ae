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

TEST(Writer, RejectsPatchesThatAreNotLineStarts) {
  const std::string text = "G1 X1\nG1 X2\n";
  const std::vector<WordPatch> bad{{3, 'S', "1"}};
  EXPECT_THROW(patched(text, bad), std::invalid_argument);
  const std::vector<WordPatch> letter{{0, 'X', "1"}};
  EXPECT_THROW(patched(text, letter), std::invalid_argument);
}

}  // namespace
}  // namespace vcpost::gcode
