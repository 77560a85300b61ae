// Working (effective) diameter of a milling tool at one toolpath point
// (docs/models.md §2): which edge points cut in this pass, and how far
// from the tool axis they are.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geometry/tool.h"

namespace vcpost::geometry {

// On which side of the path, looking along the feed with the surface normal
// up, the previous adjacent pass lies (where material is already removed).
enum class Side { left, right };
enum class SpindleDirection { clockwise /* M3 */, counter_clockwise /* M4 */ };
enum class MillingMode { down /* climb */, up /* conventional */ };

// The cutting situation at one point, in the tool frame (tool.h: origin at
// the ball centre for a ball mill, tool axis +z).
struct CutSetup {
  double ap = 0;                    // depth of cut along the normal, mm, > 0
  double ae = 0;                    // width of cut to the previous pass, on the surface, mm, >= 0
  Eigen::Vector3d normal{0, 0, 1};  // N: unit surface normal at CC, out of the material
  Eigen::Vector3d feed{1, 0, 0};    // motion direction; projected onto the tangent plane
  Side side = Side::left;
};

// Why an evaluation is degenerate or special; several may be set.
enum class EngagementFlag : std::uint32_t {
  nothing_engaged = 1u << 0,    // no edge point cuts (D_max etc. are empty)
  shank_engaged = 1u << 1,      // the engaged zone reaches the shank: D_max = D
  zero_ae = 1u << 2,            // ae = 0: the previous pass removed everything
  zero_ap = 1u << 3,            // ap = 0: no stock
  ap_exceeds_d = 1u << 4,       // ap >= D: the whole tool end is in the stock
  undercut = 1u << 5,           // N_z <= 0: the surface faces sideways or down
  feed_along_normal = 1u << 6,  // F has no component in the tangent plane
};

struct EngagementFlags {
  std::uint32_t bits = 0;
  bool has(EngagementFlag flag) const { return (bits & static_cast<std::uint32_t>(flag)) != 0; }
  void set(EngagementFlag flag) { bits |= static_cast<std::uint32_t>(flag); }
};

// The names of the flags set, in the order above ("nothing_engaged",
// "shank_engaged", ...): the words of `vcpost deff --json` and the library.
std::vector<std::string> flag_names(EngagementFlags flags);

// An edge point in the tool frame and its working diameter 2r,
// r = distance from the tool axis.
struct CuttingPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // mm
  double diameter = 0;                                 // 2r, mm
};

// The cutting points of Mgherony and Miko on the rim Gamma (tool surface cut
// by the stock plane), with lateral coordinate s = S0.P, S0 = unit(N x F):
//   p1 = smallest s (right groove edge), p2 = largest s (left groove edge),
//   p1a/p1b = 1' and 1'' at s = s_min + ae, p2a/p2b = 2' and 2'' at
//   s = s_max - ae (a = ahead of the tool centre, F.P > 0; b = behind);
//   cut = the groove edge away from the previous pass (left -> p1, right -> p2).
struct CuttingPoints {
  CuttingPoint p1, p2, p1a, p1b, p2a, p2b, cut;
};

struct Engagement {
  EngagementFlags flags;
  // Extremes of 2r over the engaged edge points (exact); empty when nothing
  // is engaged.
  std::optional<double> d_max, d_min;
  // Empty when there is no rim (ap = 0 or undercut / degenerate input).
  std::optional<CuttingPoints> points;
  // The frame the points are expressed in: F (projected, unit), S0 = N x F, N.
  Eigen::Vector3d feed_dir = Eigen::Vector3d::UnitX();
  Eigen::Vector3d side_dir = Eigen::Vector3d::UnitY();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

// Whether evaluate_engagement computes the cutting points: they cost about
// a sixth of a ball evaluation, and a post with the D_max policy and no
// per-point report never reads them.
enum class CuttingPointsWanted { yes, no };

// D_max, D_min and (unless not wanted: then `points` stays empty) the
// cutting points, exactly (closed form and 1-D root finding; a bull-nose
// or flat mill fed level, in closed form along its profile). Where the
// stock plane cuts a level feed's end face along F, the cutting point on
// that chord is its middle (the point nearest the axis).
// REQUIRES: tool valid (see parse_tool), |normal| and |feed| > 0.
// Degenerate set-ups (flags above) return with the flags set, never throw.
Engagement evaluate_engagement(const Tool& tool, const CutSetup& setup,
                               CuttingPointsWanted points = CuttingPointsWanted::yes);

// Area-weighted mean of 2r over the engaged zone, by adaptive quadrature,
// capped: a bounded number of evaluations whatever the set-up; empty when
// nothing is engaged. The ball's over the area; the bull-nose's round the
// engaged zone's boundary (Green's theorem on the tool); a level feed (F_z
// = 0, Z-level passes), either tool, by one integral along the tool's
// profile (level_engagement.h), feeds all but level turned level first;
// the flat end mill's circle by circle, its removed arcs in closed form.
// How near each comes to the reference integrals: docs/models.md §2.
std::optional<double> engaged_mean_diameter(const Tool& tool, const CutSetup& setup);

// Up or down milling from the side of the previous pass and the spindle
// direction: M3 with the previous pass on the left is down (climb) milling.
MillingMode milling_mode(Side previous_pass, SpindleDirection spindle);

// Unit vector (cos a, sin a, 0) projected onto the plane normal to `normal`
// and normalised: the paper's feed angle A as a feed direction on the surface.
Eigen::Vector3d feed_from_angle(double feed_angle_rad, const Eigen::Vector3d& normal);

// Unit normal with tilt beta to +z (the paper's A_N2) and azimuth of its xy
// projection to +x (A_N1), radians.
Eigen::Vector3d normal_from_angles(double tilt_rad, double azimuth_rad);

// Spindle speed (rpm) that gives cutting speed vc (m/min) at diameter d (mm);
// and the cutting speed at d and n.
double spindle_speed_for(double vc_m_per_min, double diameter_mm);
double cutting_speed(double diameter_mm, double rpm);

}  // namespace vcpost::geometry
