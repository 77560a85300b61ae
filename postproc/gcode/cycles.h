// Canned cycles (G73, G74, G76, G81-G89) as the straight moves, dwells and
// spindle changes they stand for, in the XY plane. The rules are LinuxCNC's
// (its interp_cycles: positioning at the old Z, the R plane, retract to R
// (G99) or to the initial level (G98), L repeats with G91 increments); the
// Fanuc-only forms (G76 fine boring, G87 back boring) without the tool
// shift, whose direction is a machine parameter vcpost cannot know.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "postproc/gcode/code_names.h"
#include "postproc/program/events.h"

namespace vcpost::gcode {

struct CycleCall {
  int code = G_81_drill;                            // code_names.h: G73 G74 G76 G81 .. G89
  bool fanuc = false;                               // Fanuc forms of G76 and G87 (else RS274NGC's)
  Eigen::Vector3d start = Eigen::Vector3d::Zero();  // tool position before the block, mm
  double x = 0.0, y = 0.0;                          // first hole (absolute), mm
  double dx = 0.0, dy = 0.0;         // G91: added before every repeat (x, y are then the start)
  double r = 0.0;                    // R plane (absolute), mm
  double bottom = 0.0;               // hole bottom (absolute), mm
  double initial = 0.0;              // initial level (G98 retract), mm
  bool retract_to_r = true;          // G99
  double q = 0.0;                    // peck depth (G73 G83), mm
  double peck_clearance = 0.254;     // G73/G83 back-off, mm (rs274's 0.01 in)
  double dwell = 0.0;                // P, seconds
  double i = 0.0, j = 0.0, k = 0.0;  // RS274NGC G87 offsets and top (absolute k), mm
  int repeats = 1;
  bool spindle_cw = true;  // direction before the cycle
  program::SourceRef source;
};

// Appends the cycle's events and returns where the tool ends (the last
// hole at the clearance level). Requires q > 0 for G73/G83 and r >= bottom
// (checked by the caller, which knows the words' columns).
Eigen::Vector3d expand_cycle(const CycleCall& call, std::vector<program::Event>& events);

}  // namespace vcpost::gcode
