// The subcommands of `vcpost`. Each add_* function registers one subcommand
// on the app; its callback does the work and reports failure by throwing
// CommandError (or CLI11's own errors for bad arguments).
#pragma once

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

#include "machines/profile.h"

namespace vcpost::cli {

// Documented exit codes (README): 0 ok, 1 warnings with --strict,
// 2 usage or input error, 3 internal error.
enum ExitCode : int { exit_ok = 0, exit_warnings = 1, exit_input_error = 2, exit_internal = 3 };

// A failure to report as one line on stderr with the given exit code;
// the message already names the argument or file:line:col at fault.
class CommandError : public std::runtime_error {
 public:
  CommandError(const std::string& message, int exit_code = exit_input_error)
      : std::runtime_error(message), exit_code_(exit_code) {}
  int exit_code() const { return exit_code_; }

 private:
  int exit_code_;
};

void add_deff_command(CLI::App& app);
void add_moves_command(CLI::App& app);
void add_machines_command(CLI::App& app);
void add_post_command(CLI::App& app);
void add_report_command(CLI::App& app);
void add_verify_command(CLI::App& app);

// The profile of `--machine NAME|FILE`: a shipped profile's name, or a
// TOML file. Throws CommandError (exit 2) naming file:line:col and the key.
machines::MachineProfile load_machine(const std::string& name_or_file);

}  // namespace vcpost::cli
