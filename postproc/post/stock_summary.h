// What the in-process stock (issue 44) was and what it gave: for the
// end-of-run lines, the JSON summary and the report.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vcpost::post {

// The bands of the real ap against the nominal --ap, in this order: at most
// the nominal, up to 1.5 times it, up to twice it, beyond.
inline constexpr std::array<double, 3> kApBandLimits = {1.0, 1.5, 2.0};

struct StockSummary {
  std::string source;  // e.g. "BLK FORM at part.h:19", "--stock-box", "--stock-model stock.stl"
  Eigen::AlignedBox3d box;  // the stock's extent, mm
  double cell_mm = 0;
  std::uint32_t nx = 0, ny = 0;
  std::string cell_note;           // how the cell was chosen (default, coarsened)
  std::uint64_t memory_bytes = 0;  // the height field and the copies kept of it
  std::uint32_t copies = 0;  // copies kept: one per evaluated section but the last (the field)
  std::vector<std::uint32_t> swept;   // sections swept (ToolSection::index), in program order
  std::vector<std::string> warnings;  // sections left unswept (W4730, W4731), in words
  double build_s = 0;                 // the read-ahead's time

  // The evaluated points of the posted sections.
  double nominal_ap_mm = 0;          // --ap
  std::uint64_t points_stock = 0;    // ap from the stock (clamped ones included)
  std::uint64_t points_clamped = 0;  // ap held under the tool's diameter
  std::uint64_t points_air = 0;      // no material there: nothing cut
  std::uint64_t points_given = 0;    // --ap (tilted frames)
  double stock_time_s = 0, air_time_s = 0;
  // Cutting time of the stock's points in each ap band (kApBandLimits).
  std::array<double, 4> band_time_s{};
  std::uint64_t over_nominal_points = 0;  // ap above --ap
  double over_nominal_time_s = 0;
  double ap_max_mm = 0;
};

// The summary in words, one line each (no warnings: those are in
// `warnings`): the stock's source, grid and memory, the sections swept, the
// share of cutting time in each ap band and the time above --ap.
std::vector<std::string> stock_lines(const StockSummary& stock);

}  // namespace vcpost::post
