#include "postproc/gcode/diagnostics.h"

#include <array>
#include <cstdio>

namespace vcpost::gcode {

namespace {

using enum Code;
constexpr Severity E = Severity::error;
constexpr Severity W = Severity::warning;

constexpr std::array kTable{
    CodeInfo{bad_character, E, "unexpected character"},
    CodeInfo{nul_byte, E, "NUL or control byte in the program text"},
    CodeInfo{bad_number, E, "bad number"},
    CodeInfo{unclosed_comment, E, "comment not closed on its line"},
    CodeInfo{nested_comment, E, "nested comment"},
    CodeInfo{line_too_long, E, "line too long"},
    CodeInfo{unknown_word, E, "unknown word"},
    CodeInfo{word_repeated, E, "word given twice in one block"},
    CodeInfo{word_without_use, E, "word with no code in its block that uses it"},
    CodeInfo{dialect_mismatch, E, "the program is written in another dialect"},
    CodeInfo{bad_expression, E, "bad expression"},
    CodeInfo{unknown_parameter, E, "parameter read before it was set"},
    CodeInfo{parameter_out_of_range, E, "parameter number out of range"},
    CodeInfo{machine_state, E, "value known only to the running control"},
    CodeInfo{math_domain, E, "arithmetic error"},
    CodeInfo{parameters_not_in_dialect, E, "parameters are not part of this dialect"},
    CodeInfo{unsupported_flow, E, "program flow that cannot be followed soundly"},
    CodeInfo{unknown_subroutine, E, "subroutine not found"},
    CodeInfo{unmatched_control, E, "control word without its opening word"},
    CodeInfo{call_depth, E, "subroutine or loop nesting too deep"},
    CodeInfo{missing_program_end, W, "program ends without M2 or M30"},
    CodeInfo{external_macro, W, "macro call to a program not in this file"},
    CodeInfo{unknown_g_code, E, "unknown G code"},
    CodeInfo{unknown_m_code, E, "unknown M code"},
    CodeInfo{modal_group_conflict, E, "two codes of one modal group in a block"},
    CodeInfo{unsupported_code, E, "code not supported by vcpost"},
    CodeInfo{too_many_m_codes, E, "too many M codes in a block"},
    CodeInfo{mode_code_passed, W, "control mode code passed through unchanged"},
    CodeInfo{missing_arc_data, E, "arc without its centre or radius"},
    CodeInfo{arc_radius_mismatch, E, "arc radius to end differs from radius to start"},
    CodeInfo{arc_r_too_small, E, "arc radius too small for the chord"},
    CodeInfo{arc_zero_radius, E, "arc of zero radius"},
    CodeInfo{missing_feed, E, "feed move with a zero feed rate"},
    CodeInfo{axis_not_supported, E, "axis not supported by the 3-axis reader"},
    CodeInfo{missing_axis_word, E, "axis word missing"},
    CodeInfo{words_without_motion, E, "axis words without a motion mode"},
    CodeInfo{machine_coordinates, W, "machine-coordinate move taken with zero offsets"},
    CodeInfo{work_offset_change, E, "work coordinate system changed after motion"},
    CodeInfo{bad_word_value, E, "bad word value"},
    CodeInfo{frame_change, W, "coordinate frame changed after motion"},
    CodeInfo{cycle_value, E, "canned cycle word missing or out of range"},
};

}  // namespace

const CodeInfo& info(Code code) {
  for (const auto& entry : kTable) {
    if (entry.code == code) return entry;
  }
  return kTable[0];  // unreachable: every enumerator is in the table (tested)
}

std::string code_id(Code code, Severity severity) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%c%04u", severity == Severity::error ? 'E' : 'W',
                static_cast<unsigned>(code));
  return buffer;
}

std::string format(const Diagnostic& d, std::string_view file_name) {
  std::string out(file_name);
  out += ':' + std::to_string(d.line) + ':' + std::to_string(d.column) + ": ";
  out += d.severity == Severity::error ? "error[" : "warning[";
  out += code_id(d.code, d.severity);
  out += "]: ";
  out += d.message;
  return out;
}

GcodeError::GcodeError(Diagnostic diagnostic)
    : std::runtime_error(format(diagnostic, "")), diagnostic_(std::move(diagnostic)) {}

}  // namespace vcpost::gcode
