// How the Klartext interpreter gets a program that CALL PGM names: the
// command line gives it a loader that reads files (the reader reads none).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace vcpost::heidenhain {

// A program that CALL PGM names, as its caller's loader found it.
struct CalledProgram {
  std::string_view text;  // kept alive by the loader as long as the interpreter
  std::string name;       // its path, for messages (file:line:col)
};

// Finds the program `path` names (as written after CALL PGM or SEL PGM),
// `caller` the name of the program that calls it ("" for the main one);
// empty when there is none.
using ProgramLoader =
    std::function<std::optional<CalledProgram>(std::string_view path, std::string_view caller)>;

}  // namespace vcpost::heidenhain
