// G and M code knowledge as constexpr tables: code (times 10, so G61.1 is
// 611), modal group and whether vcpost follows it. The interpreter checks
// modal-group conflicts and refusals from these tables, not from switches.
#pragma once

#include <array>
#include <optional>

namespace vcpost::gcode {

enum class Group : unsigned char {
  non_modal,      // G4, G10, G28, G53, G92 ... (group 0)
  motion,         // G0 G1 G2 G3 G80 cycles (group 1)
  plane,          // G17 G18 G19
  distance,       // G90 G91
  arc_distance,   // G90.1 G91.1
  feed_mode,      // G93 G94 G95
  units,          // G20 G21
  cutter_comp,    // G40 G41 G42
  tool_length,    // G43 G49
  return_mode,    // G98 G99
  coordinate,     // G54 .. G59.3
  path_control,   // G61 G61.1 G64
  spindle_mode,   // G96 G97
  high_speed,     // Mazak/Fanuc G5 P2, G5.1, G8
  // M groups
  stopping,       // M0 M1 M2 M30 M60 M99
  spindle,        // M3 M4 M5
  tool_change,    // M6
  coolant,        // M7 M8 M9
  subprogram,     // M98
  overrides,      // M48 M49 ...
};

inline constexpr std::size_t kGroupCount = static_cast<std::size_t>(Group::overrides) + 1;

enum class Support : unsigned char {
  followed,  // interpreted
  ignored,   // no effect on motion, S or F: accepted and passed through
  refused,   // changes the motion in a way vcpost does not follow: an error
};

struct CodeEntry {
  int code;  // x10
  Group group;
  Support support;
};

inline constexpr std::array kGCodes{
    CodeEntry{0, Group::motion, Support::followed},      CodeEntry{10, Group::motion, Support::followed},
    CodeEntry{20, Group::motion, Support::followed},     CodeEntry{30, Group::motion, Support::followed},
    CodeEntry{40, Group::non_modal, Support::followed},  CodeEntry{50, Group::high_speed, Support::ignored},
    CodeEntry{51, Group::high_speed, Support::ignored},  CodeEntry{80, Group::high_speed, Support::ignored},
    CodeEntry{90, Group::non_modal, Support::ignored},   CodeEntry{100, Group::non_modal, Support::refused},
    CodeEntry{150, Group::non_modal, Support::refused},  CodeEntry{160, Group::non_modal, Support::refused},
    CodeEntry{170, Group::plane, Support::followed},     CodeEntry{180, Group::plane, Support::followed},
    CodeEntry{190, Group::plane, Support::followed},     CodeEntry{200, Group::units, Support::followed},
    CodeEntry{210, Group::units, Support::followed},     CodeEntry{280, Group::non_modal, Support::followed},
    CodeEntry{300, Group::non_modal, Support::refused},  CodeEntry{330, Group::motion, Support::refused},
    CodeEntry{382, Group::motion, Support::refused},     CodeEntry{383, Group::motion, Support::refused},
    CodeEntry{384, Group::motion, Support::refused},     CodeEntry{385, Group::motion, Support::refused},
    CodeEntry{400, Group::cutter_comp, Support::followed}, CodeEntry{410, Group::cutter_comp, Support::followed},
    CodeEntry{420, Group::cutter_comp, Support::followed}, CodeEntry{430, Group::tool_length, Support::followed},
    CodeEntry{490, Group::tool_length, Support::followed}, CodeEntry{500, Group::non_modal, Support::refused},
    CodeEntry{510, Group::non_modal, Support::refused},  CodeEntry{520, Group::non_modal, Support::refused},
    CodeEntry{530, Group::non_modal, Support::followed}, CodeEntry{540, Group::coordinate, Support::followed},
    CodeEntry{550, Group::coordinate, Support::followed}, CodeEntry{560, Group::coordinate, Support::followed},
    CodeEntry{570, Group::coordinate, Support::followed}, CodeEntry{580, Group::coordinate, Support::followed},
    CodeEntry{590, Group::coordinate, Support::followed}, CodeEntry{591, Group::coordinate, Support::followed},
    CodeEntry{592, Group::coordinate, Support::followed}, CodeEntry{593, Group::coordinate, Support::followed},
    CodeEntry{610, Group::path_control, Support::ignored}, CodeEntry{611, Group::path_control, Support::ignored},
    CodeEntry{640, Group::path_control, Support::ignored}, CodeEntry{650, Group::non_modal, Support::refused},
    CodeEntry{660, Group::non_modal, Support::refused},  CodeEntry{670, Group::non_modal, Support::refused},
    CodeEntry{680, Group::non_modal, Support::refused},  CodeEntry{690, Group::non_modal, Support::ignored},
    CodeEntry{730, Group::motion, Support::refused},     CodeEntry{760, Group::motion, Support::refused},
    CodeEntry{800, Group::motion, Support::followed},    CodeEntry{810, Group::motion, Support::refused},
    CodeEntry{820, Group::motion, Support::refused},     CodeEntry{830, Group::motion, Support::refused},
    CodeEntry{840, Group::motion, Support::refused},     CodeEntry{850, Group::motion, Support::refused},
    CodeEntry{860, Group::motion, Support::refused},     CodeEntry{870, Group::motion, Support::refused},
    CodeEntry{880, Group::motion, Support::refused},     CodeEntry{890, Group::motion, Support::refused},
    CodeEntry{900, Group::distance, Support::followed},  CodeEntry{901, Group::arc_distance, Support::followed},
    CodeEntry{910, Group::distance, Support::followed},  CodeEntry{911, Group::arc_distance, Support::followed},
    CodeEntry{920, Group::non_modal, Support::refused},  CodeEntry{921, Group::non_modal, Support::refused},
    CodeEntry{922, Group::non_modal, Support::refused},  CodeEntry{923, Group::non_modal, Support::refused},
    CodeEntry{930, Group::feed_mode, Support::followed}, CodeEntry{940, Group::feed_mode, Support::followed},
    CodeEntry{950, Group::feed_mode, Support::followed}, CodeEntry{960, Group::spindle_mode, Support::refused},
    CodeEntry{970, Group::spindle_mode, Support::ignored}, CodeEntry{980, Group::return_mode, Support::ignored},
    CodeEntry{990, Group::return_mode, Support::ignored}, CodeEntry{1170, Group::non_modal, Support::ignored},
};

inline constexpr std::array kMCodes{
    CodeEntry{0, Group::stopping, Support::followed},   CodeEntry{10, Group::stopping, Support::followed},
    CodeEntry{20, Group::stopping, Support::followed},  CodeEntry{300, Group::stopping, Support::followed},
    CodeEntry{30, Group::spindle, Support::followed},   CodeEntry{40, Group::spindle, Support::followed},
    CodeEntry{50, Group::spindle, Support::followed},   CodeEntry{60, Group::tool_change, Support::followed},
    CodeEntry{70, Group::coolant, Support::followed},   CodeEntry{80, Group::coolant, Support::followed},
    CodeEntry{90, Group::coolant, Support::followed},   CodeEntry{480, Group::overrides, Support::ignored},
    CodeEntry{490, Group::overrides, Support::ignored}, CodeEntry{600, Group::stopping, Support::ignored},
    CodeEntry{980, Group::subprogram, Support::followed}, CodeEntry{990, Group::stopping, Support::followed},
};

// The entry of a code given as a word value (61.1 -> 611); nullopt if the
// value is no code of the table (including non-tenths such as 1.25).
template <std::size_t N>
constexpr std::optional<CodeEntry> find_code(const std::array<CodeEntry, N>& table, double value) {
  const double tenths = value * 10.0;
  // No code is that large; casting a larger value (or NaN) would be undefined.
  if (!(tenths > -1e9 && tenths < 1e9)) return std::nullopt;
  const long rounded = static_cast<long>(tenths + (tenths < 0 ? -0.5 : 0.5));
  if (tenths - static_cast<double>(rounded) > 1e-6 || static_cast<double>(rounded) - tenths > 1e-6)
    return std::nullopt;
  for (const auto& entry : table)
    if (entry.code == rounded) return entry;
  return std::nullopt;
}

static_assert(find_code(kGCodes, 61.1)->group == Group::path_control);
static_assert(!find_code(kGCodes, 1.5).has_value());
static_assert(!find_code(kGCodes, 1e300).has_value());

}  // namespace vcpost::gcode
