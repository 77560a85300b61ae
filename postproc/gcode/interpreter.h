// The G-code interpreter: program text -> motion events, one block at a
// time (streaming: memory does not grow with the program's length; only
// the subroutine index and the call/loop stacks are kept).
//
// Each block is a transaction: it is read into a Block, its words are
// checked (modal groups, required words) against a copy of the modal state,
// and only then are the state committed and its events appended. A block in
// error changes nothing and throws GcodeError (file position included); the
// caller decides whether to stop (the interpreter cannot go on soundly).
//
// Output units: mm, mm/min, rpm, seconds (see program/events.h). Positions
// are in the program's work coordinate system, offsets not applied, as in
// rs274's canonical calls.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "postproc/gcode/block.h"
#include "postproc/gcode/code_names.h"
#include "postproc/gcode/diagnostics.h"
#include "postproc/gcode/dialect.h"
#include "postproc/gcode/nurbs.h"
#include "postproc/gcode/parameters.h"
#include "postproc/program/events.h"

namespace vcpost::gcode {

struct CycleCall;

// nurbs: G5.2, control points are read (nurbs.h); the tool moves at G5.3.
enum class Motion { none, rapid, linear, arc_cw, arc_ccw, spline_cubic, spline_quadratic, nurbs };

// The modal state between blocks (all lengths mm).
struct ModalState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Motion motion = Motion::none;
  program::Plane plane = program::Plane::xy;
  bool inches = false;
  bool absolute = true;
  bool arc_absolute = false;  // G90.1; LinuxCNC starts in G91.1
  program::FeedMode feed_mode = program::FeedMode::per_minute;
  double feed = 0.0;  // mm/min, mm/rev or 1/min as feed_mode says
  double spindle_rpm = 0.0;
  int selected_tool = 0;
  int tool_in_spindle = 0;
  int work_system = G_54_work_1;  // code_names.h
  bool moved = false;             // any motion yet (frame changes warned after)
  // Canned cycles: the active one (x10, 0 none; RS274NGC keeps it in the
  // motion group, Fanuc in a group of its own beside G0/G1) and what its
  // blocks leave for the next (R, Z, Q, P, the initial level).
  int cycle = 0;
  bool retract_to_r = true;  // G99 (RS274NGC's start), G98 Fanuc's
  double cycle_r = 0.0, cycle_z = 0.0, cycle_q = 0.0, cycle_p = 0.0;
  double cycle_i = 0.0, cycle_j = 0.0, cycle_k = 0.0;
  double cycle_initial = 0.0;
  bool cycle_initial_set = false;
  bool spindle_ccw = false;
};

// Origin offsets (mm, machine = program + offsets), as far as the program
// sets them; the machine's own are unknown and taken as 0, as rs274 does
// with its default parameter file.
struct Origins {
  std::array<Eigen::Vector3d, 10> work{};  // G54 .. G59.3, G54.1
  Eigen::Vector3d g92 = Eigen::Vector3d::Zero();
  Eigen::Vector3d g92_saved = Eigen::Vector3d::Zero();
  Eigen::Vector3d local = Eigen::Vector3d::Zero();   // Fanuc G52
  Eigen::Vector3d home28 = Eigen::Vector3d::Zero();  // machine coordinates
  Eigen::Vector3d home30 = Eigen::Vector3d::Zero();
  Origins() {
    for (auto& w : work) w.setZero();
  }
};

struct InterpreterLimits {
  std::size_t max_call_depth = 64;
  std::uint64_t max_loop_iterations = 10'000'000;
  // Lines executed in all (loops, calls and skipped lines included): ten
  // times the longest real programs (tens of millions of blocks), so that a
  // program that runs for ever ends with an error (40 subroutines each
  // calling the next twice make 2^39 calls without any loop). A loop or an
  // M98 L repeat whose first pass shows it would pass the bound is refused
  // at once. The fuzzers set less.
  std::uint64_t max_blocks = 100'000'000;
  // Moves one canned-cycle block may make (L repeats times pecks): its
  // moves are held at once, so the bound is the block's memory (about
  // 100 MB). A Fanuc G83 with L320 and Q2, 0.002 mm pecks, makes 3.5 M;
  // real peck drilling makes thousands. The fuzzers set less. Also the
  // control points and the moves of one G5.2/G5.3 curve.
  std::uint64_t max_cycle_moves = 1'000'000;
  // Warnings kept (later ones are counted only): memory stays flat even
  // when every block of a long program warns.
  std::size_t max_warnings = 1000;
};

class Interpreter {
 public:
  // `text` must outlive the interpreter (e.g. a memory-mapped file).
  Interpreter(std::string_view text, Dialect dialect, InterpreterLimits limits = {});

  // Reads and executes the next block and appends its events to `events`
  // (which it does not clear). Returns false when the program has ended
  // (M2/M30, closing '%', end of text); then nothing is appended.
  // Throws GcodeError; after a throw, further calls return false.
  bool next(std::vector<program::Event>& events);

  // The block last read by next() (its text, words and spans).
  const Block& block() const { return block_; }
  const ModalState& state() const { return state_; }
  // Warnings so far (errors are thrown), at most limits.max_warnings of them;
  // warning_count() counts all.
  const std::vector<Diagnostic>& warnings() const { return warnings_; }
  std::uint64_t warning_count() const { return warning_count_; }
  // Number of lines read (including skipped ones).
  std::uint64_t lines_read() const { return lines_read_; }

 private:
  struct Line {
    std::string_view text;
    std::string_view eol;
    std::uint64_t offset = 0;
    std::uint32_t number = 0;
  };
  struct Frame {
    std::uint64_t return_offset = 0;
    std::uint32_t return_line = 0;
    bool fanuc = false;
    bool own_locals = false;       // o-call and G65: a frame of local parameters
    long repeat_left = 0;          // M98 L count
    std::uint64_t pass_start = 0;  // lines_read_ when the current pass began
    std::uint64_t body_offset = 0;
    std::uint32_t body_line = 0;
    std::size_t flow_depth = 0;
  };
  // Subroutines by "o<name>" (o-word subs) or "O<number>" (programs for
  // M98): where the body starts, and for o-word subs whether the flow of
  // the program has met the definition, or a call has run it before that.
  struct Sub {
    std::uint64_t body_offset = 0;
    std::uint32_t body_line = 0;
    bool met = false;
    bool called_ahead = false;
  };
  struct Flow {
    ControlKind kind = ControlKind::none;
    std::string name;
    std::uint64_t start_offset = 0;  // the opening line (while) or the first body line (repeat)
    std::uint32_t start_line = 0;
    long remaining = 0;
    bool taken = false;            // an if branch has run
    std::uint64_t pass_start = 0;  // lines_read_ when the current pass began
  };

  bool line_at(std::uint64_t offset, std::uint32_t number, Line& line) const;
  void jump(std::uint64_t offset, std::uint32_t number);
  [[noreturn]] void fail(Code code, std::uint32_t column, std::string message) const;
  void warn(Code code, std::uint32_t column, std::string message);

  // One block in execution (interpreter_step.h).
  struct Step;

  // Flow control (interpreter_flow.cpp): o-words, Fanuc's IF/WHILE/GOTO
  // and program numbers, M98/M99 and G65.
  void handle_control();
  bool flow_top_is(ControlKind kind) const;
  void skip_current_line();
  void branch(const Control& c);
  void loop(const Control& c);
  void skip_to(const std::string& name, std::initializer_list<ControlKind> stops,
               bool fanuc_nesting);
  Sub* lookup_sub(const std::string& name, bool fanuc);
  Sub& find_sub(const std::string& name, bool fanuc);
  void define_sub(const Control& c);
  std::size_t call_depth_limit() const;
  void call(const std::string& name, const std::vector<double>& arguments, bool fanuc, long repeat,
            bool own_locals);
  bool return_from_sub();
  // One more pass of a loop or an M98 repeat: counted against the iteration
  // limit, and refused when `left` more passes like the one just run
  // (from `pass_start`) would pass the block bound.
  void count_pass(std::uint64_t pass_start, long left, std::uint32_t column);
  void macro_call(const Step& step);
  void call_subprogram(const Step& step);

  // Sinumerik (interpreter_sinumerik.cpp): its drilling cycles, CYCLE800
  // and the keywords passed through.
  void siemens_words(Step& step);
  void swivel_working_plane(Step& step, const SiemensCycle& sc);
  void run_siemens_cycle(ModalState& s, const SiemensCycle& cycle,
                         std::vector<program::Event>& events);

  void commit_assignments();
  void warn_unread_rest();

  // The block's words, family by family (interpreter.cpp, in the order
  // execute() applies them).
  void execute(std::vector<program::Event>& events);
  void index_words(Step& step);
  bool index_m_word(Step& step, const Word& w, std::uint8_t slot);
  void classify_words(Step& step);
  void check_unused_words(const Step& step);
  void emit_message(Step& step);
  void set_units(Step& step);
  void set_feed_mode(Step& step);
  void set_feed(Step& step);
  void set_spindle_speed(Step& step);
  void analog_output(Step& step);
  void select_tool(Step& step);
  void change_tool(Step& step);
  void spindle(Step& step);
  void coolant(Step& step);
  void dwell(Step& step);
  void set_plane(Step& step);
  void cutter_compensation(Step& step);
  void tool_length(Step& step);
  static bool changes_origins(const Step& step);
  void set_origins(Step& step);
  void set_origin_g10(Step& step);
  void set_origin_g92_g52(Step& step);
  void set_distance_modes(Step& step);
  void tilt_working_plane(Step& step);
  void set_tilt(Step& step, const program::WorkingFrame& frame);
  void take_axis_words(Step& step);
  void set_motion_mode(Step& step);
  void move(Step& step);
  void reference_return(Step& step);
  void canned_cycle(Step& step);
  int cycle_repeats(const Step& step) const;
  void place_cycle(const Step& step, CycleCall& call, double r_word, double z_word) const;
  void motion(Step& step);
  void arc(Step& step, const Eigen::Vector3d& end);
  void spline(Step& step, const Eigen::Vector3d& end);
  void nurbs_point(Step& step, const Eigen::Vector3d& end);
  void end_nurbs(Step& step);
  NurbsFrame nurbs_frame(const Step& step) const;
  Eigen::Vector3d centre_from_radius(const Step& step, const Eigen::Vector3d& end, bool cw) const;
  Eigen::Vector3d centre_from_offsets(const Step& step, const Eigen::Vector3d& end) const;
  bool stop(Step& step);
  Eigen::Vector3d target_of(const Step& step, bool absolute) const;
  // A length word in mm: `inches` are the block's units (G20/G21 of the
  // block itself included).
  double length(const Word& w, bool inches) const;
  // A warning given once per program for `key` (a code, x10, with its letter).
  void warn_once(char letter, int key, Code code, std::uint32_t column, std::string message);

  std::string_view text_;
  Dialect dialect_;
  InterpreterLimits limits_;
  Parameters parameters_;
  ModalState state_;
  Origins origins_;
  program::WorkingFrame tilt_;  // G68.2 (3+2); identity when none
  SiemensCycle mcall_;          // the Sinumerik MCALL cycle in effect
  SiemensCycle mcall_next_;     // set by the block in execution
  NurbsCurve nurbs_;            // G5.2's control points
  std::vector<std::pair<char, int>> warned_once_;
  Block block_;
  std::vector<Diagnostic> warnings_;
  std::vector<Frame> frames_;
  std::vector<Flow> flow_;
  std::unordered_map<std::string, Sub> subs_;
  std::uint64_t pos_ = 0;
  std::uint32_t line_ = 0;  // number of the line at pos_ minus one
  std::uint64_t lines_read_ = 0;
  std::uint64_t loop_iterations_ = 0;
  std::uint64_t warning_count_ = 0;
  bool percent_seen_ = false;
  bool content_seen_ = false;  // a line with words or control before this one
  bool ended_ = false;
};

}  // namespace vcpost::gcode
