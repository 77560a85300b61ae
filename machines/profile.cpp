#include "machines/profile.h"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <iterator>
#include <sstream>
#include <utility>

namespace vcpost::machines {

namespace {

// The schema: every table and its keys. Anything else in a file is an error.
constexpr std::array<std::string_view, 41> kSchemaKeys = {
    "machine.name",
    "machine.description",
    "machine.dialect",
    "machine.output_format",
    "spindle.n_min_rpm",
    "spindle.n_max_rpm",
    "spindle.acceleration_rpm_per_s",
    "spindle.deceleration_rpm_per_s",
    "spindle.s_resolution_rpm",
    "spindle.min_change_rpm",
    "spindle.min_change_percent",
    "spindle.max_changes_per_s",
    "spindle.change_in_motion",
    "spindle.change_code",
    "spindle.stops_path_on_change",
    "spindle.stop_cost_s",
    "spindle.at_speed_window_percent",
    "spindle.s_in_feed",
    "control.block_time_s",
    "feed.f_min_mm_per_min",
    "feed.f_max_mm_per_min",
    "feed.rapid_mm_per_min",
    "tool.default_teeth",
    "output.program_number",
    "output.high_speed_mode",
    "output.geometry_compensation",
    "output.work_offset",
    "output.decimals",
    "output.feed_decimals",
    "output.line_numbers",
    "output.canned_cycles",
    "output.cutter_compensation",
    "output.percent_lines",
    "output.tool_change",
    "output.tool_change_home",
    "output.tool_length_offset",
    "output.coolant_mist",
    "output.coolant_flood",
    "output.coolant_off",
    "output.speed_word",
    "output.tilted_plane",
};

// [output] keys only the G-code writer reads (see check_heidenhain).
constexpr std::array<std::string_view, 7> kGcodeOnlyOutputKeys = {
    "high_speed_mode",  "geometry_compensation", "work_offset", "percent_lines",
    "tool_change_home", "tool_length_offset",    "line_numbers"};

constexpr std::array<std::string_view, 7> kTables = {"machine", "spindle", "control", "feed",
                                                     "tool",    "output",  "sources"};

// Appended piece by piece ("literal" + temporary string trips a GCC 12
// -Wrestrict false positive).
std::string cat(std::initializer_list<std::string_view> parts) {
  std::string out;
  for (const auto p : parts) out.append(p);
  return out;
}

// A number as a person writes it: 9000, 0.5.
std::string number_text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// Limits of the profile's values: beyond them no machine exists, and a
// value there is a typo (1e300 for 1e-3, 1e-300 for 1e3) that would turn
// into NaN or overflow downstream (a rapid rate of 1e-300 mm/min made
// every G0 last 1e303 s). Every rate and time has a floor below any real
// machine; a time may also be 0 (none).
constexpr double kMaxSpindleRpm = 200000;    // spindle.n_max_rpm
constexpr double kMinSpindleRpm = 1;         // spindle.n_min_rpm
constexpr double kMinResolutionRpm = 0.001;  // spindle.s_resolution_rpm
constexpr double kMinSpindleRate = 1;        // spindle.*celeration_rpm_per_s, rpm/s
constexpr double kMaxSpindleRate = 1000000;  // spindle.*celeration_rpm_per_s, rpm/s
constexpr double kMinChangesPerS = 0.001;    // spindle.max_changes_per_s: one per 1000 s
constexpr double kMaxChangesPerS = 1000;     // spindle.max_changes_per_s
constexpr double kMinTimeS = 0.0001;         // control.block_time_s, spindle.stop_cost_s: 0 or this
constexpr double kMaxBlockTimeS = 10;        // control.block_time_s
constexpr double kMinFeed = 0.01;            // feed.f_min_mm_per_min, feed.f_max_mm_per_min
constexpr double kMinRapid = 10;             // feed.rapid_mm_per_min, mm/min
constexpr double kMaxFeed = 1000000;         // feed.*_mm_per_min, mm/min

// A range limit in full: 1000000, not 1e+06.
std::string limit_text(double v) {
  std::ostringstream out;
  out.precision(12);
  out << v;
  return out.str();
}

std::string join(std::span<const std::string_view> names) {
  std::string out;
  for (const auto name : names) {
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out;
}

// Reads one table of the profile; every accessor names file:line:col and
// the full key in its error.
class Reader {
 public:
  Reader(const toml::table& root, const std::string& file) : root_(root), file_(file) {}

  [[noreturn]] void fail(Code code, const toml::source_region& where,
                         const std::string& message) const {
    throw ProfileError(code, {file_, where.begin.line, where.begin.column}, message);
  }

  // Rejects tables and keys outside the schema, in the order of the file.
  void check_unknown() const {
    for (const auto& [key, node] : root_) {
      const std::string_view name = key.str();
      if (std::find(kTables.begin(), kTables.end(), name) == kTables.end()) {
        fail(Code::E5002, key.source(),
             cat({"unknown table '", name, "' (known: ", join(kTables), ")"}));
      }
      if (!node.is_table()) {
        fail(Code::E5003, key.source(), cat({"'", name, "' must be a table ([", name, "])"}));
      }
      if (name == "sources") continue;
      std::vector<std::string_view> known;
      for (const auto full : kSchemaKeys) {
        if (full.substr(0, name.size()) == name && full[name.size()] == '.')
          known.push_back(full.substr(name.size() + 1));
      }
      for (const auto& item : *node.as_table()) {
        const toml::key& sub = item.first;
        if (std::find(known.begin(), known.end(), sub.str()) == known.end()) {
          fail(Code::E5002, sub.source(),
               cat({"unknown key '", name, ".", sub.str(), "' (known in [", name,
                    "]: ", join(known), ")"}));
        }
      }
    }
  }

  const toml::table* table(std::string_view name) const {
    const auto* node = root_.get(name);
    return node ? node->as_table() : nullptr;
  }

  // The node of a key, or nullptr when absent (error if required).
  const toml::node* node(std::string_view tbl, std::string_view key, bool required) const {
    const auto* t = table(tbl);
    const toml::node* n = t ? t->get(key) : nullptr;
    if (!n && required) {
      if (!t) {
        toml::source_region start;
        start.begin = {1, 1};
        fail(Code::E5004, start,
             cat({"missing table [", tbl, "] (needed for ", quoted(tbl, key), ")"}));
      }
      fail(Code::E5004, t->source(), cat({"missing required key ", quoted(tbl, key)}));
    }
    return n;
  }

  std::optional<double> number(std::string_view tbl, std::string_view key, bool required) const {
    const auto* n = node(tbl, key, required);
    if (!n) return std::nullopt;
    double v = 0.0;
    if (const auto* i = n->as_integer()) {
      v = static_cast<double>(i->get());
    } else if (const auto* f = n->as_floating_point()) {
      v = f->get();
    } else {
      fail(Code::E5003, n->source(), quoted(tbl, key) + " must be a number, not " + type_name(*n));
    }
    if (!std::isfinite(v)) fail(Code::E5005, n->source(), quoted(tbl, key) + " must be finite");
    return v;
  }

  std::optional<std::int64_t> integer(std::string_view tbl, std::string_view key,
                                      bool required) const {
    const auto* n = node(tbl, key, required);
    if (!n) return std::nullopt;
    if (const auto* i = n->as_integer()) return i->get();
    fail(Code::E5003, n->source(), quoted(tbl, key) + " must be an integer, not " + type_name(*n));
  }

  std::optional<bool> boolean(std::string_view tbl, std::string_view key, bool required) const {
    const auto* n = node(tbl, key, required);
    if (!n) return std::nullopt;
    if (const auto* b = n->as_boolean()) return b->get();
    fail(Code::E5003, n->source(),
         quoted(tbl, key) + " must be true or false, not " + type_name(*n));
  }

  std::optional<std::string> string(std::string_view tbl, std::string_view key,
                                    bool required) const {
    const auto* n = node(tbl, key, required);
    if (!n) return std::nullopt;
    if (const auto* s = n->as_string()) return s->get();
    fail(Code::E5003, n->source(), quoted(tbl, key) + " must be a string, not " + type_name(*n));
  }

  // Range checks on a key already read (it exists).
  void require(bool ok, std::string_view tbl, std::string_view key, const std::string& reason,
               Code code = Code::E5005) const {
    if (ok) return;
    fail(code, node(tbl, key, true)->source(), quoted(tbl, key) + " " + reason);
  }

  template <class Enum, std::size_t N>
  Enum choice(std::string_view tbl, std::string_view key,
              const std::array<std::pair<std::string_view, Enum>, N>& names) const {
    const std::string value = *string(tbl, key, true);
    for (const auto& [name, e] : names)
      if (name == value) return e;
    std::vector<std::string_view> list;
    for (const auto& [name, e] : names) list.push_back(name);
    fail(Code::E5007, node(tbl, key, true)->source(),
         quoted(tbl, key) + " is \"" + value + "\", not one of: " + join(list));
  }

  static std::string quoted(std::string_view tbl, std::string_view key) {
    return cat({"'", tbl, ".", key, "'"});
  }

 private:
  static std::string type_name(const toml::node& n) {
    switch (n.type()) {
      case toml::node_type::string:
        return "a string";
      case toml::node_type::integer:
        return "an integer";
      case toml::node_type::floating_point:
        return "a number";
      case toml::node_type::boolean:
        return "a boolean";
      case toml::node_type::table:
        return "a table";
      case toml::node_type::array:
        return "an array";
      default:
        return "a date/time";
    }
  }

  const toml::table& root_;
  const std::string& file_;
};

// The checks of a value against the limits above, worded once: "must be at
// least <limit><rest>" and "must be at most <limit><rest>"; `rest` is the
// unit (" rpm") and any note.
void require_at_least(const Reader& r, double v, double lo, std::string_view tbl,
                      std::string_view key, std::string_view rest) {
  r.require(v >= lo, tbl, key, cat({"must be at least ", limit_text(lo), rest}));
}
void require_at_most(const Reader& r, double v, double hi, std::string_view tbl,
                     std::string_view key, std::string_view rest) {
  r.require(v <= hi, tbl, key, cat({"must be at most ", limit_text(hi), rest}));
}

// The low end of a range not above its high end, two keys of one table.
void require_ordered(const Reader& r, std::string_view tbl, std::string_view lo_key, double lo,
                     std::string_view hi_key, double hi) {
  r.require(lo <= hi, tbl, lo_key,
            cat({"(", number_text(lo), ") is greater than ", tbl, ".", hi_key, " (",
                 number_text(hi), ")"}),
            Code::E5006);
}

constexpr std::array<std::pair<std::string_view, Dialect>, 5> kDialects = {
    {{"rs274ngc", Dialect::rs274ngc},
     {"fanuc", Dialect::fanuc},
     {"mazak", Dialect::mazak},
     {"sinumerik", Dialect::sinumerik},
     {"heidenhain", Dialect::heidenhain}}};
constexpr std::array<std::pair<std::string_view, OutputFormat>, 4> kFormats = {
    {{"rs274ngc", OutputFormat::rs274ngc},
     {"fanuc", OutputFormat::fanuc},
     {"mazak", OutputFormat::mazak},
     {"heidenhain", OutputFormat::heidenhain}}};
constexpr std::array<std::pair<std::string_view, SChangeInMotion>, 3> kInMotion = {
    {{"inline", SChangeInMotion::inline_word},
     {"code", SChangeInMotion::code},
     {"own_block", SChangeInMotion::own_block}}};

constexpr std::array<std::pair<std::string_view, SInFeed>, 2> kSInFeed = {
    {{"never", SInFeed::never}, {"priced", SInFeed::priced}}};

constexpr std::array<std::pair<std::string_view, ToolChange>, 2> kToolChanges = {
    {{"m6", ToolChange::m6}, {"manual", ToolChange::manual}}};

constexpr std::array<std::pair<std::string_view, TiltedPlane>, 3> kTiltedPlanes = {
    {{"setup", TiltedPlane::setup},
     {"g68.2", TiltedPlane::g68_2},
     {"plane-spatial", TiltedPlane::plane_spatial}}};

constexpr std::array<std::pair<std::string_view, ToolChangeHome>, 3> kToolChangeHomes = {
    {{"none", ToolChangeHome::none}, {"g28", ToolChangeHome::g28}, {"g53", ToolChangeHome::g53}}};

bool schema_has(std::string_view key) {
  // [sources] may note a key or a whole table (not itself).
  return std::find(kSchemaKeys.begin(), kSchemaKeys.end(), key) != kSchemaKeys.end() ||
         (key != "sources" && std::find(kTables.begin(), kTables.end(), key) != kTables.end());
}

}  // namespace

std::span<const std::string_view> schema_keys() { return kSchemaKeys; }

namespace {
// The name of `value` in one of the name tables above.
template <class Enum, std::size_t N>
std::string_view name_in(const std::array<std::pair<std::string_view, Enum>, N>& names,
                         Enum value) {
  for (const auto& [name, e] : names)
    if (e == value) return name;
  return "?";
}
}  // namespace

std::string_view to_string(Dialect d) { return name_in(kDialects, d); }
std::string_view to_string(OutputFormat f) { return name_in(kFormats, f); }
std::string_view to_string(SChangeInMotion m) { return name_in(kInMotion, m); }
std::string_view to_string(SInFeed f) { return name_in(kSInFeed, f); }
std::string_view to_string(ToolChange t) { return name_in(kToolChanges, t); }
std::string_view to_string(ToolChangeHome h) { return name_in(kToolChangeHomes, h); }
std::string_view to_string(TiltedPlane t) { return name_in(kTiltedPlanes, t); }

const SourceNote* MachineProfile::source_of(std::string_view key) const {
  const SourceNote* table_note = nullptr;
  const std::string_view table = key.substr(0, key.find('.'));
  for (const auto& note : sources_) {
    if (note.key == key) return &note;
    if (note.key == table) table_note = &note;
  }
  return table_note;
}

namespace {

// [spindle]: the speed range, rates, S resolution and how an S change acts.
SpindleSpec read_spindle(const Reader& r) {
  SpindleSpec s;
  s.n_min_rpm = *r.number("spindle", "n_min_rpm", true);
  // Below 1 rpm a whole S is 0, which means spindle off.
  require_at_least(r, s.n_min_rpm, kMinSpindleRpm, "spindle", "n_min_rpm", " rpm");
  s.n_max_rpm = *r.number("spindle", "n_max_rpm", true);
  r.require(s.n_max_rpm > 0, "spindle", "n_max_rpm", "must be > 0 rpm");
  require_at_most(r, s.n_max_rpm, kMaxSpindleRpm, "spindle", "n_max_rpm", " rpm");
  require_ordered(r, "spindle", "n_min_rpm", s.n_min_rpm, "n_max_rpm", s.n_max_rpm);
  s.acceleration_rpm_per_s = *r.number("spindle", "acceleration_rpm_per_s", true);
  require_at_least(r, s.acceleration_rpm_per_s, kMinSpindleRate, "spindle",
                   "acceleration_rpm_per_s", " rpm/s");
  require_at_most(r, s.acceleration_rpm_per_s, kMaxSpindleRate, "spindle", "acceleration_rpm_per_s",
                  " rpm/s");
  s.deceleration_rpm_per_s = *r.number("spindle", "deceleration_rpm_per_s", true);
  require_at_least(r, s.deceleration_rpm_per_s, kMinSpindleRate, "spindle",
                   "deceleration_rpm_per_s", " rpm/s (a rate, given without sign)");
  require_at_most(r, s.deceleration_rpm_per_s, kMaxSpindleRate, "spindle", "deceleration_rpm_per_s",
                  " rpm/s");
  s.s_resolution_rpm = *r.number("spindle", "s_resolution_rpm", true);
  require_at_least(r, s.s_resolution_rpm, kMinResolutionRpm, "spindle", "s_resolution_rpm", " rpm");
  r.require(s.s_resolution_rpm <= s.n_max_rpm, "spindle", "s_resolution_rpm",
            "must be at most spindle.n_max_rpm");
  r.require(
      std::ceil(s.n_min_rpm / s.s_resolution_rpm) <= std::floor(s.n_max_rpm / s.s_resolution_rpm),
      "spindle", "s_resolution_rpm", "leaves no S value between n_min_rpm and n_max_rpm",
      Code::E5006);
  s.min_change_rpm = *r.number("spindle", "min_change_rpm", true);
  r.require(s.min_change_rpm >= 0, "spindle", "min_change_rpm", "must be >= 0 rpm");
  r.require(s.min_change_rpm <= s.n_max_rpm, "spindle", "min_change_rpm",
            "must be at most spindle.n_max_rpm");
  s.min_change_percent = *r.number("spindle", "min_change_percent", true);
  r.require(s.min_change_percent >= 0 && s.min_change_percent < 100, "spindle",
            "min_change_percent", "must be in [0, 100)");
  s.max_changes_per_s = *r.number("spindle", "max_changes_per_s", true);
  r.require(s.max_changes_per_s >= kMinChangesPerS, "spindle", "max_changes_per_s",
            cat({"must be at least ", limit_text(kMinChangesPerS), " (one S word per ",
                 limit_text(1 / kMinChangesPerS), " s)"}));
  require_at_most(r, s.max_changes_per_s, kMaxChangesPerS, "spindle", "max_changes_per_s", "");
  s.change_in_motion = r.choice("spindle", "change_in_motion", kInMotion);
  s.change_code = r.string("spindle", "change_code", false).value_or("");
  if (s.change_in_motion == SChangeInMotion::code) {
    r.require(!s.change_code.empty(), "spindle", "change_in_motion",
              "is \"code\", but spindle.change_code does not name the code (e.g. \"G117\")",
              Code::E5006);
  } else if (!s.change_code.empty()) {
    r.require(false, "spindle", "change_code",
              "is only meaningful with change_in_motion = \"code\"", Code::E5006);
  }
  s.stops_path_on_change = *r.boolean("spindle", "stops_path_on_change", true);
  if (const auto v = r.number("spindle", "stop_cost_s", false)) {
    r.require(*v == 0 || (*v >= kMinTimeS && *v <= 10), "spindle", "stop_cost_s",
              cat({"must be 0 or in [", limit_text(kMinTimeS), ", 10] s"}));
    s.stop_cost_s = *v;
  }
  if (const auto v = r.number("spindle", "at_speed_window_percent", false)) {
    r.require(*v >= 0 && *v < 100, "spindle", "at_speed_window_percent",
              "must be in [0, 100) (0: the control does not wait for the spindle)");
    s.at_speed_window_percent = *v;
  }
  if (r.node("spindle", "s_in_feed", false)) {
    s.s_in_feed = r.choice("spindle", "s_in_feed", kSInFeed);
    r.require(s.s_in_feed == SInFeed::never || s.stops_path_on_change, "spindle", "s_in_feed",
              "is \"priced\", but the path does not stop at an S word "
              "(stops_path_on_change = false): every block may take one",
              Code::E5006);
  }
  return s;
}

// [control]
ControlSpec read_control(const Reader& r) {
  ControlSpec c;
  c.block_time_s = *r.number("control", "block_time_s", true);
  r.require(c.block_time_s == 0 || c.block_time_s >= kMinTimeS, "control", "block_time_s",
            cat({"must be 0 or at least ", limit_text(kMinTimeS), " s"}));
  require_at_most(r, c.block_time_s, kMaxBlockTimeS, "control", "block_time_s", " s");
  return c;
}

// [feed]
FeedSpec read_feed(const Reader& r) {
  FeedSpec f;
  f.f_min_mm_per_min = *r.number("feed", "f_min_mm_per_min", true);
  require_at_least(r, f.f_min_mm_per_min, kMinFeed, "feed", "f_min_mm_per_min", " mm/min");
  require_at_most(r, f.f_min_mm_per_min, kMaxFeed, "feed", "f_min_mm_per_min", " mm/min");
  f.f_max_mm_per_min = *r.number("feed", "f_max_mm_per_min", true);
  require_ordered(r, "feed", "f_min_mm_per_min", f.f_min_mm_per_min, "f_max_mm_per_min",
                  f.f_max_mm_per_min);
  f.rapid_mm_per_min = *r.number("feed", "rapid_mm_per_min", true);
  require_at_least(r, f.rapid_mm_per_min, kMinRapid, "feed", "rapid_mm_per_min", " mm/min");
  require_at_most(r, f.f_max_mm_per_min, kMaxFeed, "feed", "f_max_mm_per_min", " mm/min");
  require_at_most(r, f.rapid_mm_per_min, kMaxFeed, "feed", "rapid_mm_per_min", " mm/min");
  return f;
}

// [tool]
ToolSpec read_tool(const Reader& r) {
  ToolSpec t;
  const auto teeth = *r.integer("tool", "default_teeth", true);
  r.require(teeth >= 1 && teeth <= 100, "tool", "default_teeth", "must be in 1..100");
  t.default_teeth = static_cast<int>(teeth);
  return t;
}

// An [output] coolant code: "M<n>". An rs274ngc control (LinuxCNC, grbl)
// knows only M7, M8 and M9; an ISO control takes the machine's own codes,
// but not one the language already gives a meaning (stop, end, spindle,
// tool change, subprogram call).
std::string coolant_code(const Reader& r, std::string_view key, std::string fallback,
                         OutputFormat format) {
  const auto text = r.string("output", key, false);
  if (!text) return fallback;
  int m = -1;
  const auto* end = text->data() + text->size();
  const bool is_m = text->size() >= 2 && text->size() <= 4 && (*text)[0] == 'M' &&
                    std::from_chars(text->data() + 1, end, m).ptr == end;
  r.require(is_m, "output", key, "must be an M code such as \"M8\"", Code::E5007);
  if (format == OutputFormat::rs274ngc) {
    r.require(m >= 7 && m <= 9, "output", key,
              "must be M7, M8 or M9 with output_format \"rs274ngc\"", Code::E5007);
  }
  constexpr std::array<int, 10> kTaken = {0, 1, 2, 3, 4, 5, 6, 30, 98, 99};
  r.require(std::find(kTaken.begin(), kTaken.end(), m) == kTaken.end(), "output", key,
            "is " + *text + ", a code with another meaning (stop, end, spindle, tool change, call)",
            Code::E5007);
  return *text;
}

// [output]: the optional settings of the written program.
OutputSpec read_output(const Reader& r, OutputFormat format) {
  OutputSpec o;
  if (const auto v = r.integer("output", "program_number", false)) {
    r.require(*v >= 1 && *v <= 9999, "output", "program_number", "must be in 1..9999");
    o.program_number = static_cast<int>(*v);
  }
  o.high_speed_mode = r.boolean("output", "high_speed_mode", false).value_or(o.high_speed_mode);
  o.geometry_compensation =
      r.boolean("output", "geometry_compensation", false).value_or(o.geometry_compensation);
  if (const auto v = r.integer("output", "work_offset", false)) {
    r.require(*v >= 54 && *v <= 59, "output", "work_offset", "must be 54..59 (G54..G59)");
    o.work_offset = static_cast<int>(*v);
  }
  if (const auto v = r.integer("output", "decimals", false)) {
    r.require(*v >= 0 && *v <= 6, "output", "decimals", "must be in 0..6");
    o.decimals = static_cast<int>(*v);
  }
  if (const auto v = r.integer("output", "feed_decimals", false)) {
    r.require(*v >= 0 && *v <= 6, "output", "feed_decimals", "must be in 0..6");
    o.feed_decimals = static_cast<int>(*v);
  }
  o.line_numbers = r.boolean("output", "line_numbers", false).value_or(o.line_numbers);
  o.canned_cycles = r.boolean("output", "canned_cycles", false).value_or(o.canned_cycles);
  o.cutter_compensation =
      r.boolean("output", "cutter_compensation", false).value_or(o.cutter_compensation);
  o.percent_lines = r.boolean("output", "percent_lines", false).value_or(o.percent_lines);
  if (r.node("output", "tool_change", false))
    o.tool_change = r.choice("output", "tool_change", kToolChanges);
  if (r.node("output", "tool_change_home", false))
    o.tool_change_home = r.choice("output", "tool_change_home", kToolChangeHomes);
  o.tool_length_offset =
      r.boolean("output", "tool_length_offset", false).value_or(o.tool_length_offset);
  o.coolant_mist = coolant_code(r, "coolant_mist", o.coolant_mist, format);
  o.coolant_flood = coolant_code(r, "coolant_flood", o.coolant_flood, format);
  o.coolant_off = coolant_code(r, "coolant_off", o.coolant_off, format);
  if (r.node("output", "tilted_plane", false)) {
    o.tilted_plane = r.choice("output", "tilted_plane", kTiltedPlanes);
    // Each language has its own way: PLANE in Klartext, G68.2 in G-code.
    const bool klartext = format == OutputFormat::heidenhain;
    if (o.tilted_plane == TiltedPlane::plane_spatial)
      r.require(klartext, "output", "tilted_plane",
                "\"plane-spatial\" is Klartext's; G-code output takes \"g68.2\" or \"setup\"",
                Code::E5007);
    if (o.tilted_plane == TiltedPlane::g68_2)
      r.require(!klartext && format != OutputFormat::rs274ngc, "output", "tilted_plane",
                "\"g68.2\" is Fanuc's (output_format \"fanuc\" or \"mazak\"); LinuxCNC has no "
                "tilted plane (\"setup\"), Klartext takes \"plane-spatial\"",
                Code::E5007);
  }
  return o;
}

// LinuxCNC's analog outputs: motion.analog-out-00 .. -63 (num_aio at most 64).
constexpr int kMaxAnalogOutput = 63;

// [output] speed_word: "S", or "M67 E<n>" on a LinuxCNC control (rs274ngc
// read and written): the only control with an output synchronized with motion.
std::optional<int> speed_output(const Reader& r, Dialect dialect, OutputFormat format) {
  const auto text = r.string("output", "speed_word", false);
  if (!text || *text == "S") return std::nullopt;
  int n = -1;
  const auto* end = text->data() + text->size();
  const bool m67 = text->size() >= 6 && text->size() <= 7 && text->compare(0, 5, "M67 E") == 0 &&
                   std::from_chars(text->data() + 5, end, n).ptr == end && n >= 0 &&
                   n <= kMaxAnalogOutput;
  r.require(m67, "output", "speed_word",
            cat({"is \"", *text, "\", not \"S\" or \"M67 E<n>\" with n in 0..",
                 std::to_string(kMaxAnalogOutput), " (LinuxCNC's motion.analog-out-<n>)"}),
            Code::E5020);
  r.require(dialect == Dialect::rs274ngc && format == OutputFormat::rs274ngc, "output",
            "speed_word",
            "is \"" + *text +
                "\", LinuxCNC's analog output: it needs machine.dialect and "
                "machine.output_format \"rs274ngc\"",
            Code::E5021);
  return n;
}

// [sources]: where each value comes from, "vendor: ..." or "assumed: ...".
std::vector<SourceNote> read_sources(const Reader& r) {
  std::vector<SourceNote> notes;
  if (const auto* sources = r.table("sources")) {
    for (const auto& [key, node] : *sources) {
      const std::string k(key.str());
      if (!schema_has(k)) {
        r.fail(Code::E5008, key.source(),
               "'sources.\"" + k + "\"' names no key or table of the profile");
      }
      const auto* text_node = node.as_string();
      if (!text_node) {
        r.fail(Code::E5003, node.source(),
               "'sources.\"" + k + "\"' must be a string \"vendor: ...\" or \"assumed: ...\"");
      }
      const std::string& note = text_node->get();
      SourceNote n{k, false, ""};
      auto rest = [&](std::size_t prefix) {
        std::string t = note.substr(prefix);
        t.erase(0, t.find_first_not_of(' '));
        return t;
      };
      if (note.rfind("vendor:", 0) == 0) {
        n.vendor = true;
        n.text = rest(7);
      } else if (note.rfind("assumed:", 0) == 0) {
        n.text = rest(8);
      } else {
        r.fail(Code::E5008, node.source(),
               "'sources.\"" + k + "\"' must start with \"vendor:\" or \"assumed:\"");
      }
      if (n.text.empty()) {
        r.fail(Code::E5008, node.source(),
               "'sources.\"" + k + "\"' needs the document or the reason after the colon");
      }
      // Notes are printed as one-line comments, where no control character
      // may stand (a line break would even end the comment).
      if (std::any_of(n.text.begin(), n.text.end(), [](char c) {
            return (static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f;
          })) {
        r.fail(Code::E5008, node.source(),
               "'sources.\"" + k + "\"' must be one line of text without control characters");
      }
      notes.push_back(std::move(n));
    }
  }
  return notes;
}

// A Heidenhain control (TNC): it reads and is written Klartext, both or
// neither (a control's language is read and written by its own dialect);
// it takes a new S only in `TOOL CALL S`, a block of its own; and the
// [output] keys of the G-code writer mean nothing in Klartext (no G05,
// G61.1, G54, '%', G28/G53, G43 H, N words or M0 tool change; the
// program number names the program: BEGIN PGM <number> MM), so a value
// given for one is refused rather than silently dropped.
void check_heidenhain(const Reader& r, Dialect dialect, OutputFormat format,
                      SChangeInMotion change_in_motion) {
  const bool reads = dialect == Dialect::heidenhain;
  const bool writes = format == OutputFormat::heidenhain;
  if (reads != writes) {
    r.require(false, "machine", writes ? "output_format" : "dialect",
              writes ? "is \"heidenhain\" (Klartext), but machine.dialect is a G-code dialect: "
                       "a control's language is read and written by one dialect"
                     : "is \"heidenhain\" (Klartext), but machine.output_format is G-code: "
                       "a control's language is read and written by one dialect",
              Code::E5011);
  }
  if (!reads) return;
  r.require(change_in_motion == SChangeInMotion::own_block, "spindle", "change_in_motion",
            "must be \"own_block\" on a Heidenhain control: a TNC takes a new S only in a "
            "`TOOL CALL S` block of its own",
            Code::E5012);
  for (const auto key : kGcodeOnlyOutputKeys) {
    if (r.node("output", key, false)) {
      r.require(false, "output", key,
                "is a G-code setting that Klartext output has no use for (remove it from a "
                "Heidenhain profile)",
                Code::E5013);
    }
  }
  if (const auto compensation = r.boolean("output", "cutter_compensation", false)) {
    r.require(!*compensation, "output", "cutter_compensation",
              "must be false on a Heidenhain control: the CL path is the tool centre and "
              "Klartext output writes CUTCOM as a comment with R0",
              Code::E5013);
  }
  if (const auto change = r.string("output", "tool_change", false)) {
    r.require(*change == "m6", "output", "tool_change",
              "must be \"m6\" (the TNC's TOOL CALL) on a Heidenhain control", Code::E5013);
  }
}

}  // namespace

MachineProfile profile_from_toml(std::string_view text, const std::string& file) {
  toml::table root;
  try {
    root = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw ProfileError(Code::E5001, {file, e.source().begin.line, e.source().begin.column},
                       std::string(e.description()));
  }
  const Reader r(root, file);
  r.check_unknown();

  MachineProfile p;
  p.origin_ = file;
  p.name_ = *r.string("machine", "name", true);
  r.require(!p.name_.empty(), "machine", "name", "must not be empty");
  p.description_ = r.string("machine", "description", false).value_or("");
  p.dialect_ = r.choice("machine", "dialect", kDialects);
  p.output_format_ = r.choice("machine", "output_format", kFormats);
  p.spindle_ = read_spindle(r);
  p.control_ = read_control(r);
  p.feed_ = read_feed(r);
  p.tool_ = read_tool(r);
  p.output_ = read_output(r, p.output_format_);
  check_heidenhain(r, p.dialect_, p.output_format_, p.spindle_.change_in_motion);
  if (p.output_format_ == OutputFormat::heidenhain) p.output_.cutter_compensation = false;
  p.output_.speed_output = speed_output(r, p.dialect_, p.output_format_);
  p.sources_ = read_sources(r);
  return p;
}

SpindleSpec planned_spindle(const MachineProfile& profile) {
  SpindleSpec s = profile.spindle();
  if (!profile.output().speed_output) return s;
  s.change_in_motion = SChangeInMotion::inline_word;
  s.change_code.clear();
  s.stops_path_on_change = false;
  s.stop_cost_s = 0;
  s.at_speed_window_percent = 0;
  s.s_in_feed = SInFeed::never;
  return s;
}

MachineProfile profile_from_stream(std::istream& in, const std::string& file) {
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ProfileError(Code::E5010, {file}, "cannot read");
  return profile_from_toml(text.str(), file);
}

}  // namespace vcpost::machines
