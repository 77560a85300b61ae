// OpenCASCADE shapes with known geometry, for tests, benchmarks and the
// sample generator. Lengths in mm.
#pragma once

#include <Geom_BSplineSurface.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <filesystem>
#include <string>

namespace vcpost::occt {

// A wavy mould surface: a clamped bicubic B-spline face over
// [0, size] x [0, size] at z around 0, poles x poles control points on a
// regular grid with heights amplitude * sin(2 pi x / wavelength) *
// cos(2 pi y / wavelength). Untrimmed; (u,v) in [0, 1]^2; the face normal
// points to +z (material below).
TopoDS_Face wavy_bspline_face(double size = 100, int poles = 12, double amplitude = 5,
                              double wavelength = 60);

// One B-spline surface cut into nu x nv faces at equal steps of its (u,v)
// domain (each face an exact Geom_BSplineSurface segment) and sewn into one
// open shell, so neighbouring faces share their edges and vertices: a
// multi-face model whose union is exactly the uncut surface. Defined in
// sample_parts.cpp (which vcpost-samplegen compiles on its own). Throws
// std::runtime_error when OCCT refuses; REQUIRES nu, nv >= 1.
TopoDS_Shape bspline_patches(const Handle(Geom_BSplineSurface) & surface, int nu, int nv);

// wavy_bspline_face's surface as nu x nv sewn faces (bspline_patches): the
// multi-face benchmark and test model (10 x 10: 100 faces).
TopoDS_Shape wavy_patches(int nu, int nv, double size = 100, int poles = 12, double amplitude = 5,
                          double wavelength = 60);

// Writes any shape as an AP214 STEP file in mm (through a temporary file
// renamed when complete; OCCT's transfer statistics silenced). Defined in
// sample_parts.cpp. Throws std::runtime_error naming the path.
void write_shape_step(const std::filesystem::path& path, const TopoDS_Shape& shape,
                      const std::string& name);

}  // namespace vcpost::occt
