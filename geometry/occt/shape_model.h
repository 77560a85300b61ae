// Building a BrepModel from an OpenCASCADE shape in process (tests, the
// sample generator). Includes OCCT headers: only for code that already uses
// OCCT. Lengths of the shape are taken as mm.
#pragma once

#include <TopoDS_Shape.hxx>
#include <string>

#include "geometry/occt/brep_model.h"

namespace vcpost::occt {

// Tessellates the shape (BRepMesh) and indexes its faces. `source` names the
// shape in error messages; `length_unit` is recorded in StepInfo. Throws
// ModelError (no_faces, kernel_failure).
BrepModel model_from_shape(const TopoDS_Shape& shape, const BrepOptions& options = {},
                           const std::string& source = "<shape>",
                           const std::string& length_unit = "");

}  // namespace vcpost::occt
