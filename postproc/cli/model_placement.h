// `--model-transform`: where the model sits in the program's frame, as
// steps (geometry/rigid_transform.h) or read from a VERICUT project
// (`vcproject:FILE.vcproject`), and the model wrapped so that it answers in
// the program's frame. docs/model-placement.md.
#pragma once

#include <string>
#include <string_view>

#include "geometry/rigid_transform.h"
#include "postproc/cli/model_loader.h"

namespace vcpost::cli {

// What VERICUT's project says of the design model.
struct ProjectPlacement {
  geometry::RigidTransform transform;  // the design STL in the program's (NCS) frame
  std::string model_file;              // the STL the project places, as it names it
  std::string csystem;                 // the coordinate system taken as the program's
};

// Reads a VERICUT project's text: the one component of Type="design" and its
// <STL> (Position X Y Z, Rotation I J K in degrees: turns about X by I, then
// Y by J, then Z by K, about fixed axes; then the shift), each component up
// its <Attach> chain the same way, and the coordinate system the G-code
// "Program Zero" table goes to (or the only one). The placement is the STL
// in that system's frame. Throws geometry::TransformError (E4112 via
// CommandError) naming what is missing or ambiguous; `name` is for messages.
ProjectPlacement read_vcproject_placement(std::string_view xml, const std::string& name);

// `--model-transform TEXT`: steps, or `vcproject:FILE`. Throws the parser's
// TransformError (E4110, E4111) or CommandError (E4112, E2002).
struct ModelPlacement {
  geometry::RigidTransform transform;
  std::string words;  // for the description, e.g. "placed by rz=-90"
};
ModelPlacement parse_model_placement(const std::string& text);

// Wraps `loaded` so that it answers in the program's frame; its description
// says how it was placed.
void place_model(LoadedModel& loaded, const ModelPlacement& placement);

}  // namespace vcpost::cli
