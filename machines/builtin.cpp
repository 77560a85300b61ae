#include "machines/builtin.h"

#include <algorithm>

namespace vcpost::machines {

namespace detail {
// Defined in the generated builtin_profiles_data.cpp (machines/CMakeLists.txt).
extern const BuiltinProfile kBuiltinProfiles[];
extern const std::size_t kBuiltinProfileCount;
}  // namespace detail

std::span<const BuiltinProfile> builtin_profiles() {
  return {detail::kBuiltinProfiles, detail::kBuiltinProfileCount};
}

bool is_builtin_profile(std::string_view name) {
  const auto all = builtin_profiles();
  return std::any_of(all.begin(), all.end(), [&](const auto& p) { return p.name == name; });
}

MachineProfile builtin_profile(std::string_view name) {
  std::string names;
  for (const auto& p : builtin_profiles()) {
    if (p.name == name) return profile_from_toml(p.text, std::string(p.path));
    names += names.empty() ? "" : ", ";
    names += p.name;
  }
  throw ProfileError(Code::E5009, {std::string(name)},
                     "no built-in machine profile of this name (built-in: " + names +
                         "; a profile file's path must end in .toml)");
}

}  // namespace vcpost::machines
