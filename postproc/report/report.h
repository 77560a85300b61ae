// The dry-run report of a post job: collects every evaluated point (hand
// `point_sink()` to post::post_program) into bounded statistics and plot
// data, then renders the HTML page (the JSON documents: json_documents.h). The per-point CSV
// is streamed by csv_writer.h from the same rows. No I/O here.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "postproc/post/post_job.h"
#include "postproc/report/json_documents.h"
#include "postproc/report/plot_data.h"
#include "postproc/report/point_row.h"
#include "postproc/report/statistics.h"

namespace vcpost::report {

// Where a tool section's evaluated points start on the cutting-time axis.
struct SectionMark {
  std::uint32_t section = 0;  // post::ToolSection::index
  double cut_time_s = 0;
};

// Everything the page and the summary need, sized independently of the
// number of points.
struct ReportData {
  ReportInputs inputs;
  post::PostSummary summary;  // the job's own totals (S/F words, times)
  ReportStatistics statistics;
  double run_time_s = 0;
  // Along cutting time, min/max decimated: vc before/after (m/min), S
  // before/after (rpm).
  std::vector<PlotPoint> vc_before, vc_after, s_before, s_after;
  std::uint64_t plot_bucket_points = 1;  // points per bucket of the decimation
  DeviationHistogram histogram;
  // Plan-view grids: signed worst deviation (fraction) and the highest cusp (um).
  PlanGrid dev_before, dev_after, cusp;
  std::vector<Region> regions_after, regions_before;
  std::vector<SectionMark> section_marks;  // one per section with evaluated points
  // With an in-process stock: the highest real ap per cell (mm, the
  // stock's, 0 where nothing was there to cut).
  PlanGrid ap;
};

class ReportCollector {
 public:
  // Plot sizes: up to 2 * plot_buckets buckets along time, plan grids with
  // `grid_cells` cells along the longer side.
  explicit ReportCollector(ReportInputs inputs, std::size_t plot_buckets = 2000,
                           int grid_cells = 240);

  // Adds one point (in path order) and returns its row (valid until the
  // next call), e.g. for the CSV writer.
  const PointRow& add(const pipeline::PathSample& sample, const pipeline::PointResult& result,
                      const post::PointRecord& record);

  // A PointSink for post_program that adds every point and then hands its
  // row to `also` (when given).
  post::PointSink point_sink(std::function<void(const PointRow&)> also = {});

  ReportData finish(const post::PostSummary& summary, double run_time_s) const;

 private:
  ReportInputs inputs_;
  PointRow row_;
  double cut_time_s_ = 0;
  StatisticsAccumulator statistics_;
  MinMaxDecimator decimator_;
  DeviationHistogram histogram_;
  PlanGrid dev_before_, dev_after_, cusp_, ap_;
  RegionTracker regions_after_, regions_before_;
  std::vector<SectionMark> section_marks_;
};

// Regions listed: vc off nominal by more than these shares.
inline constexpr double kRegionThresholdAfter = 0.05;
inline constexpr double kRegionThresholdBefore = 0.10;

// The self-contained HTML page. `chart_library` is the charting library's
// JavaScript (Chart.js 3), inlined as it is. Throws std::invalid_argument
// when it would end the inline script early (contains "</script").
std::string render_html(const ReportData& data, std::string_view chart_library);

// Report formats, by the output file's extension.
enum class ReportFormat { json, csv, html };
// .json, .csv, .html or .htm (any case); empty for anything else.
std::optional<ReportFormat> format_of(std::string_view file_name);

}  // namespace vcpost::report
