// What `vcpost post` and `vcpost report` share: their options and the
// job's settings made of them (the run is job_runner.h's). The commands
// differ only in what they write (the program, the report, or both).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "machines/profile.h"
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
  // The in-process stock (docs/stock.md): at most one source.
  bool stock_from_program = false;     // --stock-from-program
  std::string stock_box, stock_model;  // --stock-box, --stock-model FILE.stl
  std::optional<double> stock_cell;    // --stock-cell MM
  double stock_memory_mb = 1024;       // --stock-memory MB
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

}  // namespace vcpost::cli
