// core/csv_line.h: the one CSV record splitter of the error-table generator
// and the deff batch reader, on records whose cells are written out by hand.
#include "core/csv_line.h"

#include <gtest/gtest.h>

namespace vcpost::csv {
namespace {

using Cells = std::vector<std::string>;

TEST(CsvLine, PlainQuotedAndEmptyCells) {
  EXPECT_EQ(split_line("a,b,c").cells, (Cells{"a", "b", "c"}));
  EXPECT_EQ(split_line("").cells, (Cells{""}));
  EXPECT_EQ(split_line("a,,").cells, (Cells{"a", "", ""}));
  EXPECT_EQ(split_line(R"("a, b","say ""hi""",c)").cells, (Cells{"a, b", R"(say "hi")", "c"}));
  EXPECT_FALSE(split_line(R"("x",y)").error);
}

TEST(CsvLine, BlanksKeptUnlessTrimmed) {
  EXPECT_EQ(split_line(" a ,\tb").cells, (Cells{" a ", "\tb"}));
  EXPECT_EQ(split_line(" a ,\tb\t, \"c d\" ", {.trim_blanks = true}).cells,
            (Cells{"a", "b", "c d"}));
}

TEST(CsvLine, ErrorsNameTheirCell) {
  const SplitLine open = split_line(R"(a,"b)");
  EXPECT_EQ(open.error, LineError::unterminated_quote);
  EXPECT_EQ(open.error_cell, 2u);
  EXPECT_EQ(open.cells, (Cells{"a"}));
  const SplitLine after = split_line(R"(a,b,"c"d)");
  EXPECT_EQ(after.error, LineError::text_after_quote);
  EXPECT_EQ(after.error_cell, 3u);
  // A blank after the closing quote is text unless blanks are trimmed.
  EXPECT_EQ(split_line(R"("c" ,d)").error, LineError::text_after_quote);
  EXPECT_FALSE(split_line(R"("c" ,d)", {.trim_blanks = true}).error);
}

TEST(CsvLine, AQuoteInsideAnUnquotedCell) {
  EXPECT_EQ(split_line(R"(a"b,c)").cells, (Cells{R"(a"b)", "c"}));
  const SplitLine strict = split_line(R"(x,a"b)", {.quote_in_unquoted = false});
  EXPECT_EQ(strict.error, LineError::quote_in_unquoted);
  EXPECT_EQ(strict.error_cell, 2u);
}

}  // namespace
}  // namespace vcpost::csv
