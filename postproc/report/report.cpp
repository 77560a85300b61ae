#include "postproc/report/report.h"

#include <algorithm>

#include "core/text.h"

namespace vcpost::report {
namespace {

enum Series : std::size_t { vc_before_k, vc_after_k, s_before_k, s_after_k, series_count };

}  // namespace

ReportCollector::ReportCollector(ReportInputs inputs, std::size_t plot_buckets, int grid_cells)
    : inputs_(std::move(inputs)),
      statistics_(inputs_.vc_nominal, inputs_.tool_shape.radius()),
      decimator_(series_count, plot_buckets),
      dev_before_(inputs_.plan_min, inputs_.plan_max, grid_cells),
      dev_after_(inputs_.plan_min, inputs_.plan_max, grid_cells),
      cusp_(inputs_.plan_min, inputs_.plan_max, grid_cells),
      ap_(inputs_.plan_min, inputs_.plan_max, grid_cells),
      regions_after_(kRegionThresholdAfter, 20),
      regions_before_(kRegionThresholdBefore, 20) {}

const PointRow& ReportCollector::add(const pipeline::PathSample& sample,
                                     const pipeline::PointResult& result,
                                     const post::PointRecord& record) {
  if (section_marks_.empty() || section_marks_.back().section != record.section)
    section_marks_.push_back({record.section, cut_time_s_});
  row_ = make_row(sample, result, record, inputs_);
  statistics_.add(row_);
  // Plots run along cutting time: the middle of the stretch the point stands for.
  const double x = cut_time_s_ + 0.5 * row_.weight_s;
  decimator_.add(x, {row_.vc_before, row_.vc_after, row_.s_before, row_.s_after});
  if (row_.dev_before && row_.dev_after) {
    histogram_.add(*row_.dev_before, *row_.dev_after, row_.weight_s);
    const Eigen::Vector2d xy = row_.point.head<2>();
    dev_before_.add(xy, *row_.dev_before);
    dev_after_.add(xy, *row_.dev_after);
  }
  if (row_.cusp_um) cusp_.add(row_.point.head<2>(), *row_.cusp_um);
  if (row_.ap && row_.ap_source != pipeline::ApSource::given)
    ap_.add(row_.point.head<2>(), *row_.ap);
  regions_after_.add(row_, row_.vc_after, row_.dev_after, cut_time_s_);
  regions_before_.add(row_, row_.vc_before, row_.dev_before, cut_time_s_);
  cut_time_s_ += row_.weight_s;
  return row_;
}

post::PointSink ReportCollector::point_sink(std::function<void(const PointRow&)> also) {
  return [this, also = std::move(also)](const pipeline::PathSample& sample,
                                        const pipeline::PointResult& result,
                                        const post::PointRecord& record) {
    const PointRow& row = add(sample, result, record);
    if (also) also(row);
  };
}

ReportData ReportCollector::finish(const post::PostSummary& summary, double run_time_s) const {
  return ReportData{inputs_,
                    summary,
                    statistics_.result(),
                    run_time_s,
                    decimator_.series(vc_before_k),
                    decimator_.series(vc_after_k),
                    decimator_.series(s_before_k),
                    decimator_.series(s_after_k),
                    decimator_.bucket_width(),
                    histogram_,
                    dev_before_,
                    dev_after_,
                    cusp_,
                    regions_after_.result(),
                    regions_before_.result(),
                    section_marks_,
                    ap_};
}

std::optional<ReportFormat> format_of(std::string_view file_name) {
  const auto dot = file_name.rfind('.');
  if (dot == std::string_view::npos) return std::nullopt;
  const std::string ext = to_lower(file_name.substr(dot + 1));
  if (ext == "json") return ReportFormat::json;
  if (ext == "csv") return ReportFormat::csv;
  if (ext == "html" || ext == "htm") return ReportFormat::html;
  return std::nullopt;
}

}  // namespace vcpost::report
