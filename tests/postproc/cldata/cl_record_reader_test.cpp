// The lexical layer: records, continuation, comments, positions, limits.
#include <gtest/gtest.h>

#include <sstream>

#include "postproc/cldata/record_reader.h"

namespace vcpost::cldata {
namespace {

std::vector<ClRecord> records_of(const std::string& text, ClLexOptions options = {}) {
  std::istringstream in(text);
  ClRecordReader reader(in, "t.cl", options);
  std::vector<ClRecord> out;
  ClRecord r;
  // Copy views into owned storage is not needed: each record is checked
  // before the next read, so keep only kinds and numbers here.
  while (reader.next(r)) out.push_back(r);
  return out;
}

TEST(ClRecordReader, StatementWithParametersAndColumns) {
  std::istringstream in("  GOTO / 1.5, -2 ,+3.25e1\n");
  ClRecordReader reader(in, "t.cl");
  ClRecord r;
  ASSERT_TRUE(reader.next(r));
  EXPECT_EQ(r.kind, ClRecordKind::statement);
  EXPECT_EQ(r.major, "GOTO");
  EXPECT_EQ(r.separator, '/');
  EXPECT_EQ(r.source.line, 1u);
  EXPECT_EQ(r.source.column, 3u);
  EXPECT_EQ(r.source.offset, 2u);
  ASSERT_EQ(r.params.size(), 3u);
  EXPECT_DOUBLE_EQ(r.params[0].value, 1.5);
  EXPECT_DOUBLE_EQ(r.params[1].value, -2.0);
  EXPECT_DOUBLE_EQ(r.params[2].value, 32.5);
  EXPECT_EQ(r.params[0].column, 10u);  // "  GOTO / 1.5": the '1' is column 10
  EXPECT_EQ(r.params[1].column, 15u);
  EXPECT_FALSE(reader.next(r));
}

TEST(ClRecordReader, ContinuationJoinsLinesAndKeepsEachParametersLine) {
  std::istringstream in(
      "CIRCLE / 7.4550, 5.8500, 1.8000,  $\r\n0.0000, 0.0000, 1.0000,  0.0250\r\nFINI\r\n");
  ClRecordReader reader(in, "t.cl");
  ClRecord r;
  ASSERT_TRUE(reader.next(r));
  EXPECT_EQ(r.major, "CIRCLE");
  ASSERT_EQ(r.params.size(), 7u);
  EXPECT_DOUBLE_EQ(r.params[6].value, 0.025);
  EXPECT_EQ(r.params[2].line, 1u);
  EXPECT_EQ(r.params[3].line, 2u);
  EXPECT_EQ(r.params[3].column, 1u);
  EXPECT_EQ(r.params[6].column, 26u);
  ASSERT_TRUE(reader.next(r));
  EXPECT_EQ(r.major, "FINI");
  EXPECT_EQ(r.source.line, 3u);
}

TEST(ClRecordReader, CommentsTextRecordsAndTwoWordMajor) {
  std::istringstream in(
      "$$ centerline data\nPARTNO CORE_WORK (A)\ntool path/FIXED_CONTOUR,TOOL,BALL_MILL\n"
      "GOTO/1,2,3 $$ trailing comment\nEND-OF-PATH\n");
  ClRecordReader reader(in, "t.cl");
  ClRecord r;
  ASSERT_TRUE(reader.next(r));
  EXPECT_EQ(r.kind, ClRecordKind::comment);
  EXPECT_EQ(r.text, "centerline data");
  ASSERT_TRUE(reader.next(r));
  EXPECT_EQ(r.major, "PARTNO");
  EXPECT_EQ(r.separator, ' ');
  EXPECT_EQ(r.text, "CORE_WORK (A)");
  EXPECT_TRUE(r.params.empty());
  ASSERT_TRUE(reader.next(r));
  EXPECT_EQ(r.major, "TOOL PATH");
  ASSERT_EQ(r.params.size(), 3u);
  EXPECT_FALSE(r.params[0].is_number);
  EXPECT_EQ(r.params[0].text, "FIXED_CONTOUR");
  ASSERT_TRUE(reader.next(r));
  EXPECT_EQ(r.major, "GOTO");
  ASSERT_EQ(r.params.size(), 3u);
  EXPECT_DOUBLE_EQ(r.params[2].value, 3.0);
  ASSERT_TRUE(reader.next(r));
  EXPECT_EQ(r.major, "END-OF-PATH");
  EXPECT_EQ(r.separator, 0);
}

TEST(ClRecordReader, BareCoordinateLineIsAPointsRecord) {
  const auto records = records_of("GOTO / 7.4675, 5.8283, 1.8000\n       7.4675, 5.8717, 1.8000\n");
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[1].kind, ClRecordKind::points);
  EXPECT_EQ(records[1].source.column, 8u);
}

TEST(ClRecordReader, MalformedNumberStaysAWordForTheReaderToJudge) {
  std::istringstream in("GOTO/1.2.3,4,5\n");
  ClRecordReader reader(in, "t.cl");
  ClRecord r;
  ASSERT_TRUE(reader.next(r));
  EXPECT_FALSE(r.params[0].is_number);
  EXPECT_EQ(r.params[0].text, "1.2.3");
}

TEST(ClRecordReader, NulByteIsRefusedWithItsColumn) {
  std::string text = "GOTO/1,2,3\nGOTO/1,";
  text += '\0';
  text += "2,3\n";
  std::istringstream in(text);
  ClRecordReader reader(in, "t.cl");
  ClRecord r;
  ASSERT_TRUE(reader.next(r));
  try {
    reader.next(r);
    FAIL() << "no error";
  } catch (const ClError& e) {
    EXPECT_EQ(e.code(), Code::E3102);
    EXPECT_EQ(e.diagnostic().line, 2u);
    EXPECT_EQ(e.diagnostic().column, 8u);
    EXPECT_STREQ(e.what(), "t.cl:2:8: error[E3102]: invalid byte 0x00 in CL data");
  }
}

TEST(ClRecordReader, TenMegabyteLineIsRefusedWithoutBufferingIt) {
  std::string text = "GOTO/1,2,3\nPPRINT ";
  text.append(10u << 20, 'A');
  text += "\nFINI\n";
  std::istringstream in(text);
  ClRecordReader reader(in, "t.cl");
  ClRecord r;
  ASSERT_TRUE(reader.next(r));
  try {
    reader.next(r);
    FAIL() << "no error";
  } catch (const ClError& e) {
    EXPECT_EQ(e.code(), Code::E3101);
    EXPECT_EQ(e.diagnostic().line, 2u);
  }
}

TEST(ClRecordReader, ContinuationAtEndOfFileIsTruncation) {
  std::istringstream in("GOTO/1,2,$\n");
  ClRecordReader reader(in, "t.cl");
  ClRecord r;
  EXPECT_THROW(
      {
        try {
          reader.next(r);
        } catch (const ClError& e) {
          EXPECT_EQ(e.code(), Code::E3106);
          throw;
        }
      },
      ClError);
}

TEST(ClRecordReader, LastLineWithoutNewlineAndBlankLines) {
  const auto records = records_of("\n\nRAPID\n\nGOTO/0,0,1");
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[1].source.line, 5u);
}

}  // namespace
}  // namespace vcpost::cldata
