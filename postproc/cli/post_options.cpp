// The options of `vcpost post` and `vcpost report` and the job's settings
// made of them. The run is job_runner.cpp's.
#include "postproc/cli/post_options.h"

#include <fstream>
#include <sstream>

#include "postproc/cli/commands.h"
#include "postproc/cli/klartext_programs.h"
#include "postproc/cli/number_options.h"
#include "postproc/gcode/dialect.h"
#include "postproc/tools/tools_file.h"

namespace vcpost::cli {
namespace {

std::string read_text_file(const std::string& path, const std::string& option) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CommandError(Code::E2002, option + ": cannot read '" + path + "'");
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

// The in-process stock's settings but the triangles of --stock-model,
// which the run reads (job_runner.cpp); none without a source.
std::optional<post::StockSettings> stock_settings(const PostArguments& args) {
  const int sources = (args.stock_from_program ? 1 : 0) + (args.stock_box.empty() ? 0 : 1) +
                      (args.stock_model.empty() ? 0 : 1);
  if (sources == 0) {
    if (args.stock_cell)
      throw CommandError("--stock-cell: sets the grid of a stock; none is given");
    return std::nullopt;
  }
  if (sources > 1)
    throw CommandError(Code::E4725,
                       "--stock-from-program, --stock-box and --stock-model: give one stock");
  post::StockSettings stock;
  stock.from_program = args.stock_from_program;
  if (!args.stock_box.empty()) stock.box = post::parse_stock_box(args.stock_box);
  stock.model_name = args.stock_model;
  stock.cell_mm = args.stock_cell;
  stock.memory_limit = static_cast<std::size_t>(args.stock_memory_mb * (1 << 20));
  return stock;
}

}  // namespace

post::PostSettings settings_from(const PostArguments& args) {
  post::PostSettings settings;
  settings.program_loader = klartext_program_files(args.program);
  settings.tools = tool_choices(args);
  if (!args.model.empty() && !(args.ap > 0)) throw CommandError("--ap: required");
  settings.point.ap = args.ap;
  settings.stock = stock_settings(args);
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

namespace {

// The program, the model and where the model sits.
void add_input_options(CLI::App& command, PostArguments& args) {
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
}

// The tools, their speeds and the allowance the CAM left on them.
void add_tool_options(CLI::App& command, PostArguments& args) {
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
}

// The in-process stock (docs/stock.md): its source, grid and memory.
void add_in_process_stock_options(CLI::App& command, PostArguments& args) {
  command.add_flag("--stock-from-program", args.stock_from_program,
                   "in-process stock: the block the program declares (Klartext BLK FORM, APT CL "
                   "INSERT/Stock Size); ap at each point from the material the earlier sections "
                   "left (not the --stock allowance)");
  command.add_option("--stock-box", args.stock_box,
                     "in-process stock: a block XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX, mm, in the "
                     "program's frame");
  command.add_option("--stock-model", args.stock_model,
                     "in-process stock: an STL of the raw part (mm), placed like the model by "
                     "--model-transform");
  command
      .add_option("--stock-cell", args.stock_cell,
                  "the in-process stock's grid cell, mm (default: the smallest evaluated tool's "
                  "D/50 within [0.05, 1], coarser where --stock-memory requires)")
      ->check(positive_number(0.001, 100));
  command
      .add_option("--stock-memory", args.stock_memory_mb,
                  "most memory the in-process stock and its copies take, MB")
      ->check(positive_number(1, 1 << 20))
      ->capture_default_str();
}

// The depth and width of cut.
void add_cut_options(CLI::App& command, PostArguments& args) {
  command
      .add_option("--ap", args.ap,
                  "depth of cut along the surface normal, mm (required with --model); with an "
                  "in-process stock the nominal one, and the one tilted (3+2) points take")
      ->check(positive_number());
  add_in_process_stock_options(command, args);
  command
      .add_option("--ae", args.ae,
                  "width of cut, mm: used where the toolpath shows no neighbouring pass")
      ->check(positive_number());
  command.add_flag("--ae-override", args.ae_override,
                   "use --ae everywhere instead of measuring it from the toolpath");
}

// The machine, how the speed is chosen and the feed coupled to it.
void add_machine_options(CLI::App& command, PostArguments& args) {
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
}

// How the program's path is read and evaluated.
void add_path_options(CLI::App& command, PostArguments& args) {
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
}

// The run: its summary, threads and what it prints.
void add_run_options(CLI::App& command, PostArguments& args) {
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

}  // namespace

void add_job_options(CLI::App& command, PostArguments& args) {
  add_input_options(command, args);
  add_tool_options(command, args);
  add_cut_options(command, args);
  add_machine_options(command, args);
  add_path_options(command, args);
  add_run_options(command, args);
}

}  // namespace vcpost::cli
