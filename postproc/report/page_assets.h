// The HTML report's page as files of its own (postproc/report/page/),
// embedded byte for byte at build time (cmake/embed_files.cmake).
#pragma once

#include <string_view>

namespace vcpost::report::assets {

// page/report.html: the page, with the slots @TITLE@, @STYLE@, @DATA@,
// @CHART_JS@ and @SCRIPT@ once each, in that order.
extern const std::string_view page_html;
// page/report.css: the page's style sheet (@STYLE@).
extern const std::string_view page_css;
// page/report.js: the page's drawing code (@SCRIPT@), run after Chart.js.
extern const std::string_view page_js;

}  // namespace vcpost::report::assets
