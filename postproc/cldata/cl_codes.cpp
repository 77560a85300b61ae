#include "postproc/cldata/cl_codes.h"

#include <array>

namespace vcpost::cldata {

namespace {

constexpr std::array<ClCodeInfo, 24> table{{
    {ClCode::line_too_long, "E3101", Severity::error, "line longer than the reader's limit"},
    {ClCode::invalid_byte, "E3102", Severity::error, "control, NUL or non-ASCII byte outside text"},
    {ClCode::bad_number, "E3103", Severity::error, "malformed number"},
    {ClCode::wrong_parameters, "E3104", Severity::error, "wrong number or kind of parameters"},
    {ClCode::unexpected_word, "E3105", Severity::error, "minor word not valid in this record"},
    {ClCode::truncated_record, "E3106", Severity::error, "'$' continuation at the end of the file"},
    {ClCode::orphan_points, "E3107", Severity::error, "coordinates without a GOTO record"},
    {ClCode::tool_axis_not_z, "E3108", Severity::error,
     "tool axis other than +Z (multi-axis path) cannot be 3-axis motion"},
    {ClCode::arc_inconsistent, "E3109", Severity::error, "arc end point not on the circle"},
    {ClCode::arc_without_goto, "E3110", Severity::error, "CIRCLE/MOVARC not followed by GOTO"},
    {ClCode::bad_nurbs, "E3111", Severity::error, "malformed NURBS/KNOT/CNTRL data"},
    {ClCode::unsupported_cycle, "E3112", Severity::error, "canned cycle that is not expanded"},
    {ClCode::apt_source_statement, "E3113", Severity::error,
     "APT source statement that needs geometry (not CL data)"},
    {ClCode::no_start_position, "E3114", Severity::error, "relative move before any position"},
    {ClCode::surface_speed_no_tool, "E3115", Severity::error,
     "SPINDL SMM/SFM without a cutter diameter"},
    {ClCode::bad_units, "E3116", Severity::error, "unknown UNITS"},
    {ClCode::unsupported_record, "E3117", Severity::error, "record that vcpost cannot convert"},
    {ClCode::unknown_record, "W3150", Severity::warning, "unknown record ignored (no longer given: E3118)"},
    {ClCode::missing_fini, "W3151", Severity::warning, "no FINI or END-OF-PATH: file may be cut"},
    {ClCode::after_fini, "W3152", Severity::warning, "records after FINI ignored"},
    {ClCode::tool_not_modelled, "W3153", Severity::warning,
     "cutter shape is not a ball, bull-nose or flat mill"},
    {ClCode::ignored_option, "W3154", Severity::warning, "option without effect on motion ignored"},
    {ClCode::unknown_word, "E3118", Severity::error,
     "record vcpost does not know: refused, not ignored"},
    {ClCode::frame_not_identity, "E3119", Severity::error,
     "CSYS, TRNTYP or ORIGIN that would move the CL points: not applied"},
}};

}  // namespace

std::span<const ClCodeInfo> cl_code_table() { return table; }

const ClCodeInfo& info(ClCode code) { return table[static_cast<std::size_t>(code)]; }

std::string format(const ClDiagnostic& diagnostic, std::string_view file_name) {
  const ClCodeInfo& i = info(diagnostic.code);
  std::string out;
  if (!file_name.empty()) {
    out += file_name;
    out += ':';
  }
  out += std::to_string(diagnostic.line);
  out += ':';
  out += std::to_string(diagnostic.column);
  out += i.severity == Severity::error ? ": error[" : ": warning[";
  out += i.id;
  out += "]: ";
  out += diagnostic.message;
  return out;
}

}  // namespace vcpost::cldata
