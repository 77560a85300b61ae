// Triangle meshes of the sample surfaces, for STL models with a known
// surface (the mesh model's tests and benchmarks, vcpost-samplegen stl).
//
// Units: mm. The mesh is a grid over the surface's (u,v) domain, each cell
// cut into two triangles along a diagonal; every vertex is S(u,v) exactly
// (as computed in double; a binary STL then rounds it to float). Triangles
// are counterclockwise seen from the tool's side (their right-handed normal
// agrees with the surface normal). Cells that collapse to a point on one
// side (a pole) lose their zero-area triangle.
#pragma once

#include <cstdint>

#include "geometry/mesh/stl_reader.h"
#include "postproc/samplegen/surfaces.h"

namespace vcpost::samplegen {

// cells_u x cells_v cells at equal steps of u and v. REQUIRES both >= 1.
mesh::StlMesh triangulate_grid(const SampleSurface& surface, int cells_u, int cells_v);

// About `triangles` triangles (2 per cell), the cells' count in u and in v
// in the ratio of the surface's extent along u and along v, so the cells
// are about square on the surface. REQUIRES triangles >= 2.
mesh::StlMesh triangulate(const SampleSurface& surface, std::uint64_t triangles);

}  // namespace vcpost::samplegen
