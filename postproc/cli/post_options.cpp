// The job behind `vcpost post` and `vcpost report`: options, set-up, the
// run, and the report files beside it. The work itself is in postproc/post
// and postproc/report; this file only wires files to them.
#include "postproc/cli/post_options.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "machines/builtin.h"
#include "postproc/cldata/cl_codes.h"
#include "postproc/cli/atomic_file.h"
#include "postproc/cli/commands.h"
#include "postproc/cli/distinct_files.h"
#include "postproc/cli/held_output.h"
#include "postproc/cli/interrupt.h"
#include "postproc/cli/klartext_programs.h"
#include "postproc/cli/log.h"
#include "postproc/cli/model_placement.h"
#include "postproc/cli/number_options.h"
#include "postproc/cli/program_text.h"
#include "postproc/cli/section_words.h"
#include "postproc/gcode/diagnostics.h"
#include "postproc/output/gcode_writer.h"
#include "postproc/program/timing.h"
#include "postproc/report/chart_library.h"
#include "postproc/report/csv_writer.h"
#include "postproc/report/report.h"
#include "postproc/tools/tools_file.h"

namespace vcpost::cli {
namespace {

// The inputs `post --summary-json` names, as the report names them.
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

std::string read_text_file(const std::string& path, const std::string& option) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CommandError("E2002", option + ": cannot read '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The tools and speeds of --tool, --tools, --post-tools and --vc.
tools::ToolChoices tool_choices(const PostArguments& args) {
  tools::ToolChoices choices;  // a ToolTableError leaves with its own code
  for (const std::string& spec : args.tools) choices.table.add(tools::parse_tool_option(spec));
  if (!args.tools_file.empty()) {
    tools::ToolTable file;
    tools::load_tools_file(read_text_file(args.tools_file, "--tools"), args.tools_file, file);
    for (const tools::ToolEntry& e : file.numbered()) choices.table.add(e);
  }
  if (!args.post_tools.empty()) choices.post_tools = tools::parse_tool_list(args.post_tools);
  for (const std::string& vc : args.vc) tools::add_vc_option(vc, choices);
  for (const std::string& stock : args.stock) tools::add_stock_option(stock, choices);
  // Without a model (CL translated as it is) no speed is computed.
  if (!args.model.empty() && !choices.vc && choices.vc_by_tool.empty())
    throw CommandError("--vc: required");
  return choices;
}

}  // namespace

post::PostSettings settings_from(const PostArguments& args) {
  post::PostSettings settings;
  settings.program_loader = klartext_program_files(args.program);
  settings.tools = tool_choices(args);
  if (!args.model.empty() && !(args.ap > 0)) throw CommandError("--ap: required");
  settings.point.ap = args.ap;
  settings.point.ae = args.ae;
  settings.point.ae_override = args.ae_override;
  settings.point.contact_tolerance = args.tolerance;
  settings.point.cl_point =
      args.cl_point == "center" ? geometry::ClPoint::center : geometry::ClPoint::tip;
  // CLI11 admits only the policies' names.
  settings.point.policy =
      geometry::parse_diameter_policy(args.policy).value_or(geometry::DiameterPolicy::max);
  settings.sample_spacing_mm = args.spacing;
  settings.threads = args.threads;
  settings.adjust_feed = args.adjust_feed;
  settings.fz_mm = args.fz;
  settings.teeth = args.teeth;
  if (!args.dialect.empty()) {
    settings.dialect = gcode::dialect_from_name(args.dialect);
    if (!settings.dialect) throw CommandError("--dialect: unknown dialect '" + args.dialect + "'");
  }
  return settings;
}

bool is_gross_mismatch(const post::ToolSection& s) {
  const std::uint64_t on_model = s.touching + s.gouging;
  return s.postable && s.gouging >= kGrossMismatchMinGouging &&
         s.touching * 100 < on_model * kGrossMismatchMaxTouchingPercent;
}

void require_motion(const post::PostSummary& summary, const std::string& name) {
  if (summary.motion_events == 0) {
    throw CommandError("'" + name +
                       "': the program has no motion (empty, comments only, or cut short before "
                       "its first move): nothing to post");
  }
}

void require_posted(const post::PostSummary& summary, const std::string& name) {
  require_motion(summary, name);
  if (!summary.sections.empty() &&
      std::none_of(summary.sections.begin(), summary.sections.end(),
                   [](const post::ToolSection& s) { return s.entry.has_value(); })) {
    throw CommandError(
        "--tool: required (the program names no tool vcpost can read: no CL CUTTER/TLDATA, no "
        "CAM tool comment); give --tool ball:D, --tool T<n>=ball:D or --tools FILE.toml");
  }
  if (summary.samples > 0 && summary.touching + summary.gouging == 0) {
    const std::string hint =
        "check the work offset and units of the program against the model, and --cl-point (tip "
        "or center)";
    std::string message = "the toolpath never touches the model (" +
                          std::to_string(summary.samples) + " points checked)";
    if (summary.lifted == 0) throw CommandError("E2005", message + ": " + hint);
    // Points above the model within the search distance: how high, and
    // when one offset dominates (stock left on, a smaller tool), why.
    message += ": " + std::to_string(summary.lifted) + " sit above it" +
               (summary.missed > 0 ? ", " + std::to_string(summary.missed) +
                                         " miss it entirely (no contact within "
                                         "the search distance)"
                                   : std::string());
    bool offset = false;
    for (const post::ToolSection& s : summary.sections) {
      if (s.lift.points == 0) continue;
      const std::string label =
          summary.sections.size() > 1 ? section_name(s) + ": " : std::string();
      message += "; " + label + depth_words(s.lift, "lift height");
      if (s.offset && s.offset->offset_mm > 0 && s.entry) {
        message += "; " + label + lift_words(*s.offset, s.entry->diameter / 2);
        offset = true;
      }
    }
    if (!offset) message += "; no one offset dominates: " + hint;
    throw CommandError("E2005", message);
  }
  // A section whose points on the model mostly gouge it: not a few gouges
  // to warn about, the program and the model disagree (another tool
  // diameter, units, work offset or --cl-point). Points in the air (lifted
  // or far from the model) do not count either way: a program with many
  // air moves is judged by its points on the model.
  std::vector<const post::ToolSection*> gross;
  for (const post::ToolSection& s : summary.sections) {
    if (is_gross_mismatch(s)) gross.push_back(&s);
  }
  if (gross.empty()) return;
  std::uint64_t touching = 0, gouging = 0, points = 0;
  for (const post::ToolSection* s : gross) {
    touching += s->touching;
    gouging += s->gouging;
    points += s->points;
  }
  // The error gives the sections' own diagnosis, worded as the end-of-run
  // lines word it.
  std::string message = "the toolpath gouges the model at " + std::to_string(gouging) + " of " +
                        std::to_string(points) + " points and touches it at only " +
                        std::to_string(touching) + ": the program does not match the model";
  bool offset = false;
  for (const post::ToolSection* s : gross) {
    const std::string label = summary.sections.size() > 1 ? section_name(*s) + ": " : std::string();
    if (s->gouge.points > 0) message += "; " + label + depth_words(s->gouge, "gouge depth");
    if (s->lift.points > 0) message += "; " + label + depth_words(s->lift, "lift height");
    if (s->offset) message += "; " + label + offset_words(*s->offset);
    offset = offset || s->offset.has_value();
  }
  if (!offset) {
    message +=
        "; no one offset dominates (depths that vary with the surface's slope: a shifted "
        "work offset, other units or another tool diameter)";
  }
  throw CommandError("E2011", message);
}

namespace {

// One report file: its format and, for the streamed CSV, its open file.
struct ReportFile {
  std::string path;  // "-": standard output (JSON)
  report::ReportFormat format = report::ReportFormat::json;
  std::unique_ptr<AtomicFile> file;
  std::unique_ptr<report::CsvWriter> csv;
};

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
    throw CommandError("E2004",
                       "HTML report: the charting library '" + path + "' is missing; install " +
                           std::string(report::kChartLibraryPackage) + " (scripts/setup.sh)");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<NamedFile> job_inputs(const PostArguments& args) {
  std::vector<NamedFile> inputs{{"program", args.program}, {"--model", args.model}};
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

// The program's name in messages.
std::string program_name(const PostArguments& args) {
  return args.program == "-" ? "<stdin>" : args.program;
}

// The nominal vc of the posted sections: one number, or their range.
std::string vc_words(const post::PostSummary& summary) {
  double low = HUGE_VAL, high = -HUGE_VAL;
  for (const post::ToolSection& s : summary.sections) {
    if (!s.posted) continue;
    low = std::min(low, s.vc_nominal);
    high = std::max(high, s.vc_nominal);
  }
  std::ostringstream out;
  out << low;
  if (high > low) out << "-" << high;
  return out.str();
}

// The share of the posted cutting time whose S a spindle limit decided,
// and of the coupled blocks whose F a feed limit decided: all but nothing
// left to the model means --vc or --fz is beyond the machine (W2031, W2032).
constexpr double kAllClamped = 0.99;

double clamped_speed_share(const post::PostSummary& summary) {
  double cutting = 0;
  for (const auto& s : summary.s_placement.sections) cutting += s.cutting_time_s;
  return cutting > 0 ? (summary.time_clamped_max_s + summary.time_clamped_min_s) / cutting : 0;
}

double clamped_feed_share(const post::PostSummary& summary) {
  return summary.coupled_feed_blocks > 0 ? static_cast<double>(summary.clamped_feed_blocks) /
                                               static_cast<double>(summary.coupled_feed_blocks)
                                         : 0;
}

bool has_warnings(const post::PostSummary& summary) {
  // Without a model the points kept (no normal) are counted in their own line.
  const bool off_model = !summary.path_normals && summary.lifted + summary.missed > 0;
  return summary.gouging > 0 || off_model || summary.missing_end ||
         !summary.unread_after_end.empty() || summary.stopped_spindle_cuts > 0 ||
         clamped_speed_share(summary) >= kAllClamped || clamped_feed_share(summary) >= kAllClamped;
}

void print_warnings(const post::PostSummary& summary, const std::string& name) {
  if (summary.stopped_spindle_cuts > 0) {
    log().warn(
        "{}:{}: W2030: {} points cut the model with the spindle stopped (S0, M5 or SPINDL/OFF "
        "before them): the control would cut with a standing tool; vcpost keeps their S",
        name, summary.first_stopped_spindle_line, summary.stopped_spindle_cuts);
  }
  if (clamped_speed_share(summary) >= kAllClamped) {
    log().warn(
        "W2031: the spindle's {} speed decides S on {:.0f} % of the cutting time: vc {} m/min is "
        "beyond this machine with this tool (check --vc, the tool and --machine)",
        summary.time_clamped_max_s >= summary.time_clamped_min_s ? "highest" : "lowest",
        100 * clamped_speed_share(summary), vc_words(summary));
  }
  if (clamped_feed_share(summary) >= kAllClamped) {
    log().warn(
        "W2032: the machine's feed limit (f_min or f_max) decides F on {:.0f} % of the coupled "
        "blocks: --fz is beyond this machine (check --fz, the teeth and --machine)",
        100 * clamped_feed_share(summary));
  }
  if (summary.missing_end)
    log().warn("the program ends without M2, M30 or a closing '%': is the file complete?");
  // The reader's own diagnostic, with its file position and code.
  if (!summary.unread_after_end.empty()) std::cerr << summary.unread_after_end << '\n';
  if (summary.gouging > 0) log().warn("{} points gouge the model", summary.gouging);
  if (!summary.path_normals && summary.lifted + summary.missed > 0) {
    log().warn("{} cutting points do not touch the model (their blocks keep the program's S)",
               summary.lifted + summary.missed);
  }
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

// "X is a symbolic link" notes for the end-of-run lines.
void note_links(const AtomicFile& file, const std::string& name, std::vector<std::string>& notes) {
  if (file.through_link()) {
    notes.push_back("'" + name + "' is a symbolic link: wrote its target '" +
                    file.written().string() + "'");
  }
}

// The report is drawn for one tool and vc: the first section the job
// evaluates (read ahead), or else the plain --tool and --vc.
report::ReportInputs report_inputs(const PostArguments& args, const post::PostSettings& settings,
                                   const LoadedModel& model,
                                   const machines::MachineProfile& profile, post::ProgramKind kind,
                                   const std::optional<post::ToolSection>& first) {
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
  // Top views over the model's plan grown by the tool radius (programmed
  // points of a touching ball lie within it).
  const Eigen::AlignedBox3d box = model.model->bounds();
  const double margin = tool.radius() + 1;
  if (!box.isEmpty()) {
    in.plan_min = box.min().head<2>() - Eigen::Vector2d::Constant(margin);
    in.plan_max = box.max().head<2>() + Eigen::Vector2d::Constant(margin);
  } else {
    in.plan_min = Eigen::Vector2d::Constant(-margin);
    in.plan_max = Eigen::Vector2d::Constant(margin);
  }
  return in;
}

}  // namespace

void add_job_options(CLI::App& command, PostArguments& args) {
  command.add_option("program", args.program, "G-code or APT CL program ('-': standard input)")
      ->required();
  command.add_option(
      "--model", args.model,
      "finished-surface model: STEP (mm or inch) or STL (mm); required but for APT CL "
      "input, which without it is translated for --machine with its own speeds");
  command.add_option(
      "--model-transform", args.model_transform,
      "where the model sits in the program's frame: steps applied in order, rx=DEG, ry=DEG, "
      "rz=DEG, x=MM, y=MM, z=MM, or matrix=16 numbers (e.g. rz=-90 or rx=180,rz=180,z=-22); "
      "or vcproject:FILE.vcproject (VERICUT's placement of the design STL)");
  command.add_option("--tool", args.tools,
                     "the tool: ball:D, bull:D:rc, flat:D, drill:D or other (mm), for every tool; "
                     "T8=ball:14 for tool 8 (repeatable; default: what the program says, CL "
                     "CUTTER/TLDATA or CAM tool comments)");
  command.add_option("--tools", args.tools_file,
                     "tool table, TOML: [[tool]] number, shape, diameter, corner_radius, teeth, "
                     "name (see postproc/tools/README.md)");
  command.add_option("--post-tools", args.post_tools,
                     "post only these tools' sections, e.g. T2,T8 (default: every ball-end mill "
                     "whose path touches the model)");
  command.add_option("--vc", args.vc,
                     "nominal cutting speed, m/min, for every tool; T2=150 for tool 2 (repeatable; "
                     "required with --model)");
  command.add_option(
      "--stock", args.stock,
      "allowance the CAM left, mm, for every tool (0.3; negative: into the model, e.g. "
      "-1.2); T3=0.2 for tool 3, T3=0.2:0.1 radial:axial for bull-nose and flat end "
      "mills (repeatable): contact, ae and the engagement are taken on the model offset by it");
  command
      .add_option("--ap", args.ap,
                  "depth of cut along the surface normal, mm (required with --model)")
      ->check(positive_number());
  command
      .add_option("--ae", args.ae,
                  "width of cut, mm: used where the toolpath shows no neighbouring pass")
      ->check(positive_number());
  command.add_flag("--ae-override", args.ae_override,
                   "use --ae everywhere instead of measuring it from the toolpath");
  command
      .add_option("--machine", args.machine,
                  "machine profile: a built-in name (vcpost machines list) or a TOML file")
      ->capture_default_str();
  command
      .add_option("--policy", args.policy,
                  "reference diameter: max (no edge faster than vc), tangent, mean")
      ->check(CLI::IsMember({"max", "tangent", "mean"}))
      ->capture_default_str();
  command.add_flag("--adjust-feed", args.adjust_feed,
                   "couple the feed to the speed: F = fz * z * n");
  command
      .add_option("--fz", args.fz,
                  "feed per tooth for --adjust-feed, mm (default: the program's F at its S)")
      ->check(positive_number());
  command
      .add_option("--teeth", args.teeth,
                  "number of teeth for --adjust-feed: every tool's but those with teeth in "
                  "--tools (default: the profile's)")
      ->check(CLI::Range(1, 1000));
  command
      .add_option("--cl-point", args.cl_point,
                  "what the program's points are: the tool tip or the ball centre")
      ->check(CLI::IsMember({"tip", "center"}))
      ->capture_default_str();
  command
      .add_option(
          "--spacing", args.spacing,
          "largest distance between evaluated points, mm (at least " + shown(kMinSpacingMm) + ")")
      ->check(positive_number(kMinSpacingMm, 1e6))
      ->capture_default_str();
  command
      .add_option("--contact-tolerance", args.tolerance,
                  "distance error still counted as contact, mm")
      ->check(positive_number())
      ->capture_default_str();
  command.add_option("--dialect", args.dialect,
                     "G-code dialect: rs274ngc, fanuc, mazak, sinumerik (default: the profile's)");
  command.add_option("--summary-json", args.summary_json,
                     "write the job's JSON summary to this file ('-': standard error)");
  command
      .add_option("--threads", args.threads,
                  "worker threads for contact and engagement (default 0: one per core); "
                  "the output does not depend on it")
      ->check(CLI::Range(0, 256));
  command.add_flag("-q,--quiet", args.quiet, "print nothing but errors");
  command
      .add_option("--log-level", args.log_level,
                  "what goes to standard error besides errors: warning, info (warnings and the "
                  "end-of-run lines) or debug (also each stage's time and counts)")
      ->check(CLI::IsMember({"error", "warning", "info", "debug"}))
      ->capture_default_str();
  command.add_flag("-v,--verbose", args.verbose, "the same as --log-level debug");
  command.add_flag("--strict", args.strict,
                   "exit 1 when there were warnings (gouges, points without contact)");
}

namespace {

// The first section the job will post (read ahead), which the report is
// drawn for; its errors are the job's, worded as the job words them.
std::optional<post::ToolSection> first_section(std::string_view text, const std::string& name,
                                               const machines::MachineProfile& profile,
                                               const post::PostSettings& settings) {
  try {
    return post::first_postable_section(text, name, profile, settings);
  } catch (const post::PostError& e) {
    throw CommandError(e.code(), e.what());
  } catch (const gcode::GcodeError& e) {
    throw CommandError(gcode::format(e.diagnostic(), name));
  } catch (const cldata::ClError& e) {
    throw CommandError(e.what());
  } catch (const program::TimingError& e) {
    throw CommandError(e.code(), e.located(name));
  }
}

// A CSV writer on each .csv report's file; the writers, to feed the rows to.
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

// post::post_program, dropping the program's text behind the writer, with
// the errors that carry a source line worded "file:line: ..." (a
// GcodeError, ClError or PostError leaves with its own code).
post::PostSummary post_translating_errors(ProgramText& program, const std::string& name,
                                          const geometry::SurfaceModel& model,
                                          const machines::MachineProfile& profile,
                                          const post::PostSettings& settings,
                                          const std::function<void(std::string_view)>& sink,
                                          const post::Progress& progress,
                                          const post::PointSink& points) {
  try {
    return post::post_program(program.view(), name, model, profile, settings, sink, progress,
                              points,
                              [&program](std::uint64_t offset) { program.release_before(offset); });
  } catch (const gcode::GcodeError& e) {
    throw CommandError(e.code(), gcode::format(e.diagnostic(), name));
  } catch (const program::TimingError& e) {
    throw CommandError(e.code(), e.located(name));
  } catch (const output::OutputError& e) {
    throw CommandError(e.code(), name + ":" + e.what());  // what(): "line:col: error[E....]: ..."
  } catch (const plan::PlanError& e) {
    throw CommandError(e.code(), std::string("planning: ") + e.what());
  }
}

// Finishes the CSV reports and writes the JSON and HTML ones, each file
// committed; returns what goes to standard output ('-').
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
        throw CommandError("E2004", std::string("HTML report: ") + e.what());
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

}  // namespace

JobRun run_job(const PostArguments& args, bool write_program) {
  const auto started = std::chrono::steady_clock::now();
  // CLI11 admits only the levels' names.
  set_log_level(args.quiet     ? spdlog::level::err
                : args.verbose ? spdlog::level::debug
                               : parse_log_level(args.log_level).value_or(spdlog::level::info));
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
  std::string chart_library;
  for (const auto& r : reports) {
    if (r.format == report::ReportFormat::html && chart_library.empty())
      chart_library = read_chart_library();
  }

  auto stage = std::chrono::steady_clock::now();
  const machines::MachineProfile profile = load_machine(args.machine);
  log().debug("machine profile {}: loaded in {:.3f} s", profile.name(), seconds_since(stage));
  // Without a model, CL data is translated for the profile with its own
  // speeds (every section kept): vcpost as a plain 3-axis post-processor.
  // Without a model G-code (and Klartext) is posted with each point's
  // normal found from the toolpath itself (pipeline/path_normals.h).
  const bool without_model = args.model.empty();
  const bool translate_only =
      without_model && post::program_kind(text, post::reading_dialect(settings, profile)) ==
                           post::ProgramKind::cldata;
  if (without_model) {
    if (!write_program || !reports.empty())
      throw CommandError(
          "--model: required (the report evaluates the toolpath on the model; without one "
          "there is no gouge check and no cusp map)");
    if (!args.model_transform.empty())
      throw CommandError("--model-transform: places a --model; none is given");
  }
  if (without_model && !translate_only) {
    if (!(args.ap > 0)) throw CommandError("--ap: required");
    settings.normals_from_path = true;
  }
  std::optional<ModelPlacement> placement;
  if (!args.model_transform.empty()) placement = parse_model_placement(args.model_transform);
  stage = std::chrono::steady_clock::now();
  LoadedModel model = without_model ? no_model() : load_model(args.model);
  if (placement) place_model(model, *placement);
  if (!without_model)
    log().debug("model {}: {}, loaded in {:.3f} s", args.model, model.description,
                seconds_since(stage));

  // On a terminal at the info level, one line rewritten in place; at the
  // debug level a line every tenth of the program instead.
  const bool show_progress = log().level() == spdlog::level::info && ::isatty(STDERR_FILENO);
  int tenths_logged = 0;
  const post::Progress progress = [&](double done) {
    if (show_progress)
      std::cerr << "\rvcpost: posting " << static_cast<int>(done * 100) << " %" << std::flush;
    const int tenths = static_cast<int>(done * 10);
    if (tenths > tenths_logged) {
      tenths_logged = tenths;
      log().debug("posting: {} %", 10 * tenths);
    }
  };

  std::optional<AtomicFile> file;
  if (write_program && args.output != "-") file.emplace(args.output);
  HeldOutput pending;  // stdout is written only once the job has succeeded
  // A dry run still writes the program, to nowhere, so the report can say
  // how many S and F words the rewrite would change.
  std::function<void(std::string_view)> sink = [](std::string_view) {};
  if (write_program) {
    sink = [&](std::string_view bytes) {
      if (file) {
        file->write(bytes);
      } else {
        pending.append(bytes);
      }
    };
  }

  // Reports: the CSV streams while the points come; the rest is written at the end.
  std::optional<report::ReportCollector> collector;
  std::vector<report::CsvWriter*> csv_writers;
  if (!reports.empty()) {
    collector.emplace(report_inputs(args, settings, model, profile, post::detect_program_kind(text),
                                    first_section(text, name, profile, settings)));
    csv_writers = start_csv_reports(reports);
  }
  post::PointSink points;
  if (collector) {
    points = collector->point_sink([&](const report::PointRow& row) {
      for (auto* csv : csv_writers) csv->write(row);
    });
  }

  stage = std::chrono::steady_clock::now();
  const post::PostSummary summary = post_translating_errors(program, name, *model.model, profile,
                                                            settings, sink, progress, points);
  if (show_progress) std::cerr << "\r\x1b[K";
  log().debug(
      "posted in {:.3f} s: {} points ({} touching, {} gouging, {} in the air), {} S words, "
      "{} F words, {} tool sections",
      seconds_since(stage), summary.samples, summary.touching, summary.gouging,
      summary.lifted + summary.missed, summary.s_words, summary.f_words, summary.sections.size());
  if (translate_only) {
    require_motion(summary, name);
  } else {
    require_posted(summary, name);
  }
  if (args.strict && has_warnings(summary)) {
    // Refused before anything is committed: --strict leaves no file it refused.
    print_warnings(summary, name);
    throw CommandError("E2010", "warnings with --strict; nothing written");
  }
  std::string to_stdout;  // written after every file is complete

  const double run_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (collector) {
    stage = std::chrono::steady_clock::now();
    to_stdout = write_reports(collector->finish(summary, run_time), reports, chart_library);
    log().debug("{} reports written in {:.3f} s", reports.size(), seconds_since(stage));
  }
  // The program last: a failed report leaves no posted program behind.
  if (file) file->commit();
  std::vector<std::string> notes;
  for (const auto& r : reports) {
    if (r.file) note_links(*r.file, r.path, notes);
  }
  if (file) note_links(*file, args.output, notes);
  for (const std::string& w : post::unused_tool_choices(*settings.tools, summary.sections))
    notes.push_back("warning: " + w);
  errno = 0;
  if (deliver(pending, std::cout)) std::cout << to_stdout << std::flush;
  if (!std::cout) {
    throw CommandError("E2003", std::string("cannot write to standard output: ") +
                                    (errno != 0 ? std::strerror(errno) : "write error"));
  }
  JobRun run{summary, std::nullopt, std::nullopt, std::move(model), profile, run_time, notes};
  for (const post::ToolSection& section : summary.sections) {
    if (!section.posted) continue;
    run.tool = section.entry->geometry();
    run.vc = section.vc_nominal;
    break;
  }
  return run;
}

namespace {

// One line per section, when there is more than one or one is kept.
void print_sections(const post::PostSummary& summary) {
  const bool all_posted = std::all_of(summary.sections.begin(), summary.sections.end(),
                                      [](const post::ToolSection& s) { return s.posted; });
  if (summary.sections.size() <= 1 && all_posted) return;
  for (const post::ToolSection& s : summary.sections) {
    std::ostringstream line;  // numbers as the stream writes them (vc: 6 digits)
    line << "  line " << s.first_line << ": " << section_name(s) << ": ";
    if (s.posted) {
      line << "posted at vc " << s.vc_nominal << " m/min, " << s.points << " points, " << s.s_words
           << " S words";
      if (s.before && s.after) {
        line << ", within +-10 %: "
             << static_cast<int>(std::round(s.before->within_10_percent * 100)) << " % before, "
             << static_cast<int>(std::round(s.after->within_10_percent * 100)) << " % after";
      }
    } else {
      line << "kept, " << s.reason << " (" << s.points << " points)";
    }
    log().info("{}", line.str());
  }
}

// The allowance each evaluated section's contact was taken with, when any.
void print_allowances(const post::PostSummary& summary) {
  for (const post::ToolSection& s : summary.sections) {
    if (!s.postable || s.stock.is_zero()) continue;
    std::ostringstream line;
    line << "  " << section_name(s) << ": contact with the model offset by " << s.stock.radial;
    if (!s.stock.is_uniform()) line << " mm radially, " << s.stock.axial << " axially";
    line << " mm (--stock)";
    log().info("{}", line.str());
  }
}

// Gouge and lift depths of the evaluated sections, and the diagnosis of a
// path consistently off the model.
void print_depths(const post::PostSummary& summary) {
  for (const post::ToolSection& s : summary.sections) {
    const std::string name = summary.sections.size() > 1 ? section_name(s) + ": " : std::string();
    for (const auto& [depth, what] :
         {std::pair{&s.gouge, "gouge depth"}, std::pair{&s.lift, "lift height"}}) {
      if (depth->points > 0) log().info("  {}{}", name, depth_words(*depth, what));
    }
    if (s.offset) log().warn("{}{}", name, offset_words(*s.offset));
  }
}

}  // namespace

void finish_job(const PostArguments& args, const JobRun& run) {
  const post::PostSummary& summary = run.summary;
  std::vector<std::string> notes = run.notes;
  if (!args.summary_json.empty()) {
    const std::string json =
        report::post_summary_json(summary_inputs(args, run), run.tool.has_value(), summary,
                                  run.run_time_s)
            .dump(2) +
        "\n";
    if (args.summary_json == "-") {
      std::cerr << json;
    } else {
      AtomicFile out(args.summary_json);
      out.write(json);
      out.commit();
      note_links(out, args.summary_json, notes);
    }
  }
  std::ostringstream totals;  // vc as the stream writes it
  totals << summary.samples << " points, " << summary.s_words << " S words";
  if (args.adjust_feed) totals << ", " << summary.f_words << " F words";
  if (summary.before && summary.after) {
    totals << "; cutting time within +-10 % of vc " << vc_words(summary)
           << " m/min: " << static_cast<int>(std::round(summary.before->within_10_percent * 100))
           << " % before, " << static_cast<int>(std::round(summary.after->within_10_percent * 100))
           << " % after";
  }
  log().info("{}", totals.str());
  print_sections(summary);
  print_allowances(summary);
  for (const auto& path : args.reports) {
    if (path != "-") log().info("report written to {}", path);
  }
  for (const auto& note : notes) {
    constexpr std::string_view kWarning = "warning: ";
    if (note.starts_with(kWarning)) {
      log().warn("{}", note.substr(kWarning.size()));
    } else {
      log().info("{}", note);
    }
  }
  if (summary.repeated_lines > 0) {
    log().info(
        "{} lines run more than once (subroutines, loops): each has the lowest S (F) of its runs",
        summary.repeated_lines);
  }
  print_depths(summary);
  for (const std::string& note : summary.tool_notes) log().info("note: {}", note);
  if (summary.path_normals) {
    const pipeline::PathNormalCounts& n = *summary.path_normals;
    log().info(
        "no --model: each point's normal from the toolpath: {} two-sided, {} one-sided, {} "
        "without one (no pass near enough: no S of their own, a pass with none keeps the "
        "program's); no gouge check, no cusp map",
        n.two_sided, n.one_sided, n.kept);
  } else if (args.model.empty()) {
    log().info("no --model: the CL data is translated for {} with its own speeds",
               run.profile.name());
  } else if (!summary.sections.empty() &&
             std::none_of(summary.sections.begin(), summary.sections.end(),
                          [](const post::ToolSection& s) { return s.posted; })) {
    log().warn(
        "no section is posted (each section's reason is above): the program keeps its own "
        "speeds");
  }
  print_warnings(summary, program_name(args));
}

}  // namespace vcpost::cli
