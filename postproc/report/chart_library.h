// Where the charting library the HTML report inlines is installed: Chart.js
// 3 from Debian's libjs-chart.js (scripts/setup.sh installs it). The build
// finds the file and bakes its absolute path in; the CLI reads it when it
// writes a page and says what to install when it is missing.
#pragma once

#include <string_view>

namespace vcpost::report {

// Absolute path of chart.min.js as configured at build time (may not exist
// on this machine any more; the caller checks).
std::string_view chart_library_path();

// The package that provides it, for error messages.
inline constexpr std::string_view kChartLibraryPackage = "libjs-chart.js";

}  // namespace vcpost::report
