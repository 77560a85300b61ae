// Motion events -> a HEIDENHAIN Klartext program (a TNC's conversational
// language, .h files), for a profile with machine.output_format =
// "heidenhain".
//
// What is written, one numbered block per line from 0:
//   BEGIN PGM <name> MM, then BLK FORM 0.1 Z / 0.2 (the blank, for the
//       control's graphics) where the CL data give the stock before the
//       first motion: SolidWorks CAM's `INSERT/Stock Size X.. Y.. Z..` gives
//       only the size, placed from X0 Y0 up and from Z0 down (the part in
//       positive space, its top at Z0, as the shared SolidWorks CL files are)
//   TOOL CALL <n> Z S<rpm> for a tool change (with the speed that follows it
//       before anything else happens), TOOL CALL S<rpm> for a new speed of
//       the tool in the spindle (a TNC takes S nowhere else), TOOL DEF <n>
//       for a preselection
//   L X Y Z R0 FMAX (rapid) and L X Y Z F<f> (feed; FU<f> per revolution):
//       coordinates and F modal, written where they change; R0 (no radius
//       compensation: CL points are the tool centre's path, CUTCOM is
//       written as a comment) on the first L after a tool call and on rapids
//   CC X Y (the pole) and C X Y DR+/- for an arc in the XY plane of less
//       than a turn; a helix or a full turn as CC and CP IPA+/-<deg> [IZ<dz>]
//       DR+/- (polar, incremental: how a TNC takes a helix)
//   M3/M4/M5, the profile's coolant codes, M0/M1, CYCL DEF 9.0/9.1 for a
//       dwell, `;` comments, M30 and END PGM <name> MM at the end.
// Tilted working planes (3+2), as KlartextFormat::tilted_plane says:
// plane_spatial, `PLANE SPATIAL SPA SPB SPC STAY` (the frame's spatial
// angles) and `L A+Q120 C+Q122 R0 FMAX` (the rotary axes to the angles the
// TNC has computed into Q120-Q122, as the shop's hyperMILL programs for the
// DMU write it), `PLANE RESET STAY` back; the TNC turns about the datum,
// so a point c of the frame is written at c + R^T t (t the frame's
// origin). setup: each frame a set-up of its own as in the G-code writer
// (M5, a comment naming the part's direction up and the preset's point, M0,
// M3/M4 again), the points in the frame's coordinates.
// Holes are written as their L moves (the CL reader expands each cycle into
// them); CannedCycle events are skipped.
//
// Units: events are mm, mm/min, rpm; the program is in mm. Errors:
// E3250 an arc outside the XY plane (a TNC takes it only with the tool axis
// turned), E3251 inverse-time feed, E3252 a helix of more than 15 turns (IPA
// holds 5400 deg); E3203 (event_writer.h) a number that cannot be written.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "machines/profile.h"
#include "postproc/output/event_writer.h"
#include "postproc/program/events.h"

namespace vcpost::output {

struct KlartextFormat {
  std::string program_name = "1000";  // BEGIN PGM / END PGM name
  int decimals = 4;                   // digits after the point for lengths, 0..6
  int feed_decimals = 0;              // for F
  std::string coolant_mist = "M7", coolant_flood = "M8", coolant_off = "M9";
  bool comments = true;  // messages and notes as `;` comments
  std::string end_of_line = "\n";
  machines::TiltedPlane tilted_plane = machines::TiltedPlane::plane_spatial;
};

// The format a profile asks for ([output]: program_number names the program).
KlartextFormat klartext_format_for(const machines::MachineProfile& profile);

// The stock CL data give in a message (`INSERT/Stock Size X95. Y150.
// Z120.`): its size, mm; nullopt for any other message.
std::optional<Eigen::Vector3d> stock_size(std::string_view message);

// Streams: each write() appends the blocks of one event (the blocks before
// the first motion wait for it, so that BLK FORM can follow BEGIN PGM).
// REQUIRES: `out` outlives the writer.
class KlartextWriter : public EventWriter {
 public:
  KlartextWriter(std::ostream& out, KlartextFormat format);

  void write(const program::Event& event) override;
  void finish() override;

  std::uint64_t blocks_written() const { return next_block_; }

 private:
  void block(std::string text);
  void start();
  void comment(std::string_view text);
  void flush_tool_call();
  void motion(const program::Event& event);
  void arc(const program::ArcFeed& arc);
  std::string length(double value, const program::SourceRef& source) const;
  std::string feed_words(const program::SourceRef& source);
  void axis(std::string& words, char letter, double value, std::string& last, bool force,
            const program::SourceRef& source) const;
  void end_program();
  void working_frame(const program::WorkingFrame& frame);
  // A point of the frame in effect as written (see the header).
  Eigen::Vector3d written(const Eigen::Vector3d& p) const { return p + shift_; }

  std::ostream& out_;
  KlartextFormat format_;
  bool started_ = false;  // BEGIN PGM written (at the first motion)
  bool ended_ = false;
  std::uint64_t next_block_ = 0;
  std::vector<std::string> before_start_;  // blocks before the first motion
  std::optional<Eigen::Vector3d> stock_;

  struct ToolCall {
    int number = 0;
    std::optional<double> rpm;
  };
  std::optional<ToolCall> tool_call_;  // a tool change not yet written
  bool after_tool_call_ = true;        // R0 due on the next L
  struct PendingFeed {
    double rate = 0;
    bool per_revolution = false;
  };
  std::optional<PendingFeed> pending_feed_;
  std::string last_feed_;  // "F500" as last written on a feed block
  std::string last_x_, last_y_, last_z_;
  program::CompensationSide compensation_ = program::CompensationSide::off;
  bool spindle_on_ = false, spindle_ccw_ = false;
  program::WorkingFrame frame_;
  Eigen::Vector3d shift_ = Eigen::Vector3d::Zero();  // R^T t under PLANE SPATIAL
  std::vector<program::WorkingFrame> setups_;        // setup: the frames met
};

}  // namespace vcpost::output
