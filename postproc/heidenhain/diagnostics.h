// Diagnostics of the Klartext reader: its typed codes (E33xx errors, W33xx
// warnings; summaries, severities and hints in the one code table,
// core/error_codes.csv), the error it throws and the warnings it collects.
// Format: "<file>:<line>:<col>: error[E3310]: <message>".
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/error.h"

namespace vcpost::heidenhain {

using vcpost::Severity;

// Codes are stable: never renumber, only append.
enum class Code : std::uint16_t {
  line_too_long = 3301,             // a block (its ~ lines together) longer than the limit
  bad_byte = 3302,                  // NUL, control or non-ASCII byte outside comments and names
  bad_number = 3303,                // a word whose value is no number or Q parameter
  unknown_block = 3304,             // a block that starts with no Klartext keyword
  missing_begin = 3305,             // a block before BEGIN PGM, or none at all
  bad_units = 3306,                 // BEGIN PGM without MM or INCH
  unexpected_word = 3307,           // a word its block does not take (L with DR+, C with PA)
  missing_word = 3308,              // a word its block needs (C without DR, CR without R)
  bad_parameter = 3309,             // a Q parameter number out of range
  arc_radius_mismatch = 3310,       // C/CP end not on the circle about CC
  arc_radius_too_small = 3311,      // CR radius below half the chord
  no_pole = 3312,                   // C, CP, LP before any CC
  tangent_undefined = 3313,         // CT without a contour to continue, or along it
  corner_not_between_lines = 3314,  // RND/CHF not between two straight lines, or too large
  unknown_label = 3315,             // CALL LBL / GOTO to a label not in the file
  call_depth = 3316,                // subprogram calls nested beyond the limit
  loop_limit = 3317,                // repeats and jumps beyond the limit
  math_domain = 3318,               // FN 4 by zero, FN 5 of a negative ...
  unsupported_function =
      3319,             // a function whose effect cannot be followed (FN 14, CALL PGM, FK, FU ...)
  tilted_plane = 3320,  // PLANE ... or CYCL DEF 19 with a tilt (3+2: issue 40)
  tool_axis_change = 3321,   // rotary axes that turn the tool or the part; TOOL CALL X/Y
  unsupported_cycle = 3322,  // a machining cycle whose moves are not modelled
  cycle_value = 3323,        // a drilling cycle's Q value missing or out of range
  cycle_not_defined = 3324,  // CYCL CALL / M99 without a cycle defined
  missing_feed = 3325,       // a feed move before any F
  unclosed_quote = 3326,     // a "name" without its closing quote
  // 3327: posting Klartext (the post job's, not the reader's)
  bad_formula = 3328,         // a Q parameter formula that does not parse
  approach_undefined = 3329,  // APPR/DEP whose path cannot be built as the TNC builds it
  fk_contour = 3330,          // FK free contour programming (FPOL, FL, FC ...)
  program_not_found = 3331,   // CALL PGM / SEL PGM of a program that cannot be read
  called_tool_call = 3332,    // a TOOL CALL in a called program, when posting the main one
  // Warnings
  machine_cycle = 3340,        // a machine or probing cycle passed: assumed to move nothing
  m_code_passed = 3341,        // an M code that does not move the tool, passed
  machine_coordinates = 3342,  // M91/M92/M140 taken as a retract to a safe height
  missing_end = 3343,          // the text ends without END PGM, M2 or M30
  function_passed = 3344,      // FUNCTION ..., FN 15/16 print and the like, passed
  helix_unknown = 3345,        // cycle 208 without the tool's radius: along the axis
};

// "E3310" / "W3342" (the severity the table gives the code).
std::string code_id(Code code);
Severity severity_of(Code code);

struct Diagnostic {
  Code code = Code::unknown_block;
  std::uint32_t line = 0;    // 1-based
  std::uint32_t column = 0;  // 1-based, bytes
  std::string message;
  std::string file;  // a called program's name; "" for the program being posted
  Severity severity() const { return severity_of(code); }
};

// "<file>:<line>:<col>: error[E3310]: <message>" (the diagnostic's own file,
// a called program, when it has one)
std::string format(const Diagnostic& diagnostic, std::string_view file_name);

// Thrown for input the reader cannot follow soundly: the block is not
// executed and the interpreter stops.
class KlartextError : public vcpost::Error {
 public:
  explicit KlartextError(Diagnostic diagnostic);
  const Diagnostic& diagnostic() const { return diagnostic_; }

 private:
  Diagnostic diagnostic_;
};

}  // namespace vcpost::heidenhain
