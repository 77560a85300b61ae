// Heidenhain's drilling cycles (200 drilling, 201 reaming, 203 universal
// drilling, 205 universal pecking, 207 rigid tapping, 208 bore milling) as
// the straight moves, dwells and spindle changes they stand for, at one hole.
// The sequences follow the TNC user's manual's descriptions of each cycle;
// what the program cannot say is assumed and documented (docs/heidenhain.md):
// the control's advanced stop distance (0.2 mm). Cycle 208 mills a helix of
// radius (Q335 - tool diameter) / 2 when the tool's radius is known (the
// control's tool table: the caller gives it), else it goes along the
// hole's axis.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "postproc/program/events.h"

namespace vcpost::heidenhain {

// One hole, every length in mm (absolute, datum shift applied), feeds mm/min.
struct DrillHole {
  int cycle = 200;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();  // the tool before the cycle (over the hole)
  double surface = 0;                               // Q203
  double clearance = 0;                             // Q200, above the surface
  double second_clearance = 0;                      // Q204, above the surface
  double depth = 0;                                 // Q201, < 0
  double plunge = 0;                                // Q202 (200 203 205), > 0
  double feed = 0;                                  // Q206; 207: pitch x speed
  double retract_feed = 0;                          // Q208 (201 203 205); 0: the feed
  double dwell_top = 0;                             // Q210, s
  double dwell_bottom = 0;                          // Q211, s
  double decrement = 0;                             // Q212 (203 205)
  int chip_breaks = 0;                              // Q213 (203)
  double min_plunge = 0;                            // Q205 (203 205)
  double chip_retract = 0.2;                        // Q256 (203)
  bool spindle_ccw = false;                         // 207: the direction before the hole
  double helix_radius = 0;                          // 208: (Q335 - D) / 2; 0: along the axis
  double pitch = 0;                                 // 208: Q334, depth per turn
  int helix_rotation = 1;                           // 208: +1 counterclockwise
  double restore_feed = 0;                          // the program's feed after the hole (0: none)
  program::SourceRef source;
};

// Appends the CannedCycle event and the hole's events; returns where the
// tool ends (over the hole at the higher clearance).
Eigen::Vector3d expand_hole(const DrillHole& hole, std::vector<program::Event>& events);

}  // namespace vcpost::heidenhain
