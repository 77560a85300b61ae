// The machine-profile driver (see fuzz/finding.h for the contract of drivers).
#pragma once

#include <string>
#include <string_view>

#include "fuzz/finding.h"
#include "machines/profile.h"

namespace vcpost::fuzz {

// Loads a profile; a valid one must survive its own TOML round trip
// (profile_to_toml, then profile_from_toml gives the same text again).
inline std::string run_profile(std::string_view text) {
  try {
    const auto profile = machines::profile_from_toml(text, "fuzz.toml");
    const std::string once = machines::profile_to_toml(profile);
    std::string twice;
    try {
      twice = machines::profile_to_toml(machines::profile_from_toml(once, "round-trip.toml"));
    } catch (const machines::ProfileError& e) {
      throw FuzzFinding(std::string("written profile does not load again: ") + e.what());
    }
    if (once != twice) throw FuzzFinding("profile changed in its TOML round trip");
  } catch (const machines::ProfileError& e) {
    return std::string(e.id());
  }
  return "ok";
}

}  // namespace vcpost::fuzz
