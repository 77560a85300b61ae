// The run of `vcpost post` and `vcpost report`: the program posted (and
// written), the report files beside it, and what the run did for the
// end-of-run lines (end_of_run.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "machines/profile.h"
#include "postproc/cli/atomic_file.h"
#include "postproc/cli/model_loader.h"
#include "postproc/cli/post_options.h"
#include "postproc/post/acceptance.h"
#include "postproc/post/post_job.h"

namespace vcpost::cli {

// What one run did, for the command's own output.
struct JobRun {
  post::PostSummary summary;
  // The first posted section's tool and vc (the summary's `tool` and
  // `vc_nominal`); empty when no section was posted.
  std::optional<geometry::Tool> tool;
  std::optional<double> vc;
  LoadedModel model;
  machines::MachineProfile profile;
  double run_time_s = 0;
  std::vector<std::string> notes;  // e.g. an output written through a symbolic link
};

// Runs the job: posts (writing the program to args.output when
// `write_program`, atomically, '-' = standard output) and writes every
// report file of args.reports. Checks all outputs before any work; throws
// CommandError (exit 2) for bad options, unreadable input, unknown report
// formats, an output that is an input or another output, or a post the
// acceptance rules refuse (post/acceptance.h); nothing is left half-written.
JobRun run_job(const PostArguments& args, bool write_program);

// Throws the CommandError of a refused post: E2005 for a toolpath that
// never touches the model, E2011 for a gross mismatch, E2001 for the rest.
void require_accepted(const post::Verdict& verdict);

// --stock-model's triangles into `stock`, placed like the model by
// --model-transform (the shared VERICUT projects place the stock STL as the
// design STL); nothing without --stock-model. Throws the STL reader's errors.
void load_stock_model(const PostArguments& args, post::StockSettings& stock);

// The program's name in messages ("<stdin>" for '-').
std::string program_name(const PostArguments& args);

// "X is a symbolic link" notes for the end-of-run lines.
void note_links(const AtomicFile& file, const std::string& name, std::vector<std::string>& notes);

}  // namespace vcpost::cli
