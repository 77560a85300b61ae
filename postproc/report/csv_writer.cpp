#include "postproc/report/csv_writer.h"

#include <charconv>
#include <cmath>

namespace vcpost::report {
namespace {

// Fixed-point with trailing zeros trimmed ("9330", "0.25"); fast enough
// for ten million rows (no locale, no printf).
void append_number(std::string& out, double value, int decimals) {
  if (!std::isfinite(value)) return;
  char buffer[64];
  const auto [end, ec] =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  if (ec != std::errc()) return;
  char* last = end;
  if (decimals > 0) {
    while (last[-1] == '0') --last;
    if (last[-1] == '.') --last;
  }
  std::string_view text(buffer, static_cast<std::size_t>(last - buffer));
  if (text == "-0") text = "0";
  out.append(text);
}

void field(std::string& out, const std::optional<double>& value, int decimals) {
  out += ',';
  if (value) append_number(out, *value, decimals);
}

void field(std::string& out, double value, int decimals) {
  out += ',';
  append_number(out, value, decimals);
}

void vector_fields(std::string& out, const std::optional<Eigen::Vector3d>& v, int decimals) {
  for (int i = 0; i < 3; ++i) {
    out += ',';
    if (v) append_number(out, (*v)[i], decimals);
  }
}

void append_row(std::string& out, const PointRow& r) {
  char line[16];
  const auto [end, ec] = std::to_chars(line, line + sizeof line, r.line);
  out.append(line, ec == std::errc() ? static_cast<std::size_t>(end - line) : 0);
  vector_fields(out, r.point, 4);
  vector_fields(out, r.cc, 4);
  vector_fields(out, r.normal, 6);
  vector_fields(out, r.cc ? std::optional<Eigen::Vector3d>(r.feed) : std::nullopt, 6);
  field(out, r.ae, 4);
  field(out, r.d_ref, 4);
  field(out, r.d_max, 4);
  field(out, r.d_min, 4);
  field(out, r.d_cut, 4);
  field(out, r.s_before, 2);
  field(out, r.s_after, 2);
  field(out, r.vc_before, 3);
  field(out, r.vc_after, 3);
  field(out, r.dev_after ? std::optional<double>(100 * *r.dev_after) : std::nullopt, 3);
  out += ',';
  out += flags_text(r.flags);
  field(out, r.time_s, 4);
  field(out, r.weight_s, 6);
  field(out, r.dev_before ? std::optional<double>(100 * *r.dev_before) : std::nullopt, 3);
  out += ',';
  out += geometry::to_string(r.status);
  out += ',';
  out += pipeline::to_string(r.ae_source);
  out += ',';
  out += plan::to_string(r.bound);
  field(out, r.cusp_um, 3);
  field(out, r.ra_um, 3);
  field(out, r.rz_um, 3);
  out += ',';
  out += r.normal_source ? pipeline::to_string(*r.normal_source) : "model";
  field(out, r.ap, 4);
  out += ',';
  if (r.ap) out += pipeline::to_string(r.ap_source);
}

}  // namespace

std::string csv_row(const PointRow& row) {
  std::string out;
  append_row(out, row);
  return out;
}

CsvWriter::CsvWriter(std::function<void(std::string_view)> sink, std::size_t chunk_bytes)
    : sink_(std::move(sink)), chunk_bytes_(chunk_bytes) {
  buffer_.reserve(chunk_bytes_ + 1024);
  buffer_.append(kCsvHeader);
  buffer_ += '\n';
}

void CsvWriter::write(const PointRow& row) {
  append_row(buffer_, row);
  buffer_ += '\n';
  ++rows_;
  if (buffer_.size() >= chunk_bytes_) {
    sink_(buffer_);
    buffer_.clear();
  }
}

void CsvWriter::finish() {
  if (!buffer_.empty()) sink_(buffer_);
  buffer_.clear();
}

}  // namespace vcpost::report
