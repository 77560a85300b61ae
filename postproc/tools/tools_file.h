// The tools file of `--tools FILE.toml`: a tool table written by the user
// (schema and example in postproc/tools/README.md). Reads text it is given.
#pragma once

#include <string>
#include <string_view>

#include "postproc/tools/tool_table.h"

namespace vcpost::tools {

// Adds every [[tool]] of `text` to `table` with origin tools_file and
// where = "file:line". Throws ToolTableError with file:line:col for a TOML
// syntax error, an unknown key or table, a missing or mistyped value (E1604)
// and a value out of range or a number given twice (E1605).
void load_tools_file(std::string_view text, const std::string& file_name, ToolTable& table);

}  // namespace vcpost::tools
