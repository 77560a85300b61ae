// Diagnostics of the APT CL reader: its typed codes (E31xx errors, W31xx
// warnings; summaries and severities in the one code table,
// core/error_codes.csv), the error type it throws and the warnings it collects.
// Format of a diagnostic: "file:line:col: error[E3103]: message".
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/error.h"

namespace vcpost::cldata {

using vcpost::Severity;

// Codes are stable: never renumber, only append.
enum class ClCode {
  line_too_long,               // E3101
  invalid_byte,                // E3102
  bad_number,                  // E3103
  wrong_parameters,            // E3104
  unexpected_word,             // E3105
  truncated_record,            // E3106
  orphan_points,               // E3107
  tool_axis_not_z,             // E3108
  arc_inconsistent,            // E3109
  arc_without_goto,            // E3110
  bad_nurbs,                   // E3111
  unsupported_cycle,           // E3112
  apt_source_statement,        // E3113
  no_start_position,           // E3114
  surface_speed_no_tool,       // E3115
  bad_units,                   // E3116
  unsupported_record,          // E3117
  unknown_record,              // W3150 (no longer given: unknown records are E3118)
  missing_fini,                // W3151
  after_fini,                  // W3152
  tool_not_modelled,           // W3153
  ignored_option,              // W3154
  unknown_word,                // E3118
  frame_not_identity,          // E3119
  tool_change_without_number,  // E3120
  bad_cutter_size,             // E3122
};

struct ClCodeInfo {
  ClCode code;
  std::string_view id;  // "E3101"
  Severity severity;
  std::string_view summary;
};

// The whole table, in code order (for docs and tests).
std::span<const ClCodeInfo> cl_code_table();
const ClCodeInfo& info(ClCode code);

// A problem at a place in a CL file. line and column are 1-based (0 = unknown).
struct ClDiagnostic {
  ClCode code = ClCode::unknown_record;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  std::string message;
};

// "file:line:col: error[E3103]: message" (file may be empty).
std::string format(const ClDiagnostic& diagnostic, std::string_view file_name);

// Thrown for input the reader cannot convert soundly; what() is the formatted
// diagnostic with the file name.
class ClError : public vcpost::Error {
 public:
  ClError(ClDiagnostic diagnostic, std::string_view file_name)
      : vcpost::Error(cldata::info(diagnostic.code).id, format(diagnostic, file_name),
                      {std::string(file_name), diagnostic.line, diagnostic.column}),
        diagnostic_(std::move(diagnostic)) {}
  const ClDiagnostic& diagnostic() const { return diagnostic_; }
  ClCode code() const { return diagnostic_.code; }

 private:
  ClDiagnostic diagnostic_;
};

}  // namespace vcpost::cldata
