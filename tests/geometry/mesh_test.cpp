// The STL reader and the mesh model: exact closest points on shapes whose
// answers are worked out by hand, agreement of binary and ASCII files, a
// brute-force cross-check, warm queries, bad files and the shared data.
#include <gtest/gtest.h>
#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <thread>

#include "geometry/mesh/mesh_model.h"
#include "geometry/mesh/stl_reader.h"
#include "tests/geometry/bad_input_list.h"
#include "tests/sanitizers.h"

namespace vcpost::mesh {
namespace {

using Eigen::Vector3d;
namespace fs = std::filesystem;

// The cube [0,10]^3 as 12 outward-facing triangles.
StlMesh cube() {
  StlMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back(10.0 * (i & 1), 10.0 * ((i >> 1) & 1), 10.0 * ((i >> 2) & 1));
  // Corner index bits: x=1, y=2, z=4. Quads counterclockwise seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])});
    m.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[2]), std::uint32_t(q[3])});
  }
  return m;
}

// A UV sphere of radius r about c (poles on z), outward-facing.
StlMesh uv_sphere(double r, const Vector3d& c, int rings, int segments) {
  StlMesh m;
  m.vertices.push_back(c + Vector3d(0, 0, r));
  for (int i = 1; i < rings; ++i) {
    const double th = M_PI * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double ph = 2 * M_PI * j / segments;
      m.vertices.push_back(
          c + r * Vector3d(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
    }
  }
  m.vertices.push_back(c + Vector3d(0, 0, -r));
  const auto at = [&](int i, int j) {
    return std::uint32_t(1 + (i - 1) * segments + (j % segments));
  };
  const auto south = std::uint32_t(m.vertices.size() - 1);
  for (int j = 0; j < segments; ++j) {
    m.triangles.push_back({0, at(1, j), at(1, j + 1)});
    for (int i = 1; i + 1 < rings; ++i) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
    m.triangles.push_back({at(rings - 1, j), south, at(rings - 1, j + 1)});
  }
  return m;
}

// Reference closest point, computed differently from the model: the plane
// projection when it falls inside (barycentric signs), else the nearest of
// the three clamped segment projections.
Vector3d reference_closest(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                           const Vector3d& c) {
  const Vector3d n = (b - a).cross(c - a).normalized();
  const Vector3d q = p - n.dot(p - a) * n;
  const auto side = [&](const Vector3d& u, const Vector3d& v) {
    return (v - u).cross(q - u).dot(n);
  };
  if (side(a, b) >= 0 && side(b, c) >= 0 && side(c, a) >= 0) return q;
  Vector3d best = a;
  for (const auto& [u, v] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
    const double t = std::clamp((p - u).dot(v - u) / (v - u).squaredNorm(), 0.0, 1.0);
    const Vector3d s = u + t * (v - u);
    if ((p - s).norm() < (p - best).norm()) best = s;
  }
  return best;
}

double brute_force_distance(const StlMesh& m, const Vector3d& p) {
  double d = INFINITY;
  for (const auto& t : m.triangles)
    d = std::min(
        d, (p - reference_closest(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]])).norm());
  return d;
}

constexpr double exact = 1e-12;

TEST(MeshModel, CubeFaceEdgeVertexContactsByHand) {
  const MeshModel model(cube());
  // Above the top face: CC straight below, facet normal +z, distance 3.
  auto c = model.closest_point({5, 4, 13}, 100, nullptr);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->type, geometry::ContactType::face);
  EXPECT_NEAR((c->point - Vector3d(5, 4, 10)).norm(), 0, exact);
  EXPECT_NEAR((c->normal - Vector3d(0, 0, 1)).norm(), 0, exact);
  EXPECT_NEAR(c->distance, 3, exact);
  // Beyond the edge x=10, z=10: CC on the edge, N = (3,0,4)/5, distance 5.
  c = model.closest_point({13, 5, 14}, 100, nullptr);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->type, geometry::ContactType::edge);
  EXPECT_NEAR((c->point - Vector3d(10, 5, 10)).norm(), 0, exact);
  EXPECT_NEAR((c->normal - Vector3d(0.6, 0, 0.8)).norm(), 0, exact);
  EXPECT_NEAR(c->distance, 5, exact);
  // Beyond the corner (10,10,10): vertex contact, N = (2,3,6)/7, distance 7.
  c = model.closest_point({12, 13, 16}, 100, nullptr);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->type, geometry::ContactType::vertex);
  EXPECT_NEAR((c->point - Vector3d(10, 10, 10)).norm(), 0, exact);
  EXPECT_NEAR((c->normal - Vector3d(2, 3, 6) / 7.0).norm(), 0, exact);
  EXPECT_NEAR(c->distance, 7, exact);
  // Exactly on the edge: the edge's pseudo-normal (1,0,1)/sqrt 2.
  c = model.closest_point({10, 5, 10}, 100, nullptr);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->distance, 0, exact);
  EXPECT_NEAR((c->normal - Vector3d(1, 0, 1) / std::sqrt(2.0)).norm(), 0, exact);
}

TEST(MeshModel, InsideTheSolidIsAGouge) {
  const MeshModel model(cube());
  // 1 mm under the top face (and 2 from the others): nearest is the top face.
  auto c = model.closest_point({5, 5, 9}, 100, nullptr);
  ASSERT_TRUE(c);
  EXPECT_NEAR((c->point - Vector3d(5, 5, 10)).norm(), 0, exact);
  EXPECT_NEAR((c->normal - Vector3d(0, 0, 1)).norm(), 0, exact);
  const auto ball = geometry::classify_ball_contact({5, 5, 9}, 6, 1e-6, c);
  EXPECT_EQ(ball.status, geometry::BallStatus::gouging);
  EXPECT_NEAR(ball.distance_error, -7, exact);
  // Inside near a corner, 1 mm from three faces at once: a tie, any face
  // will do, but the normal must still point out of the material.
  c = model.closest_point({9, 9, 9}, 100, nullptr);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->distance, 1, exact);
  EXPECT_LT((Vector3d(9, 9, 9) - c->point).dot(c->normal), 0);
}

TEST(MeshModel, BallInAConcaveCornerTouchesBothFaces) {
  // A V-groove: two planes z = |x| (for |x| <= 10, y in [0, 10]), normals up.
  StlMesh m;
  m.vertices = {{-10, 0, 10}, {0, 0, 0}, {10, 0, 10}, {-10, 10, 10}, {0, 10, 0}, {10, 10, 10}};
  m.triangles = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}};
  const MeshModel model(m);
  // Ball of radius 3 resting in the groove: centre at height 3*sqrt 2 on the
  // axis; it touches both planes at distance 3 (the normals (+-1,0,1)/sqrt 2).
  const double h = 3 * std::sqrt(2.0);
  const auto c = model.closest_point({0, 5, h}, 10, nullptr);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->type, geometry::ContactType::face);
  EXPECT_NEAR(c->distance, 3, exact);
  // The foot of C = (0, h) on z = x is (h/2, h/2) = (3/sqrt 2, 3/sqrt 2).
  EXPECT_NEAR(std::abs(c->point.x()), 3 / std::sqrt(2.0), exact);
  EXPECT_NEAR(c->point.z(), 3 / std::sqrt(2.0), exact);
  EXPECT_NEAR(std::abs(c->normal.x()), 1 / std::sqrt(2.0), exact);
}

TEST(MeshModel, MaxDistanceIsInclusive) {
  const MeshModel model(cube());
  EXPECT_FALSE(model.closest_point({5, 5, 13}, 2.999, nullptr));
  EXPECT_TRUE(model.closest_point({5, 5, 13}, 3.0, nullptr));
  EXPECT_FALSE(model.closest_point({5, 5, 13}, -1, nullptr));
  EXPECT_EQ(model.face_count(), 12);
  EXPECT_NEAR((model.bounds().min() - Vector3d(0, 0, 0)).norm(), 0, 0);
  EXPECT_NEAR((model.bounds().max() - Vector3d(10, 10, 10)).norm(), 0, 0);
}

TEST(MeshModel, AgreesWithBruteForceOnASphere) {
  const StlMesh m = uv_sphere(50, {3, -2, 7}, 40, 80);
  const MeshModel model(m);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-80, 80);
  for (int i = 0; i < 400; ++i) {
    const Vector3d p(u(rng), u(rng), u(rng));
    const auto c = model.closest_point(p, 1e9, nullptr);
    ASSERT_TRUE(c);
    EXPECT_NEAR(c->distance, brute_force_distance(m, p), 1e-11) << p.transpose();
    EXPECT_NEAR((p - c->point).norm(), c->distance, 1e-11);
    // CC lies on its own triangle: barycentric weights reproduce it.
    const auto& t = m.triangles[c->face];
    const Vector3d q = (1 - c->uv.x() - c->uv.y()) * m.vertices[t[0]] +
                       c->uv.x() * m.vertices[t[1]] + c->uv.y() * m.vertices[t[2]];
    EXPECT_NEAR((q - c->point).norm(), 0, 1e-11);
  }
}

TEST(MeshModel, WarmQueriesGiveTheColdAnswerAlongAPath) {
  const StlMesh m = uv_sphere(30, {0, 0, 0}, 60, 120);
  const MeshModel model(m);
  geometry::ContactHint hint;
  std::uint64_t same_face_as_previous = 0;
  int previous_face = -1;
  for (int i = 0; i <= 2000; ++i) {
    // A spiral at 6 mm above the sphere, like a ball centre on a finishing pass.
    const double t = i / 2000.0;
    const double th = 0.2 + 1.2 * t, ph = 40 * t;
    const Vector3d p =
        36.0 * Vector3d(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
    const auto warm = model.closest_point(p, 10, &hint);
    const auto cold = model.closest_point(p, 10, nullptr);
    ASSERT_TRUE(warm && cold);
    if (cold->face == previous_face) ++same_face_as_previous;
    previous_face = cold->face;
    EXPECT_EQ(warm->distance, cold->distance);
    EXPECT_NEAR((warm->point - cold->point).norm(), 0, 1e-12);
    // Inscribed facets lie inside the sphere: 6 mm at the vertices, a bit more between.
    EXPECT_GE(warm->distance, 6 - 1e-12);
    EXPECT_LE(warm->distance, 6 + 30 * (1 - std::cos(M_PI / 60)) + 1e-9);
  }
  // A query counts as warm when the hint's triangle was the answer: at
  // least every point whose cold answer repeats the previous point's face
  // (more where the contact is on an edge, a tie the hint's triangle wins).
  EXPECT_GE(hint.warm_queries, same_face_as_previous);
  EXPECT_GT(hint.warm_queries, 400u);
  EXPECT_EQ(hint.warm_queries + hint.cold_queries, 2001u);
}

TEST(StlReader, BinaryAndAsciiAgree) {
  // Float-exact coordinates so the binary file (single precision) is exact.
  const StlMesh m = cube();
  const StlMesh bin = parse_stl(to_binary_stl(m, "solid cube, a binary file anyway"), "cube.stl");
  const StlMesh asc = parse_stl(to_ascii_stl(m, "cube"), "cube.stl");
  EXPECT_EQ(bin.format, StlFormat::binary);  // its header starts with "solid": the size decides
  EXPECT_EQ(asc.format, StlFormat::ascii);
  EXPECT_EQ(asc.solid_name, "cube");
  ASSERT_EQ(bin.vertices.size(), 8u);  // 36 corners welded into 8
  ASSERT_EQ(asc.vertices.size(), 8u);
  EXPECT_EQ(bin.triangles, asc.triangles);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(bin.vertices[i], asc.vertices[i]);
  // Welding renumbers the corners (first use order); the triangles keep
  // their order and corner order, so their coordinates are the original ones.
  ASSERT_EQ(bin.triangles.size(), m.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(bin.vertices[bin.triangles[t][k]], m.vertices[m.triangles[t][k]]);
  const MeshModel a(bin), b(asc);
  const auto ca = a.closest_point({12, 13, 16}, 100, nullptr);
  const auto cb = b.closest_point({12, 13, 16}, 100, nullptr);
  ASSERT_TRUE(ca && cb);
  EXPECT_EQ(ca->point, cb->point);
  EXPECT_EQ(ca->face, cb->face);
}

// Past 2^20 triangles a binary file is welded in two halves side by side:
// the numbers (first use in file order), triangles, drops and the first
// bad number's message must be those of one pass.
TEST(StlReader, LargeBinaryWeldsAsOnePass) {
  StlMesh m;
  // Points of a paraboloid: no three on a line, so no flat triangle.
  for (int x = -300; x <= 300; ++x)
    for (int y = -300; y <= 300; y += 3) m.vertices.emplace_back(x, y, x * x + y * y);
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::uint32_t> pick(0, std::uint32_t(m.vertices.size() - 1));
  const std::size_t n = (std::size_t{1} << 20) + 4321;
  std::size_t flat = 0;
  for (std::size_t t = 0; t < n; ++t) {
    std::array<std::uint32_t, 3> tri{pick(rng), pick(rng), pick(rng)};
    if (t % 101 == 0) tri[1] = tri[0];  // two corners the same: dropped
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) ++flat;
    m.triangles.push_back(tri);
  }
  std::string bytes = to_binary_stl(m, "large");
  const StlMesh got = parse_stl(bytes, "large.stl");
  std::vector<std::uint32_t> number(m.vertices.size(), 0xffffffffu);
  std::vector<Vector3d> order;
  std::vector<std::array<std::uint32_t, 3>> kept;
  for (const auto& tri : m.triangles) {
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;
    std::array<std::uint32_t, 3> t{};
    for (int k = 0; k < 3; ++k) {
      if (number[tri[k]] == 0xffffffffu) {
        number[tri[k]] = std::uint32_t(order.size());
        order.push_back(m.vertices[tri[k]]);
      }
      t[k] = number[tri[k]];
    }
    kept.push_back(t);
  }
  EXPECT_EQ(got.degenerate_dropped, flat);
  EXPECT_TRUE(got.vertices == order);
  EXPECT_TRUE(got.triangles == kept);
  // A bad number in each half: the first one's message.
  const auto poison = [&](std::size_t t) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(bytes.data() + 84 + 50 * t + 16, &nan, 4);
  };
  poison(n - 10);
  poison(1000);
  try {
    parse_stl(bytes, "large.stl");
    ADD_FAILURE() << "no error";
  } catch (const StlError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 1001 vertex 1 "), std::string::npos) << e.what();
  }
}

TEST(StlReader, AsciiVariantsAndUnits) {
  // Upper case keywords, CRLF, tabs, exponents, several solids, no name.
  const std::string text =
      "solid\r\n facet normal 0 0 0\r\n\touter loop\r\n vertex 0 0 0\r\n VERTEX 1e1 0 0\r\n"
      " vertex 0 +1.0E+1 0\r\n endloop\r\n ENDFACET\r\nendsolid\r\n"
      "solid second\n facet normal nan nan nan\n outer loop\n vertex 0 0 1\n vertex 1 0 1\n"
      " vertex 0 1 1\n endloop\n endfacet\nendsolid second\n";
  const StlMesh m = parse_stl(text, "t.stl", {.unit_mm = 25.4});
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.vertices[1], Vector3d(254, 0, 0));
  EXPECT_EQ(m.vertices[2], Vector3d(0, 254, 0));
  EXPECT_EQ(m.vertices[5], Vector3d(0, 25.4, 25.4));
  EXPECT_THROW(parse_stl(text, "t.stl", {.unit_mm = 0}), StlError);
  // A degenerate facet is dropped and counted, the rest kept.
  StlMesh d = cube();
  d.vertices.emplace_back(20, 0, 0);
  d.triangles.push_back({0, 1, 8});  // collinear corners
  const StlMesh r = parse_stl(to_binary_stl(d, ""), "d.stl");
  EXPECT_EQ(r.triangles.size(), 12u);
  EXPECT_EQ(r.degenerate_dropped, 1u);
}

TEST(StlReader, BinaryCountBelowTheRecordsIsRefused) {
  // The cube's 12 triangles with the header's count set to 6: reading up to
  // the count dropped half the mesh silently; now E4609 at the first record
  // past the count. Fewer than 50 extra bytes (no whole record) stay ignored.
  std::string bytes = to_binary_stl(cube(), "");
  bytes[80] = 6;
  try {
    parse_stl(bytes, "c.stl");
    ADD_FAILURE() << "accepted";
  } catch (const StlError& e) {
    EXPECT_EQ(e.code(), Code::E4609);
    EXPECT_NE(std::string(e.what()).find(
                  "c.stl: offset 384: error[E4609]: binary STL header announces 6 triangles but "
                  "the file holds 12 whole triangle records"),
              std::string::npos)
        << e.what();
  }
  std::string padded = to_binary_stl(cube(), "") + std::string(49, '\0');
  EXPECT_EQ(parse_stl(padded, "c.stl").triangles.size(), 12u);
}

TEST(StlReader, BadFilesGiveTheirMessages) {
  const fs::path dir = fs::path(VCPOST_SOURCE_DIR) / "tests/geometry/bad/stl";
  int cases = 0;
  for (const auto& [file, expected] : vcpost::testing::read_bad_input_list(dir)) {
    try {
      read_stl_file(dir / file);
      ADD_FAILURE() << file << " was accepted";
    } catch (const StlError& e) {
      std::string message = e.what();
      const std::string prefix = (dir / "").string();
      if (message.rfind(prefix, 0) == 0) message = message.substr(prefix.size());
      EXPECT_EQ(message, expected);
      EXPECT_EQ(e.id(), expected.substr(expected.find("[E") + 1, 5));
    }
    ++cases;
  }
  EXPECT_GE(cases, 14);
  // Files never written by anyone.
  try {
    read_stl_file(dir / "no_such_file.stl");
    ADD_FAILURE();
  } catch (const StlError& e) {
    EXPECT_EQ(e.code(), Code::E4601);
    EXPECT_NE(std::string(e.what()).find("no_such_file.stl: error[E4601]: STL file not found"),
              std::string::npos);
  }
  try {
    read_stl_file(dir);
    ADD_FAILURE();
  } catch (const StlError& e) {
    EXPECT_EQ(e.code(), Code::E4602);
  }
}

// The APT + STL pairs of the shared data (PROVENANCE.md): the STL loads with
// the triangle count and box it documents, and the model agrees with brute force.
TEST(StlReader, SharedDataPairsLoad) {
  const fs::path dir = fs::path(VCPOST_SHARED_DATA_DIR) / "cldata";
  if (!fs::exists(dir)) GTEST_SKIP() << "shared data absent: " << dir;
  struct Case {
    const char* file;
    std::size_t triangles;
    Vector3d lo, hi;
  };
  // PROVENANCE.md rounds the boxes (37.75 is 37.7528 in the file): 0.01 mm.
  const Case cases[] = {{"basemach.STL", 1564, {0, 0, -10}, {350, 150, 0}},
                        {"Telemecanique-Tilt-Support2.stl", 1480, {0, 0, 0}, {37.75, 45, 30}}};
  for (const auto& k : cases) {
    const StlMesh m = read_stl_file(dir / k.file);
    EXPECT_EQ(m.format, StlFormat::binary);
    EXPECT_EQ(m.triangles.size() + m.degenerate_dropped, k.triangles) << k.file;
    const MeshModel model(m);
    EXPECT_NEAR((model.bounds().min() - k.lo).cwiseAbs().maxCoeff(), 0, 1e-2) << k.file;
    EXPECT_NEAR((model.bounds().max() - k.hi).cwiseAbs().maxCoeff(), 0, 1e-2) << k.file;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 200; ++i) {
      const Vector3d p = k.lo + (k.hi - k.lo).cwiseProduct(Vector3d(u(rng), u(rng), u(rng))) * 1.2 -
                         0.1 * (k.hi - k.lo);
      const auto c = model.closest_point(p, 1e9, nullptr);
      ASSERT_TRUE(c);
      EXPECT_NEAR(c->distance, brute_force_distance(m, p), 1e-9) << k.file;
    }
  }
}

// The wavy mould z = 5 sin(2 pi x / 60) cos(2 pi y / 60) over [0, 100]^2 as
// a 224 x 224 grid of split quads: 100,352 triangles (as in mesh_bench).
StlMesh wavy_mesh() {
  const auto height = [](double x, double y) {
    return 5 * std::sin(2 * M_PI * x / 60) * std::cos(2 * M_PI * y / 60);
  };
  StlMesh m;
  constexpr int n = 224;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = 100.0 * i / n, y = 100.0 * j / n;
      m.vertices.emplace_back(x, y, height(x, y));
    }
  const auto at = [&](int i, int j) { return std::uint32_t(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

// A walk over the wavy mould: steps of 0.05 to 0.5 mm with a slowly turning
// heading, reflected off a window 3 mm wider than the mesh; each point is
// 3 to 7 mm above the surface along its normal (lifted, touching, gouging
// balls of R 5), and beyond the border moved out sideways (border edges).
std::vector<Vector3d> wavy_walk(std::size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> step(0.05, 0.5), turn(-0.3, 0.3), radius(3, 7);
  Eigen::Vector2d xy(50, 50);
  double heading = 0.7;
  const double k = 2 * M_PI / 60;
  std::vector<Vector3d> out;
  for (std::size_t i = 0; i < count; ++i) {
    heading += turn(rng);
    xy += step(rng) * Eigen::Vector2d(std::cos(heading), std::sin(heading));
    for (int a = 0; a < 2; ++a) {
      if (xy[a] < -3 || xy[a] > 103) {
        xy[a] = std::clamp(xy[a], -3.0, 103.0);
        heading = a == 0 ? M_PI - heading : -heading;
      }
    }
    const Eigen::Vector2d in = xy.cwiseMax(0.0).cwiseMin(100.0);
    const double x = in.x(), y = in.y();
    const Vector3d n = Vector3d(-5 * k * std::cos(k * x) * std::cos(k * y),
                                5 * k * std::sin(k * x) * std::sin(k * y), 1)
                           .normalized();
    const Vector3d foot(x, y, 5 * std::sin(k * x) * std::cos(k * y));
    out.push_back(foot + radius(rng) * n + Vector3d(xy.x() - x, xy.y() - y, 0));
  }
  return out;
}

// 5000 warm queries (each with the previous answer's hint) against cold
// ones at every point, and against a brute force over all 100,352 triangles
// at every 25th; the walk meets contacts inside faces, on edges and on
// vertices.
TEST(MeshModel, WarmWalkOnAHundredThousandTrianglesGivesTheColdAnswers) {
  const StlMesh m = wavy_mesh();
  ASSERT_EQ(m.triangles.size(), 100352u);
  const MeshModel model(m);
  const std::vector<Vector3d> walk = wavy_walk(5000, 4);
  geometry::ContactHint hint;
  int types[3] = {0, 0, 0};
  std::uint64_t same_face_as_previous = 0;
  int previous_face = -1;
  for (std::size_t i = 0; i < walk.size(); ++i) {
    const Vector3d& p = walk[i];
    const auto warm = model.closest_point(p, 20, &hint);
    const auto cold = model.closest_point(p, 20, nullptr);
    ASSERT_TRUE(warm && cold) << p.transpose();
    ASSERT_LT((warm->point - cold->point).norm(), 1e-9) << i << ": " << p.transpose();
    ASSERT_NEAR(warm->distance, cold->distance, 1e-12) << i;
    ASSERT_LT((warm->normal - cold->normal).norm(), 1e-9) << i;
    ++types[static_cast<int>(warm->type)];
    if (cold->face == previous_face) ++same_face_as_previous;
    previous_face = cold->face;
    if (i % (25 * vcpost::testing::kSanitizedStride) == 0) {
      EXPECT_NEAR(warm->distance, brute_force_distance(m, p), 1e-11) << i;
    }
  }
  EXPECT_GT(types[0], 500);  // inside a triangle
  EXPECT_GT(types[1], 100);  // on an edge (the convex parts: inscribed facets)
  EXPECT_GT(types[2], 10);   // on a vertex
  // Every query whose answer is the previous answer's triangle counts as
  // warm (ties on shared edges may count more), and every query counts once.
  EXPECT_GE(hint.warm_queries, same_face_as_previous);
  EXPECT_GT(same_face_as_previous, 500u);
  EXPECT_EQ(hint.warm_queries + hint.cold_queries, walk.size());
}

// The same 20,000 warm queries on two threads at once, each with its own
// hint, and on one thread: bit for bit the same answers.
TEST(MeshModel, TwoThreadsGiveTheOneThreadAnswersBitForBit) {
  const MeshModel model(wavy_mesh());
  const std::vector<Vector3d> walk = wavy_walk(20000, 9);
  const auto run = [&](std::vector<geometry::ModelContact>& out) {
    geometry::ContactHint hint;
    out.resize(walk.size());
    for (std::size_t i = 0; i < walk.size(); ++i) out[i] = *model.closest_point(walk[i], 20, &hint);
  };
  std::vector<geometry::ModelContact> one, a, b;
  run(one);
  std::thread other([&] { run(b); });
  run(a);
  other.join();
  const auto same = [](const geometry::ModelContact& x, const geometry::ModelContact& y) {
    return std::memcmp(x.point.data(), y.point.data(), sizeof(double) * 3) == 0 &&
           std::memcmp(x.normal.data(), y.normal.data(), sizeof(double) * 3) == 0 &&
           std::memcmp(&x.distance, &y.distance, sizeof(double)) == 0 && x.face == y.face &&
           x.type == y.type && std::memcmp(x.uv.data(), y.uv.data(), sizeof(double) * 2) == 0;
  };
  for (std::size_t i = 0; i < walk.size(); ++i) {
    ASSERT_TRUE(same(one[i], a[i]) && same(one[i], b[i])) << "query " << i;
  }
}

bool bit_equal(const geometry::ModelContact& x, const geometry::ModelContact& y) {
  return std::memcmp(x.point.data(), y.point.data(), sizeof(double) * 3) == 0 &&
         std::memcmp(x.normal.data(), y.normal.data(), sizeof(double) * 3) == 0 &&
         std::memcmp(&x.distance, &y.distance, sizeof(double)) == 0 && x.face == y.face &&
         x.type == y.type && std::memcmp(x.uv.data(), y.uv.data(), sizeof(double) * 2) == 0;
}

// The index is built on oneTBB's threads in a fixed order of operations:
// two builds on one thread and one on two give the same answers bit for bit
// (cold and warm, 4000 points of a walk over the wavy mould; ties between
// triangles sharing an edge or a vertex are decided by the order the
// hierarchy visits them, so this holds only if the boxes are the same).
// The answers are the closest points: the distance is |p - point|, the
// point lies on the reported triangle at the reported barycentric weights,
// and a brute force over all triangles gives the same distance (every 10th
// point).
TEST(MeshModel, IndexBuiltOnOneOrTwoThreadsGivesTheSameAnswersBitForBit) {
  const StlMesh m = wavy_mesh();
  const auto build = [&](std::size_t threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return std::make_unique<MeshModel>(m);
  };
  const auto one = build(1), again = build(1), two = build(2);
  const std::vector<Vector3d> walk = wavy_walk(4000, 17);
  geometry::ContactHint hint_one, hint_again, hint_two;
  int types[3] = {0, 0, 0};
  for (std::size_t i = 0; i < walk.size(); ++i) {
    const Vector3d& p = walk[i];
    for (const bool warm : {false, true}) {
      const auto a = one->closest_point(p, 20, warm ? &hint_one : nullptr);
      const auto b = again->closest_point(p, 20, warm ? &hint_again : nullptr);
      const auto c = two->closest_point(p, 20, warm ? &hint_two : nullptr);
      ASSERT_TRUE(a && b && c) << i;
      ASSERT_TRUE(bit_equal(*a, *b)) << "two one-thread builds differ at query " << i;
      ASSERT_TRUE(bit_equal(*a, *c)) << "one- and two-thread builds differ at query " << i;
      if (warm) continue;
      ++types[static_cast<int>(a->type)];
      const auto& t = m.triangles[static_cast<std::size_t>(a->face)];
      const Vector3d on = m.vertices[t[0]] + a->uv[0] * (m.vertices[t[1]] - m.vertices[t[0]]) +
                          a->uv[1] * (m.vertices[t[2]] - m.vertices[t[0]]);
      EXPECT_LT((on - a->point).norm(), 1e-9) << i;
      EXPECT_GE(a->uv.minCoeff(), 0.0) << i;
      EXPECT_LE(a->uv.sum(), 1.0 + 1e-12) << i;
      EXPECT_NEAR(a->distance, (p - a->point).norm(), 1e-12) << i;
      if (i % (10 * vcpost::testing::kSanitizedStride) == 0) {
        EXPECT_NEAR(a->distance, brute_force_distance(m, p), 1e-11) << i;
      }
    }
  }
  EXPECT_GT(types[0], 400);  // inside a triangle
  EXPECT_GT(types[1], 50);   // on an edge
  EXPECT_GT(types[2], 5);    // on a vertex
}

// The welded mesh (corners shared by index, as the reader builds it from a
// binary STL) against the same triangles as a soup (three corners of its
// own each, nothing shared) and against a brute force computed apart: the
// same contact point and normal at 600 points of a walk over the wavy
// mould, and the reader shares the corners (about one vertex for two
// triangles). Above the surface the normal is (p - point)/|p - point| on an
// edge or a vertex and the facet normal inside a face.
TEST(MeshModel, SharedCornersGiveTheSoupsContactsAndTheBruteForceOnes) {
  const StlMesh welded = parse_stl(to_binary_stl(wavy_mesh(), "wavy"), "wavy.stl");
  ASSERT_EQ(welded.triangles.size(), 100352u);
  EXPECT_EQ(welded.vertices.size(), 225u * 225u);
  StlMesh soup;
  for (const auto& t : welded.triangles) {
    const auto first = static_cast<std::uint32_t>(soup.vertices.size());
    for (const auto i : t) soup.vertices.push_back(welded.vertices[i]);
    soup.triangles.push_back({first, first + 1, first + 2});
  }
  const MeshModel shared(welded), separate(soup);
  const std::vector<Vector3d> walk = wavy_walk(600, 23);
  int types[3] = {0, 0, 0};
  for (std::size_t i = 0; i < walk.size(); ++i) {
    const Vector3d& p = walk[i];
    const auto a = shared.closest_point(p, 20, nullptr);
    const auto b = separate.closest_point(p, 20, nullptr);
    ASSERT_TRUE(a && b) << i;
    ++types[static_cast<int>(a->type)];
    EXPECT_LT((a->point - b->point).norm(), 1e-9) << i;
    if (i % vcpost::testing::kSanitizedStride != 0) continue;
    // Brute force: the nearest of every triangle's reference closest point.
    Vector3d best_point = Vector3d::Zero();
    double best = INFINITY;
    for (const auto& t : welded.triangles) {
      const Vector3d q =
          reference_closest(p, welded.vertices[t[0]], welded.vertices[t[1]], welded.vertices[t[2]]);
      if ((p - q).norm() < best) {
        best = (p - q).norm();
        best_point = q;
      }
    }
    EXPECT_LT((a->point - best_point).norm(), 1e-9) << i;
    EXPECT_LT((b->point - best_point).norm(), 1e-9) << i;
    EXPECT_NEAR(a->distance, best, 1e-11) << i;
    EXPECT_NEAR(b->distance, best, 1e-11) << i;
    if (best < 1e-6) continue;  // the normal below is a direction from p
    const auto& t = welded.triangles[static_cast<std::size_t>(a->face)];
    const Vector3d facet = (welded.vertices[t[1]] - welded.vertices[t[0]])
                               .cross(welded.vertices[t[2]] - welded.vertices[t[0]])
                               .normalized();
    const Vector3d expected =
        a->type == geometry::ContactType::face ? facet : Vector3d((p - best_point) / best);
    EXPECT_LT((a->normal - expected).norm(), 1e-9) << i;
    EXPECT_LT((b->normal - a->normal).norm(), 1e-9) << i;
  }
  EXPECT_GT(types[0], 50);  // inside a triangle
  EXPECT_GT(types[1], 10);  // on an edge
}

// Three faces on one edge (the x axis from 0 to 10): two in z = 0 facing
// +z on either side, one in y = 0 facing -y. On the shared edge the
// normal is the edge's pseudo-normal, the sum of the three facet normals
// (0, -1, 2)/sqrt(5); on a border edge of one face it is that face's.
TEST(MeshModel, EdgeOfThreeFacesAndBorderEdgesByHand) {
  StlMesh m;
  m.vertices = {{0, 0, 0}, {10, 0, 0}, {5, 10, 0}, {5, -10, 0}, {5, 0, 10}};
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const MeshModel model(m);
  const auto shared = model.closest_point({5, 0, 0}, 1, nullptr);
  ASSERT_TRUE(shared);
  EXPECT_EQ(shared->type, geometry::ContactType::edge);
  EXPECT_LT((shared->normal - Vector3d(0, -1, 2) / std::sqrt(5.0)).norm(), exact);
  const auto border = model.closest_point({7.5, 5, 0}, 1, nullptr);
  ASSERT_TRUE(border);
  EXPECT_EQ(border->type, geometry::ContactType::edge);
  EXPECT_EQ(border->face, 0);
  EXPECT_LT((border->normal - Vector3d(0, 0, 1)).norm(), exact);
}

// A binary STL's corners are floats: the model keeps them in single
// precision (half the memory) and reads them back as the same doubles. The
// same mesh with one unused corner that is not a float (inside the bounds,
// so it changes nothing else) is kept in double precision: the two give
// the same answers bit for bit, cold and warm, at 4000 points of a walk
// over the wavy mould (faces, edges and vertices; the edge pseudo-normals
// are recomputed from the two faces, the vertex ones kept).
TEST(MeshModel, SinglePrecisionCornersGiveTheDoublePrecisionAnswersBitForBit) {
  const StlMesh read = parse_stl(to_binary_stl(wavy_mesh(), "wavy"), "wavy.stl");
  StlMesh widened = read;
  widened.vertices.emplace_back(50.1, 50.1, 0.1);
  ASSERT_NE(double(float(0.1)), 0.1);
  const MeshModel single(read), full(widened);
  ASSERT_EQ(single.face_count(), full.face_count());
  ASSERT_EQ(single.bounds().min(), full.bounds().min());
  ASSERT_EQ(single.bounds().max(), full.bounds().max());
  const std::vector<Vector3d> walk = wavy_walk(4000, 31);
  geometry::ContactHint hint_single, hint_full;
  int types[3] = {0, 0, 0};
  for (std::size_t i = 0; i < walk.size(); ++i) {
    for (const bool warm : {false, true}) {
      const auto a = single.closest_point(walk[i], 20, warm ? &hint_single : nullptr);
      const auto b = full.closest_point(walk[i], 20, warm ? &hint_full : nullptr);
      ASSERT_TRUE(a && b) << i;
      ASSERT_TRUE(bit_equal(*a, *b)) << "query " << i << (warm ? " warm" : " cold");
      if (!warm) ++types[static_cast<int>(a->type)];
    }
  }
  EXPECT_GT(types[0], 400);  // inside a triangle
  EXPECT_GT(types[1], 50);   // on an edge
  EXPECT_GT(types[2], 5);    // on a vertex
  EXPECT_EQ(hint_single.warm_queries, hint_full.warm_queries);
}

}  // namespace
}  // namespace vcpost::mesh
