// profile_to_toml(): the profile written back as a TOML file with its
// source notes as comments (for `vcpost machines show`).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "machines/profile.h"

namespace vcpost::machines {

namespace {

std::string quote(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {  // TOML escapes DEL too
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

// Shortest text that reads back to the same double.
std::string number(double v) {
  if (v == 0) return "0";  // -0.0 would print "-0", which reads back as the integer 0
  char buf[40];
  if (v == std::floor(v) && std::abs(v) < 1e15) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
  }
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  std::string s = buf;
  // TOML wants digits on both sides of a point and no bare exponent.
  if (s.find_first_of("eE") != std::string::npos && s.find('.') == std::string::npos) {
    const auto e = s.find_first_of("eE");
    s.insert(e, ".0");
  }
  return s;
}

std::string boolean(bool b) { return b ? "true" : "false"; }

class Writer {
 public:
  explicit Writer(const MachineProfile& p) : p_(p) {}

  void table(std::string_view name) {
    out_ += out_.empty() ? "" : "\n";
    out_ += '[';
    out_ += name;
    out_ += "]\n";
    table_ = name;
    for (const auto& note : p_.sources()) {
      if (note.key == name) {
        out_ += "# ";
        out_ += note.vendor ? "vendor: " : "assumed: ";
        out_ += note.text;
        out_ += '\n';
      }
    }
  }

  void key(std::string_view name, const std::string& value) {
    std::string line(name);
    line += " = ";
    line += value;
    std::string full(table_);
    full += '.';
    full += name;
    const SourceNote* note = p_.source_of(full);
    if (line.size() < 40) line.resize(40, ' ');
    line += "  # ";
    if (!note) {
      line += "no source given";
    } else if (note->key == full) {
      line += note->vendor ? "vendor: " : "assumed: ";
      line += note->text;
    } else {
      line += note->vendor ? "vendor (see table)" : "assumed (see table)";
    }
    out_ += line;
    out_ += '\n';
  }

  void raw(const std::string& text) { out_ += text; }
  const std::string& text() const { return out_; }

 private:
  const MachineProfile& p_;
  std::string out_;
  std::string_view table_;
};

}  // namespace

std::string profile_to_toml(const MachineProfile& p) {
  Writer w(p);
  w.table("machine");
  w.key("name", quote(p.name()));
  if (!p.description().empty()) w.key("description", quote(p.description()));
  w.key("dialect", quote(to_string(p.dialect())));
  w.key("output_format", quote(to_string(p.output_format())));

  const auto& s = p.spindle();
  w.table("spindle");
  w.key("n_min_rpm", number(s.n_min_rpm));
  w.key("n_max_rpm", number(s.n_max_rpm));
  w.key("acceleration_rpm_per_s", number(s.acceleration_rpm_per_s));
  w.key("deceleration_rpm_per_s", number(s.deceleration_rpm_per_s));
  w.key("s_resolution_rpm", number(s.s_resolution_rpm));
  w.key("min_change_rpm", number(s.min_change_rpm));
  w.key("min_change_percent", number(s.min_change_percent));
  w.key("max_changes_per_s", number(s.max_changes_per_s));
  w.key("change_in_motion", quote(to_string(s.change_in_motion)));
  if (!s.change_code.empty()) w.key("change_code", quote(s.change_code));
  w.key("stops_path_on_change", boolean(s.stops_path_on_change));
  w.key("stop_cost_s", number(s.stop_cost_s));
  w.key("at_speed_window_percent", number(s.at_speed_window_percent));
  w.key("s_in_feed", quote(to_string(s.s_in_feed)));

  w.table("control");
  w.key("block_time_s", number(p.control().block_time_s));

  const auto& f = p.feed();
  w.table("feed");
  w.key("f_min_mm_per_min", number(f.f_min_mm_per_min));
  w.key("f_max_mm_per_min", number(f.f_max_mm_per_min));
  w.key("rapid_mm_per_min", number(f.rapid_mm_per_min));

  w.table("tool");
  w.key("default_teeth", std::to_string(p.tool().default_teeth));

  const auto& o = p.output();
  w.table("output");
  // Klartext output has no use for the G-code writer's keys (a Heidenhain
  // profile refuses them): left out, so that the text loads again.
  const bool gcode = p.output_format() != OutputFormat::heidenhain;
  const auto gcode_key = [&](std::string_view name, const std::string& value) {
    if (gcode) w.key(name, value);
  };
  w.key("program_number", std::to_string(o.program_number));
  gcode_key("high_speed_mode", boolean(o.high_speed_mode));
  gcode_key("geometry_compensation", boolean(o.geometry_compensation));
  gcode_key("work_offset", std::to_string(o.work_offset));
  w.key("decimals", std::to_string(o.decimals));
  w.key("feed_decimals", std::to_string(o.feed_decimals));
  gcode_key("line_numbers", boolean(o.line_numbers));
  w.key("canned_cycles", boolean(o.canned_cycles));
  w.key("cutter_compensation", boolean(o.cutter_compensation));
  gcode_key("percent_lines", boolean(o.percent_lines));
  w.key("tool_change", quote(to_string(o.tool_change)));
  gcode_key("tool_change_home", quote(to_string(o.tool_change_home)));
  gcode_key("tool_length_offset", boolean(o.tool_length_offset));
  w.key("coolant_mist", quote(o.coolant_mist));
  w.key("coolant_flood", quote(o.coolant_flood));
  w.key("coolant_off", quote(o.coolant_off));
  w.key("speed_word",
        quote(o.speed_output ? "M67 E" + std::to_string(*o.speed_output) : std::string("S")));
  w.key("tilted_plane", quote(to_string(o.tilted_plane)));

  if (!p.sources().empty()) {
    w.raw("\n[sources]\n");
    for (const auto& note : p.sources()) {
      w.raw(quote(note.key) + " = " +
            quote(std::string(note.vendor ? "vendor: " : "assumed: ") + note.text) + "\n");
    }
  }
  return w.text();
}

}  // namespace vcpost::machines
