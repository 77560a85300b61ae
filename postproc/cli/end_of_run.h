// What `vcpost post` and `vcpost report` print when the job is done: the
// end-of-run lines on standard error (at the info level: not with
// --quiet), the warnings, and the --summary-json file.
#pragma once

#include <string>

#include "postproc/cli/job_runner.h"
#include "postproc/cli/post_options.h"
#include "postproc/post/post_job.h"

namespace vcpost::cli {

// The end-of-run lines and the --summary-json file. (Warnings with
// --strict end run_job with exit 1 before any output is committed.)
void finish_job(const PostArguments& args, const JobRun& run);

// Whether the run has a warning (gouges, points off the model, a missing
// end, lines after it, cuts with the spindle stopped, S or F all but
// decided by the machine's limits), and the warnings' lines.
bool has_warnings(const post::PostSummary& summary);
void print_warnings(const post::PostSummary& summary, const std::string& name);

}  // namespace vcpost::cli
