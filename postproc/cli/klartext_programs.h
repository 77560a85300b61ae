// The programs a Klartext program calls (CALL PGM, SEL PGM), found and read
// for the interpreter: a path relative to the calling program's folder, or
// TNC:\... taken from the main program's folder (the control's drive is not
// here: TNC:\dir\sub.h is looked for as dir/sub.h there, then sub.h beside
// the caller). Names compare without case, as the TNC's do; a name without
// an extension is tried with .h.
#pragma once

#include <filesystem>

#include "postproc/heidenhain/interpreter.h"

namespace vcpost::cli {

// A loader for programs called from `main_program` ("-" or empty: none is
// found). It keeps every text it read as long as it lives (copies of it
// share them).
heidenhain::ProgramLoader klartext_program_files(const std::filesystem::path& main_program);

}  // namespace vcpost::cli
