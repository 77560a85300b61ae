// Surface-quality predictions of ball-end finishing (docs/models.md §3):
// cusp (scallop) heights, the theoretical roughness of the arc profile,
// feed marks of the teeth and the working-diameter band from runout.
//
// Units: lengths in mm, angles in radians. Every function is pure and
// throws std::invalid_argument, with a message naming the bad value, for
// input outside its stated range (non-finite values included).
#pragma once

#include <optional>

#include "geometry/engagement.h"

namespace vcpost::geometry {

// Cusp height of a ball of radius R on a flat surface, passes ae apart:
// h = R - sqrt(R^2 - (ae/2)^2).
// REQUIRES: radius > 0, 0 <= stepover < 2*radius.
double flat_cusp_height(double radius, double stepover);

// Cusp on an inclined plane, the paper's reading beside the exact one.
struct InclinedCusp {
  double alpha3 = 0;         // atan(cos(A) tan(alpha1)): cross-feed slope, rad
  double paper_spacing = 0;  // ae / cos(alpha3), mm (Miko, Beno, Mankova)
  // Flat cusp at paper_spacing, mm; empty when paper_spacing >= 2R (the
  // paper's balls would not overlap although the true passes do).
  std::optional<double> paper_height;
  double exact_spacing = 0;  // true distance of the passes on the plane, mm
  double exact_height = 0;   // flat cusp at exact_spacing, mm
};

// Passes stepover ae apart as seen from above (xy plane, perpendicular to
// the feed's plan view), on a plane of slope alpha1; feed_angle A is the
// angle, in plan view, between the feed direction and the level (contour)
// line: A = 0 contouring, A = pi/2 ramping straight up the slope.
// exact_spacing = ae*sqrt((1 + t^2)/(1 + t^2 sin^2 A)), t = tan(alpha1).
// (With A in plan view the paper's ae/cos(alpha3) is the spacing along the
// vertical section perpendicular to the feed's plan view, not the shortest
// one; the two agree at A = 0 and pi/2.)
// REQUIRES: radius > 0, stepover >= 0, 0 <= slope < pi/2, feed_angle finite,
// exact_spacing < 2*radius.
InclinedCusp inclined_cusp(double radius, double stepover, double slope, double feed_angle);

enum class Curvature { convex, concave };

// Cusp on a surface whose normal section across the feed is a circle of
// radius rho; ae is the arc length between the passes on the surface. The
// ball centres lie on a circle of radius rho + R (convex) or rho - R
// (concave) about the curvature centre, ae/rho apart in angle; the cusp is
// the point at distance R from both, and its height is measured from the
// surface along the normal (radially).
// REQUIRES: radius > 0, stepover >= 0, rho > 0 (convex) or rho >= radius
// (concave: a smaller hollow gouges), stepover/rho < pi, and the two balls
// overlap (centre distance < 2R).
double curved_cusp_height(double radius, double stepover, double rho, Curvature curvature);

// Theoretical roughness of a profile made of circle arcs of radius R
// repeating every `spacing`.
struct Roughness {
  double ra = 0;  // mean |z - m| over a period, m the mean line (equal areas), mm
  double rz = 0;  // peak to valley, R - sqrt(R^2 - spacing^2/4), mm
};

// Ra and Rz of the arc profile, in closed form (no empirical Rz/Ra ratio;
// Ra/Rz -> 4/(9 sqrt 3) = 0.2566 for spacing << R).
// REQUIRES: radius > 0, 0 <= spacing < 2*radius.
Roughness arc_profile_roughness(double radius, double spacing);

// Transverse profile (across the feed): arcs of the ball every stepover ae.
Roughness transverse_roughness(double radius, double stepover);

// Longitudinal profile (along the feed): arcs of the ball every feed per
// tooth fz (docs/models.md: the same arc model with fz in place of ae).
Roughness longitudinal_roughness(double radius, double feed_per_tooth);

// Transverse profile on a surface inclined by alpha across the feed, passes
// ae apart in plan view: the arc profile with ae / cos(alpha).
// REQUIRES additionally 0 <= slope < pi/2 and ae/cos(alpha) < 2R.
Roughness oblique_roughness(double radius, double stepover, double slope);

// Height of the feed marks the teeth leave (Martellotti, trochoidal tooth
// paths): h = fz^2 / (8 (Reff +- fz z / pi)), + for up milling, - for down
// milling; down milling leaves the higher marks.
// REQUIRES: feed_per_tooth >= 0, working_radius > 0, teeth >= 1, and for
// down milling working_radius > fz z / pi.
double feed_mark_height(double feed_per_tooth, double working_radius, int teeth, MillingMode mode);

// Tool setting errors (Dedic et al.). The tool's axis is offset by `offset`
// from the spindle axis and tilted by `tilt` about the spindle gauge line;
// the tool sticks out `overhang` from the gauge line to its tip and cuts at
// `cut_height` above the tip.
struct Runout {
  double offset = 0;      // rho, parallel axis offset, mm, >= 0
  double tilt = 0;        // tau, rad, [0, pi/2)
  double overhang = 0;    // L, gauge line to tool tip, mm, > 0
  double cut_height = 0;  // cutting point above the tip, mm, [0, overhang]
};

struct RunoutBand {
  // rho + (L - cut_height) sin(tau): the radial displacement of the cutting
  // point from the spindle axis, offset and tilt taken as leaning the same
  // way (the worst case; the tilt's cos(tau) shortening is neglected).
  double effective_offset = 0;
  double d_min = 0;  // max(0, Deff - 2 rho_eff), mm
  double d_max = 0;  // Deff + 2 rho_eff, mm
  // With rho_eff > 0 each tooth cuts on its own radius, so the feed marks
  // repeat once per revolution (every fz*z) instead of once per tooth.
  bool marks_once_per_revolution = false;
};

// REQUIRES: working_diameter >= 0, runout within the ranges above.
RunoutBand runout_band(double working_diameter, const Runout& runout);

}  // namespace vcpost::geometry
