// The report files of `vcpost post --report` and `vcpost report -o`: their
// formats, opened before any work; the CSV streamed, the JSON and HTML
// written at the end; and the inputs the report and --summary-json name.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "postproc/cli/atomic_file.h"
#include "postproc/cli/job_runner.h"
#include "postproc/cli/model_loader.h"
#include "postproc/cli/post_options.h"
#include "postproc/post/post_job.h"
#include "postproc/report/csv_writer.h"
#include "postproc/report/report.h"

namespace vcpost::cli {

// One report file: its format and, for the streamed CSV, its open file.
struct ReportFile {
  std::string path;  // "-": standard output (JSON)
  report::ReportFormat format = report::ReportFormat::json;
  std::unique_ptr<AtomicFile> file;
  std::unique_ptr<report::CsvWriter> csv;
};

// Every file of args.reports, its format known and its file open (an
// unknown format or an unwritable folder fails before any work).
std::vector<ReportFile> open_reports(const PostArguments& args);

// The charting library the HTML report embeds (E2004 when missing).
std::string read_chart_library();

// A CSV writer on each .csv report's file; the writers, to feed the rows to.
std::vector<report::CsvWriter*> start_csv_reports(std::vector<ReportFile>& reports);

// Finishes the CSV reports and writes the JSON and HTML ones, each file
// committed; returns what goes to standard output ('-').
std::string write_reports(const report::ReportData& data, std::vector<ReportFile>& reports,
                          const std::string& chart_library);

// The report is drawn for one tool and vc: the first section the job
// evaluates (read ahead), or else the plain --tool and --vc. Its top views
// span `plan` (the model's bounds, or without a model the path's) grown by
// the tool's radius.
report::ReportInputs report_inputs(const PostArguments& args, const post::PostSettings& settings,
                                   const LoadedModel& model,
                                   const machines::MachineProfile& profile, post::ProgramKind kind,
                                   const std::optional<post::ToolSection>& first,
                                   const Eigen::AlignedBox3d& plan);

// The inputs `post --summary-json` names, as the report names them.
report::ReportInputs summary_inputs(const PostArguments& args, const JobRun& run);

}  // namespace vcpost::cli
