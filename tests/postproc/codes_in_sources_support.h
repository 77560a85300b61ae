// The diagnostic codes a module's sources raise, read from the sources
// themselves (each `Code::E1234` token), so a bad-input test can check that
// every one of them has its bad file.
#pragma once

#include <filesystem>
#include <set>
#include <string>

namespace vcpost::testing {

// The ids ("E3104", "W3151") named as Code::... in the .cpp and .h files of
// `folder` (relative to the source root), not its subfolders.
std::set<std::string> codes_in_sources(const std::filesystem::path& folder);

}  // namespace vcpost::testing
