// The files of one run must be distinct: no output may be an input (the
// program, the model, the machine profile, the tools table) or another
// output, whatever the spelling of their names (relative, through symbolic
// links, hard links).
// Checked before any work, so a mistyped option never costs a file.
#pragma once

#include <string>
#include <vector>

namespace vcpost::cli {

struct NamedFile {
  std::string role;  // how the user named it, e.g. "-o", "--summary-json", "--model"
  std::string path;  // "-" (standard input or output) and "" are skipped
};

// Throws CommandError (exit 2) naming both options when an output is an
// input or when two outputs are the same file. Files compare by device and
// inode when they exist, else by the path their links lead to. A character
// device (/dev/null, a terminal) is written in place and loses nothing, so
// it may appear more than once.
void require_distinct_files(const std::vector<NamedFile>& inputs,
                            const std::vector<NamedFile>& outputs);

}  // namespace vcpost::cli
