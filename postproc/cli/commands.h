// The subcommands of `vcpost`. Each add_* function registers one subcommand
// on the app; its callback does the work and reports failure by throwing a
// vcpost::Error (CommandError for the command's own checks; the libraries'
// errors pass through with their codes) or CLI11's own errors for bad
// arguments. main() turns an Error into one line on stderr and the exit
// status of its code's row in the code table.
#pragma once

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/error.h"
#include "machines/profile.h"

namespace vcpost::cli {

// Documented exit codes (README): 0 ok, 1 warnings with --strict,
// 2 usage or input error, 3 internal error.
enum ExitCode : int { exit_ok = 0, exit_warnings = 1, exit_input_error = 2, exit_internal = 3 };

// A failure of the command itself (bad usage, an unreadable or unwritable
// file); the message already names the argument or file:line:col at fault.
// Without a code it is E2001 (bad command line, exit 2).
class CommandError : public vcpost::Error {
 public:
  explicit CommandError(const std::string& message) : vcpost::Error(Code::E2001, message) {}
  CommandError(Code code, const std::string& message) : vcpost::Error(code, message) {}
  // "file:line:col: error[code]: message".
  CommandError(Code code, const SourceLocation& where, const std::string& message)
      : vcpost::Error(code, format_diagnostic(code, where, message), where) {}
};

// The exit status of an exception that escapes a command: the code table's
// for a vcpost::Error, exit_internal for anything else.
int exit_code_of(const std::exception& error);

void add_deff_command(CLI::App& app);
void add_moves_command(CLI::App& app);
void add_machines_command(CLI::App& app);
void add_post_command(CLI::App& app);
void add_report_command(CLI::App& app);
void add_verify_command(CLI::App& app);
void add_explain_command(CLI::App& app);

// `text` with control bytes (CR, NUL, ESC ...) and DEL shown as \xNN: a
// message quoting a file's bytes must not move the cursor or hide itself.
std::string printable(std::string_view text);

// Writes to stdout; throws CommandError (exit 2) with the system's reason
// when the bytes are not taken (the rest of the output would be lost too).
void write_standard_output(std::string_view bytes);

// Flushes stdout (C and C++ streams) and throws CommandError (exit 2) when
// anything written to it was lost (a full disk, /dev/full, a closed pipe
// with SIGPIPE ignored): a command's output that did not arrive is no success.
void finish_standard_output();

// The profile of `--machine NAME|FILE`: a shipped profile's name, or a
// TOML file. Throws CommandError (exit 2) naming file:line:col and the key.
machines::MachineProfile load_machine(const std::string& name_or_file);

}  // namespace vcpost::cli
