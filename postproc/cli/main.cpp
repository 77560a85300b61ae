// vcpost: constant cutting speed for 3-axis ball-end finishing.
// Thin entry point: registers the subcommands, maps errors to exit codes.
#include <exception>
#include <iostream>

#include "postproc/cli/commands.h"
#include "postproc/cli/interrupt.h"

int main(int argc, char** argv) {
  using namespace vcpost::cli;
  install_signal_handlers();  // before any thread: interrupts leave no temporary file
  CLI::App app{
      "vcpost: keeps the real cutting speed constant in 3-axis ball-end finishing by\n"
      "rewriting the spindle speed from the tool's working diameter at every point."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "vcpost 0.1.0");
  app.footer(
      "Exit codes: 0 done; 1 warnings with --strict; 2 bad usage or input, or an output that\n"
      "cannot be written (missing or read-only folder, disk full, file-size limit); 3 internal\n"
      "error; killed by SIGINT/SIGTERM/SIGHUP/SIGPIPE after removing unfinished outputs\n"
      "(the shell shows 128 + the signal's number: 130 for SIGINT, 143 for SIGTERM).");
  add_deff_command(app);
  add_moves_command(app);
  add_machines_command(app);
  add_post_command(app);
  add_report_command(app);
  add_verify_command(app);
  add_explain_command(app);

  const CLI::App& commands = app;
  if (argc > 1 && argv[1][0] != '-' &&
      commands.get_subcommands([&](const CLI::App* command) { return command->get_name() == argv[1]; })
          .empty()) {
    std::cerr << "vcpost: error: unknown command '" << printable(argv[1])
              << "'; the commands are deff, machines, moves, post, report, verify (vcpost --help)\n";
    return exit_input_error;
  }
  try {
    app.parse(argc, argv);
    finish_standard_output();
  } catch (const CLI::ParseError& e) {
    // CLI11 prints help and usage errors itself; usage errors exit 2.
    const int code = app.exit(e);
    return code == 0 ? exit_ok : exit_input_error;
  } catch (const std::exception& e) {
    // One line: a vcpost::Error is the user's to fix (or a known internal
    // fault, E9xxx), anything else is an internal error.
    const bool known = dynamic_cast<const vcpost::Error*>(&e) != nullptr;
    std::cerr << (known ? "vcpost: error: " : "vcpost: internal error: ") << printable(e.what()) << '\n';
    return exit_code_of(e);
  }
  return exit_ok;
}
