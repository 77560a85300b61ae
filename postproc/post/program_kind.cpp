#include "postproc/post/program_kind.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "postproc/gcode/block.h"

namespace vcpost::post {

gcode::Dialect dialect_of(const machines::MachineProfile& profile) {
  switch (profile.dialect()) {
    case machines::Dialect::fanuc:
      return gcode::fanuc_dialect();
    case machines::Dialect::mazak:
      return gcode::mazak_dialect();
    case machines::Dialect::sinumerik:
      return gcode::sinumerik_dialect();
    case machines::Dialect::heidenhain:  // read by its own reader: the kind names it
      return gcode::heidenhain_dialect();
    case machines::Dialect::rs274ngc:
      break;
  }
  gcode::Dialect dialect = gcode::rs274ngc_dialect();
  dialect.speed_output = profile.output().speed_output;
  return dialect;
}

gcode::Dialect output_dialect_of(const machines::MachineProfile& profile) {
  switch (profile.output_format()) {
    case machines::OutputFormat::fanuc:
      return gcode::fanuc_dialect();
    case machines::OutputFormat::mazak:
      return gcode::mazak_dialect();
    case machines::OutputFormat::heidenhain:
      return gcode::heidenhain_dialect();
    case machines::OutputFormat::rs274ngc:
      break;
  }
  gcode::Dialect dialect = gcode::rs274ngc_dialect();
  dialect.speed_output = profile.output().speed_output;
  return dialect;
}

gcode::Dialect with_speed_output(gcode::Dialect dialect, const machines::MachineProfile& profile) {
  if (dialect.kind == machines::Dialect::rs274ngc)
    dialect.speed_output = profile.output().speed_output;
  return dialect;
}

std::string_view to_string(ProgramKind kind) {
  switch (kind) {
    case ProgramKind::cldata:
      return "cldata";
    case ProgramKind::heidenhain:
      return "heidenhain";
    case ProgramKind::gcode:
      break;
  }
  return "gcode";
}

namespace {

// `[n] BEGIN PGM <name> MM|INCH`: the first block of every Klartext program.
bool is_begin_pgm(std::string_view line) {
  std::size_t i = 0;
  while (i < line.size() && std::isdigit(static_cast<unsigned char>(line[i]))) ++i;
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  if (line.substr(i, 10) != "BEGIN PGM ") return false;
  const std::size_t units = line.find_last_of(' ');
  const std::string_view last = line.substr(units + 1);
  return last == "MM" || last == "INCH";
}

}  // namespace

ProgramKind program_kind(std::string_view text, const gcode::Dialect& dialect) {
  const ProgramKind seen = detect_program_kind(text);
  return dialect.kind == machines::Dialect::heidenhain && seen != ProgramKind::cldata
             ? ProgramKind::heidenhain
             : seen;
}

ProgramKind detect_program_kind(std::string_view text) {
  // The first statement that is not blank or a comment decides. A line is
  // looked at no further than just past the readers' line limit: a longer
  // one is refused by the reader (of the kind its start shows), and a file
  // of one endless line costs no more than the limit (65,536 bytes for
  // G-code and CL alike).
  constexpr std::size_t look = gcode::kMaxLineLength + 2;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t scan = std::min(text.size() - pos, look);
    const std::size_t nl = text.substr(pos, scan).find('\n');
    const bool cut = nl == std::string_view::npos && scan < text.size() - pos;
    std::string_view line = text.substr(pos, nl == std::string_view::npos ? scan : nl);
    pos += nl == std::string_view::npos ? text.size() : nl + 1;
    while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
    if (line.empty() || line.starts_with("$$") || line.front() == '(' || line.front() == ';' ||
        line.front() == '%') {
      if (cut) return line.starts_with("$$") ? ProgramKind::cldata : ProgramKind::gcode;
      continue;
    }
    if (is_begin_pgm(line)) return ProgramKind::heidenhain;
    std::string word;
    for (const char ch : line) {
      if (!std::isalpha(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') break;
      word += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    }
    const std::string_view rest = line.substr(word.size());
    const bool statement = word.size() >= 3 &&
                           rest.find_first_not_of(' ') != std::string_view::npos &&
                           rest[rest.find_first_not_of(' ')] == '/';
    if (statement || word == "PARTNO" || word == "FINI" || word == "TOOL" || word == "END") {
      return ProgramKind::cldata;
    }
    return ProgramKind::gcode;
  }
  return ProgramKind::gcode;
}

}  // namespace vcpost::post
