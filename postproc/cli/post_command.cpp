// `vcpost post`: the main job. Reads the program and the model, posts, and
// writes the program atomically (and, with --report, the report beside it);
// all the work is in postproc/post/ and postproc/report/.
#include "postproc/cli/commands.h"
#include "postproc/cli/end_of_run.h"
#include "postproc/cli/job_runner.h"
#include "postproc/cli/post_options.h"

namespace vcpost::cli {
namespace {

constexpr const char* kPostDescription =
    "Rewrites the spindle speed S (and with --adjust-feed the feed F) of a ball-end finishing\n"
    "program so that the real cutting speed at the tool's working diameter stays at --vc, within\n"
    "what the machine profile allows. G-code input keeps every byte but the S/F words; APT CL\n"
    "input becomes G-code in the profile's format; without --model it is only translated,\n"
    "with its own speeds (a plain 3-axis post-processor: --vc and --ap are then not needed).\n"
    "\n"
    "Examples:\n"
    "  vcpost post finish.nc --model part.step --tool ball:10 --vc 120 --ap 0.3 \\\n"
    "              --machine mazak-3axis -o finish.ccs.nc --summary-json summary.json \\\n"
    "              --report finish.html\n"
    "  vcpost post whole_part.cls --machine linuxcnc-3axis -o whole_part.ngc\n";

}  // namespace

void add_post_command(CLI::App& app) {
  auto args = std::make_shared<PostArguments>();
  auto* post = app.add_subcommand("post", "Rewrite S (and F) so the cutting speed stays nominal");
  post->description(kPostDescription);
  add_job_options(*post, *args);
  post->add_option("-o,--output", args->output,
                   "output program ('-': standard output); written whole or not at all")
      ->required();
  post->add_option(
      "--report", args->reports,
      "also write the dry-run report of this job: FILE.json (summary), FILE.csv (every point) "
      "or FILE.html (plots); may be given more than once");
  post->callback([args] { finish_job(*args, run_job(*args, true)); });
}

}  // namespace vcpost::cli
