// vcpost: constant cutting speed for 3-axis ball-end finishing.
// Thin entry point: builds the command line, maps errors to exit codes.
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "postproc/cli/app.h"
#include "postproc/cli/commands.h"
#include "postproc/cli/interrupt.h"

// The whole body is in the try: building the command line can throw too.
int main(int argc, char** argv) try {
  using namespace vcpost::cli;
  install_signal_handlers();  // before any thread: interrupts leave no temporary file
  CLI::App app;
  configure_app(app);

  const CLI::App& commands = app;
  if (argc > 1 && argv[1][0] != '-' &&
      commands
          .get_subcommands([&](const CLI::App* command) { return command->get_name() == argv[1]; })
          .empty()) {
    std::string names;  // from the command line's own definition
    for (const CLI::App* command : commands.get_subcommands({})) {
      names += (names.empty() ? "" : ", ") + command->get_name();
    }
    std::cerr << "vcpost: error: unknown command '" << printable(argv[1]) << "'; the commands are "
              << names << " (vcpost --help)\n";
    return exit_input_error;
  }
  if (const auto refusal = empty_option_value(std::vector<std::string>(argv + 1, argv + argc))) {
    std::cerr << "vcpost: error: " << printable(*refusal) << '\n';
    return exit_input_error;
  }
  try {
    app.parse(argc, argv);
    finish_standard_output();
  } catch (const CLI::ParseError& e) {
    // CLI11 prints help and usage errors itself; usage errors exit 2.
    // Help goes to standard output alone (`vcpost post --help | head`).
    standard_output_is_the_only_output();
    const int code = app.exit(e);
    return code == 0 ? exit_ok : exit_input_error;
  }
  return exit_ok;
} catch (const std::exception& e) {
  using namespace vcpost::cli;
  // One line: a vcpost::Error is the user's to fix (or a known internal
  // fault, E9xxx), anything else is an internal error.
  const bool known = dynamic_cast<const vcpost::Error*>(&e) != nullptr;
  std::cerr << (known ? "vcpost: error: " : "vcpost: internal error: ") << printable(e.what())
            << '\n';
  return exit_code_of(e);
}
