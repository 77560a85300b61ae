// `vcpost explain [CODE]`: a diagnostic code's meaning and what to do, from
// the one code table (core/error_codes.csv); without CODE, the whole list.
#include <iostream>
#include <string>

#include "core/error.h"
#include "postproc/cli/commands.h"
#include "postproc/cli/interrupt.h"

namespace vcpost::cli {

int exit_code_of(const std::exception& error) {
  const auto* known = dynamic_cast<const vcpost::Error*>(&error);
  if (known == nullptr) return exit_internal;
  // A warning's row exits 0; thrown, it still stopped the run.
  return known->exit_code() == exit_ok ? exit_input_error : known->exit_code();
}

namespace {

void print_entry(const CodeInfo& row) {
  std::cout << row.id << "  " << row.name << " (" << to_string(row.severity) << ", exit "
            << row.exit_code << ")\n"
            << "  " << row.summary << "\n"
            << "  what to do: " << row.hint << '\n';
}

}  // namespace

void add_explain_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "explain", "Print what a diagnostic code (E1403, W3150 ...) means and what to do about it");
  auto code = std::make_shared<std::string>();
  cmd->add_option("CODE", *code,
                  "the code as printed in error[...] or warning[...]; "
                  "without it, every code is listed");
  cmd->footer("The same table is docs/errors.md.");
  cmd->callback([code] {
    standard_output_is_the_only_output();
    if (code->empty()) {
      for (const CodeInfo& row : code_table())
        std::cout << row.id << "  " << row.name << ": " << row.summary << '\n';
      return;
    }
    const CodeInfo* row = find_code(*code);
    if (row == nullptr) {
      throw CommandError("explain: no code '" + *code +
                         "' (codes look like E1403 or W3150; `vcpost explain` lists them)");
    }
    print_entry(*row);
  });
}

}  // namespace vcpost::cli
