// `vcpost report`: the post job run dry. Nothing is written but the report:
// how far vc deviates from nominal with the program's own S, what the
// rewrite would achieve on this machine, and where its limits bind.
#include "postproc/cli/commands.h"
#include "postproc/cli/end_of_run.h"
#include "postproc/cli/job_runner.h"
#include "postproc/cli/post_options.h"

namespace vcpost::cli {
namespace {

constexpr const char* kReportDescription =
    "Runs the post job dry (same options as `vcpost post`) and writes its report: the format\n"
    "follows the file name: .json (summary with stable keys), .csv (one row per evaluated point),\n"
    ".html (one self-contained page with plots, opens offline); '-' prints the JSON summary.\n"
    "\n"
    "Example:\n"
    "  vcpost report finish.nc --model part.step --tool ball:10 --vc 120 --ap 0.3 \\\n"
    "                --machine mazak-3axis -o finish.html -o finish.csv\n";

}  // namespace

void add_report_command(CLI::App& app) {
  auto args = std::make_shared<PostArguments>();
  auto* report = app.add_subcommand(
      "report", "Dry run: report how vc deviates, before and after (JSON, CSV, HTML)");
  report->description(kReportDescription);
  add_job_options(*report, *args);
  report
      ->add_option("-o,--output", args->reports,
                   "report file: .json, .csv or .html ('-': JSON on standard output); may be given "
                   "more than once")
      ->required();
  report->callback([args] { finish_job(*args, run_job(*args, false)); });
}

}  // namespace vcpost::cli
