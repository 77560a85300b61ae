// Loads the finished-surface model a toolpath is posted against: STEP
// through OpenCASCADE, STL as a triangle mesh, chosen by content.
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

}  // namespace vcpost::cli
