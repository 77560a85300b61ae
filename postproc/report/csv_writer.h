// The per-point CSV of the report: a header row, then one row per
// evaluated point in path order, streamed through a sink in large pieces
// (memory does not grow with the program).
//
// Columns (the first 24 are the and keep their names and order):
// line, x y z (programmed point, mm), cc_x.. (contact point), n_x.. (unit
// normal the tool sees), f_x.. (unit feed on the tangent plane), ae, d_ref,
// d_max, d_min, d_cut (mm), s_before, s_after (rpm), vc_before, vc_after
// (m/min at d_ref), dev_pct (vc_after / vc_nominal - 1, %), flags
// (`|`-separated, see point_row.h); then time_s, weight_s, dev_before_pct,
// status, ae_source, bound, cusp_um, ra_um, rz_um. Missing values are empty.
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "postproc/report/point_row.h"

namespace vcpost::report {

inline constexpr std::string_view kCsvHeader =
    "line,x,y,z,cc_x,cc_y,cc_z,n_x,n_y,n_z,f_x,f_y,f_z,ae,d_ref,d_max,d_min,d_cut,"
    "s_before,s_after,vc_before,vc_after,dev_pct,flags,"
    "time_s,weight_s,dev_before_pct,status,ae_source,bound,cusp_um,ra_um,rz_um,normal,ap_mm,ap_"
    "source";

class CsvWriter {
 public:
  // Writes the header at once (through `sink`).
  explicit CsvWriter(std::function<void(std::string_view)> sink, std::size_t chunk_bytes = 1 << 20);
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  void write(const PointRow& row);
  // Hands the rest to the sink; call once at the end.
  void finish();
  std::uint64_t rows() const { return rows_; }

 private:
  std::function<void(std::string_view)> sink_;
  std::size_t chunk_bytes_;
  std::string buffer_;
  std::uint64_t rows_ = 0;
};

// The text of one row without its line end (for tests and the writer).
std::string csv_row(const PointRow& row);

}  // namespace vcpost::report
