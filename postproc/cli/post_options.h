// What `vcpost post` and `vcpost report` share: their options, the job's
// set-up from them, and the run itself with its report files. The commands
// differ only in what they write (the program, the report, or both).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "machines/profile.h"
#include "postproc/cli/model_loader.h"
#include "postproc/post/post_job.h"

namespace vcpost::cli {

// The smallest --spacing: 1 um, far below any surface finish a ball-end
// mill leaves, and above which a 1 m move is at most a million points.
inline constexpr double kMinSpacingMm = 0.001;

struct PostArguments {
  std::string program, model, machine = "generic", output, summary_json;
  std::string model_transform;  // --model-transform: steps or vcproject:FILE
  std::string policy = "max", cl_point = "tip", dialect;
  std::vector<std::string> tools;      // --tool: "ball:10" (every tool) or "T8=ball:14"
  std::string tools_file, post_tools;  // --tools FILE.toml, --post-tools T2,T8
  std::vector<std::string> vc;         // --vc: "120" (every tool) or "T2=150"
  std::vector<std::string> stock;      // --stock: "0.3" (every tool), "T3=-1.2" or "T3=0.2:0.1"
  double ap = 0, spacing = 0.5, tolerance = 0.01;
  std::optional<double> ae, fz;
  std::optional<int> teeth;
  int threads = 0;  // 0: one per core
  bool ae_override = false, adjust_feed = false, quiet = false, strict = false;
  std::string log_level = "info";  // --log-level; -q (error) and -v (debug) override it
  bool verbose = false;
  std::vector<std::string> reports;  // report files; the format follows the extension
};

// Registers the options common to both commands on `command` (not -o or
// the report files, which each command words its own way).
void add_job_options(CLI::App& command, PostArguments& args);

// The job's settings from the options (tools from --tool/--tools/
// --post-tools, speeds from --vc); throws CommandError for bad ones.
post::PostSettings settings_from(const PostArguments& args);

// A gross program/model mismatch (E2011): an evaluated section with at
// least kGrossMismatchMinGouging gouging points of which fewer than
// kGrossMismatchMaxTouchingPercent % of its points on the model (touching
// or gouging) touch it. Points in the air (lifted, or too far from the
// model) count neither way.
inline constexpr std::uint64_t kGrossMismatchMinGouging = 10;
inline constexpr std::uint64_t kGrossMismatchMaxTouchingPercent = 10;
bool is_gross_mismatch(const post::ToolSection& section);

// Throws CommandError when the program has no motion, no section had a
// tool vcpost can read, no point of the toolpath touches the model, or a
// section is a gross mismatch (E2011, with the sections' depths and a hint
// about the work offset, units and --cl-point).
void require_posted(const post::PostSummary& summary, const std::string& name);
// Only the first of those: the program has a motion.
void require_motion(const post::PostSummary& summary, const std::string& name);

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
// formats, an output that is an input or another output, or a toolpath that
// never touches the model; nothing is left half-written.
JobRun run_job(const PostArguments& args, bool write_program);

// The end-of-run lines on stderr (at the info level: not with --quiet) and the --summary-json
// file. (Warnings with --strict end run_job with exit 1 before any output
// is committed.)
void finish_job(const PostArguments& args, const JobRun& run);

}  // namespace vcpost::cli
