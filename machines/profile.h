// Machine profiles: what a machine and its control can do with the spindle
// and the feed, validated from a TOML file into an immutable value.
//
// Units are in the key names: rpm, rpm/s, mm/min, s, percent. The schema
// (tables, keys, types, ranges) is documented in machines/README.md and
// enforced by profile_from_toml(): unknown keys are errors, so a typo never
// silently falls back to a default.
//
// Provenance: the [sources] table of a profile says, per key, whether a
// value comes from a vendor document ("vendor: <document>") or is an
// assumption ("assumed: <why>"); the loader keeps these notes so that
// `vcpost machines show` and the report can print them.
#pragma once

#include <cstdint>
#include <istream>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "machines/dialect.h"

namespace vcpost::machines {

// The format of the program written from CL data for this machine: G-code
// of a dialect, or Klartext (heidenhain, postproc/output/klartext_writer.h).
enum class OutputFormat { rs274ngc, fanuc, mazak, heidenhain };
// How an S change in a motion block reaches the spindle:
// inline_word: the S word goes into the motion block as it is;
// code: the block also needs a code (Mazak's G117);
// own_block: the S word must stand in a block of its own between moves.
enum class SChangeInMotion { inline_word, code, own_block };

// Where a control whose path stops at an S word (stops_path_on_change) may
// get one inside a feed stream: never (only where the path stops or leaves
// the material anyway), or priced: also there, where the cutting time the
// word brings to nominal vc outweighs the stop it costs (stop_aware_plan.h).
enum class SInFeed { never, priced };

struct SpindleSpec {
  double n_min_rpm = 100.0;    // lowest speed the spindle holds, > 0 (S0 means off)
  double n_max_rpm = 10000.0;  // highest speed, >= n_min_rpm
  // Slew limits of the spindle drive, > 0. The planner assumes the spindle
  // reaches a commanded speed at least this fast.
  double acceleration_rpm_per_s = 2000.0;
  double deceleration_rpm_per_s = 2000.0;
  double s_resolution_rpm = 1.0;  // smallest S step the control takes, > 0 (1 = integer S)
  // A change is worth a new S word only if it is at least both of these
  // (threshold = max(min_change_rpm, min_change_percent % of the current S)).
  double min_change_rpm = 1.0;      // >= 0
  double min_change_percent = 1.0;  // 0 <= p < 100
  double max_changes_per_s = 10.0;  // most S words per second, > 0: words at least 1/this apart
  SChangeInMotion change_in_motion = SChangeInMotion::inline_word;
  std::string change_code;  // e.g. "G117"; non-empty iff change_in_motion == code
  // How the control takes an S word in motion: false ("inline"): the path
  // keeps its speed, so S words may go on any block; true ("stops path"): the
  // path stops at every S word (LinuxCNC, grbl, Fanuc with the speed arrival
  // check, Sinumerik with acknowledgement before motion), so the planner puts
  // S words only where the path stops or leaves the material anyway.
  bool stops_path_on_change = false;
  // Path time one S word in motion costs where it stops the path (braking,
  // the stop, speeding up again), s, 0..10 (0 when inline).
  double stop_cost_s = 0.0;
  // The control holds the path after an S change until the spindle is within
  // this share of the new speed, percent, 0 <= w < 100; 0: it does not wait.
  double at_speed_window_percent = 0.0;
  SInFeed s_in_feed = SInFeed::never;  // only with stops_path_on_change
};

struct FeedSpec {
  double f_min_mm_per_min = 1.0;      // > 0
  double f_max_mm_per_min = 10000.0;  // >= f_min
  double rapid_mm_per_min = 20000.0;  // > 0
};

struct ControlSpec {
  double block_time_s = 0.001;  // processing time of one block, >= 0
};

struct ToolSpec {
  int default_teeth = 2;  // number of teeth when the command line gives none, >= 1
};

// How the written program changes tools. m6: T<n> M6, the control's
// changer; manual: the spindle stopped and a program stop (M0) with the
// tool named, for a control without a changer or M6 (grbl).
enum class ToolChange { m6, manual };

// The move up before a tool change the control does not make itself:
// none (the control's M6 moves: LinuxCNC's TOOL_CHANGE_QUILL_UP), g28
// (G91 G28 Z0. then G90: Z to the reference point, Fanuc and Mazak posts),
// g53 (G53 G0 Z0: Z to machine zero in one absolute block).
enum class ToolChangeHome { none, g28, g53 };

// How the written program tilts the working plane (3+2) of a tilted CL
// frame (output.tilted_plane): setup, each frame a set-up of its own (a
// plain 3-axis machine: its own work offset, a program stop and a comment
// that says how to clamp the part); g68_2, Fanuc's G68.2 / G53.1 / G69;
// plane_spatial, Klartext PLANE SPATIAL ... STAY / PLANE RESET STAY.
enum class TiltedPlane { setup, g68_2, plane_spatial };

// Options of the G-code written from CL data (see postproc/output/).
struct OutputSpec {
  int program_number = 1000;           // O word, 1..9999
  bool high_speed_mode = false;        // G05 P2 after each tool change
  bool geometry_compensation = false;  // G61.1
  int work_offset = 54;                // G54..G59
  int decimals = 4;                    // digits after the point for lengths, 0..6
  int feed_decimals = 1;               // digits after the point for F, 0..6
  bool line_numbers = false;           // N words
  bool canned_cycles = false;          // CL hole cycles as G73/G81-G89 (else their moves)
  bool cutter_compensation = true;     // CL CUTCOM as G41/G42 D, G40 (else comments)
  bool percent_lines = true;           // '%' first and last line (grbl refuses '%')
  ToolChange tool_change = ToolChange::m6;
  ToolChangeHome tool_change_home = ToolChangeHome::none;
  bool tool_length_offset = true;  // G43 H<tool> after a tool change (grbl has no G43 H)
  // The M codes of CL COOLNT/MIST, FLOOD (and ON), OFF: "M7", "M8", "M9"
  // unless the control differs (grbl refuses M7 unless built with it).
  std::string coolant_mist = "M7";
  std::string coolant_flood = "M8";
  std::string coolant_off = "M9";
  // The word that carries the spindle speed (output.speed_word): none, the
  // S word; n, LinuxCNC's analog output n ("M67 E<n>"): a spindle whose
  // speed command is wired to motion.analog-out-<n> takes each change in
  // motion as M67 E<n> Q<rpm>, set at the start of the next motion without
  // a stop of the path (an S word stops it). The spindle's start keeps its
  // S word, with M68 E<n> Q<rpm> (immediate) beside it. 0..63.
  std::optional<int> speed_output;
  TiltedPlane tilted_plane = TiltedPlane::setup;
};

// Provenance of one key ("spindle.n_max_rpm", or a whole table "feed").
struct SourceNote {
  std::string key;
  bool vendor = false;  // true: taken from a vendor document
  std::string text;     // the document, or why the value was assumed
};

class MachineProfile;

// A profile that failed to load. what() is the whole one-line message:
// "<file>:<line>:<col>: error[E5xxx]: '<table.key>' <reason>" (no
// ":<line>:<col>" when no position applies, e.g. an unreadable file);
// where() holds the same place (line 0 when none applies).
class ProfileError : public vcpost::Error {
 public:
  ProfileError(Code code, const SourceLocation& where, const std::string& message)
      : vcpost::Error(code, format_diagnostic(code, where, message), where) {}
};

// The validated profile. Immutable: built only by the loaders below.
class MachineProfile {
 public:
  const std::string& name() const { return name_; }
  const std::string& description() const { return description_; }
  Dialect dialect() const { return dialect_; }
  OutputFormat output_format() const { return output_format_; }
  const SpindleSpec& spindle() const { return spindle_; }
  const FeedSpec& feed() const { return feed_; }
  const ControlSpec& control() const { return control_; }
  const ToolSpec& tool() const { return tool_; }
  const OutputSpec& output() const { return output_; }
  // Notes in the order of the file. A key without a note has no stated source.
  const std::vector<SourceNote>& sources() const { return sources_; }
  // The note that covers a key: its own, else its table's; nullptr if none.
  const SourceNote* source_of(std::string_view key) const;
  // Where the profile came from: a built-in name ("built-in mazak-3axis") or the file path.
  const std::string& origin() const { return origin_; }

  friend MachineProfile profile_from_toml(std::string_view text, const std::string& file);

 private:
  MachineProfile() = default;
  std::string name_;
  std::string description_;
  Dialect dialect_ = Dialect::rs274ngc;
  OutputFormat output_format_ = OutputFormat::rs274ngc;
  SpindleSpec spindle_;
  FeedSpec feed_;
  ControlSpec control_;
  ToolSpec tool_;
  OutputSpec output_;
  std::vector<SourceNote> sources_;
  std::string origin_;
};

// Parses and validates a profile. `file` names the source in messages.
// Throws ProfileError on the first problem found.
MachineProfile profile_from_toml(std::string_view text, const std::string& file);
// The same from a stream (read whole).
MachineProfile profile_from_stream(std::istream& in, const std::string& file);

// The spindle as the planner places its speed changes: as [spindle] says
// for the S word; with output.speed_word "M67 E<n>" a change rides on the
// motion without a stop, so it is placed as on a control that takes S in
// motion (inline, no stop cost, no wait for the spindle, no priced S).
SpindleSpec planned_spindle(const MachineProfile& profile);

// Every key of the schema, as "table.key" (for `machines show` and tests).
std::span<const std::string_view> schema_keys();

// The profile as a complete TOML file: every key with its value, a comment
// with its source note ("vendor: ...", "assumed: ...", or "no source
// given"), and the [sources] table; loading the text gives the same profile.
std::string profile_to_toml(const MachineProfile& profile);

std::string_view to_string(Dialect d);
std::string_view to_string(OutputFormat f);
std::string_view to_string(SChangeInMotion m);
std::string_view to_string(SInFeed f);
std::string_view to_string(ToolChange t);
std::string_view to_string(ToolChangeHome h);
std::string_view to_string(TiltedPlane t);

}  // namespace vcpost::machines
