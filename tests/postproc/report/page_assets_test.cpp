// The report's page as embedded from postproc/report/page/: the build
// carried each file whole, and the template holds every slot the writer
// fills exactly once, in the order it fills them.
#include "postproc/report/page_assets.h"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <string>
#include <string_view>

#include "tests/postproc/cli_run_support.h"

namespace {

namespace assets = vcpost::report::assets;

std::size_t count(std::string_view text, std::string_view what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string_view::npos;
       at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

TEST(ReportPage, EmbedsTheFilesByteForByte) {
  const std::filesystem::path page =
      std::filesystem::path(VCPOST_SOURCE_DIR) / "postproc/report/page";
  EXPECT_EQ(assets::page_html, vcpost::testing::slurp(page / "report.html"));
  EXPECT_EQ(assets::page_css, vcpost::testing::slurp(page / "report.css"));
  EXPECT_EQ(assets::page_js, vcpost::testing::slurp(page / "report.js"));
}

TEST(ReportPage, TemplateHoldsEachSlotOnceInOrder) {
  constexpr std::array<std::string_view, 5> kSlots = {"@TITLE@", "@STYLE@", "@DATA@", "@CHART_JS@",
                                                      "@SCRIPT@"};
  std::size_t last = 0;
  for (const std::string_view slot : kSlots) {
    EXPECT_EQ(count(assets::page_html, slot), 1U) << slot;
    const std::size_t at = assets::page_html.find(slot);
    ASSERT_NE(at, std::string_view::npos) << slot;
    EXPECT_GE(at, last) << slot << " comes before the slot it should follow";
    last = at;
    // The style sheet and the script fill their elements: neither holds one.
    EXPECT_EQ(count(assets::page_css, slot) + count(assets::page_js, slot), 0U) << slot;
  }
}

}  // namespace
