// G-code dialects as settings (from the machine profile or --dialect), not
// as separate readers: one tokenizer and interpreter read them all.
#pragma once

#include <optional>
#include <string_view>

#include "machines/dialect.h"

namespace vcpost::gcode {

// What a number without a decimal point means on a length word
// (X Y Z I J K R): "X1000" = 1000 mm, or 1000 least increments (1.000 mm
// with increment_mm = 0.001), as Fanuc controls do without parameter
// 3401#0 (DPI).
enum class IntegerLengths { units, increments };

struct Dialect {
  machines::Dialect kind = machines::Dialect::rs274ngc;
  IntegerLengths integer_lengths = IntegerLengths::units;
  double increment_mm = 0.001;     // least input increment, metric
  double increment_inch = 0.0001;  // least input increment, inch
  // `(MSG,...)`, `#` parameters and `[...]` expressions; named parameters
  // `#<x>` and O-word control only in RS274NGC.
  bool numbered_parameters = true;
  bool named_parameters = true;
  bool o_word_control = true;  // o100 sub / call / if / while ... (RS274NGC)
  bool fanuc_macros = false;   // IF [..] THEN, program numbers O1234, M98/M99
  // Unknown M codes: machine-specific on Fanuc-like controls (warning), an
  // error for LinuxCNC.
  bool unknown_m_is_error = true;
  // Lines starting with '/' are skipped (the control's block-delete switch
  // on). rs274's default is off: they run.
  bool block_delete = false;
  // LinuxCNC's analog output n that carries the spindle speed (a profile's
  // output.speed_word "M67 E<n>"): M67/M68 E<n> Q<rpm> sets the speed as an
  // S word does. None: M67/M68 set an output vcpost does not follow.
  std::optional<int> speed_output;
};

Dialect rs274ngc_dialect();
Dialect fanuc_dialect();  // ISO/Fanuc: integer lengths are increments
Dialect mazak_dialect();  // Mazak EIA: Fanuc-like, macros, G05 P2, G61.1
// Siemens Sinumerik 840D, the 3-axis milling subset CAM posts write:
// ';' comments, MSG("..."), CR= arcs, R parameters and X=<expression>,
// G64/G641/G642, T/D, MCALL CYCLE81-CYCLE89 drilling cycles, M30.
Dialect sinumerik_dialect();
// Heidenhain TNC conversational (Klartext): the kind only (machines::Dialect::heidenhain).
Dialect heidenhain_dialect();

// "rs274ngc" (also "linuxcnc", "ngc"), "fanuc" (also "iso"), "mazak"
// (also "eia"), "sinumerik" (also "840d", "siemens"), "heidenhain" (also
// "klartext", "tnc"); nullopt for another name.
std::optional<Dialect> dialect_from_name(std::string_view name);

}  // namespace vcpost::gcode
