// Where a ball, bull-nose or flat end mill touches the model.
//
// Every tool end is the set of points within rc of its core disc: the disc
// of radius R0 = R - rc in the plane of the corner circle's centres (the
// tool frame's z = 0, tool.h). A ball has R0 = 0 (the disc is the ball's
// centre), a flat end mill rc = 0 (the disc is the end face). The tool's
// distance to the surface is the core disc's distance minus rc, and the
// touching point CC is the surface point closest to the disc: on the ball
// the closest point to the centre (docs/models.md §1), on the bull-nose
// the closest point to the torus' core circle or, over a crest, to the
// disc inside it, on the flat end mill the rim or the face.
#pragma once

#include <Eigen/Core>

#include "geometry/model.h"
#include "geometry/tool.h"

namespace vcpost::geometry {

// The tool frame's origin (the core disc's centre) from a CL point: the tip
// lies rc below it; ClPoint::center gives the origin itself (for a ball its
// centre, as ball_center).
Eigen::Vector3d tool_origin(const Eigen::Vector3d& cl_point, const Tool& tool, ClPoint kind);

// The contact of `tool` with its frame's origin at `origin` (axis +z):
// BallContact's fields for the ball of radius rc at the core disc point
// closest to the surface (center = that point, normal = from CC to it,
// distance_error = the tool's signed distance from the surface). For a ball
// exactly ball_contact. For the others the disc point is found by projected
// gradient steps on the disc (the gradient of the distance is the normal's
// horizontal part), on a smooth surface's rim by secant steps on the rim
// angle: at most 16 queries, warm-started from hint->rim turned as the last
// contact turned (plus that turn's change, bounded by a tenth of it), until
// a step is below 1e-10 R (gradient steps) or 1e-8 R (secant steps, which
// converge superlinearly); the answer is the best disc point met (on
// convergence the last, unless one met is lower by more than round-off). A
// lifted answer (a valley's other flank may be the one touched) is searched
// again from the opposite rim point and from the centre, and one still
// lifted from the lowest of 16 rim points 22.5 degrees apart (a wall beyond
// the rim over a floor): at most 80 queries. Lifted means by more than tolerance / 10 on a smooth
// surface, by the tolerance on a mesh (SurfaceModel::faceted). The surface is searched up to 2 R0 +
// rc + search_margin from each disc point. REQUIRES: tool valid, tolerance >= 0, search_margin >=
// 0.
BallContact tool_contact(const SurfaceModel& model, const Tool& tool, const Eigen::Vector3d& origin,
                         double tolerance, double search_margin, ContactHint* hint);

}  // namespace vcpost::geometry
