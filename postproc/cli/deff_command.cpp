#include "postproc/cli/commands.h"

namespace vcpost::cli {

void add_deff_command(CLI::App& app) {
  auto* deff = app.add_subcommand("deff", "Working diameter of the tool at one point or a sweep");
  deff->callback([] { throw CommandError("deff: being written", exit_internal); });
}

}  // namespace vcpost::cli
