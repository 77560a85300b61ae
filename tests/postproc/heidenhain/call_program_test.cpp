// CALL PGM, SEL PGM / CALL SELECTED: the called program read inline, in its
// own units, with its own labels and QL parameters, the Q parameters and
// the control's state shared; its events are the CALL PGM block's; errors
// name the called file. Programs held in memory; values by hand, 1e-9 mm.
#include <gtest/gtest.h>

#include <map>

#include "tests/postproc/heidenhain/klartext_support.h"

namespace vcpost::heidenhain {
namespace {

using program::Event;
using testing::end_of;
using testing::expect_point;
using testing::motions;

const std::map<std::string, std::string, std::less<>> kPrograms = {
    {"SUB1",
     "BEGIN PGM SUB1 INCH\n"
     "L IX+1\n"        // 25.4 mm
     "QL1 = 3\n"       // its own QL1
     "Q5 = QL1 + 1\n"  // Q5 = 4, seen by the caller
     "FN 9: IF +0 EQU +0 GOTO LBL 1\n"
     "L IX+1\n"  // jumped over: its own LBL 1 below
     "LBL 1\n"
     "END PGM SUB1 INCH\n"},
    {"SELF", "BEGIN PGM SELF MM\nCALL PGM SELF\nEND PGM SELF MM\n"},
    {"ENDS", "BEGIN PGM ENDS MM\nL IX+1\nM30\nEND PGM ENDS MM\n"},
    {"BAD", "BEGIN PGM BAD MM\nL IX+1\nC X+0 Y+0 DR+\nEND PGM BAD MM\n"},
    {"TOOL", "BEGIN PGM TOOL MM\nTOOL CALL 2 Z S3000\nEND PGM TOOL MM\n"},
};

std::optional<CalledProgram> from_memory(std::string_view path, std::string_view) {
  const auto it = kPrograms.find(path);
  if (it == kPrograms.end()) return std::nullopt;
  return CalledProgram{it->second, it->first};
}

std::vector<Event> run_with_calls(const std::string& text) {
  Interpreter interpreter(text);
  interpreter.set_program_loader(from_memory);
  return testing::run("", &interpreter);
}

std::optional<Diagnostic> error_with_calls(const std::string& text, bool posting = false) {
  Interpreter interpreter(text);
  interpreter.set_program_loader(from_memory);
  if (posting) interpreter.refuse_tool_calls_in_called_programs();
  try {
    testing::run("", &interpreter);
  } catch (const KlartextError& e) {
    return e.diagnostic();
  }
  return std::nullopt;
}

TEST(KlartextCallProgram, ReadsTheCalledProgramInline) {
  const auto events = run_with_calls(
      "BEGIN PGM MAIN MM\n"
      "L X+0 Y+0 Z+0 F100\n"
      "QL1 = 7\n"
      "LBL 1\n"
      "CALL PGM SUB1\n"  // X 25.4 (inch), Q5 = 4
      "L X+Q5 Y+QL1\n"   // (4, 7): mm again, QL1 its own
      "SEL PGM \"SUB1\"\n"
      "CALL SELECTED\n"  // X 4 + 25.4
      "END PGM MAIN MM\n");
  const auto m = motions(events);
  ASSERT_EQ(m.size(), 4u);
  expect_point(end_of(m[1]), 25.4, 0, 0);
  expect_point(end_of(m[2]), 4, 7, 0);
  expect_point(end_of(m[3]), 29.4, 7, 0);
  EXPECT_EQ(program::source_of(m[1]).line, 5u);  // the CALL PGM block's
  EXPECT_EQ(program::source_of(m[3]).line, 8u);  // CALL SELECTED's
  EXPECT_EQ(
      std::count_if(events.begin(), events.end(),
                    [](const Event& e) { return std::holds_alternative<program::ProgramEnd>(e); }),
      1);  // the called END PGM returns
}

TEST(KlartextCallProgram, RefusedWithTheCalledFileNamed) {
  const std::string head = "BEGIN PGM MAIN MM\nL X+0 Y+0 Z+0 F100\n";
  EXPECT_EQ(error_with_calls(head + "CALL PGM NONE\n")->code, Code::E3331);
  EXPECT_EQ(error_with_calls(head + "CALL SELECTED\n")->code, Code::E3331);
  EXPECT_EQ(error_with_calls(head + "CALL PGM SELF\n")->code, Code::E3316);
  EXPECT_EQ(error_with_calls(head + "CALL PGM ENDS\n")->code, Code::E3319);
  const auto bad = error_with_calls(head + "CALL PGM BAD\n");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->code, Code::E3312);
  EXPECT_EQ(bad->file, "BAD");
  EXPECT_EQ(bad->line, 3u);
  EXPECT_EQ(format(*bad, "main.h").rfind("BAD:3:1: error[E3312]", 0), 0u);
  EXPECT_FALSE(error_with_calls(head + "CALL PGM TOOL\n"));  // reading: a TOOL CALL is fine
  EXPECT_EQ(error_with_calls(head + "CALL PGM TOOL\n", true)->code, Code::E3332);
  const std::string text = head + "CALL PGM SUB1\n";  // the interpreter reads it in place
  Interpreter alone(text);                            // no loader: refused, not skipped
  EXPECT_THROW(testing::run("", &alone), KlartextError);
}

}  // namespace
}  // namespace vcpost::heidenhain
