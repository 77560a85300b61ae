// The report files of a job: opened before any work, the CSV streamed
// while the points come, the JSON and HTML written at the end.
#include "postproc/cli/job_reports.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "postproc/cli/commands.h"
#include "postproc/report/chart_library.h"

namespace vcpost::cli {

report::ReportInputs summary_inputs(const PostArguments& args, const JobRun& run) {
  report::ReportInputs in;
  in.program = args.program == "-" ? "<stdin>" : args.program;
  in.program_kind = std::string(post::to_string(run.summary.kind));
  in.model = args.model;
  in.model_kind = run.model.kind;
  in.model_description = run.model.description;
  in.machine = run.profile.name();
  if (run.tool) in.tool = geometry::to_string(*run.tool);
  if (run.vc) in.vc_nominal = *run.vc;
  in.policy = args.policy;
  in.cl_point = args.cl_point;
  in.ap_mm = args.ap;
  in.ae_mm = args.ae;
  in.ae_override = args.ae_override;
  in.adjust_feed = args.adjust_feed;
  in.spacing_mm = args.spacing;
  in.n_min_rpm = run.profile.spindle().n_min_rpm;
  in.n_max_rpm = run.profile.spindle().n_max_rpm;
  return in;
}

std::vector<ReportFile> open_reports(const PostArguments& args) {
  std::vector<ReportFile> out;
  for (const std::string& path : args.reports) {
    ReportFile r;
    r.path = path;
    if (path != "-") {
      const auto format = report::format_of(path);
      if (!format) {
        throw CommandError("report '" + path +
                           "': unknown format; name the file .json, .csv or .html");
      }
      r.format = *format;
    }
    if (path != "-") r.file = std::make_unique<AtomicFile>(path);  // fails before any work
    out.push_back(std::move(r));
  }
  return out;
}

std::string read_chart_library() {
  const std::string path(report::chart_library_path());
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw CommandError(Code::E2004,
                       "HTML report: the charting library '" + path + "' is missing; install " +
                           std::string(report::kChartLibraryPackage) + " (scripts/setup.sh)");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<report::CsvWriter*> start_csv_reports(std::vector<ReportFile>& reports) {
  std::vector<report::CsvWriter*> writers;
  for (auto& r : reports) {
    if (r.format != report::ReportFormat::csv) continue;
    AtomicFile* out = r.file.get();
    r.csv =
        std::make_unique<report::CsvWriter>([out](std::string_view bytes) { out->write(bytes); });
    writers.push_back(r.csv.get());
  }
  return writers;
}

std::string write_reports(const report::ReportData& data, std::vector<ReportFile>& reports,
                          const std::string& chart_library) {
  std::string to_stdout;
  for (auto& r : reports) {
    if (r.format == report::ReportFormat::csv) {
      r.csv->finish();
      r.file->commit();
      continue;
    }
    std::string bytes;
    if (r.format == report::ReportFormat::json) {
      bytes = report::report_json(data).dump(2) + "\n";
    } else {
      try {
        bytes = report::render_html(data, chart_library);
      } catch (const std::invalid_argument& e) {
        throw CommandError(Code::E2004, std::string("HTML report: ") + e.what());
      }
    }
    if (r.path == "-") {
      to_stdout += bytes;
    } else {
      r.file->write(bytes);
      r.file->commit();
    }
  }
  return to_stdout;
}

report::ReportInputs report_inputs(const PostArguments& args, const post::PostSettings& settings,
                                   const LoadedModel& model,
                                   const machines::MachineProfile& profile, post::ProgramKind kind,
                                   const std::optional<post::ToolSection>& first,
                                   const Eigen::AlignedBox3d& plan) {
  geometry::Tool tool = geometry::Tool::ball(10);
  const tools::ToolChoices& choices = *settings.tools;
  double vc = choices.vc.value_or(0);
  if (first) {
    tool = *first->entry->geometry();
    vc = first->vc_nominal;
  } else if (const auto& every = choices.table.every_tool(); every && every->geometry()) {
    tool = *every->geometry();
  }
  if (!(vc > 0)) vc = choices.vc_by_tool.begin()->second;
  report::ReportInputs in;
  in.program = args.program == "-" ? "<stdin>" : args.program;
  in.program_kind = std::string(post::to_string(kind));
  in.model = args.model;
  in.model_kind = model.kind;
  in.model_description = model.description;
  in.machine = profile.name();
  in.tool = geometry::to_string(tool);
  in.policy = args.policy;
  in.cl_point = args.cl_point;
  in.tool_shape = tool;
  in.cl_kind = settings.point.cl_point;
  in.vc_nominal = vc;
  in.ap_mm = args.ap;
  in.ae_mm = args.ae;
  in.ae_override = args.ae_override;
  in.adjust_feed = args.adjust_feed;
  in.spacing_mm = args.spacing;
  in.n_min_rpm = profile.spindle().n_min_rpm;
  in.n_max_rpm = profile.spindle().n_max_rpm;
  // Top views over the plan grown by the tool radius (programmed points of
  // a ball touching the model lie within it).
  const double margin = tool.radius() + 1;
  if (!plan.isEmpty()) {
    in.plan_min = plan.min().head<2>() - Eigen::Vector2d::Constant(margin);
    in.plan_max = plan.max().head<2>() + Eigen::Vector2d::Constant(margin);
  } else {
    in.plan_min = Eigen::Vector2d::Constant(-margin);
    in.plan_max = Eigen::Vector2d::Constant(margin);
  }
  return in;
}

}  // namespace vcpost::cli
