#include "postproc/gcode/dialect.h"

#include <algorithm>
#include <string>

#include "core/text.h"

namespace vcpost::gcode {

Dialect rs274ngc_dialect() { return Dialect{}; }

Dialect fanuc_dialect() {
  Dialect d;
  d.kind = machines::Dialect::fanuc;
  d.integer_lengths = IntegerLengths::increments;
  d.named_parameters = false;
  d.o_word_control = false;
  d.fanuc_macros = true;
  d.unknown_m_is_error = false;
  return d;
}

Dialect mazak_dialect() {
  Dialect d = fanuc_dialect();
  d.kind = machines::Dialect::mazak;
  return d;
}

Dialect sinumerik_dialect() {
  Dialect d;
  d.kind = machines::Dialect::sinumerik;
  d.numbered_parameters = false;  // R parameters instead of #n
  d.named_parameters = false;
  d.o_word_control = false;
  d.unknown_m_is_error = false;
  return d;
}

Dialect heidenhain_dialect() {
  Dialect d;
  d.kind = machines::Dialect::heidenhain;
  d.numbered_parameters = false;
  d.named_parameters = false;
  d.o_word_control = false;
  d.unknown_m_is_error = false;
  return d;
}

std::optional<Dialect> dialect_from_name(std::string_view name) {
  const std::string lower = to_lower(name);
  if (lower == "rs274ngc" || lower == "linuxcnc" || lower == "ngc") return rs274ngc_dialect();
  if (lower == "fanuc" || lower == "iso") return fanuc_dialect();
  if (lower == "mazak" || lower == "eia") return mazak_dialect();
  if (lower == "sinumerik" || lower == "840d" || lower == "siemens") return sinumerik_dialect();
  if (lower == "heidenhain" || lower == "klartext" || lower == "tnc") return heidenhain_dialect();
  return std::nullopt;
}

}  // namespace vcpost::gcode
