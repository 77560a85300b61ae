// The job behind `vcpost post` and `vcpost report`: checks the outputs,
// reads the program, the profile and the model, posts, judges the result
// (post/acceptance.h) and commits the files. The work itself is in
// postproc/post and postproc/report; this file only wires files to them.
#include "postproc/cli/job_runner.h"

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <functional>
#include <iostream>

#include "geometry/mesh/stl_reader.h"
#include "machines/builtin.h"
#include "postproc/cldata/cl_codes.h"
#include "postproc/cli/atomic_file.h"
#include "postproc/cli/commands.h"
#include "postproc/cli/distinct_files.h"
#include "postproc/cli/end_of_run.h"
#include "postproc/cli/held_output.h"
#include "postproc/cli/interrupt.h"
#include "postproc/cli/job_reports.h"
#include "postproc/cli/log.h"
#include "postproc/cli/model_placement.h"
#include "postproc/cli/program_text.h"
#include "postproc/gcode/diagnostics.h"
#include "postproc/heidenhain/diagnostics.h"
#include "postproc/output/gcode_writer.h"
#include "postproc/plan/spindle_plan.h"
#include "postproc/program/timing.h"

namespace vcpost::cli {
namespace {

std::vector<NamedFile> job_inputs(const PostArguments& args) {
  std::vector<NamedFile> inputs{
      {"program", args.program}, {"--model", args.model}, {"--stock-model", args.stock_model}};
  if (!machines::is_builtin_profile(args.machine)) inputs.push_back({"--machine", args.machine});
  inputs.push_back({"--tools", args.tools_file});
  return inputs;
}

std::vector<NamedFile> job_outputs(const PostArguments& args, bool write_program) {
  std::vector<NamedFile> outputs;
  if (write_program) outputs.push_back({"-o", args.output});
  outputs.push_back({"--summary-json", args.summary_json});
  for (const auto& r : args.reports) outputs.push_back({write_program ? "--report" : "-o", r});
  return outputs;
}

// Seconds since `start`, for the debug level's stage times.
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Writes the held program to `out`: its first 4 KB alone, so that once they
// have gone through, a reader leaving early (`| head`) is no failure worth
// a message (interrupt.h). False when `out` failed.
bool deliver(HeldOutput& held, std::ostream& out) {
  bool first = true;
  return held.for_each_chunk([&](std::string_view bytes) {
    if (first) {
      first = false;
      const std::string_view head = bytes.substr(0, 4096);
      if (!out.write(head.data(), static_cast<std::streamsize>(head.size())).flush()) return false;
      standard_output_delivered();
      bytes.remove_prefix(head.size());
    }
    return static_cast<bool>(out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())));
  });
}

// The charting library when a report is HTML, else empty.
std::string chart_library_for(const std::vector<ReportFile>& reports) {
  for (const auto& r : reports) {
    if (r.format == report::ReportFormat::html) return read_chart_library();
  }
  return {};
}

// Without a model, CL data is translated for the profile with its own
// speeds (every section kept): vcpost as a plain 3-axis post-processor;
// true then. G-code (and Klartext) is posted with each point's normal
// found from the toolpath itself (pipeline/path_normals.h), which `settings`
// is set to. Throws CommandError for options that need a model.
bool without_model_use(const PostArguments& args, std::string_view text,
                       const machines::MachineProfile& profile, bool write_program,
                       bool has_reports, post::PostSettings& settings) {
  if (!args.model.empty()) return false;
  const bool translate_only = post::program_kind(text, post::reading_dialect(settings, profile)) ==
                              post::ProgramKind::cldata;
  if (translate_only && (!write_program || has_reports))
    throw CommandError(
        "--model: required (the report of CL data evaluates its toolpath on the model; "
        "G-code and Klartext are reported without one, with the normals from the toolpath)");
  if (!args.model_transform.empty())
    throw CommandError("--model-transform: places a --model; none is given");
  if (settings.stock)
    throw CommandError("--model: required with an in-process stock (ap is taken at the contact)");
  if (!translate_only) {
    if (!(args.ap > 0)) throw CommandError("--ap: required");
    settings.normals_from_path = true;
  }
  return translate_only;
}

// The model of --model placed by --model-transform (no model without one).
LoadedModel placed_model(const PostArguments& args) {
  std::optional<ModelPlacement> placement;
  if (!args.model_transform.empty()) placement = parse_model_placement(args.model_transform);
  const auto stage = std::chrono::steady_clock::now();
  LoadedModel model = args.model.empty() ? no_model() : load_model(args.model);
  if (placement) place_model(model, *placement);
  if (!args.model.empty())
    log().debug("model {}: {}, loaded in {:.3f} s", args.model, model.description,
                seconds_since(stage));
  return model;
}

// The post's progress: on a terminal (`show`), one line rewritten in
// place; at the debug level a line every tenth of the program.
post::Progress progress_lines(bool show) {
  return [show, tenths_logged = 0](double done) mutable {
    if (show)
      std::cerr << "\rvcpost: posting " << static_cast<int>(done * 100) << " %" << std::flush;
    const int tenths = static_cast<int>(done * 10);
    if (tenths > tenths_logged) {
      tenths_logged = tenths;
      log().debug("posting: {} %", 10 * tenths);
    }
  };
}

// Where the posted program goes: its file (written atomically), or
// standard output, held until the job has succeeded.
struct ProgramOutput {
  std::optional<AtomicFile> file;
  HeldOutput pending;
  // The writer's sink. A dry run (not `write_program`) still writes the
  // program, to nowhere, so the report can say how many S and F words the
  // rewrite would change.
  std::function<void(std::string_view)> sink(bool write_program) {
    if (!write_program) return [](std::string_view) {};
    return [this](std::string_view bytes) {
      if (file) {
        file->write(bytes);
      } else {
        pending.append(bytes);
      }
    };
  }
};

// The held program, then what the reports put on standard output; throws
// CommandError (E2003) when standard output did not take them.
void deliver_standard_output(HeldOutput& pending, const std::string& to_stdout) {
  errno = 0;
  if (deliver(pending, std::cout)) std::cout << to_stdout << std::flush;
  if (!std::cout) {
    throw CommandError(Code::E2003, std::string("cannot write to standard output: ") +
                                        (errno != 0 ? std::strerror(errno) : "write error"));
  }
}

// The first section posted, whose tool and vc the summary names; null when none was.
const post::ToolSection* first_posted(const post::PostSummary& summary) {
  for (const post::ToolSection& section : summary.sections) {
    if (section.posted) return &section;
  }
  return nullptr;
}

// Runs `work`, a pass over the program, with the errors that carry a
// source line worded "file:line:col: ..." as the reader's own (a
// PostError, ClError or HeidenhainError leaves with its own code and
// words).
template <class Work>
auto located_errors(const std::string& name, Work&& work) -> decltype(work()) {
  try {
    return std::forward<Work>(work)();
  } catch (const gcode::GcodeError& e) {
    throw CommandError(e.code(), gcode::format(e.diagnostic(), name));
  } catch (const heidenhain::KlartextError& e) {
    throw CommandError(e.code(), heidenhain::format(e.diagnostic(), name));
  } catch (const program::TimingError& e) {
    throw CommandError(e.code(), e.located(name));
  } catch (const output::OutputError& e) {
    throw CommandError(e.code(), name + ":" + e.what());  // what(): "line:col: error[E....]: ..."
  } catch (const plan::PlanError& e) {
    throw CommandError(e.code(), std::string("planning: ") + e.what());
  }
}

// The command line's code for each refusal of post/acceptance.h.
Code code_of(post::Refusal refusal) {
  switch (refusal) {
    case post::Refusal::never_touches:
      return Code::E2005;
    case post::Refusal::gross_mismatch:
      return Code::E2011;
    case post::Refusal::none:
    case post::Refusal::no_motion:
    case post::Refusal::no_tool:
      break;
  }
  return Code::E2001;
}

}  // namespace

std::string program_name(const PostArguments& args) {
  return args.program == "-" ? "<stdin>" : args.program;
}

void note_links(const AtomicFile& file, const std::string& name, std::vector<std::string>& notes) {
  if (file.through_link()) {
    notes.push_back("'" + name + "' is a symbolic link: wrote its target '" +
                    file.written().string() + "'");
  }
}

void load_stock_model(const PostArguments& args, post::StockSettings& stock) {
  if (args.stock_model.empty()) return;
  const mesh::StlMesh stl = mesh::read_stl_file(args.stock_model);
  std::optional<ModelPlacement> placement;
  if (!args.model_transform.empty()) placement = parse_model_placement(args.model_transform);
  auto corners = std::make_shared<std::vector<Eigen::Vector3f>>();
  corners->reserve(3 * stl.triangles.size());
  for (const auto& t : stl.triangles) {
    for (const std::uint32_t v : t) {
      const Eigen::Vector3d p =
          placement ? placement->transform.apply(stl.vertices[v]) : stl.vertices[v];
      corners->push_back(p.cast<float>());
    }
  }
  stock.triangles = std::move(corners);
}

void require_accepted(const post::Verdict& verdict) {
  if (!verdict.accepted()) throw CommandError(code_of(verdict.refusal), verdict.message);
}

namespace {

// The log's level: --quiet, --verbose or --log-level (CLI11 admits only
// the levels' names).
void set_log_level_of(const PostArguments& args) {
  set_log_level(args.quiet     ? spdlog::level::err
                : args.verbose ? spdlog::level::debug
                               : parse_log_level(args.log_level).value_or(spdlog::level::info));
}

// Without a model: the normals, read ahead of the job into `settings`;
// returns the extent of the path they lie on (the report's top views).
Eigen::AlignedBox3d read_normals_ahead(std::string_view text, const std::string& name,
                                       const machines::MachineProfile& profile,
                                       post::PostSettings& settings) {
  const auto stage = std::chrono::steady_clock::now();
  settings.path_normals = std::make_shared<const post::PathNormalsAhead>(
      located_errors(name, [&] { return post::read_path_normals(text, name, profile, settings); }));
  log().debug("normals from the toolpath: {} points, found in {:.3f} s",
              settings.path_normals->normals.size(), seconds_since(stage));
  return settings.path_normals->bounds;
}

// Posts the program, its text behind the writer dropped as it goes.
post::PostSummary post_dropping_text(ProgramText& program, const std::string& name,
                                     const LoadedModel& model,
                                     const machines::MachineProfile& profile,
                                     const post::PostSettings& settings,
                                     const std::function<void(std::string_view)>& sink,
                                     const post::Progress& progress,
                                     const post::PointSink& points) {
  return located_errors(name, [&] {
    return post::post_program(program.view(), name, *model.model, profile, settings, sink, progress,
                              points,
                              [&program](std::uint64_t offset) { program.release_before(offset); });
  });
}

void log_posted(const post::PostSummary& summary, std::chrono::steady_clock::time_point stage) {
  log().debug(
      "posted in {:.3f} s: {} points ({} touching, {} gouging, {} in the air), {} S words, "
      "{} F words, {} tool sections",
      seconds_since(stage), summary.samples, summary.touching, summary.gouging,
      summary.lifted + summary.missed, summary.s_words, summary.f_words, summary.sections.size());
}

// The job's verdict on the post (post/acceptance.h), then --strict's: both
// before anything is committed (--strict leaves no file it refused).
void require_acceptable(const post::PostSummary& summary, const std::string& name,
                        bool translate_only, bool strict) {
  require_accepted(translate_only ? post::judge_motion(summary, name)
                                  : post::judge_posted(summary, name));
  if (strict && has_warnings(summary)) {
    print_warnings(summary, name);
    throw CommandError(Code::E2010, "warnings with --strict; nothing written");
  }
}

// The end of run's notes: the outputs written through a link, and the
// tool choices no section used.
std::vector<std::string> end_notes(const PostArguments& args,
                                   const std::vector<ReportFile>& reports,
                                   const ProgramOutput& output, const post::PostSettings& settings,
                                   const post::PostSummary& summary) {
  std::vector<std::string> notes;
  for (const auto& r : reports) {
    if (r.file) note_links(*r.file, r.path, notes);
  }
  if (output.file) note_links(*output.file, args.output, notes);
  for (const std::string& w : post::unused_tool_choices(*settings.tools, summary.sections))
    notes.push_back("warning: " + w);
  return notes;
}

}  // namespace

JobRun run_job(const PostArguments& args, bool write_program) {
  const auto started = std::chrono::steady_clock::now();
  set_log_level_of(args);
  require_distinct_files(job_inputs(args), job_outputs(args, write_program));
  ProgramText program(args.program);
  const std::string_view text = program.view();
  const std::string name = program_name(args);
  log().debug("program {}: {} bytes, read in {:.3f} s", name, text.size(), seconds_since(started));
  post::PostSettings settings = settings_from(args);
  std::vector<ReportFile> reports = open_reports(args);
  if (!args.summary_json.empty() && args.summary_json != "-") {
    AtomicFile probe(args.summary_json);  // its folder fails now, not after the program is written
  }
  const std::string chart_library = chart_library_for(reports);

  auto stage = std::chrono::steady_clock::now();
  const machines::MachineProfile profile = load_machine(args.machine);
  log().debug("machine profile {}: loaded in {:.3f} s", profile.name(), seconds_since(stage));
  const bool translate_only =
      without_model_use(args, text, profile, write_program, !reports.empty(), settings);
  LoadedModel model = placed_model(args);
  const Eigen::AlignedBox3d plan = settings.normals_from_path
                                       ? read_normals_ahead(text, name, profile, settings)
                                       : model.model->bounds();
  if (settings.stock) load_stock_model(args, *settings.stock);

  // On a terminal at the info level, one line rewritten in place.
  const bool show_progress = log().level() == spdlog::level::info && ::isatty(STDERR_FILENO);
  const post::Progress progress = progress_lines(show_progress);

  ProgramOutput output;
  if (write_program && args.output != "-") output.file.emplace(args.output);
  const std::function<void(std::string_view)> sink = output.sink(write_program);

  // Reports: the CSV streams while the points come; the rest is written at the end.
  std::optional<report::ReportCollector> collector;
  std::vector<report::CsvWriter*> csv_writers;
  post::PointSink points;
  if (!reports.empty()) {
    collector.emplace(report_inputs(
        args, settings, model, profile, post::detect_program_kind(text),
        located_errors(name,
                       [&] { return post::first_postable_section(text, name, profile, settings); }),
        plan));
    csv_writers = start_csv_reports(reports);
    points = collector->point_sink([&](const report::PointRow& row) {
      for (auto* csv : csv_writers) csv->write(row);
    });
  }

  stage = std::chrono::steady_clock::now();
  const post::PostSummary summary =
      post_dropping_text(program, name, model, profile, settings, sink, progress, points);
  if (show_progress) std::cerr << "\r\x1b[K";
  log_posted(summary, stage);
  require_acceptable(summary, name, translate_only, args.strict);
  std::string to_stdout;  // written after every file is complete

  const double run_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (collector) {
    stage = std::chrono::steady_clock::now();
    to_stdout = write_reports(collector->finish(summary, run_time), reports, chart_library);
    log().debug("{} reports written in {:.3f} s", reports.size(), seconds_since(stage));
  }
  // The program last: a failed report leaves no posted program behind.
  if (output.file) output.file->commit();
  std::vector<std::string> notes = end_notes(args, reports, output, settings, summary);
  deliver_standard_output(output.pending, to_stdout);
  JobRun run{summary, std::nullopt, std::nullopt, std::move(model), profile, run_time, notes};
  if (const post::ToolSection* first = first_posted(summary)) {
    run.tool = first->entry->geometry();
    run.vc = first->vc_nominal;
  }
  return run;
}

}  // namespace vcpost::cli
