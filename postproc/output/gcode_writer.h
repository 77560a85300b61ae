// Motion events -> 3-axis G-code in the output format of a machine profile
// (machine.output_format: rs274ngc, fanuc, mazak, and the [output] keys):
// header (`%`, the O number where the control takes one), tool change
// (T M6, or by hand: M5, a comment, T M0; before it the move up, G28 or
// G53, where the control's M6 does not make it), G43, optional high-speed
// mode (G05 P2) and geometry compensation (G61.1), integer S, M3/M4, the
// profile's coolant codes, modal G0/G1/G2/G3 and coordinates, fixed
// decimal format, optional N numbers, the dwell word the control reads
// (G4 P seconds in rs274ngc, G4 X seconds on Fanuc and Mazak), M30.
//
// Units: events are mm, mm/min (or mm/rev), rpm; the program is written in
// mm (G21). Positions are written as the events give them (CL points are
// tool-tip positions in the work frame; G43 applies the length).
//
// Cutter compensation, in wear mode. CL data are tool-centre paths (the CAM
// system has offset the contour by the tool's radius already; CUTCOM says
// on which side the material is), so CUTCOM/LEFT|RIGHT becomes G41|G42 with
// D = CUTCOM's register, else the tool's number, and the control's D
// register must hold only the wear (the difference from the nominal
// radius, 0 for a tool at its size), as CAM posts write "wear"/"control
// wear" compensation: a D holding the whole radius would offset the path a
// second time. G41/G42 goes with the first straight move after CUTCOM (the
// entry move rs274 and Fanuc controls start compensation on; an arc first
// gets it on a block of its own before it), G40 with the first straight
// move after CUTCOM/OFF (rs274 wants a straight move after G40: an arc in
// between stays compensated), and a G40 block of its own ends the
// compensation before a tool change (which ends it), a canned cycle, a side
// change and the program's end.
//
// Canned cycles (Format::canned_cycles): a CannedCycle event is written as
// its cycle block (G98/G99 G73/G81-G89 X Y Z R [Q] [P] F) in place of the
// hole's moves that follow it, so that the control (and rs274, and vcpost's
// own reader) makes those very moves: a rapid up to the hole's return level
// before it, when the tool is below, stays a G0; a return level above R is
// G98 where the cycle's last move out ends there (G73 G81 G82 G85 G86, and
// G83 where it pecks out to R), else G99 and a G0 up after the hole. A hole the cycle cannot make
// exactly (tool above the return level, a plane other than G17) keeps its moves. G80 ends the cycle
// before the next other move, tool change or M30.
//
// Tilted working planes (3+2: a WorkingFrame event, the motion after it in
// the frame's coordinates), as Format::tilted_plane says: g68_2, G69 (a
// tilt in effect ends first) and `G68.2 X Y Z I J K` (the frame's origin,
// its Euler angles Z-X'-Z'') then G53.1 (the tool along the frame's z);
// G69 back to the untilted frame. setup: each frame a set-up of its own,
// numbered in the order met (the untilted frame the first): the spindle
// stopped (M5) where it turns, a comment that says how to clamp the part
// and on which point to set the set-up's work offset, M0, the offset
// (work_offset + its number - 1, at most G59: E3205), the spindle started
// again; the positions that follow are the frame's. Either way cutter
// compensation and a canned cycle end before, and every axis is written
// on the next move.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "machines/profile.h"
#include "postproc/output/event_writer.h"
#include "postproc/program/events.h"

namespace vcpost::output {

enum class DwellWord {
  x_seconds,      // G04 X1.5 (Mazak, Fanuc)
  p_seconds,      // G04 P1.5 (RS274NGC / LinuxCNC)
  p_milliseconds  // G04 P1500 (Fanuc without a decimal point)
};

// The output format of a machine profile (format_for() fills it from one).
// The defaults are those of the Mazak format.
struct Format {
  std::optional<int> program_number = 1000;  // O word, 1..9999; none: no O line (rs274ngc,
                                             // where O starts a subroutine keyword)
  std::string title;                         // header comment; empty: none
  bool percent_lines = true;                 // '%' first and last line
  bool high_speed_mode = false;  // G05 P2 after each tool change, G05 P0 before the next / M30
  bool geometry_compensation = false;  // G61.1 after the header, G64 at the end
  int work_offset = 54;                // G54..G59
  int decimals = 4;                    // digits after the point for X Y Z I J K (mm), 0..6
  int feed_decimals = 1;               // for F
  bool line_numbers = false;           // N words (wrapping after N99999)
  int line_number_start = 10;
  int line_number_step = 10;
  bool tool_length_offset = true;  // G43 H<tool> on the first move after a tool change
  // A tool change as M5 (when the spindle turns), a comment naming the tool
  // and T<n> M0 (the operator changes it), for a control without M6 (grbl).
  bool manual_tool_change = false;
  // The move up before a tool change: none (the control's M6 moves
  // itself), g28 (G91 G28 Z0. / G90) or g53 (G53 G0 Z0.).
  machines::ToolChangeHome home_before_tool_change = machines::ToolChangeHome::none;
  std::string coolant_mist = "M7", coolant_flood = "M8", coolant_off = "M9";
  DwellWord dwell = DwellWord::x_seconds;  // also the cycles' P: seconds in rs274ngc, else ms
  bool canned_cycles = false;              // CannedCycle events as cycles (else their moves)
  bool cutter_compensation = true;         // G41/G42 D and G40 (see above; else comments)
  // G98 G83 comes out to R between pecks (Fanuc, Mazak); rs274 comes out to
  // the G98 level, which no CL peck cycle does: such holes stay moves.
  bool g83_pecks_out_to_r = true;
  // The spindle speed on LinuxCNC's analog output n (output.speed_word
  // "M67 E<n>"): a change while the spindle turns as M67 E<n> Q<rpm> with
  // the next motion (set at its start, without a stop of the path), the
  // speed before a start as S<rpm> M68 E<n> Q<rpm> (immediate). None: S.
  std::optional<int> speed_output;
  bool comments = true;  // messages and notes as ( ) comments
  machines::TiltedPlane tilted_plane = machines::TiltedPlane::setup;  // see the header
  std::string end_of_line = "\n";
};

// The format a profile asks for: machine.output_format chooses the header
// and the dwell word, [output] the rest.
Format format_for(const machines::MachineProfile& profile);

// Streams: each write() appends the blocks of one event; memory does not
// grow with the program. REQUIRES: `out` outlives the writer.
class GcodeWriter : public EventWriter {
 public:
  GcodeWriter(std::ostream& out, Format format);

  // Throws OutputError for an event the format cannot express.
  void write(const program::Event& event) override;

  // Ends the program (M30, '%') unless a ProgramEnd event already did.
  void finish() override;

  std::uint64_t blocks_written() const { return blocks_; }

 private:
  void header();
  void block(std::string_view words);
  void motion(const program::Event& event);
  // One writer per kind of event but the motions (motion()), which write()
  // hands them to.
  void write_event(const program::SetFeedRate& e);
  void write_event(const program::SetSpindleSpeed& e);
  void write_event(const program::SpindleOn& e);
  void write_event(const program::SpindleOff& e);
  void write_event(const program::SelectTool& e);
  void write_event(const program::ChangeTool& e);
  void write_event(const program::ToolLengthOffset& e);
  void write_event(const program::CutterCompensation& e);
  void write_event(const program::SelectPlane& e);
  void write_event(const program::Coolant& e);
  void write_event(const program::Dwell& e);
  void write_event(const program::ProgramStop& e);
  void write_event(const program::ProgramEnd& e);
  void write_event(const program::Message& e);
  void write_event(const program::WorkingFrame& e);
  void write_event(const program::CannedCycle& e);
  std::string number(double value, int decimals, const program::SourceRef& source) const;
  void append_axis(std::string& words, char axis, double value, std::string& last, bool force,
                   const program::SourceRef& source);
  std::string take_pending();
  void start_hole(const program::CannedCycle& cycle);
  bool take_hole_event(const program::Event& event);
  void write_cycle();
  void end_cycle();
  void comment(std::string_view text);
  void compensation_words(std::string& words, bool straight);
  void end_compensation();
  void end_program();
  void change_tool(const program::ChangeTool& change);
  void working_frame(const program::WorkingFrame& frame);
  void new_setup(const program::WorkingFrame& frame);
  void tilt(const program::WorkingFrame& frame);

  std::ostream& out_;
  Format format_;
  bool started_ = false;
  bool ended_ = false;
  std::uint64_t blocks_ = 0;
  int next_n_ = 0;

  int motion_mode_ = -1;  // 0, 1, 2, 3 as last written
  int plane_ = 17;
  bool per_revolution_ = false;  // G95 (else G94) as last written
  std::string last_x_, last_y_, last_z_;
  std::optional<double> last_f_;
  struct PendingFeed {
    bool per_revolution = false;
    std::string f_word;  // "F150."
  };
  std::optional<PendingFeed> pending_feed_;  // the feed waiting for the next block
  std::string pending_;                      // S (speed output) words waiting for the next block
  std::optional<int> pending_g43_;           // tool number whose G43 is due
  bool high_speed_on_ = false;
  bool spindle_on_ = false;                    // M3/M4 written since the last M5 or tool change
  bool spindle_ccw_ = false;                   // the last M4 (else M3)
  program::WorkingFrame frame_;                // the frame in effect (identity: untilted)
  std::vector<program::WorkingFrame> setups_;  // setup: the frames met, the untilted first
  program::CompensationSide comp_wanted_ = program::CompensationSide::off;   // as CUTCOM says
  program::CompensationSide comp_written_ = program::CompensationSide::off;  // G40/G41/G42
  std::optional<int> comp_register_;              // CUTCOM's register, for D
  std::optional<int> tool_;                       // the tool in the spindle, the D otherwise
  Eigen::Vector3d at_ = Eigen::Vector3d::Zero();  // end of the last motion event
  bool at_known_ = false;

  // The hole whose events are being read: its first `lead` and last `tail`
  // moves are written as moves, the rest is the cycle block.
  struct Hole {
    program::CannedCycle cycle;
    std::uint32_t events_left = 0, moves_seen = 0, lead = 0, tail = 0;
    bool retract_to_r = true;  // G99 (else G98)
  };
  std::optional<Hole> hole_;
  std::optional<Hole> modal_cycle_;  // the cycle in effect in the output
  double initial_z_ = 0.0;           // the G98 level of the cycle in effect
};

}  // namespace vcpost::output
