// Hole-making cycles of APT CL data (CYCLE/...): the record read into one
// value, and that value expanded into the moves a control's canned cycle
// makes at one hole (the motion of rs274's G73/G81-G89 in the G98 form).
//
// Forms read (the tool axis is +Z; distances along it from each GOTO
// point, which is the top of the hole):
//   ISO 4343 couplets: CYCLE/kind[,variant],FEDTO,d,RAPTO,c[,RTRCTO,r]
//       [,DWELL,t][,STEP,s1[,s2]][,1STPECK,s1][,SUBPECK,s2],MMPM|IPM|MMPR|IPR,f
//       (SolidWorks CAM, NX CLSF, ICAM's ISO 4343:2000 form)
//   ISO 4343:1978 positional: CYCLE/DRILL,d,MMPM|IPM|MMPR|IPR,f,c[,r]
//   CAMWorks: CYCLE/DRILL,G98|G99,d[,PECKING,s1,s2],MMPM|..,f,c,r[ r][ DWELL,t]
// Kinds and what they become (the canned cycle whose moves they are):
//   DRILL G81 (G82 with DWELL), FACE G82, DEEP|DEEP2|PECK|DRILL,DEEP G83,
//   BRKCHP|DRILL,BRKCHP G73, TAP G84 (spindle reversed at the bottom),
//   BORE|BORE5|REAM G85 (G89 with DWELL), BORE6 G86 (spindle stopped, rapid out), BORE9 G89.
// Anything else (BORE,BACK, THRU, CSINK, words not listed) is refused with
// E3112 naming the word.
#pragma once

#include <Eigen/Core>
#include <deque>
#include <optional>
#include <string_view>

#include "postproc/cldata/record_reader.h"
#include "postproc/program/events.h"

namespace vcpost::cldata {

enum class CycleKind {
  drill,       // G81 / G82
  deep,        // G83: pecks with full retract to the clearance level
  chip_break,  // G73: pecks with a short retract
  tap,         // G84
  bore,        // G85: feed in, feed out
  bore_stop,   // G86: feed in, spindle stop, rapid out
  bore_dwell,  // G89: feed in, dwell, feed out
};

struct ClCycle {
  CycleKind kind = CycleKind::drill;
  double depth = 0;               // mm below the GOTO point
  double clearance = 0;           // RAPTO: mm above the GOTO point, where feeding starts
  std::optional<double> retract;  // RTRCTO: mm above the GOTO point (G98 level); none: clearance
  double feed = 0;
  program::FeedMode mode = program::FeedMode::per_minute;
  double dwell_s = 0;     // at the bottom
  double first_peck = 0;  // mm; 0: one stroke
  double next_peck = 0;   // mm; 0: as first_peck
};

// Reads CYCLE/<kind>,... (not OFF, ON, INIT, CLEAR: the caller handles those).
// `mm_per_unit` converts the file's lengths. Throws ClError (E3112 for a
// cycle or word not understood, E3104/E3103 for missing or bad values).
ClCycle parse_cycle(const ClRecord& record, double mm_per_unit, std::string_view file_name);

// How far above the last peck's bottom a G83 comes back down in rapid, and
// how far a G73 backs off (rs274's 0.010 in).
inline constexpr double peck_clearance_mm = 0.254;

// The canned cycle whose moves expand_cycle gives at every hole of `cycle`
// in every control vcpost writes for (rs274 and the Fanuc form agree on
// them): G81, G82 with a dwell, G83 and G73 with one peck depth and no
// dwell (one stroke: G81/G82), G84 turning clockwise, G85 (G89 with a
// dwell), G86, G89. None: a form no canned cycle makes (two peck depths, a
// peck cycle with a dwell, a left-hand tap): the hole is written as moves.
std::optional<int> canned_code(const ClCycle& cycle, program::SpindleDirection direction);

// The events of one hole at `hole` (its top), starting from `from`, with
// the spindle turning in `direction`. Feed changes are not emitted: the
// caller sets the cycle's feed before.
void expand_cycle(const ClCycle& cycle, const Eigen::Vector3d& hole, const Eigen::Vector3d& from,
                  program::SpindleDirection direction, const program::SourceRef& source,
                  std::deque<program::Event>& out);

}  // namespace vcpost::cldata
