#include "postproc/post/stock_summary.h"

#include <cmath>
#include <sstream>

namespace vcpost::post {

std::vector<std::string> stock_lines(const StockSummary& s) {
  std::vector<std::string> lines;
  std::ostringstream grid;  // numbers as the stream writes them
  grid << "in-process stock: " << s.source << ", " << s.nx << " x " << s.ny << " cells of "
       << s.cell_mm << " mm (" << s.cell_note << "), "
       << std::round(static_cast<double>(s.memory_bytes) / (1 << 20) * 10) / 10 << " MB with "
       << s.copies << (s.copies == 1 ? " copy" : " copies") << ", built in "
       << std::round(s.build_s * 100) / 100 << " s; sections swept:";
  if (s.swept.empty()) grid << " none";
  for (const std::uint32_t i : s.swept) grid << " " << i;
  lines.push_back(grid.str());
  std::ostringstream points;
  points << "ap from the stock at " << s.points_stock << " points";
  if (s.points_clamped > 0) points << " (" << s.points_clamped << " held under the tool's D)";
  points << ", nothing to cut at " << s.points_air << ", --ap at " << s.points_given
         << " (tilted); max " << std::round(s.ap_max_mm * 1000) / 1000 << " mm";
  lines.push_back(points.str());
  if (s.stock_time_s > 0) {
    auto pct = [&](double t) { return static_cast<int>(std::round(100 * t / s.stock_time_s)); };
    std::ostringstream bands;
    bands << "cutting time by ap against --ap " << s.nominal_ap_mm
          << " mm: " << pct(s.band_time_s[0]) << " % at most, " << pct(s.band_time_s[1])
          << " % up to 1.5x, " << pct(s.band_time_s[2]) << " % up to 2x, " << pct(s.band_time_s[3])
          << " % beyond; above it at " << s.over_nominal_points << " points, "
          << std::round(s.over_nominal_time_s * 10) / 10 << " s";
    lines.push_back(bands.str());
  }
  return lines;
}

}  // namespace vcpost::post
