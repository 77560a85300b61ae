// Loads the finished-surface model a toolpath is posted against: STEP
// through OpenCASCADE, STL as a triangle mesh, chosen by content (a
// .step/.stp/.p21 name always goes to the STEP loader and its E41xx errors).
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "geometry/model.h"

namespace vcpost::cli {

struct LoadedModel {
  std::unique_ptr<geometry::SurfaceModel> model;
  std::string kind;         // "STEP" or "STL"
  std::string description;  // e.g. "12 faces, unit MILLIMETRE"
};

// Throws CommandError (exit 2) with the loader's message for a missing,
// unreadable, empty or unusable file.
LoadedModel load_model(const std::filesystem::path& path);

// No model (kind "none"): an empty surface model no toolpath touches.
LoadedModel no_model();

}  // namespace vcpost::cli
