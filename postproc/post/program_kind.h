// What language a program is in (G-code, APT CL data or Klartext,
// recognised by its content or named by the dialect) and which G-code
// dialect a machine profile reads and writes: the job's first decisions,
// apart from the job (post_job.h).
#pragma once

#include <string_view>

#include "machines/profile.h"
#include "postproc/gcode/dialect.h"

namespace vcpost::post {

enum class ProgramKind { gcode, cldata, heidenhain };
std::string_view to_string(ProgramKind kind);  // "gcode", "cldata", "heidenhain"

// The G-code dialect a machine profile reads.
gcode::Dialect dialect_of(const machines::MachineProfile& profile);
// The dialect of the G-code vcpost writes from CL data for the profile (its
// output format): what that output is read back in (verify). It differs
// from dialect_of where the control reads two languages and vcpost writes
// one (sinumerik-840d: Siemens language in, ISO dialect out).
gcode::Dialect output_dialect_of(const machines::MachineProfile& profile);

// G-code, APT CL data or Klartext, recognised by content: CL records are
// `WORD/...` statements (GOTO/, FEDRAT/, CUTTER/ ...) or bare PARTNO/FINI
// lines; a Klartext program's first block is `[n] BEGIN PGM <name> MM|INCH`.
ProgramKind detect_program_kind(std::string_view text);
// The kind for a dialect the user named (or the profile's): the heidenhain
// dialect reads Klartext whatever the content shows (its reader says what
// is wrong) but APT CL data, which is read as CL (a Heidenhain profile
// posts CL data to Klartext); every other dialect leaves the choice to the
// content.
ProgramKind program_kind(std::string_view text, const gcode::Dialect& dialect);

// A dialect named apart from the profile (--dialect names the language)
// with the profile's speed output (output.speed_word, the machine's
// wiring) where it is rs274ngc.
gcode::Dialect with_speed_output(gcode::Dialect dialect, const machines::MachineProfile& profile);

}  // namespace vcpost::post
