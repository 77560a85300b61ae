#include "postproc/cli/model_loader.h"

#include <fstream>

#include "core/text.h"
#include "geometry/analytic_surfaces.h"
#include "geometry/mesh/mesh_model.h"
#include "geometry/mesh/stl_reader.h"
#include "geometry/occt/brep_model.h"
#include "postproc/cli/commands.h"

namespace vcpost::cli {
namespace {

// STEP files open with "ISO-10303-21;"; everything else is tried as STL.
bool looks_like_step(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(64, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head.find("ISO-10303-21") != std::string::npos;
}

// A .step/.stp/.p21 name is a promise of STEP: a file that breaks it gets
// the STEP loader's message (E41xx), not the STL reader's.
bool named_step(const std::filesystem::path& path) {
  const std::string ext = to_lower(path.extension().string());
  return ext == ".step" || ext == ".stp" || ext == ".p21";
}

// A model whose faces all lie within a micrometre of one point: a length
// unit of 0 (LENGTH_MEASURE(0.)) or only degenerate faces (a sphere of
// radius 0). Nothing could touch it: said here rather than as a path that
// never touches the model.
void refuse_degenerate(const geometry::SurfaceModel& model, const std::filesystem::path& path) {
  const Eigen::AlignedBox3d box = model.bounds();
  if (box.isEmpty() || !(box.diagonal().norm() < 1e-3)) return;
  throw CommandError(Code::E4120,
                     "--model: '" + path.string() +
                         "': the model has no extent (its faces lie within 0.001 mm of "
                         "one point): a length unit of 0 or degenerate faces? Export the "
                         "model again");
}

}  // namespace

LoadedModel load_model(const std::filesystem::path& path) {
  std::error_code error;
  const bool step = named_step(path);
  const auto status = std::filesystem::status(path, error);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
      !std::filesystem::is_directory(status)) {
    // A FIFO or device cannot be sniffed and then read again: its bytes
    // would be gone (or the second open would wait forever for a writer).
    throw CommandError(
        Code::E4101, "--model: '" + path.string() +
                         "' is not a regular file (a FIFO or a device); give the model as a file");
  }
  if (!step && !std::filesystem::is_regular_file(status)) {
    throw CommandError(Code::E4101, "--model: '" + path.string() + "': no such file");
  }
  // An occt::ModelError or mesh::StlError leaves with its own code.
  if (step || looks_like_step(path)) {
    auto model = std::make_unique<occt::BrepModel>(occt::BrepModel::load_step(path));
    refuse_degenerate(*model, path);
    const auto& info = model->info();
    std::string description = std::to_string(info.faces) + " faces";
    if (!info.length_unit.empty()) description += ", unit " + info.length_unit;
    return {std::move(model), "STEP", description};
  }
  auto mesh = mesh::read_stl_file(path);
  for (const auto& v : mesh.vertices) {
    if (!(v.cwiseAbs().maxCoeff() <= occt::kMaxModelReachMm)) {
      throw CommandError(Code::E4107,
                         "--model: '" + path.string() +
                             "': the model reaches beyond 100000 mm (100 m) from the origin; parts "
                             "within it are read (a stray point or a wrong unit?)");
    }
  }
  const std::string description = std::to_string(mesh.triangles.size()) + " triangles";
  auto model = std::make_unique<mesh::MeshModel>(std::move(mesh));
  refuse_degenerate(*model, path);
  return {std::move(model), "STL", description};
}

LoadedModel no_model() {
  return {std::make_unique<geometry::AnalyticModel>(std::vector<geometry::AnalyticSurface>{}),
          "none", "no model"};
}

}  // namespace vcpost::cli
