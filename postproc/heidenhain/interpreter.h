// The Klartext interpreter: a Heidenhain TNC conversational program ->
// motion events (program/events.h), one block at a time. It streams as the
// G-code interpreter does: memory does not grow with the program; only the
// label index (built on the first jump or call, in one scan of the text)
// and the call stack are kept.
//
// Output units: mm, mm/min, rpm, seconds. Positions are in the program's
// frame as the control places it: CYCL DEF 7 datum shifts are applied (the
// part model's frame is the one the program starts in); tool length and
// radius offsets (DL, DR, RL/RR) are not, as for G-code.
//
// What is assumed where the program cannot say (docs/heidenhain.md):
// - M91/M92 (and M140 MB MAX) move in machine coordinates, whose datum the
//   program does not give: the move is taken as a retract to a safe height
//   (the highest of the stock's top and every height reached so far), the
//   other axes stay, and the event is marked (StraightTraverse::
//   machine_frame); warned once.
// - Drilling cycles 200, 201, 203, 205, 207, 208 are expanded into their
//   moves (cycles.h); machine and probing cycles (300 and above) pass with
//   a warning and move nothing; other machining cycles are refused.
// - A tilted working plane (PLANE with angles, CYCL DEF 19) is refused with
//   its own code (3+2 is read by a later reader, which adds a frame to the
//   events: plane() keeps the parsed angles); so are rotary axes that turn.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "postproc/gcode/interpreter.h"
#include "postproc/heidenhain/approach.h"
#include "postproc/heidenhain/block.h"
#include "postproc/heidenhain/cycles.h"
#include "postproc/heidenhain/diagnostics.h"
#include "postproc/heidenhain/program_loader.h"
#include "postproc/program/events.h"

namespace vcpost::heidenhain {

// The limits of calls, repeats and jumps: the G-code interpreter's.
using InterpreterLimits = gcode::InterpreterLimits;

// The stock of BLK FORM 0.1/0.2 (mm, program frame, no datum shift).
struct StockBox {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  program::SourceRef source;  // the BLK FORM 0.1 block
};

// The working plane last set (PLANE, CYCL DEF 19): its kind and its angles
// as programmed (degrees), for a reader of tilted frames to build on.
struct WorkingPlane {
  std::string kind;  // RESET, SPATIAL, PROJECTED, EULER, VECTOR, AXIAL, RELATIV, CYCL DEF 19
  std::vector<std::pair<std::string, double>> values;  // SPA 0, SPB 0, ... in order
  bool identity = true;
  program::SourceRef source;
};

class Interpreter {
 public:
  // `text` must outlive the interpreter (e.g. a memory-mapped file).
  explicit Interpreter(std::string_view text, InterpreterLimits limits = {});

  // Reads and executes the next block and appends its events to `events`
  // (not cleared). False when the program has ended (END PGM, M2/M30, end
  // of text); then nothing is appended. Throws KlartextError; after a throw
  // further calls return false.
  bool next(std::vector<program::Event>& events);

  // The block last read by next() (its bytes, number, kind, words, spans).
  const Block& block() const { return block_; }
  bool inches() const { return inches_; }
  const std::optional<StockBox>& stock() const { return stock_; }
  const std::optional<WorkingPlane>& plane() const { return plane_; }
  // Warnings so far (errors are thrown), at most limits.max_warnings.
  const std::vector<Diagnostic>& warnings() const { return warnings_; }
  std::uint64_t warning_count() const { return warning_count_; }
  std::uint64_t lines_read() const { return lines_read_; }
  // The first byte from which blocks may run more than once (the earliest
  // label read, called or jumped to so far), for a writer that must hold
  // such blocks until every run is known; empty while there is none.
  std::optional<std::uint64_t> repeat_from() const { return repeat_from_; }
  // The tool number a TOOL CALL "name" stands for in the events (names are
  // numbered 1, 2, ... in the order they are first called).
  std::optional<int> tool_number(std::string_view tool_name) const;
  // The radius (mm) of the tool in the spindle, from the control's tool
  // table, which the program does not hold: a caller that knows the tool
  // (CAM comments, --tool) gives it; cycle 208's helix needs it. A TOOL
  // CALL takes it back to what TOOL DEF gave that tool (R), or none.
  void set_tool_radius(std::optional<double> radius) { tool_radius_ = radius; }
  // CALL PGM reads the called program inline (its events as the CALL PGM
  // block's); without a loader it is refused (E3331).
  void set_program_loader(ProgramLoader loader) { loader_ = std::move(loader); }
  // A writer of the main program only (vcpost post) cannot change a speed
  // inside a called program: a TOOL CALL there is then refused (E3332).
  void refuse_tool_calls_in_called_programs() { called_tool_calls_refused_ = true; }
  // The program being read: "" for the main one, else a called one's name.
  const std::string& program_name() const { return program_name_; }

 private:
  struct Frame {
    std::uint64_t call_offset = 0;  // the CALL LBL block
    std::uint64_t return_offset = 0;
    std::uint32_t return_line = 0;
    std::uint64_t label_offset = 0;
    std::uint32_t label_line = 0;
    long remaining = 0;    // repeats still to run
    bool section = false;  // a section repeat (ends at its CALL), else a subprogram (at LBL 0)
  };
  struct Place {
    std::uint64_t offset = 0;
    std::uint32_t line = 0;
  };
  // A straight move held back because RND or CHF follows it.
  struct Held {
    program::Event move;
    std::optional<program::Event> corner_feed;  // RND/CHF F: its SetFeedRate
    double corner = 0;                          // RND radius or CHF length, mm
    bool rounding = true;
    program::SourceRef corner_source;
    bool corner_read = false;
  };
  struct Words;
  // An APPR read, its path waiting for the contour element after it.
  struct PendingApproach {
    LinkInput in;
    Eigen::Vector3d start = Eigen::Vector3d::Zero();  // PS
    Eigen::Vector3d first = Eigen::Vector3d::Zero();  // PA
    bool rapid_to_auxiliary = false;  // LT LN CT after an FMAX block: PS -> PH at rapid
    bool rapid = false;               // APPR ... FMAX
    double feed_before = 0;           // mm/min
    double feed = 0;                  // the APPR's, mm/min
    program::SourceRef source;
    std::uint32_t line = 0, column = 0;
  };
  struct LinkWords;
  // The calling program's place while a called one runs.
  struct Caller {
    std::string_view text;
    std::uint64_t pos = 0;
    std::uint32_t line = 0;
    std::string name;
    std::optional<std::unordered_map<std::string, Place>> labels;
    std::vector<Frame> frames;
    bool inches = false;
    std::vector<double> local;  // its QL parameters
    program::SourceRef call_source;
  };

  // interpreter.cpp: the block transaction.
  bool read_block();
  void execute(std::vector<program::Event>& events);
  [[noreturn]] void refuse_block() const;
  [[noreturn]] void fail(Code code, std::uint32_t at, std::string message) const;
  void warn(Code code, std::uint32_t at, std::string message);
  void warn_once(Code code, long key, std::uint32_t at, std::string message);
  program::SourceRef source() const;

  // interpreter_words.cpp: values and a block's words.
  double value(const Value& v, std::uint32_t at) const;
  // Where a Q, QL or QR parameter lives in q_ (fails when out of range).
  std::size_t parameter_index(const Value& v, std::uint32_t at) const;
  double length(double program_units) const {
    return inches_ ? program_units * 25.4 : program_units;
  }
  double feed_rate(double program_units) const {
    return inches_ ? program_units * 2.54 : program_units;  // inch programs: 1/10 inch/min
  }
  struct WordReader;
  Words read_words(std::uint32_t allowed) const;

  // interpreter.cpp: BEGIN PGM, BLK FORM.
  void begin_program();
  void blk_form();

  // interpreter_functions.cpp: TOOL CALL, M functions, FUNCTION.
  void tool_call(std::vector<program::Event>& events);
  void start_functions(const Words& w, std::vector<program::Event>& events);
  void end_functions(const Words& w, std::vector<program::Event>& events);
  void function_block();

  // interpreter_moves.cpp: L, LN, LP, CC, C, CR, CT, CP, RND, CHF.
  void motion(std::vector<program::Event>& events);
  void set_feed_and_compensation(const Words& w, std::vector<program::Event>& events);
  void rotary(const Words& w);
  Eigen::Vector3d cartesian_target(const Words& w) const;
  Eigen::Vector3d polar_target(const Words& w, bool line) const;
  void straight(const Words& w, const Eigen::Vector3d& end, std::vector<program::Event>& events);
  void arc(const Words& w, const Eigen::Vector3d& end, const Eigen::Vector2d& centre, int rotation,
           std::vector<program::Event>& events);
  void circle(const Words& w, std::vector<program::Event>& events);
  void circle_radius(const Words& w, std::vector<program::Event>& events);
  void circle_tangent(const Words& w, std::vector<program::Event>& events);
  void circle_polar(const Words& w, std::vector<program::Event>& events);
  void centre(const Words& w);
  void corner(const Words& w);
  void emit_move(program::Event move, std::vector<program::Event>& events);
  void finish_corner(const Eigen::Vector3d& end, std::vector<program::Event>& events);
  bool corner_follows() const;
  void machine_retract(const Words& w, std::vector<program::Event>& events);

  // interpreter_approach.cpp: APPR, DEP.
  LinkWords link_words(bool departure) const;
  void approach(std::vector<program::Event>& events);
  void link_approach(std::vector<program::Event>& events, std::size_t before);
  [[noreturn]] void fail_approach(const std::string& why) const;
  void departure(std::vector<program::Event>& events);

  // interpreter_flow.cpp: FN, formulas, labels, calls, called programs.
  void fn(std::vector<program::Event>& events);
  void formula();
  void label_block();
  void call_label();
  void call_program(std::string_view path);
  void return_from_program();
  void jump_to(const Label& label, std::uint32_t at);
  Place find_label(const Label& label, std::uint32_t at);
  void count_jump(std::uint32_t at);

  // interpreter_cycles.cpp: CYCL DEF, CYCL CALL, the drilling cycles.
  void cycle_def(std::vector<program::Event>& events);
  void cycle_call(std::vector<program::Event>& events);
  void run_cycle(std::uint32_t at, std::vector<program::Event>& events);
  void bore_milling(DrillHole& hole, std::uint32_t at);

  // interpreter_plane.cpp: PLANE and the tilted frame.
  void plane_block(std::vector<program::Event>& events);
  void tilt(const Eigen::Matrix3d& rotation, std::vector<program::Event>& events);
  Eigen::Matrix3d points_plane(const WorkingPlane& p) const;

  std::string_view text_;
  InterpreterLimits limits_;
  Block block_;
  std::uint64_t pos_ = 0;
  std::uint32_t line_ = 0;  // lines before pos_
  std::uint64_t lines_read_ = 0;
  std::uint64_t blocks_run_ = 0;
  std::uint64_t jumps_ = 0;
  bool begun_ = false;
  bool ended_ = false;
  bool end_event_ = false;  // ProgramEnd given (M2/M30)
  bool inches_ = false;

  Eigen::Vector3d position_ = Eigen::Vector3d::Zero();
  double highest_z_ = 0.0;
  Eigen::Vector3d shift_ = Eigen::Vector3d::Zero();  // CYCL DEF 7, mm
  program::WorkingFrame tilt_;                       // PLANE, CYCL DEF 19 (3+2)
  std::optional<Eigen::Vector2d> pole_;              // CC, mm (shift applied)
  std::optional<Eigen::Vector2d> tangent_;           // of the last contour element's end, XY
  double feed_ = 0.0;                                // modal F, mm/min (0: none yet)
  double tool_feed_ = 0.0;                           // TOOL CALL F (FAUTO)
  double spindle_rpm_ = 0.0;
  bool spindle_ccw_ = false;
  int arc_direction_ = 0;  // DR of the last arc: +1, -1; 0 none yet
  program::CompensationSide compensation_ = program::CompensationSide::off;
  std::array<double, 3> rotary_{};  // A, B, C, degrees
  bool tcpm_ = false;               // M128 / FUNCTION TCPM
  int cycle_ = 0;                   // the CYCL DEF in effect (200 ...), 0 none
  std::vector<double> q_;           // Q0-1999, QL0-499, QR0-499
  std::optional<StockBox> stock_;
  std::optional<WorkingPlane> plane_;
  std::optional<Held> held_;
  std::optional<PendingApproach> approach_;
  bool last_rapid_ = false;  // the last move was FMAX (APPR goes on at rapid)
  ProgramLoader loader_;
  bool called_tool_calls_refused_ = false;
  std::vector<Caller> programs_;                       // the callers of the program being read
  std::string program_name_;                           // "" while the main program is read
  std::optional<std::string> selected_;                // SEL PGM
  std::optional<double> tool_radius_;                  // set_tool_radius, TOOL DEF R
  std::vector<std::pair<int, double>> defined_radii_;  // TOOL DEF n R
  std::optional<std::uint64_t> repeat_from_;
  std::vector<std::pair<std::string, int>> tool_names_;
  std::vector<Frame> frames_;
  std::optional<std::unordered_map<std::string, Place>> labels_;
  std::vector<std::pair<Code, long>> warned_once_;
  std::vector<Diagnostic> warnings_;
  std::uint64_t warning_count_ = 0;
};

}  // namespace vcpost::heidenhain
