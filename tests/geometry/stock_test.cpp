// The stock height field on cases worked out by hand: a flat slot, a ball
// groove, a drilled cone, depth along a normal over a block, a slot and a
// step, the top of a tilted plane and of a box mesh, and one bad input per
// error code (tests/geometry/bad/stock).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "geometry/stock/height_field.h"
#include "tests/geometry/bad_input_list.h"

namespace vcpost::geometry::stock {
namespace {

using Eigen::Vector3d;
using Eigen::Vector3f;
namespace fs = std::filesystem;

constexpr std::size_t kGigabyte = std::size_t{1} << 30;
// Tops are floats: about 4e-6 mm of rounding at the heights used here.
constexpr double kFloat = 1e-5;

double centre(const Grid& g, std::uint32_t i, int axis) {
  return g.min[axis] + (i + 0.5) * g.cell_mm;
}

TEST(Stock, BlockHasItsTopEverywhereAndNothingOutside) {
  const HeightField field = HeightField::block({0, 0, -10}, {100, 50, 0}, 0.1, kGigabyte);
  EXPECT_EQ(field.grid().nx, 1000u);
  EXPECT_EQ(field.grid().ny, 500u);
  EXPECT_EQ(field.top(0, 0), 0.0f);
  EXPECT_EQ(field.top(999, 499), 0.0f);
  EXPECT_EQ(field.top_at(99.99, 49.99), 0.0f);
  EXPECT_EQ(field.top_at(100.01, 10), kNoMaterial);
  EXPECT_EQ(field.top_at(-0.01, 10), kNoMaterial);
  EXPECT_GE(field.memory_bytes(), 500000 * sizeof(float));
  EXPECT_LT(field.memory_bytes(), 500000 * sizeof(float) + 4096);
}

// A flat D10 along x at z = -2: a slot 10 mm wide at exactly -2, its ends
// half discs, the block top beside it.
TEST(Stock, FlatSlotIsTenWideAtItsDepth) {
  HeightField field = HeightField::block({0, 0, -10}, {100, 50, 0}, 0.1, kGigabyte);
  field.cut(Cutter{Tool::flat(10)}, {20, 25, -2}, {80, 25, -2});
  const Grid& g = field.grid();
  for (std::uint32_t iy = 0; iy < g.ny; ++iy) {
    const double y = centre(g, iy, 1);
    for (std::uint32_t ix = 0; ix < g.nx; ++ix) {
      const double x = centre(g, ix, 0);
      const double dx = x < 20 ? 20 - x : x > 80 ? x - 80 : 0;
      const bool in_slot = dx * dx + (y - 25) * (y - 25) <= 25;
      ASSERT_EQ(field.top(ix, iy), in_slot ? -2.0f : 0.0f) << x << " " << y;
    }
  }
  // Across the middle: 100 cells of 0.1 mm cut, 10 mm.
  int cut = 0;
  for (std::uint32_t iy = 0; iy < g.ny; ++iy) cut += field.top(500, iy) < 0;
  EXPECT_EQ(cut, 100);
}

// A ball D10 with its tip at -2: the groove's section is the ball's,
// z = zc - sqrt(R^2 - d^2) with the centre zc = 3 (above the top, 0).
TEST(Stock, BallGrooveHasTheBallsSection) {
  HeightField field = HeightField::block({0, 0, -10}, {100, 50, 0}, 0.1, kGigabyte);
  field.cut(Cutter{Tool::ball(10)}, {20, 25, -2}, {80, 25, -2});
  const Grid& g = field.grid();
  int checked = 0;
  for (std::uint32_t iy = 0; iy < g.ny; ++iy) {
    const double d = centre(g, iy, 1) - 25;
    const double groove = d * d < 25 ? 3 - std::sqrt(25 - d * d) : 1e9;
    EXPECT_NEAR(field.top(500, iy), std::min(0.0, groove), kFloat) << d;
    checked += groove < 0;
  }
  // |d| < 4 (where 3 - sqrt(25 - d^2) < 0): 80 cells.
  EXPECT_EQ(checked, 80);
}

// A D10 drill with a 118 degree point plunged from above to -4: the hole's
// bottom is the cone z = -4 + r cot(59 deg), its wall the diameter.
TEST(Stock, DrillPlungeLeavesACone) {
  HeightField field = HeightField::block({0, 0, -10}, {100, 50, 0}, 0.1, kGigabyte);
  field.cut(Cutter::drill(10, 118), {50.02, 25.03, 5}, {50.02, 25.03, -4});
  const Grid& g = field.grid();
  const double k = 1 / std::tan(59 * std::numbers::pi / 180);
  for (std::uint32_t iy = 200; iy < 300; ++iy) {
    for (std::uint32_t ix = 400; ix < 600; ++ix) {
      const double r = std::hypot(centre(g, ix, 0) - 50.02, centre(g, iy, 1) - 25.03);
      const double expected = r <= 5 ? std::min(0.0, -4 + k * r) : 0.0;
      ASSERT_NEAR(field.top(ix, iy), expected, kFloat) << r;
    }
  }
  EXPECT_NEAR(field.top_at(50.02, 25.03), -4 + k * std::hypot(0.03, 0.02), kFloat);
}

TEST(Stock, DepthAlongAnUpNormal) {
  HeightField field = HeightField::block({0, 0, -10}, {100, 50, 0}, 0.1, kGigabyte);
  const Vector3d up(0, 0, 1);
  EXPECT_NEAR(field.depth_along({10, 10, -3}, up, 20), 3, 1e-9);
  EXPECT_NEAR(field.depth_along({10, 10, -3}, up, 1.5), 1.5, 1e-9);
  EXPECT_EQ(field.depth_along({10, 10, 1}, up, 20), 0);   // above the stock
  EXPECT_EQ(field.depth_along({-5, 10, -3}, up, 20), 0);  // beside it
  field.cut(Cutter{Tool::flat(10)}, {20, 25, -2}, {80, 25, -2});
  EXPECT_NEAR(field.depth_along({50, 25, -5}, up, 20), 3, 1e-6);  // under the slot
  EXPECT_EQ(field.depth_along({50, 25, -1}, up, 20), 0);          // in the slot's air
  // Tilted 45 degrees across the slot from under its floor: up through
  // the floor (z -2) after 3 / cos 45.
  const Vector3d tilted = Vector3d(0, 1, 1).normalized();
  EXPECT_NEAR(field.depth_along({50, 25, -5}, tilted, 20), 3 * std::sqrt(2.0), 1e-6);
  // Downwards the ray never leaves before the bottom of the grid's reach.
  EXPECT_EQ(field.depth_along({50, 25, -5}, -up, 7), 7);
}

// A pocket at -5 for x < 50 (a flat D10 zigzag with its centres to x = 45),
// the block top 0 beyond: a step whose face is the plane x = 50.
TEST(Stock, DepthAlongATiltedNormalThroughAStep) {
  HeightField field = HeightField::block({0, 0, -10}, {100, 50, 0}, 0.1, kGigabyte);
  std::vector<Vector3d> tips;
  for (int pass = 0; pass <= 10; ++pass) {
    const double y = 5.0 * pass;
    const bool forward = pass % 2 == 0;
    tips.emplace_back(forward ? -10 : 45, y, -5);
    tips.emplace_back(forward ? 45 : -10, y, -5);
  }
  field.cut_path(Cutter{Tool::flat(10)}, tips);
  EXPECT_EQ(field.top_at(49.95, 25), -5.0f);
  EXPECT_EQ(field.top_at(50.05, 25), 0.0f);
  // From (52, 25, -4) towards -x and up at 45 degrees: the face at x = 50
  // after 2 sqrt(2) mm (z -2 there, above the pocket's floor).
  const Vector3d towards_face = Vector3d(-1, 0, 1).normalized();
  EXPECT_NEAR(field.depth_along({52, 25, -4}, towards_face, 20), 2 * std::sqrt(2.0), 1e-6);
  // The same ray from under the floor: through the floor (z -5) at x = 51.
  const Vector3d away = Vector3d(1, 0, 1).normalized();
  EXPECT_NEAR(field.depth_along({48, 25, -6}, away, 20), std::sqrt(2.0), 1e-6);
}

// Two triangles over [0,10]^2 on the plane z = 1 + 0.5 x + 0.25 y.
TEST(Stock, TopOfATiltedPlane) {
  const auto z = [](float x, float y) { return 1 + 0.5f * x + 0.25f * y; };
  const std::vector<Vector3f> corners{{0, 0, z(0, 0)}, {10, 0, z(10, 0)},   {10, 10, z(10, 10)},
                                      {0, 0, z(0, 0)}, {10, 10, z(10, 10)}, {0, 10, z(0, 10)}};
  const HeightField field = HeightField::from_triangles(corners, 0.25, kGigabyte);
  const Grid& g = field.grid();
  ASSERT_EQ(g.nx, 40u);
  ASSERT_EQ(g.ny, 40u);
  for (std::uint32_t iy = 0; iy < g.ny; ++iy) {
    for (std::uint32_t ix = 0; ix < g.nx; ++ix) {
      const double x = centre(g, ix, 0), y = centre(g, iy, 1);
      ASSERT_NEAR(field.top(ix, iy), 1 + 0.5 * x + 0.25 * y, kFloat) << x << " " << y;
    }
  }
}

// The box [0,10] x [0,20] x [-5,3] as 12 triangles: its top face over every cell.
TEST(Stock, TopOfABoxMesh) {
  std::vector<Vector3f> corners;
  const auto corner = [](int i) {
    return Vector3f((i & 1) ? 10.0f : 0.0f, ((i >> 1) & 1) ? 20.0f : 0.0f,
                    ((i >> 2) & 1) ? 3.0f : -5.0f);
  };
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    for (const int i : {q[0], q[1], q[2], q[0], q[2], q[3]}) corners.push_back(corner(i));
  }
  const HeightField field = HeightField::from_triangles(corners, 0.5, kGigabyte);
  ASSERT_EQ(field.grid().nx, 20u);
  ASSERT_EQ(field.grid().ny, 40u);
  for (std::uint32_t iy = 0; iy < 40; ++iy) {
    for (std::uint32_t ix = 0; ix < 20; ++ix) ASSERT_EQ(field.top(ix, iy), 3.0f);
  }
  EXPECT_NEAR(field.depth_along({5, 5, 0}, {0, 0, 1}, 10), 3, 1e-6);
}

// One bad input per code: each file one call (block, mesh or cut), and
// expected.txt the file, a tab, and the whole message.
void run_bad_input(const fs::path& file) {
  std::ifstream in(file);
  std::string call;
  in >> call;
  if (call == "block") {
    double x0, y0, z0, x1, y1, z1, cell, limit;
    in >> x0 >> y0 >> z0 >> x1 >> y1 >> z1 >> cell >> limit;
    HeightField::block({x0, y0, z0}, {x1, y1, z1}, cell, static_cast<std::size_t>(limit));
  } else if (call == "mesh") {
    double cell;
    in >> cell;
    std::vector<Vector3f> corners;
    std::string x, y, z;
    while (in >> x >> y >> z) corners.emplace_back(std::stof(x), std::stof(y), std::stof(z));
    HeightField::from_triangles(corners, cell, kGigabyte);
  } else if (call == "cut") {
    std::string kind, ax, ay, az;
    double diameter, corner, angle, bx, by, bz;
    in >> kind >> diameter >> corner >> angle >> ax >> ay >> az >> bx >> by >> bz;
    const Tool tool = kind == "ball"   ? Tool::ball(diameter)
                      : kind == "bull" ? Tool::bull_nose(diameter, corner)
                                       : Tool::flat(diameter);
    HeightField field = HeightField::block({0, 0, 0}, {10, 10, 10}, 1, kGigabyte);
    field.cut(Cutter{tool, angle}, {std::stod(ax), std::stod(ay), std::stod(az)}, {bx, by, bz});
  } else {
    FAIL() << file << ": unknown call " << call;
  }
}

TEST(Stock, BadInputsGiveTheirCodes) {
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "tests/geometry/bad/stock";
  std::set<std::string> codes;
  for (const auto& [file, expected] : vcpost::testing::read_bad_input_list(dir)) {
    try {
      run_bad_input(dir / file);
      ADD_FAILURE() << file << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.what(), expected) << file;
      EXPECT_EQ(e.id(), file.substr(0, 5)) << file;
      EXPECT_EQ(e.exit_code(), 2) << file;
      codes.insert(std::string(e.id()));
    }
  }
  for (int code = 4701; code <= 4707; ++code) {
    EXPECT_TRUE(codes.count("E" + std::to_string(code))) << "no bad input for E" << code;
  }
}

}  // namespace
}  // namespace vcpost::geometry::stock
