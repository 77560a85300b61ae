// G and M code knowledge as constexpr tables: code (times 10, so G61.1 is
// 611), modal group and whether vcpost follows it. The interpreter checks
// modal-group conflicts and refusals from these tables, not from switches.
#pragma once

#include <array>
#include <optional>

#include "postproc/gcode/dialect.h"

namespace vcpost::gcode {

enum class Group : unsigned char {
  non_modal,     // G4, G10, G28, G53, G92 ... (group 0)
  motion,        // G0 G1 G2 G3 G80 cycles (group 1)
  plane,         // G17 G18 G19
  distance,      // G90 G91
  arc_distance,  // G90.1 G91.1
  feed_mode,     // G93 G94 G95
  units,         // G20 G21
  cutter_comp,   // G40 G41 G42
  tool_length,   // G43 G49
  return_mode,   // G98 G99
  coordinate,    // G54 .. G59.3
  path_control,  // G61 G61.1 G64
  spindle_mode,  // G96 G97
  high_speed,    // Fanuc/Mazak G5 P2, G5.1, G8
  lathe_mode,    // G7 G8 (LinuxCNC lathe diameter / radius)
  scaling,       // Fanuc G50 G51
  mirror,        // Fanuc G50.1 G51.1
  rotation,      // Fanuc G68 G69
  polar,         // Fanuc G15 G16
  macro_modal,   // Fanuc G66 G67
  canned_cycle,  // Fanuc: G73 .. G89 and G80, beside G0/G1 (group 09)
  // M groups
  stopping,     // M0 M1 M2 M30 M60 M99
  spindle,      // M3 M4 M5
  tool_change,  // M6
  coolant,      // M7 M8 M9
  subprogram,   // M98
  overrides,    // M48 M49 ...
};

inline constexpr std::size_t kGroupCount = static_cast<std::size_t>(Group::overrides) + 1;

enum class Support : unsigned char {
  followed,  // interpreted
  ignored,   // no effect on motion, S or F: accepted and passed through
  noted,     // a control's own mode code, no effect on the path: passed
             // through with one warning naming it (once per program)
  refused,   // changes the motion in a way vcpost does not follow: an error
};

struct CodeEntry {
  int code;  // x10
  Group group;
  Support support;
  // refused: what the code does that vcpost cannot follow (for the message)
  const char* what = nullptr;
};

using Gr = Group;
using Su = Support;

// RS274NGC as LinuxCNC reads it (its G-code list is the checklist); the
// base of every dialect.
inline constexpr std::array kGCodes{
    CodeEntry{0, Gr::motion, Su::followed},
    CodeEntry{10, Gr::motion, Su::followed},
    CodeEntry{20, Gr::motion, Su::followed},
    CodeEntry{30, Gr::motion, Su::followed},
    CodeEntry{40, Gr::non_modal, Su::followed},
    CodeEntry{50, Gr::motion, Su::followed},     // cubic spline (XY plane)
    CodeEntry{51, Gr::motion, Su::followed},     // quadratic spline (XY plane)
    CodeEntry{52, Gr::motion, Su::followed},     // NURBS control points (nurbs.h)
    CodeEntry{53, Gr::non_modal, Su::followed},  // NURBS end: the tool follows the curve
    CodeEntry{70, Gr::lathe_mode, Su::refused, "makes X a diameter (lathe mode)"},
    CodeEntry{80, Gr::lathe_mode, Su::ignored},
    CodeEntry{100, Gr::non_modal, Su::followed},
    CodeEntry{170, Gr::plane, Su::followed},
    CodeEntry{171, Gr::plane, Su::refused, "selects the UV plane"},
    CodeEntry{180, Gr::plane, Su::followed},
    CodeEntry{181, Gr::plane, Su::refused, "selects the WU plane"},
    CodeEntry{190, Gr::plane, Su::followed},
    CodeEntry{191, Gr::plane, Su::refused, "selects the VW plane"},
    CodeEntry{200, Gr::units, Su::followed},
    CodeEntry{210, Gr::units, Su::followed},
    CodeEntry{280, Gr::non_modal, Su::followed},
    CodeEntry{281, Gr::non_modal, Su::followed},
    CodeEntry{300, Gr::non_modal, Su::followed},
    CodeEntry{301, Gr::non_modal, Su::followed},
    CodeEntry{330, Gr::motion, Su::refused, "is a spindle-synchronised (threading) move"},
    CodeEntry{331, Gr::motion, Su::refused, "is rigid tapping synchronised to the spindle"},
    CodeEntry{382, Gr::motion, Su::refused, "is a probing move that ends where the probe trips"},
    CodeEntry{383, Gr::motion, Su::refused, "is a probing move that ends where the probe trips"},
    CodeEntry{384, Gr::motion, Su::refused, "is a probing move that ends where the probe trips"},
    CodeEntry{385, Gr::motion, Su::refused, "is a probing move that ends where the probe trips"},
    CodeEntry{400, Gr::cutter_comp, Su::followed},
    CodeEntry{410, Gr::cutter_comp, Su::followed},
    CodeEntry{411, Gr::cutter_comp, Su::followed},
    CodeEntry{420, Gr::cutter_comp, Su::followed},
    CodeEntry{421, Gr::cutter_comp, Su::followed},
    CodeEntry{430, Gr::tool_length, Su::followed},
    CodeEntry{431, Gr::tool_length, Su::followed},
    CodeEntry{432, Gr::tool_length, Su::followed},
    CodeEntry{490, Gr::tool_length, Su::followed},
    CodeEntry{520, Gr::non_modal, Su::followed},
    CodeEntry{530, Gr::non_modal, Su::followed},
    CodeEntry{540, Gr::coordinate, Su::followed},
    CodeEntry{550, Gr::coordinate, Su::followed},
    CodeEntry{560, Gr::coordinate, Su::followed},
    CodeEntry{570, Gr::coordinate, Su::followed},
    CodeEntry{580, Gr::coordinate, Su::followed},
    CodeEntry{590, Gr::coordinate, Su::followed},
    CodeEntry{591, Gr::coordinate, Su::followed},
    CodeEntry{592, Gr::coordinate, Su::followed},
    CodeEntry{593, Gr::coordinate, Su::followed},
    CodeEntry{610, Gr::path_control, Su::ignored},
    CodeEntry{611, Gr::path_control, Su::ignored},
    CodeEntry{640, Gr::path_control, Su::ignored},
    CodeEntry{700, Gr::motion, Su::refused, "is a lathe finishing cycle"},
    CodeEntry{710, Gr::motion, Su::refused, "is a lathe roughing cycle"},
    CodeEntry{711, Gr::motion, Su::refused, "is a lathe roughing cycle"},
    CodeEntry{712, Gr::motion, Su::refused, "is a lathe roughing cycle"},
    CodeEntry{720, Gr::motion, Su::refused, "is a lathe roughing cycle"},
    CodeEntry{721, Gr::motion, Su::refused, "is a lathe roughing cycle"},
    CodeEntry{722, Gr::motion, Su::refused, "is a lathe roughing cycle"},
    CodeEntry{730, Gr::motion, Su::followed},
    CodeEntry{740, Gr::motion, Su::followed},
    CodeEntry{760, Gr::motion, Su::refused, "is a lathe threading cycle"},
    CodeEntry{800, Gr::motion, Su::followed},
    CodeEntry{810, Gr::motion, Su::followed},
    CodeEntry{820, Gr::motion, Su::followed},
    CodeEntry{830, Gr::motion, Su::followed},
    CodeEntry{840, Gr::motion, Su::followed},
    CodeEntry{850, Gr::motion, Su::followed},
    CodeEntry{860, Gr::motion, Su::followed},
    CodeEntry{870, Gr::motion, Su::followed},
    CodeEntry{880, Gr::motion, Su::followed},
    CodeEntry{890, Gr::motion, Su::followed},
    CodeEntry{900, Gr::distance, Su::followed},
    CodeEntry{901, Gr::arc_distance, Su::followed},
    CodeEntry{910, Gr::distance, Su::followed},
    CodeEntry{911, Gr::arc_distance, Su::followed},
    CodeEntry{920, Gr::non_modal, Su::followed},
    CodeEntry{921, Gr::non_modal, Su::followed},
    CodeEntry{922, Gr::non_modal, Su::followed},
    CodeEntry{923, Gr::non_modal, Su::followed},
    CodeEntry{930, Gr::feed_mode, Su::followed},
    CodeEntry{940, Gr::feed_mode, Su::followed},
    CodeEntry{950, Gr::feed_mode, Su::followed},
    CodeEntry{960, Gr::spindle_mode, Su::refused,
              "makes the spindle speed follow the radius (constant surface speed)"},
    CodeEntry{970, Gr::spindle_mode, Su::ignored},
    CodeEntry{980, Gr::return_mode, Su::followed},
    CodeEntry{990, Gr::return_mode, Su::followed},
};

// Fanuc-like controls (Fanuc, Haas, Makino, Mazak EIA): where they differ
// from RS274NGC; looked up before kGCodes.
inline constexpr std::array kFanucGCodes{
    CodeEntry{50, Gr::high_speed, Su::noted},  // G05 P10000 / P2: high-speed machining mode
    CodeEntry{51, Gr::high_speed, Su::noted},  // G05.1 Q1: AI contour control
    CodeEntry{52, Gr::motion, Su::refused, "is a NURBS move"},  // LinuxCNC's, not Fanuc's
    CodeEntry{53, Gr::motion, Su::refused, "is a NURBS move"},
    CodeEntry{70, Gr::non_modal, Su::refused, "is a hypothetical-axis (cylindrical) interpolation"},
    CodeEntry{71, Gr::non_modal, Su::refused, "is cylindrical interpolation"},
    CodeEntry{80, Gr::high_speed, Su::noted},    // G08 P1: look-ahead control
    CodeEntry{90, Gr::non_modal, Su::ignored},   // G09 exact stop, this block only
    CodeEntry{110, Gr::non_modal, Su::ignored},  // G11 data-setting mode off
    CodeEntry{121, Gr::polar, Su::refused, "is polar coordinate interpolation"},
    CodeEntry{131, Gr::polar, Su::noted},  // G13.1 polar interpolation off
    CodeEntry{150, Gr::polar, Su::noted},  // G15 polar coordinates off
    CodeEntry{160, Gr::polar, Su::refused, "reads X/Y as polar coordinates (radius, angle)"},
    CodeEntry{220, Gr::non_modal, Su::noted},  // G22/G23 stored stroke check on/off
    CodeEntry{230, Gr::non_modal, Su::noted},
    CodeEntry{270, Gr::non_modal, Su::refused,
              "checks the reference position with a move vcpost cannot place"},
    CodeEntry{290, Gr::non_modal, Su::refused,
              "returns from the reference position through an unknown point"},
    CodeEntry{310, Gr::non_modal, Su::refused, "is a skip move that ends where a signal arrives"},
    CodeEntry{500, Gr::scaling, Su::noted},  // G50 scaling off
    CodeEntry{501, Gr::mirror, Su::noted},   // G50.1 programmable mirror image off
    CodeEntry{510, Gr::scaling, Su::refused, "scales the program (G51)"},
    CodeEntry{511, Gr::mirror, Su::refused, "mirrors the program (programmable mirror image)"},
    CodeEntry{541, Gr::coordinate, Su::followed},  // G54.1 Pn additional work offsets
    CodeEntry{600, Gr::non_modal, Su::refused,
              "positions from one direction with an overshoot vcpost cannot place"},
    CodeEntry{630, Gr::path_control, Su::ignored},  // tapping mode
    CodeEntry{650, Gr::non_modal, Su::followed},    // G65 macro call
    CodeEntry{660, Gr::macro_modal, Su::refused,
              "calls a macro after every move (modal macro call)"},
    CodeEntry{670, Gr::macro_modal, Su::ignored},
    CodeEntry{531, Gr::non_modal, Su::followed},  // G53.1: the tool to the tilted frame's z
    CodeEntry{680, Gr::rotation, Su::refused, "rotates the coordinate system"},
    CodeEntry{682, Gr::rotation, Su::followed},  // G68.2: tilted working plane (Euler angles)
    CodeEntry{690, Gr::rotation, Su::followed},  // G69: rotation and tilt off
    CodeEntry{700, Gr::units, Su::refused, "is inch input on old controls; use G20"},
    CodeEntry{760, Gr::motion, Su::followed},     // fine boring
    CodeEntry{1030, Gr::non_modal, Su::noted},    // Haas G103 look-ahead limit
    CodeEntry{1170, Gr::non_modal, Su::ignored},  // Mazak G117 (axis words are a position)
    CodeEntry{1870, Gr::non_modal, Su::noted},    // Haas G187 smoothness
};

inline constexpr std::array kMCodes{
    CodeEntry{0, Gr::stopping, Su::followed},
    CodeEntry{10, Gr::stopping, Su::followed},
    CodeEntry{20, Gr::stopping, Su::followed},
    CodeEntry{300, Gr::stopping, Su::followed},
    CodeEntry{30, Gr::spindle, Su::followed},
    CodeEntry{40, Gr::spindle, Su::followed},
    CodeEntry{50, Gr::spindle, Su::followed},
    CodeEntry{60, Gr::tool_change, Su::followed},
    CodeEntry{70, Gr::coolant, Su::followed},
    CodeEntry{80, Gr::coolant, Su::followed},
    CodeEntry{90, Gr::coolant, Su::followed},
    CodeEntry{190, Gr::spindle, Su::followed},
    CodeEntry{480, Gr::overrides, Su::ignored},
    CodeEntry{490, Gr::overrides, Su::ignored},
    CodeEntry{500, Gr::overrides, Su::ignored},
    CodeEntry{510, Gr::overrides, Su::ignored},
    CodeEntry{520, Gr::overrides, Su::ignored},
    CodeEntry{530, Gr::overrides, Su::ignored},
    CodeEntry{600, Gr::stopping, Su::ignored},
    CodeEntry{610, Gr::tool_change, Su::ignored},
    CodeEntry{620, Gr::overrides, Su::ignored},
    CodeEntry{630, Gr::overrides, Su::ignored},
    CodeEntry{640, Gr::overrides, Su::ignored},
    CodeEntry{650, Gr::overrides, Su::ignored},
    CodeEntry{660, Gr::overrides, Su::ignored},
    CodeEntry{670, Gr::overrides, Su::ignored},
    CodeEntry{680, Gr::overrides, Su::ignored},
    CodeEntry{700, Gr::overrides, Su::ignored},
    CodeEntry{710, Gr::overrides, Su::ignored},
    CodeEntry{720, Gr::overrides, Su::refused,
              "restores a saved modal state (units, distance mode ...)"},
    CodeEntry{730, Gr::overrides, Su::refused,
              "restores a saved modal state at the subroutine's end"},
    CodeEntry{980, Gr::subprogram, Su::followed},
    CodeEntry{990, Gr::stopping, Su::followed},
};

// Siemens Sinumerik 840D (milling): looked up before the codes it shares
// with RS274NGC (G0-G3, G4, G17-G19, G40-G42, G53-G57, G90/G91, G93-G97).
inline constexpr std::array kSinumerikGCodes{
    CodeEntry{50, Gr::motion, Su::refused, "is a circle through an intermediate point (CIP)"},
    CodeEntry{90, Gr::non_modal, Su::ignored},  // G9 exact stop, this block
    CodeEntry{250, Gr::non_modal, Su::noted},   // G25/G26 S..: spindle speed limits
    CodeEntry{260, Gr::non_modal, Su::noted},
    CodeEntry{330, Gr::motion, Su::refused, "is a spindle-synchronised (threading) move"},
    CodeEntry{3310, Gr::motion, Su::refused, "is rigid tapping synchronised to the spindle"},
    CodeEntry{3320, Gr::motion, Su::refused, "is rigid tapping synchronised to the spindle"},
    CodeEntry{1100, Gr::non_modal, Su::refused, "sets a pole for polar coordinates"},
    CodeEntry{1110, Gr::non_modal, Su::refused, "sets a pole for polar coordinates"},
    CodeEntry{1120, Gr::non_modal, Su::refused, "sets a pole for polar coordinates"},
    CodeEntry{1530, Gr::non_modal, Su::followed},    // G153: as G53
    CodeEntry{4500, Gr::path_control, Su::ignored},  // G450/G451: corners under compensation
    CodeEntry{4510, Gr::path_control, Su::ignored},
    CodeEntry{5000, Gr::coordinate, Su::followed},   // G500: settable frames off
    CodeEntry{600, Gr::path_control, Su::ignored},   // G60 exact stop
    CodeEntry{6010, Gr::path_control, Su::ignored},  // G601-G603 exact-stop windows
    CodeEntry{6020, Gr::path_control, Su::ignored},
    CodeEntry{6030, Gr::path_control, Su::ignored},
    CodeEntry{640, Gr::path_control, Su::ignored},  // G64, G641-G645 continuous path
    CodeEntry{6410, Gr::path_control, Su::ignored},
    CodeEntry{6420, Gr::path_control, Su::ignored},
    CodeEntry{6430, Gr::path_control, Su::ignored},
    CodeEntry{6440, Gr::path_control, Su::ignored},
    CodeEntry{6450, Gr::path_control, Su::ignored},
    CodeEntry{700, Gr::units, Su::followed},  // G70 inch, G71 metric
    CodeEntry{710, Gr::units, Su::followed},
    CodeEntry{7000, Gr::units, Su::followed},  // G700/G710: F in the same units too
    CodeEntry{7100, Gr::units, Su::followed},
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

// The G code of a dialect: its own table first, then RS274NGC's (for
// Sinumerik only the codes both mean the same).
constexpr std::optional<CodeEntry> find_g_code(machines::Dialect kind, double value) {
  if (kind == machines::Dialect::sinumerik) {
    if (const auto entry = find_code(kSinumerikGCodes, value)) return entry;
    const auto base = find_code(kGCodes, value);
    if (!base) return base;
    for (int shared : {0,   10,  20,  30,  40,  170, 180, 190, 400, 410, 420, 530,
                       540, 550, 560, 570, 900, 910, 930, 940, 950, 960, 970})
      if (base->code == shared) return base;
    return std::nullopt;
  }
  if (kind != machines::Dialect::rs274ngc)
    if (const auto entry = find_code(kFanucGCodes, value)) return entry;
  return find_code(kGCodes, value);
}

static_assert(find_code(kGCodes, 61.1)->group == Group::path_control);
static_assert(find_g_code(machines::Dialect::fanuc, 5.1)->support == Support::noted);
static_assert(find_g_code(machines::Dialect::rs274ngc, 5.1)->support == Support::followed);
static_assert(find_g_code(machines::Dialect::rs274ngc, 5.2)->support == Support::followed);
static_assert(find_g_code(machines::Dialect::fanuc, 5.2)->support == Support::refused);
static_assert(!find_g_code(machines::Dialect::sinumerik, 81).has_value());
static_assert(!find_code(kGCodes, 1.5).has_value());
static_assert(!find_code(kGCodes, 1e300).has_value());

}  // namespace vcpost::gcode
