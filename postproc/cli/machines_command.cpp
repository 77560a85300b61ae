// `vcpost machines [list | show NAME|FILE]`: the shipped machine profiles,
// and any profile file checked and printed with the source of every value.
// Also load_machine(), the `--machine NAME|FILE` loader of the other commands.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include "machines/builtin.h"
#include "machines/profile.h"
#include "postproc/cli/commands.h"
#include "postproc/cli/interrupt.h"

namespace vcpost::cli {

namespace {

// A model or program given by mistake (`--machine part.step`) is named for
// what it is, not parsed as TOML into a confusing syntax error.
void refuse_non_toml(std::istream& in, const std::string& name) {
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  in.clear();
  in.seekg(0);
  std::string what;
  if (head.find("ISO-10303-21") != std::string::npos) {
    what = "a STEP file";
  } else if (head.find('\0') != std::string::npos) {
    what = "binary data (an STL model?)";
  } else if (head.rfind("solid", 0) == 0) {
    what = "an STL model";
  }
  if (!what.empty()) {
    throw CommandError(
        Code::E5010, "machine profile " + name + ": this is " + what +
                         ", not a TOML profile (--machine takes a built-in name or a .toml file)");
  }
}

}  // namespace

// A machines::ProfileError leaves with its own code.
machines::MachineProfile load_machine(const std::string& name_or_file) {
  if (machines::is_builtin_profile(name_or_file)) return machines::builtin_profile(name_or_file);
  const std::filesystem::path path(name_or_file);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    if (path.extension() != ".toml" && path.parent_path().empty())
      return machines::builtin_profile(name_or_file);  // throws with the list of names
    throw CommandError(Code::E5010, "machine profile " + name_or_file + ": no such file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CommandError(Code::E5010, "machine profile " + name_or_file + ": cannot open");
  refuse_non_toml(in, name_or_file);
  return machines::profile_from_stream(in, name_or_file);
}

namespace {

void list_profiles() {
  std::printf("%-16s %-9s %-14s %-17s %s\n", "NAME", "DIALECT", "S (rpm)", "ACCEL/DECEL rpm/s",
              "DESCRIPTION");
  for (const auto& entry : machines::builtin_profiles()) {
    const auto p = machines::builtin_profile(entry.name);
    const auto& s = p.spindle();
    const std::string range = std::to_string(static_cast<long>(s.n_min_rpm)) + "-" +
                              std::to_string(static_cast<long>(s.n_max_rpm));
    const std::string rates = std::to_string(static_cast<long>(s.acceleration_rpm_per_s)) + "/" +
                              std::to_string(static_cast<long>(s.deceleration_rpm_per_s));
    std::printf("%-16s %-9s %-14s %-17s %s\n", p.name().c_str(),
                std::string(machines::to_string(p.dialect())).c_str(), range.c_str(), rates.c_str(),
                p.description().c_str());
  }
  std::printf(
      "\n`vcpost machines show NAME` prints a profile with the source of every value;\n"
      "`--machine FILE` takes a profile of your own (start from `show generic`).\n");
}

void show_profile(const std::string& name_or_file) {
  const auto p = load_machine(name_or_file);
  std::size_t assumed = 0;
  std::size_t unsourced = 0;
  for (const auto key : machines::schema_keys()) {
    const auto* note = p.source_of(key);
    if (!note)
      ++unsourced;
    else if (!note->vendor)
      ++assumed;
  }
  const bool builtin = machines::is_builtin_profile(name_or_file);
  std::cout << "# " << p.name() << (builtin ? " (built-in, " : " (") << p.origin() << ")\n"
            << "# " << machines::schema_keys().size() << " keys: " << assumed
            << " assumed (not from a vendor document), " << unsourced << " without a source, "
            << machines::schema_keys().size() - assumed - unsourced << " from vendor documents\n\n"
            << machines::profile_to_toml(p);
}

}  // namespace

void add_machines_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "machines", "List the shipped machine profiles, or check and show one (NAME or FILE)");
  struct Options {
    std::string action = "list";
    std::string target;
  };
  auto options = std::make_shared<Options>();
  cmd->add_option("ACTION", options->action, "list | show")
      ->check(CLI::IsMember({"list", "show"}))
      ->capture_default_str();
  cmd->add_option("PROFILE", options->target,
                  "for show: a shipped profile's name or a profile file (.toml)");
  cmd->callback([options] {
    standard_output_is_the_only_output();
    if (options->action == "list") {
      if (!options->target.empty())
        throw CommandError("machines list takes no profile (did you mean `machines show " +
                           options->target + "`?)");
      list_profiles();
      return;
    }
    if (options->target.empty())
      throw CommandError("machines show needs a profile name or file (see `vcpost machines`)");
    show_profile(options->target);
  });
}

}  // namespace vcpost::cli
