// OpenCASCADE shapes with known geometry, for tests, benchmarks and the
// sample generator. Lengths in mm.
#pragma once

#include <TopoDS_Face.hxx>

namespace vcpost::occt {

// A wavy mould surface: a clamped bicubic B-spline face over
// [0, size] x [0, size] at z around 0, poles x poles control points on a
// regular grid with heights amplitude * sin(2 pi x / wavelength) *
// cos(2 pi y / wavelength). Untrimmed; (u,v) in [0, 1]^2; the face normal
// points to +z (material below).
TopoDS_Face wavy_bspline_face(double size = 100, int poles = 12, double amplitude = 5,
                              double wavelength = 60);

}  // namespace vcpost::occt
