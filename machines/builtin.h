// The profiles shipped with vcpost (machines/profiles/*.toml), compiled into
// the library at build time so that an installed vcpost needs no data folder.
#pragma once

#include <span>
#include <string_view>

#include "machines/profile.h"

namespace vcpost::machines {

struct BuiltinProfile {
  std::string_view name;  // file name without ".toml", e.g. "mazak-3axis"
  std::string_view path;  // "machines/profiles/mazak-3axis.toml" (for messages)
  std::string_view text;  // the file's bytes
};

// All shipped profiles, sorted by name.
std::span<const BuiltinProfile> builtin_profiles();

// The shipped profile `name`, validated. Throws ProfileError (E5009 with the
// list of names) when there is none of that name.
MachineProfile builtin_profile(std::string_view name);

// True if `name` is the name of a shipped profile.
bool is_builtin_profile(std::string_view name);

}  // namespace vcpost::machines
