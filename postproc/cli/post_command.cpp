// `vcpost post`: the main job. Reads the program and the model, posts, and
// writes the program atomically; all the work is in postproc/post/.
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "postproc/cldata/cl_codes.h"
#include "postproc/cli/atomic_file.h"
#include "postproc/cli/commands.h"
#include "postproc/cli/model_loader.h"
#include "postproc/gcode/diagnostics.h"
#include "postproc/output/mazak_writer.h"
#include "postproc/post/post_job.h"
#include "postproc/program/timing.h"

namespace vcpost::cli {
namespace {

constexpr const char* kDescription =
    "Rewrites the spindle speed S (and with --adjust-feed the feed F) of a ball-end finishing\n"
    "program so that the real cutting speed at the tool's working diameter stays at --vc, within\n"
    "what the machine profile allows. G-code input keeps every byte but the S/F words; APT CL\n"
    "input becomes G-code in the profile's format.\n"
    "\n"
    "Example:\n"
    "  vcpost post finish.nc --model part.step --tool ball:10 --vc 120 --ap 0.3 \\\n"
    "              --machine mazak-3axis -o finish.ccs.nc --summary-json summary.json\n";

struct Arguments {
  std::string program, model, tool, machine = "generic", output, summary_json;
  std::string policy = "max", cl_point = "tip", dialect;
  double vc = 0, ap = 0, spacing = 0.5, tolerance = 0.01;
  std::optional<double> ae, fz;
  std::optional<int> teeth;
  bool ae_override = false, adjust_feed = false, quiet = false, strict = false;
};

std::string read_program(const std::string& path) {
  if (path == "-") {
    return {std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CommandError("'" + path + "': cannot open the program");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

nlohmann::json vc_json(const std::optional<post::VcStatistics>& s) {
  if (!s) return nullptr;
  return {{"min", s->min}, {"max", s->max}, {"mean", s->mean},
          {"within_5_percent", s->within_5_percent}, {"within_10_percent", s->within_10_percent}};
}

nlohmann::json summary_json(const Arguments& args, const post::PostSummary& s,
                            const LoadedModel& model, const machines::MachineProfile& profile,
                            double run_time_s) {
  return {
      {"program", args.program},
      {"kind", s.kind == post::ProgramKind::gcode ? "gcode" : "cldata"},
      {"model", {{"file", args.model}, {"kind", model.kind}, {"description", model.description}}},
      {"machine", profile.name()},
      {"tool", args.tool},
      {"vc_nominal", args.vc},
      {"ap", args.ap},
      {"ae", args.ae ? nlohmann::json(*args.ae) : nlohmann::json(nullptr)},
      {"policy", args.policy},
      {"blocks", s.blocks},
      {"motion_events", s.motion_events},
      {"points", s.samples},
      {"contact", {{"touching", s.touching}, {"lifted", s.lifted}, {"gouging", s.gouging},
                   {"missed", s.missed}}},
      {"ae_source", {{"measured", s.ae_measured}, {"given", s.ae_given},
                     {"first_pass", s.ae_first_pass}}},
      {"time_s", {{"program", s.program_time_s}, {"cutting", s.cutting_time_s},
                  {"clamped_max", s.time_clamped_max_s}, {"clamped_min", s.time_clamped_min_s},
                  {"slew", s.time_slew_s}, {"rate", s.time_rate_s}}},
      {"words_written", {{"s", s.s_words}, {"f", s.f_words}}},
      {"vc_before", vc_json(s.before)},
      {"vc_after", vc_json(s.after)},
      {"run_time_s", run_time_s},
  };
}

void run(const Arguments& args) {
  const auto started = std::chrono::steady_clock::now();
  if (args.output != "-" && args.program != "-" && same_file(args.program, args.output)) {
    throw CommandError("-o: '" + args.output + "' is the input program; it is never overwritten");
  }
  post::PostSettings settings;
  try {
    settings.point.tool = geometry::parse_tool(args.tool);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("--tool: ") + e.what());
  }
  if (settings.point.tool.kind != geometry::ToolKind::ball) {
    throw CommandError("--tool: posting is for ball-end mills (ball:D); use `vcpost deff` for " +
                       geometry::to_string(settings.point.tool));
  }
  if (args.ap >= settings.point.tool.diameter) throw CommandError("--ap: must be below the tool diameter");
  settings.point.ap = args.ap;
  settings.point.ae = args.ae;
  settings.point.ae_override = args.ae_override;
  settings.point.vc = args.vc;
  settings.point.contact_tolerance = args.tolerance;
  settings.point.cl_point = args.cl_point == "center" ? geometry::ClPoint::center : geometry::ClPoint::tip;
  settings.point.policy = args.policy == "tangent" ? pipeline::DiameterPolicy::tangent
                          : args.policy == "mean"  ? pipeline::DiameterPolicy::mean
                                                   : pipeline::DiameterPolicy::max;
  settings.sample_spacing_mm = args.spacing;
  settings.adjust_feed = args.adjust_feed;
  settings.fz_mm = args.fz;
  settings.teeth = args.teeth;
  if (!args.dialect.empty()) {
    settings.dialect = gcode::dialect_from_name(args.dialect);
    if (!settings.dialect) throw CommandError("--dialect: unknown dialect '" + args.dialect + "'");
  }

  const machines::MachineProfile profile = load_machine(args.machine);
  const LoadedModel model = load_model(args.model);
  const std::string text = read_program(args.program);
  const std::string name = args.program == "-" ? "<stdin>" : args.program;

  const bool show_progress = !args.quiet && ::isatty(STDERR_FILENO);
  const post::Progress progress = [&](double done) {
    if (show_progress) std::cerr << "\rvcpost: posting " << static_cast<int>(done * 100) << " %" << std::flush;
  };

  std::optional<AtomicFile> file;
  if (args.output != "-") file.emplace(args.output);
  std::string pending;  // stdout is written only once the job has succeeded
  const auto sink = [&](std::string_view bytes) {
    if (file) {
      file->write(bytes);
    } else {
      pending.append(bytes);
    }
  };
  post::PostSummary summary;
  try {
    summary = post::post_program(text, name, *model.model, profile, settings, sink, progress);
  } catch (const gcode::GcodeError& e) {
    throw CommandError(e.what());
  } catch (const cldata::ClError& e) {
    throw CommandError(e.what());
  } catch (const program::TimingError& e) {
    throw CommandError(name + ":" + std::to_string(e.source().line) + ": " + e.what());
  } catch (const output::OutputError& e) {
    throw CommandError(name + ":" + std::to_string(e.source().line) + ": " + e.what());
  } catch (const plan::PlanError& e) {
    throw CommandError(std::string("planning: ") + e.what(), exit_internal);
  }
  if (show_progress) std::cerr << "\r\x1b[K";
  if (summary.samples > 0 && summary.touching + summary.gouging == 0) {
    throw CommandError(
        "the toolpath never touches the model (" + std::to_string(summary.samples) +
        " points checked): check the work offset and units of the program against the model, "
        "and --cl-point (tip or center)");
  }
  if (file) file->commit();
  std::cout << pending << std::flush;

  const double run_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (!args.summary_json.empty()) {
    const std::string json = summary_json(args, summary, model, profile, run_time).dump(2) + "\n";
    if (args.summary_json == "-") {
      std::cerr << json;
    } else {
      AtomicFile out(args.summary_json);
      out.write(json);
      out.commit();
    }
  }
  const bool warnings = summary.gouging > 0 || summary.lifted + summary.missed > 0;
  if (!args.quiet) {
    std::cerr << "vcpost: " << summary.samples << " points, " << summary.s_words << " S words";
    if (args.adjust_feed) std::cerr << ", " << summary.f_words << " F words";
    if (summary.before && summary.after) {
      std::cerr << "; cutting time within +-10 % of vc " << args.vc << " m/min: "
                << static_cast<int>(std::round(summary.before->within_10_percent * 100)) << " % before, "
                << static_cast<int>(std::round(summary.after->within_10_percent * 100)) << " % after";
    }
    std::cerr << '\n';
    if (summary.gouging > 0) std::cerr << "vcpost: warning: " << summary.gouging << " points gouge the model\n";
    if (summary.lifted + summary.missed > 0) {
      std::cerr << "vcpost: warning: " << summary.lifted + summary.missed
                << " cutting points do not touch the model (their blocks keep the program's S)\n";
    }
  }
  if (warnings && args.strict) throw CommandError("warnings with --strict", exit_warnings);
}

}  // namespace

void add_post_command(CLI::App& app) {
  auto args = std::make_shared<Arguments>();
  auto* post = app.add_subcommand("post", "Rewrite S (and F) so the cutting speed stays nominal");
  post->description(kDescription);
  post->add_option("program", args->program, "G-code or APT CL program ('-': standard input)")->required();
  post->add_option("--model", args->model, "finished-surface model: STEP (mm or inch) or STL (mm)")->required();
  post->add_option("--tool", args->tool, "ball-end mill, ball:D with D in mm, e.g. ball:10")->required();
  post->add_option("--vc", args->vc, "nominal cutting speed, m/min")->required()->check(CLI::PositiveNumber);
  post->add_option("--ap", args->ap, "depth of cut along the surface normal, mm")->required()->check(CLI::PositiveNumber);
  post->add_option("--ae", args->ae, "width of cut, mm: used where the toolpath shows no neighbouring pass")
      ->check(CLI::PositiveNumber);
  post->add_flag("--ae-override", args->ae_override, "use --ae everywhere instead of measuring it from the toolpath");
  post->add_option("--machine", args->machine, "machine profile: a built-in name (vcpost machines list) or a TOML file")
      ->capture_default_str();
  post->add_option("-o,--output", args->output, "output program ('-': standard output); written whole or not at all")
      ->required();
  post->add_option("--policy", args->policy, "reference diameter: max (no edge faster than vc), tangent, mean")
      ->check(CLI::IsMember({"max", "tangent", "mean"}))->capture_default_str();
  post->add_flag("--adjust-feed", args->adjust_feed, "couple the feed to the speed: F = fz * z * n");
  post->add_option("--fz", args->fz, "feed per tooth for --adjust-feed, mm (default: the program's F at its S)")
      ->check(CLI::PositiveNumber);
  post->add_option("--teeth", args->teeth, "number of teeth for --adjust-feed (default: the profile's)")
      ->check(CLI::PositiveNumber);
  post->add_option("--cl-point", args->cl_point, "what the program's points are: the tool tip or the ball centre")
      ->check(CLI::IsMember({"tip", "center"}))->capture_default_str();
  post->add_option("--spacing", args->spacing, "largest distance between evaluated points, mm")
      ->check(CLI::PositiveNumber)->capture_default_str();
  post->add_option("--contact-tolerance", args->tolerance, "distance error still counted as contact, mm")
      ->check(CLI::PositiveNumber)->capture_default_str();
  post->add_option("--dialect", args->dialect, "G-code dialect: rs274ngc, fanuc, mazak (default: the profile's)");
  post->add_option("--summary-json", args->summary_json, "write a JSON summary to this file ('-': standard error)");
  post->add_flag("-q,--quiet", args->quiet, "print nothing but errors");
  post->add_flag("--strict", args->strict, "exit 1 when there were warnings (gouges, points without contact)");
  post->callback([args] { run(*args); });
}

}  // namespace vcpost::cli
