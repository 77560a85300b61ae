// The language a control reads (the names of `--dialect` and of a
// profile's `dialect`): a G-code dialect, or Heidenhain's Klartext. One
// enum for the profile and the readers (gcode::Dialect::kind).
#pragma once

namespace vcpost::machines {

// heidenhain: Klartext, read by its own reader (postproc/heidenhain), not
// by the G-code interpreter.
enum class Dialect { rs274ngc, fanuc, mazak, sinumerik, heidenhain };

}  // namespace vcpost::machines
