// The motion-event vocabulary: what an NC program means, independent of how
// it was written (G-code of any dialect, APT CL data). Readers produce these
// values; the pipeline and the transcript printer consume them.
//
// Units, always: positions in mm in the program (work) coordinate system
// (the frame of the part model; work offsets and tool length offsets are NOT
// applied, as in rs274's canonical calls), feeds in mm/min (or see FeedMode),
// spindle speed in rpm, time in seconds. Position = tool tip or ball centre
// as the CL point convention of the reader says (MODELS.md 1): the events do
// not change it.
//
// Every event carries the SourceRef of the block (G-code) or record (CL) that
// produced it, so later stages can report and patch that block.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>

namespace vcpost::program {

// Where an event came from. line and column are 1-based; 0 means unknown
// (an event made up by the reader, e.g. the implicit end of a program).
// offset is the byte offset of the block's (record's) first byte in the file.
struct SourceRef {
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  std::uint64_t offset = 0;
  friend bool operator==(const SourceRef&, const SourceRef&) = default;
};

// The arc plane: G17 (XY, axis Z), G18 (XZ, axis Y), G19 (YZ, axis X).
enum class Plane { xy, xz, yz };

// How F is meant: mm/min (G94), 1/min inverse time (G93: the move takes
// 1/F minutes), mm per spindle revolution (G95).
enum class FeedMode { per_minute, inverse_time, per_revolution };

enum class SpindleDirection { clockwise, counterclockwise };

// Rapid move (G0, CL RAPID + GOTO) from start to end along a straight line.
struct StraightTraverse {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  SourceRef source;
  // A move programmed in machine coordinates whose datum the program does
  // not give (Klartext M91/M92): `end` stands for a retract to a safe
  // height, not for where the machine goes (docs/heidenhain.md).
  bool machine_frame = false;
};

// Cutting move along a straight line at the current feed.
struct StraightFeed {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  SourceRef source;
};

// Circular or helical cutting move in `plane`. centre's in-plane components
// are the circle centre; its axis component equals start's (not meaningful).
// rotation: sign = direction seen from the plane axis' positive side
// (+ counterclockwise = G3, - clockwise = G2), |rotation| = number of turns
// started (1 = less than or one full turn; 2 = one extra full turn, RS274 P2).
// The axis coordinate moves linearly from start to end (helix).
// Invariant: the in-plane distances of start and end from centre agree to the
// reader's tolerance.
struct ArcFeed {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Plane plane = Plane::xy;
  int rotation = 1;
  SourceRef source;
};

// Feed rate for the following feed moves; rate in the unit of `mode`.
struct SetFeedRate {
  double rate = 0.0;
  FeedMode mode = FeedMode::per_minute;
  SourceRef source;
  // inverse_time only: the path speed in mm/min that this F gives the feed
  // move right after it (F * move length, what rs274 prints); unset when no
  // feed move follows in the same block, and in the other modes.
  std::optional<double> path_rate = std::nullopt;
};

// Commanded spindle speed (rpm, >= 0); S0 means "spindle stopped".
struct SetSpindleSpeed {
  double rpm = 0.0;
  SourceRef source;
};

struct SpindleOn {  // M3 / M4
  SpindleDirection direction = SpindleDirection::clockwise;
  SourceRef source;
};

struct SpindleOff {  // M5
  SourceRef source;
};

struct SelectTool {  // T word: prepare tool `number`
  int number = 0;
  SourceRef source;
};

struct ChangeTool {  // M6 (CL LOADTL): tool `number` is now in the spindle
  int number = 0;
  SourceRef source;
};

// G43 H.. (enabled, register) / G49 (disabled). The length itself is the
// machine's business; it is not applied to positions (see the units note).
struct ToolLengthOffset {
  bool enabled = false;
  std::optional<int> register_number;
  SourceRef source;
};

enum class CompensationSide { off, left, right };

// G40 / G41 / G42 (CL CUTCOM); the motion events are the programmed path,
// never offset by it.
struct CutterCompensation {
  CompensationSide side = CompensationSide::off;
  SourceRef source;
  std::optional<int> register_number = std::nullopt;  // D (CL: CUTCOM's register)
};

struct SelectPlane {
  Plane plane = Plane::xy;
  SourceRef source;
};

enum class CoolantChange { mist_on, flood_on, off };

struct Coolant {  // M7 / M8 / M9, CL COOLNT
  CoolantChange change = CoolantChange::off;
  SourceRef source;
};

struct Dwell {  // G4, CL DELAY
  double seconds = 0.0;
  SourceRef source;
};

struct ProgramStop {  // M0 (optional = false), M1 (optional = true)
  bool optional = false;
  SourceRef source;
};

struct ProgramEnd {  // M2, M30, CL FINI
  SourceRef source;
};

// A comment the operator should see: `(MSG,...)`, CL PPRINT.
struct Message {
  std::string text;
  SourceRef source;
};

// The canned cycle (G73, G81-G89; Klartext CYCL DEF 200-208 by their own
// number) that makes the hole whose events follow
// (CL CYCLE/...). The reader still gives every move, dwell and spindle
// change of the hole after it: a writer for a control with canned cycles
// writes the cycle instead of them; every other stage skips this event.
struct CannedCycle {
  int code = 81;             // 73, 81, 82, 83, 84, 85, 86, 89; Klartext 200-208
  double x = 0.0, y = 0.0;   // the hole, mm
  double top_z = 0.0;        // where the hole's moves start and end (return level), mm
  double r_z = 0.0;          // R plane: feeding starts here, r_z <= top_z, mm
  double bottom_z = 0.0;     // mm
  double peck = 0.0;         // Q (G73, G83), mm > 0
  double dwell_s = 0.0;      // P (G82, G84, G86, G89), s
  std::uint32_t events = 0;  // events of the hole that follow: motion, dwell, spindle, feed
  std::uint32_t moves = 0;   // of which motion
  SourceRef source;
};

// A tilted working plane (3+2: CL CSYS, Klartext PLANE, Fanuc G68.2,
// Sinumerik CYCLE800): the events that follow are in its own frame, whose
// +z is the tool axis, until the next WorkingFrame. A point p of them is at
// rotation * p + origin in the program frame (the part's, where the model
// is). The identity (the default) is the untilted program.
struct WorkingFrame {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // columns: the frame's x, y, z
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();        // mm
  SourceRef source;
  bool is_identity() const { return rotation == Eigen::Matrix3d::Identity() && origin.isZero(0); }
  Eigen::Vector3d to_program(const Eigen::Vector3d& p) const { return rotation * p + origin; }
};

using Event = std::variant<StraightTraverse, StraightFeed, ArcFeed, SetFeedRate, SetSpindleSpeed,
                           SpindleOn, SpindleOff, SelectTool, ChangeTool, ToolLengthOffset,
                           CutterCompensation, SelectPlane, Coolant, Dwell, ProgramStop, ProgramEnd,
                           Message, CannedCycle, WorkingFrame>;

// The source of any event.
SourceRef source_of(const Event& event);

// True for StraightTraverse, StraightFeed and ArcFeed.
bool is_motion(const Event& event);

}  // namespace vcpost::program
