// `vcpost verify INPUT OUTPUT`: proves that a posted program differs from
// its input only in S and F words (or, from CL data, moves like them).
// Reading, printing and exit codes only; the proof is postproc/verify.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "postproc/cli/commands.h"
#include "postproc/cli/interrupt.h"
#include "postproc/cli/number_options.h"
#include "postproc/cli/program_text.h"
#include "postproc/gcode/dialect.h"
#include "postproc/post/post_job.h"
#include "postproc/verify/verify.h"

namespace vcpost::cli {
namespace {

// Exit code when the proof fails (distinct from input errors, 2).
// Violations printed on stderr before "... and K more".
constexpr std::size_t kShown = 20;

constexpr const char* kVerifyDescription =
    "Proves that OUTPUT is INPUT with only S and F words changed, as `vcpost post` writes it.\n"
    "\n"
    "G-code INPUT: every byte outside S/F words must be equal (lines, line endings, words,\n"
    "blanks, comments; nothing inside comments may change). An S/F word may get a new value\n"
    "(a plain positive number) or be added to a block that had none; it may not be removed\n"
    "or repeated. Then both programs are interpreted (--dialect, default the --machine\n"
    "profile's) and must give the same motions and other events, positions exactly equal;\n"
    "only spindle speeds and feed rates may differ.\n"
    "APT CL INPUT: OUTPUT (G-code in the --machine profile's output format) must hold the CL\n"
    "motions one to one: rapids as rapids, feeds as feeds, arcs with the same plane,\n"
    "direction and centre; end points within --tolerance on each axis (at least half a\n"
    "step of the profile's output decimals, the rounding a correct output has); spindle\n"
    "on/off, tool changes and cutter compensation sides (CUTCOM as G40/G41/G42) in the\n"
    "same order. S and F values are free.\n"
    "Klartext INPUT (a HEIDENHAIN .h program): each block of OUTPUT is the input's with only\n"
    "its number, its TOOL CALL's S digits and its plain F digits changed; inserted\n"
    "`TOOL CALL S` blocks stand right before a block that moves, and every block number is\n"
    "the input's plus the blocks inserted before it; both programs read into the same\n"
    "events but speeds and feeds. APT CL INPUT with Klartext OUTPUT: read back by the\n"
    "Klartext reader and compared with the CL motions as above.\n"
    "\n"
    "Prints \"verified: ...\" and exits 0 when the proof holds. Each difference goes to\n"
    "stderr as file:line:col: error[E71xx]: message (line and column in OUTPUT, the\n"
    "input's line in brackets), at most 20 of them.\n"
    "Exit codes: 0 verified; 1 differences found; 2 usage or input error (unreadable\n"
    "file, INPUT that does not read); 3 internal error.\n"
    "\n"
    "Give verify the --machine (or --dialect) given to `vcpost post`; both default to the\n"
    "generic profile.\n"
    "\n"
    "Examples:\n"
    "  vcpost post finish.nc --model part.step --tool ball:10 --vc 120 --ap 0.3 -o finish.ccs.nc\n"
    "  vcpost verify finish.nc finish.ccs.nc --changes\n"
    "  vcpost post finish.cls --model part.step --vc 120 --ap 0.3 --machine mazak-3axis \\\n"
    "              -o finish.eia\n"
    "  vcpost verify finish.cls finish.eia --machine mazak-3axis\n";

struct Arguments {
  std::string input, output;
  bool changes = false;
  bool json = false;
  std::string machine = "generic";  // as `vcpost post`: the same flags verify what it wrote
  std::string dialect;
  double tolerance = 0.0005;
};

nlohmann::json to_json(const verify::Result& r) {
  nlohmann::json changes = nlohmann::json::array();
  for (const auto& c : r.changes)
    changes.push_back({{"line", c.line},
                       {"column", c.column},
                       {"input_line", c.input_line},
                       {"letter", std::string(1, c.letter)},
                       {"old", c.added ? nlohmann::json(nullptr) : nlohmann::json(c.old_text)},
                       {"new", c.new_text},
                       {"added", c.added}});
  nlohmann::json violations = nlohmann::json::array();
  for (const auto& v : r.violations)
    violations.push_back({{"code", std::string(to_string(v.code))},
                          {"line", v.line},
                          {"column", v.column},
                          {"input_line", v.input_line},
                          {"message", v.message}});
  nlohmann::json out = {{"verified", r.ok()},
                        {"input_kind", r.kind == verify::InputKind::gcode      ? "gcode"
                                       : r.kind == verify::InputKind::klartext ? "heidenhain"
                                                                               : "cldata"},
                        {"s_changes", r.s_changes},
                        {"f_changes", r.f_changes},
                        {"motions", r.motions},
                        {"violation_count", r.violation_count},
                        {"changes", std::move(changes)},
                        {"violations", std::move(violations)}};
  if (r.kind == verify::InputKind::cldata) out["tolerance_mm"] = r.tolerance_mm;
  return out;
}

void run(const Arguments& args) {
  if (args.input == "-" && args.output == "-")
    throw CommandError("verify: INPUT and OUTPUT cannot both be '-'");
  const machines::MachineProfile profile = load_machine(args.machine);
  const ProgramText input_text(args.input), output_text(args.output);
  const std::string_view input = input_text.view(), output = output_text.view();
  const post::ProgramKind input_kind = post::detect_program_kind(input);
  const bool cl_input = input_kind == post::ProgramKind::cldata;
  // From CL data vcpost wrote the output in the profile's output format.
  verify::Options options = post::cl_output_verify_options(profile);
  if (!cl_input) options.dialect = post::dialect_of(profile);
  if (!args.dialect.empty()) {
    const auto d = gcode::dialect_from_name(args.dialect);
    if (!d) throw CommandError("verify: --dialect: unknown dialect '" + args.dialect + "'");
    options.dialect = post::with_speed_output(*d, profile);
  }
  options.speed_output = options.dialect.speed_output;
  options.tolerance_mm = args.tolerance;
  const std::string in_name = args.input == "-" ? "<stdin>" : args.input;
  const std::string out_name = args.output == "-" ? "<stdin>" : args.output;
  const post::ProgramKind output_kind = post::detect_program_kind(output);
  if (output_kind == post::ProgramKind::cldata)
    throw CommandError("verify: " + out_name +
                       " is APT CL data; OUTPUT must be G-code or Klartext");
  const bool klartext_in = input_kind == post::ProgramKind::heidenhain;
  const bool klartext_out = output_kind == post::ProgramKind::heidenhain;
  if (!cl_input && klartext_in != klartext_out)
    throw CommandError("verify: " + in_name + " and " + out_name +
                       " are not both Klartext: vcpost posts a program in its own language");

  // Changes stream out (or are only counted); JSON needs them all.
  if (!args.json) {
    if (args.changes)
      options.on_change = [](const verify::Change& c) {
        std::cout << c.line << ": " << verify::describe(c) << '\n';
      };
    else
      options.on_change = [](const verify::Change&) {};
  }
  // An input that does not read leaves as the reader's vcpost::Error.
  const verify::Result result =
      cl_input      ? (klartext_out ? verify::verify_cl_klartext(input, output, options, in_name)
                                    : verify::verify_cl(input, output, options, in_name))
      : klartext_in ? verify::verify_klartext(input, output, options, in_name)
                    : verify::verify_gcode(input, output, options, in_name);

  if (args.json) std::cout << to_json(result).dump(2) << '\n';
  finish_standard_output();
  if (!result.ok()) {
    for (std::size_t k = 0; k < result.violations.size() && k < kShown; ++k)
      std::cerr << printable(verify::format(result.violations[k], out_name)) << '\n';
    const std::uint64_t shown = std::min<std::uint64_t>(result.violations.size(), kShown);
    if (result.violation_count > shown)
      std::cerr << "... and " << result.violation_count - shown << " more\n";
    throw CommandError(Code::E7199, "verify: " + out_name + " differs from " + in_name + " in " +
                                        std::to_string(result.violation_count) +
                                        " place(s) other than S and F words");
  }
  if (!args.json)
    std::cout << "verified: only S and F words differ (" << result.s_changes << " S words, "
              << result.f_changes << " F words changed"
              << (result.kind == verify::InputKind::klartext
                      ? "; " + std::to_string(result.inserted_blocks) +
                            " TOOL CALL S blocks inserted, the blocks after them renumbered"
                      : "")
              << ")"
              << (result.kind == verify::InputKind::cldata
                      ? "; " + std::to_string(result.motions) + " motions match the CL data"
                      : "")
              << '\n';
}

}  // namespace

void add_verify_command(CLI::App& app) {
  auto args = std::make_shared<Arguments>();
  auto* cmd = app.add_subcommand(
      "verify", "Prove that a posted program differs from its input only in S and F words");
  cmd->description(kVerifyDescription);
  cmd->add_option("INPUT", args->input, "the program given to `vcpost post` (G-code or APT CL)")
      ->required();
  cmd->add_option("OUTPUT", args->output, "the program `vcpost post` wrote (G-code)")->required();
  cmd->add_flag("--changes", args->changes,
                "print each changed word: `LINE: S12000 -> S9870`, `LINE: + S9870` when added");
  cmd->add_flag("--json", args->json,
                "print the result as JSON (changes and differences) on standard output");
  cmd->add_option("--machine", args->machine,
                  "machine profile (built-in name or TOML file): the dialect, and the output "
                  "decimals for CL input")
      ->capture_default_str();
  cmd->add_option("--dialect", args->dialect,
                  "G-code dialect of both programs: rs274ngc, fanuc, mazak, sinumerik (default: "
                  "the profile's)");
  cmd->add_option("--tolerance", args->tolerance,
                  "CL input: largest per-axis distance of an output end point or arc centre from "
                  "the CL's, mm")
      ->capture_default_str()
      ->check(positive_number());
  cmd->callback([args] {
    standard_output_is_the_only_output();
    run(*args);
  });
}

}  // namespace vcpost::cli
