// The STEP files of samples/ hold the very surfaces the sample generator's
// truth is computed on: every truth CC evaluated on the STEP face at its
// known parameters (1e-9 mm, normals 1e-9), and the OpenCASCADE facade
// (BrepModel) finds every truth CC and N from the programs' points within
// the 1e-5 mm / 1e-5 rad.
#include <gtest/gtest.h>

#include <BRep_Tool.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom_Surface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "geometry/occt/brep_model.h"

namespace {

namespace fs = std::filesystem;
using Eigen::Vector3d;

struct TruthRow {
  Vector3d tip, cc, n;
};

std::vector<TruthRow> read_truth(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<TruthRow> rows;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream fields(line);
    std::string f;
    while (std::getline(fields, f, ',')) v.push_back(std::stod(f));
    if (v.size() != 14) {
      ADD_FAILURE() << file << ": " << line;
      break;
    }
    rows.push_back(
        {Vector3d(v[4], v[5], v[6]), Vector3d(v[7], v[8], v[9]), Vector3d(v[10], v[11], v[12])});
  }
  return rows;
}

TopoDS_Face read_face(const fs::path& file) {
  STEPControl_Reader reader;
  EXPECT_EQ(reader.ReadFile(file.string().c_str()), IFSelect_RetDone) << file;
  reader.TransferRoots();
  TopExp_Explorer faces(reader.OneShape(), TopAbs_FACE);
  EXPECT_TRUE(faces.More()) << file;
  return TopoDS::Face(faces.Current());
}

struct Part {
  const char* name;
  double ball_radius;
  // The STEP surface's (u,v) of a truth CC (OCCT's parametrisation).
  std::pair<double, double> (*uv)(const Vector3d&);
};

const Part parts[] = {
    {"wavy", 5,
     [](const Vector3d& p) {
       return std::pair{p.x(), p.y()};
     }},
    // Axis x, reference z: (h, -R sin a, R cos a).
    {"cylinder", 6,
     [](const Vector3d& p) {
       return std::pair{std::atan2(-p.y(), p.z()), p.x()};
     }},
    {"dome", 5,
     [](const Vector3d& p) {
       double u = std::atan2(p.y(), p.x());
       if (u < 0) u += 2 * std::numbers::pi;
       return std::pair{u, std::asin(std::clamp(p.z() / p.norm(), -1.0, 1.0))};
     }},
};

std::vector<fs::path> truth_files(const std::string& part) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(fs::path(VCPOST_SOURCE_DIR) / "samples")) {
    const std::string name = e.path().filename().string();
    if (name.rfind(part + "_", 0) == 0 && name.ends_with(".truth.csv")) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(SampleParts, StepSurfacesAreTheTruthSurfaces) {
  for (const auto& part : parts) {
    SCOPED_TRACE(part.name);
    const TopoDS_Face face =
        read_face(fs::path(VCPOST_SOURCE_DIR) / "samples" / (std::string(part.name) + ".step"));
    const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
    const double sign = face.Orientation() == TopAbs_REVERSED ? -1 : 1;
    const auto files = truth_files(part.name);
    ASSERT_GE(files.size(), 2u);
    std::size_t checked = 0;
    for (const auto& file : files) {
      for (const auto& row : read_truth(file)) {
        const auto [u, v] = part.uv(row.cc);
        GeomLProp_SLProps props(surface, u, v, 1, 1e-12);
        const gp_Pnt p = props.Value();
        EXPECT_NEAR((Vector3d(p.X(), p.Y(), p.Z()) - row.cc).norm(), 0, 1e-9) << file;
        ASSERT_TRUE(props.IsNormalDefined());
        const gp_Dir n = props.Normal();
        EXPECT_NEAR((sign * Vector3d(n.X(), n.Y(), n.Z()) - row.n).norm(), 0, 1e-9) << file;
        ++checked;
      }
    }
    EXPECT_GT(checked, 1000u);
  }
}

TEST(SampleParts, FacadeFindsEveryTruthContact) {
  for (const auto& part : parts) {
    SCOPED_TRACE(part.name);
    const auto model = vcpost::occt::BrepModel::load_step(fs::path(VCPOST_SOURCE_DIR) / "samples" /
                                                          (std::string(part.name) + ".step"));
    double worst_cc = 0, worst_angle = 0;
    for (const auto& file : truth_files(part.name)) {
      vcpost::geometry::ContactHint hint;
      for (const auto& row : read_truth(file)) {
        const Vector3d centre = row.tip + Vector3d(0, 0, part.ball_radius);
        const auto c = model.closest_point(centre, part.ball_radius + 1, &hint);
        ASSERT_TRUE(c) << file;
        worst_cc = std::max(worst_cc, (c->point - row.cc).norm());
        worst_angle =
            std::max(worst_angle, std::atan2(c->normal.cross(row.n).norm(), c->normal.dot(row.n)));
      }
    }
    EXPECT_LE(worst_cc, 1e-5);
    EXPECT_LE(worst_angle, 1e-5);
    std::cout << part.name << ": largest CC error " << worst_cc << " mm, N error " << worst_angle
              << " rad\n";
  }
}

}  // namespace
