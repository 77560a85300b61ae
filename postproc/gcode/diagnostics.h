// Diagnostics of G-code reading: the typed codes of the reader and
// interpreter, messages that name file:line:col, and the exception thrown
// for a fatal problem. Summaries, severities and hints live in the one code
// table (core/error_codes.csv, docs/errors.md): a new code goes there too.
//
// Format: "<file>:<line>:<col>: error[E1203]: <message>" (warning[W....]).
// Codes are stable: tests and users may match on them; never renumber.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/error.h"

namespace vcpost::gcode {

using vcpost::Severity;

enum class Code : std::uint16_t {
  // 1xxx: bytes and words (lexical)
  bad_character = 1001,     // a byte that starts no word, comment or blank
  nul_byte = 1002,          // NUL or other control byte inside the text
  bad_number = 1003,        // a letter without a valid number after it
  unclosed_comment = 1004,  // '(' without ')' on the same line
  nested_comment = 1005,    // '(' inside a comment
  line_too_long = 1006,     // a line longer than the reader's limit
  unknown_word = 1007,      // a letter that is no word of this dialect
  word_repeated = 1008,     // the same letter twice in one block (X1 X2)
  word_without_use = 1009,  // a word no code of its block uses (RS274NGC: G1 Q7)
  dialect_mismatch = 1010,  // the text is plainly another dialect's (names which)
  // 12xx: parameters and expressions
  bad_expression = 1201,     // unbalanced brackets, missing operand, unknown operator
  unknown_parameter = 1202,  // reading a named parameter never set
  parameter_out_of_range = 1203,
  machine_state = 1204,  // value only the running control knows (#5021, #3020 ...)
  math_domain = 1205,    // division by zero, sqrt of a negative ...
  parameters_not_in_dialect = 1206,
  // 13xx: program flow
  unsupported_flow = 1301,  // GOTO, WHILE/DO in Fanuc macros, M98 to another file ...
  unknown_subroutine = 1302,
  unmatched_control = 1303,    // endsub/endif/... without its opening word
  call_depth = 1304,           // subroutine nesting beyond the limit
  missing_program_end = 1305,  // file ends without M2/M30/% (warning)
  external_macro = 1306,       // G65 to a macro not in the file: taken as not moving (warning)
  loop_limit = 1307,           // a loop runs more than the iteration limit
  cycle_moves = 1308,          // one canned-cycle block makes more moves than the limit
  block_limit = 1309,          // the program runs more blocks than the bound
  sub_definition = 1310,       // an o-sub defined twice, or after a call ran it (rs274 refuses)
  text_after_end = 1311,       // lines after the closing '%' are not read (warning)
  // 14xx: G/M codes and modal rules
  unknown_g_code = 1401,
  unknown_m_code = 1402,  // error in RS274NGC; warning in Fanuc/Mazak (machine M codes)
  modal_group_conflict = 1403,
  unsupported_code = 1404,  // G92, G10, G68, canned cycles ... refused
  too_many_m_codes = 1405,
  mode_code_passed = 1406,  // a control's own mode code passed through (warning, once)
  // 15xx: motion
  missing_arc_data = 1501,     // G2/G3 without I/J/K or R, or without an end point for R
  arc_radius_mismatch = 1502,  // start and end radius differ beyond tolerance
  arc_r_too_small = 1503,      // |R| smaller than half the chord
  arc_zero_radius = 1504,
  missing_feed = 1505,          // feed move with F = 0
  axis_not_supported = 1506,    // A/B/C/U/V/W in a 3-axis reader
  missing_axis_word = 1507,     // G2/G3 or G28 axis rules
  words_without_motion = 1508,  // axis words but no motion mode (G80)
  machine_coordinates = 1509,   // G53/G28 moves taken with zero offsets (warning)
  work_offset_change = 1510,    // switching G54..G59 after motion: offsets unknown
  bad_word_value = 1511,        // negative S, T, non-integer where an integer is required
  frame_change = 1512,          // offsets (G92, G52, G10, G55 ...) changed after motion (warning)
  cycle_value = 1513,           // canned cycle without R/Z/Q/P, R below Z, Q <= 0
  missing_word = 1514,          // G4 without its time, M98 without P
  nurbs_curve = 1515,           // G5.3 without G5.2, too few points, frame change inside
  nurbs_axis_ignored = 1516,    // the third axis word of a G5.2 block (warning)
  // 162x: the spindle speed on an analog output (Dialect::speed_output)
  negative_speed_output = 1620,  // M67/M68 E<speed output> Q<0
  speed_output_words = 1621,     // M67/M68 without its E or Q word
};

struct CodeInfo {
  Code code;
  Severity severity;
  std::string_view summary;
};

// The code's entry (severity as usually reported, summary) from the one
// code table; every enumerator is in it (tested).
CodeInfo info(Code code);

// "E1502" / "W1509" style identifier.
std::string code_id(Code code, Severity severity);

struct Diagnostic {
  Code code = Code::bad_character;
  Severity severity = Severity::error;
  std::uint32_t line = 0;    // 1-based
  std::uint32_t column = 0;  // 1-based, bytes
  std::string message;
};

// "<file>:<line>:<col>: error[E1502]: <message>"
std::string format(const Diagnostic& diagnostic, std::string_view file_name);

// Thrown by the reader/interpreter for an error: the block is not executed
// and the interpreter stops (what follows would depend on it).
class GcodeError : public vcpost::Error {
 public:
  explicit GcodeError(Diagnostic diagnostic);
  const Diagnostic& diagnostic() const { return diagnostic_; }

 private:
  Diagnostic diagnostic_;
};

}  // namespace vcpost::gcode
