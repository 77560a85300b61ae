// Where a ball, bull-nose or flat end mill rests on a sample surface: the
// drop-cutter of the generator's raster for every tool, and the tool
// position that touches a given surface point.
//
// Units: mm. The tool is that of geometry/tool.h, axis +z: radius R, corner
// radius rc (R for a ball, 0 for a flat mill), R0 = R - rc. Its end is the
// set of points within rc of its core disc (radius R0, in the plane of the
// tool frame's origin O; the tip lies rc below O), the model vcpost's
// contact search uses (geometry/tool_contact.h). The tool touches a
// surface point X of unit normal n (out of the material) with its corner
// when the corner circle's centre X + rc*n lies on the core circle and n's
// horizontal part points from it towards the axis:
//   O = X + rc*n + R0 * (n_x, n_y, 0) / |n_xy|
// (n vertical: the end's flat part lies on X, O = X + rc*n, any axis within
// R0 of X). Touching X is not enough on a surface that curves up around
// X (a valley): there the tool rests on two points of its rim, higher,
// which is why the raster drops the tool instead of placing it on a chosen
// contact.
#pragma once

#include <Eigen/Core>

#include "postproc/samplegen/surfaces.h"

namespace vcpost::samplegen {

// The tool origin touching x (unit normal n) with its corner, as above.
// REQUIRES n unit with n_z > 0, flat_radius >= 0, corner_radius >= 0.
Eigen::Vector3d origin_touching(const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                                double flat_radius, double corner_radius);

// A tool resting on the surface.
struct ToolPlacement {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();      // parameters of the contact
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // the tool frame's origin O
  // The touching core-disc point's xy from the axis (|offset| <= R0; 0 for
  // a ball): the corner circle's centre at the contact is O + (offset, 0).
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
};

// Drop-cutter: the tool with its axis on the vertical line through xy,
// lowered until it touches the surface, nowhere below it. Every core-disc
// point q must stay at least rc from the surface, so O_z is the highest,
// over the disc, of the centre height of a ball of radius rc dropped above
// q (SampleSurface::drop). For a ball (flat_radius 0) that is the ball's
// drop itself, O = S + rc*N at its contact. Otherwise the highest point of
// the disc is found on the rim (sampled at 24 angles, the best bracket
// refined to 1e-12 rad where the height's slope along the rim changes
// sign) and inside it (a crest under the flat part: gradient ascent from
// the best of 7 inner points when that is higher than the rim, or from the
// rim's best when the ground rises inwards there), O_z to about 1e-12 mm.
// About 40 drops of the ball a point on the wavy mould.
// `guess`: a nearby contact.
// Throws SurfaceError when a contact leaves the patch.
ToolPlacement drop_tool(const SampleSurface& surface, double flat_radius, double corner_radius,
                        const Eigen::Vector2d& xy, const Eigen::Vector2d& guess);

}  // namespace vcpost::samplegen
