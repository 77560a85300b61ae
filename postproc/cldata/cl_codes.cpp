#include "postproc/cldata/cl_codes.h"

#include <array>

namespace vcpost::cldata {

namespace {

// The reader's codes in enumerator order; severity and summary come from
// the one code table.
constexpr auto kIds = std::to_array<std::string_view>({
    "E3101",  // line_too_long
    "E3102",  // invalid_byte
    "E3103",  // bad_number
    "E3104",  // wrong_parameters
    "E3105",  // unexpected_word
    "E3106",  // truncated_record
    "E3107",  // orphan_points
    "E3108",  // tool_axis_not_z
    "E3109",  // arc_inconsistent
    "E3110",  // arc_without_goto
    "E3111",  // bad_nurbs
    "E3112",  // unsupported_cycle
    "E3113",  // apt_source_statement
    "E3114",  // no_start_position
    "E3115",  // surface_speed_no_tool
    "E3116",  // bad_units
    "E3117",  // unsupported_record
    "W3150",  // unknown_record
    "W3151",  // missing_fini
    "W3152",  // after_fini
    "W3153",  // tool_not_modelled
    "W3154",  // ignored_option
    "E3118",  // unknown_word
    "E3119",  // frame_not_identity
    "E3120",  // tool_change_without_number
    "E3122",  // bad_cutter_size
});

std::array<ClCodeInfo, kIds.size()> make_table() {
  std::array<ClCodeInfo, kIds.size()> out{};
  for (std::size_t i = 0; i < kIds.size(); ++i) {
    const vcpost::CodeInfo& row = vcpost::code_info(kIds[i]);
    out[i] = ClCodeInfo{static_cast<ClCode>(i), row.id, row.severity, row.summary};
  }
  return out;
}

const std::array<ClCodeInfo, kIds.size()>& table() {
  static const std::array<ClCodeInfo, kIds.size()> rows = make_table();
  return rows;
}

}  // namespace

std::span<const ClCodeInfo> cl_code_table() { return table(); }

const ClCodeInfo& info(ClCode code) { return table()[static_cast<std::size_t>(code)]; }

std::string format(const ClDiagnostic& diagnostic, std::string_view file_name) {
  return format_diagnostic(info(diagnostic.code).id,
                           {std::string(file_name), diagnostic.line, diagnostic.column},
                           diagnostic.message);
}

}  // namespace vcpost::cldata
