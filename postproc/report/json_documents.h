// The two JSON documents vcpost writes, in one vocabulary (docs/json.md,
// checked against docs/vcpost.schema.json by the tests): the report's
// summary (`vcpost report -o FILE.json`, embedded in the HTML page) and the
// job summary of `vcpost post --summary-json`. A quantity has one key in
// both; the version after the slash changes when a key is renamed or
// removed (adding a key keeps it). No I/O here.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "postproc/post/post_job.h"
#include "postproc/report/point_row.h"

namespace vcpost::report {

struct ReportData;

inline constexpr const char* kReportSchema = "vcpost-report/2";
inline constexpr const char* kSummarySchema = "vcpost-summary/2";

// The report's summary: every key of the job summary's vocabulary, with
// percentiles, surface quality and the plots' section marks.
nlohmann::json report_json(const ReportData& data);

// `post --summary-json`. `inputs.tool` and `inputs.vc_nominal` are written
// as null when `tool_posted` is false (no section was posted).
nlohmann::json post_summary_json(const ReportInputs& inputs, bool tool_posted,
                                 const post::PostSummary& summary, double run_time_s);

}  // namespace vcpost::report
