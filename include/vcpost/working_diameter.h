// The working-diameter engine: which edge points of a milling tool cut at
// one toolpath point, and how far from the tool axis they are (the model of
// Mgherony and Miko; `vcpost deff` on the command line).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vcpost/export.h"

namespace vcpost::api {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

enum class ToolKind { ball, bull_nose, flat };

struct Tool {
  ToolKind kind = ToolKind::ball;
  double diameter = 0;       // D, mm
  double corner_radius = 0;  // rc, mm: D/2 for a ball, 0 for a flat end mill
};

// "ball:D", "bull:D:rc" or "flat:D" (mm), as `vcpost --tool` takes it.
// Throws Error for an unknown kind, a missing or bad size.
VCPOST_API Tool parse_tool(std::string_view spec);
// The inverse of parse_tool, e.g. "ball:10".
VCPOST_API std::string to_string(const Tool& tool);

// On which side of the path, looking along the feed with the normal up, the
// previous adjacent pass lies (material already removed).
enum class Side { left, right };

// The cutting situation at one point, in the tool frame (z up the tool axis).
struct CutSetup {
  double ap = 0;         // depth of cut along the normal, mm, > 0
  double ae = 0;         // width of cut to the previous pass, on the surface, mm, >= 0
  Vec3 normal{0, 0, 1};  // unit surface normal out of the material
  Vec3 feed{1, 0, 0};    // feed direction, any length; projected onto the tangent plane
  Side side = Side::left;
};

struct WorkingDiameter {
  bool engaged = false;         // some edge point cuts in this pass
  std::optional<double> d_max;  // largest 2r over the engaged edge points, mm (exact)
  std::optional<double> d_min;  // smallest, mm
  std::optional<double> d_cut;  // 2r at the cutting point (the groove edge away from
                                // the previous pass), mm; empty without a rim
  // Why the set-up is degenerate or special, as `vcpost deff --json` names
  // them: nothing_engaged, shank_engaged, zero_ae, zero_ap, ap_exceeds_d,
  // undercut, feed_along_normal.
  std::vector<std::string> flags;
};

// D_max, D_min and the cutting point's diameter for `tool` in `setup`.
// Degenerate set-ups return with flags set; throws Error for an invalid
// tool or a zero normal or feed.
VCPOST_API WorkingDiameter working_diameter(const Tool& tool, const CutSetup& setup);

// Area-weighted mean of 2r over the engaged zone (adaptive quadrature,
// error well under 1e-3 mm); empty when nothing is engaged.
VCPOST_API std::optional<double> mean_working_diameter(const Tool& tool, const CutSetup& setup);

// Spindle speed (rpm) giving cutting speed vc (m/min) at diameter d (mm):
// n = 1000 vc / (pi d).
VCPOST_API double spindle_speed_for(double vc_m_per_min, double diameter_mm);

}  // namespace vcpost::api
