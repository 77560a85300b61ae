// The cases of a bad-input folder: its expected.txt holds one
// "file<TAB>expected message" line per file ('#' starts a comment).
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace vcpost::testing {

struct BadInputCase {
  std::string file, expected;
};

// The listed cases; a missing list or a line without its tab fails the
// calling test (and is left out).
inline std::vector<BadInputCase> read_bad_input_list(const std::filesystem::path& dir) {
  std::vector<BadInputCase> cases;
  std::ifstream list(dir / "expected.txt");
  if (!list) ADD_FAILURE() << "missing " << (dir / "expected.txt");
  std::string line;
  while (std::getline(list, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto tab = line.find('\t');
    if (tab == std::string::npos) {
      ADD_FAILURE() << "malformed line in expected.txt: " << line;
      continue;
    }
    cases.push_back({line.substr(0, tab), line.substr(tab + 1)});
  }
  return cases;
}

}  // namespace vcpost::testing
