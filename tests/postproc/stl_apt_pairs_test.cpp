// The APT + STL pairs of the shared data (../shared/data/cldata,
// PROVENANCE.md: SolidWorks CAM output with the part exported in the CAM
// frame). Both files of each pair load. basemach shares one frame with its
// STL: every feed point is within a tool diameter of the part's box, the
// through-cuts go at most 0.5 mm under its bottom, and some cut touches the
// part. Telemecanique-Tilt-Support2 does not: its GOTO points span y -15..45,
// z -31..25 against the STL's box y 0..45, z 0..30 (CSYS is the identity),
// so PROVENANCE's "bounding boxes agree" holds for basemach only; that pair
// is only loaded here.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "geometry/mesh/mesh_model.h"
#include "postproc/cldata/cl_reader.h"

namespace {

namespace fs = std::filesystem;

struct Feeds {
  std::size_t count = 0, far_from_box = 0;
  double lowest = INFINITY, nearest = INFINITY, largest_diameter = 0;
};

Feeds feeds_against(const fs::path& apt, const vcpost::mesh::MeshModel& model) {
  std::ifstream in(apt);
  vcpost::cldata::ClReader reader(in, apt.filename().string());
  Feeds f;
  while (const auto e = reader.next()) {
    if (const auto* move = std::get_if<vcpost::program::StraightFeed>(&*e)) {
      ++f.count;
      f.lowest = std::min(f.lowest, move->end.z());
      const auto c = model.closest_point(move->end, 1e9, nullptr);
      EXPECT_TRUE(c);
      if (c) f.nearest = std::min(f.nearest, c->distance);
      if (model.bounds().exteriorDistance(move->end) > 12) ++f.far_from_box;
    }
  }
  for (const auto& cutter : reader.cutters())
    f.largest_diameter = std::max(f.largest_diameter, cutter.diameter());
  return f;
}

TEST(StlAptPairs, BasemachSharesTheFrameOfItsStl) {
  const fs::path dir = fs::path(VCPOST_SHARED_DATA_DIR) / "cldata";
  if (!fs::exists(dir)) GTEST_SKIP() << "shared data absent: " << dir;
  const vcpost::mesh::MeshModel model(vcpost::mesh::read_stl_file(dir / "basemach.STL"));
  const Feeds f = feeds_against(dir / "basemach.apt", model);
  EXPECT_GT(f.count, 1000u);
  EXPECT_EQ(f.largest_diameter, 8);  // 5, 6 and 8 mm flat mills (and a 4 mm drill)
  EXPECT_EQ(f.far_from_box, 0u);     // 12 mm: more than the largest cutter
  EXPECT_GE(f.lowest, model.bounds().min().z() - 0.5 - 1e-6);
  EXPECT_LE(f.nearest, 1e-3);  // a tip on the part's faces
}

TEST(StlAptPairs, TelemecaniqueLoads) {
  const fs::path dir = fs::path(VCPOST_SHARED_DATA_DIR) / "cldata";
  if (!fs::exists(dir)) GTEST_SKIP() << "shared data absent: " << dir;
  const vcpost::mesh::MeshModel model(
      vcpost::mesh::read_stl_file(dir / "Telemecanique-Tilt-Support2.stl"));
  const Feeds f = feeds_against(dir / "Telemecanique-Tilt-Support2.apt", model);
  EXPECT_GT(f.count, 100u);
  EXPECT_EQ(f.largest_diameter, 12);
}

}  // namespace
