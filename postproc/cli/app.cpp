#include "postproc/cli/app.h"

#include "postproc/cli/commands.h"
#include "vcpost/version.h"

namespace vcpost::cli {

void configure_app(CLI::App& app) {
  app.description(
      "vcpost: keeps the real cutting speed constant in 3-axis ball-end finishing by\n"
      "rewriting the spindle speed from the tool's working diameter at every point.");
  app.require_subcommand(1);
  app.set_version_flag("--version", api::version_line());
  // Set before the subcommands: each one inherits it.
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
}

std::optional<std::string> empty_option_value(const std::vector<std::string>& args) {
  for (const std::string& arg : args) {
    if (arg == "--") break;
    if (arg.size() > 3 && arg.compare(0, 2, "--") == 0 && arg.back() == '=' &&
        arg.find('=') == arg.size() - 1) {
      const std::string name = arg.substr(0, arg.size() - 1);
      std::string message = name;
      message.append(": empty value after '=' (give ").append(name).append("=VALUE or ");
      return message.append(name).append(" VALUE)");
    }
  }
  return std::nullopt;
}

}  // namespace vcpost::cli
