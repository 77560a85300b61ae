// The multi-face test model (occt::wavy_patches: the wavy B-spline face cut
// into 10 x 10 sewn faces) and the contract of warm starts on B-rep models:
// a warm query (with the previous answer's hint) gives the cold query's
// closest point within 1e-9 mm along random walks that cross face
// boundaries, and two threads with their own hints give, bit for bit, the
// answers of one thread.
#include <gtest/gtest.h>

#include <BRep_Tool.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <random>
#include <thread>
#include <vector>

#include "geometry/occt/brep_model.h"
#include "geometry/occt/sample_parts.h"
#include "geometry/occt/sample_shapes.h"
#include "geometry/occt/shape_model.h"

namespace vcpost::occt {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector2d;
using Eigen::Vector3d;
using geometry::ContactHint;
using geometry::ContactType;
using geometry::ModelContact;

Vector3d eig(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }

Handle(Geom_BSplineSurface) wavy_surface() {
  return Handle(Geom_BSplineSurface)::DownCast(BRep_Tool::Surface(wavy_bspline_face()));
}

// One model of each kind, built once for the suite.
struct Models {
  BrepModel face = model_from_shape(wavy_bspline_face());
  BrepModel patches = model_from_shape(wavy_patches(10, 10));
};
const Models& models() {
  static const Models m;
  return m;
}

// A walk over the wavy surface (100 x 100 mm, u and v in [0, 1]): steps of
// 0.05 to 0.5 mm with a slowly turning heading (so it travels and crosses
// many face boundaries), reflected off a window a little larger than the
// surface; the query is the surface point at the clamped (u,v), moved
// radius (3 to 7 mm: lifted, touching and gouging balls of R 5) along the
// normal and, outside the surface, sideways by the overshoot (edge and
// corner contacts).
std::vector<Vector3d> random_walk(std::size_t count, unsigned seed) {
  const Handle(Geom_BSplineSurface) surface = wavy_surface();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> step(0.05, 0.5), turn(-0.3, 0.3), radius(3, 7);
  Vector2d uv(0.5, 0.5);
  double heading = 0.7;
  std::vector<Vector3d> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    heading += turn(rng);
    uv += step(rng) / 100 * Vector2d(std::cos(heading), std::sin(heading));
    for (int k = 0; k < 2; ++k) {
      if (uv[k] < -0.03 || uv[k] > 1.03) {
        uv[k] = std::clamp(uv[k], -0.03, 1.03);
        heading = k == 0 ? std::numbers::pi - heading : -heading;
      }
    }
    const Vector2d inside = uv.cwiseMax(0.0).cwiseMin(1.0);
    GeomLProp_SLProps props(surface, inside.x(), inside.y(), 1, 1e-9);
    gp_Dir n = props.Normal();
    if (n.Z() < 0) n.Reverse();
    const Vector2d over = 100 * (uv - inside);
    out.push_back(eig(props.Value()) + radius(rng) * Vector3d(n.X(), n.Y(), n.Z()) +
                  Vector3d(over.x(), over.y(), 0));
  }
  return out;
}

TEST(WavyPatches, HundredSewnFacesSharingEdgesAndVertices) {
  const TopoDS_Shape shape = wavy_patches(10, 10);
  TopTools_IndexedMapOfShape faces, edges, vertices;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  TopExp::MapShapes(shape, TopAbs_EDGE, edges);
  TopExp::MapShapes(shape, TopAbs_VERTEX, vertices);
  EXPECT_EQ(faces.Extent(), 100);
  // Sewn: 10 x 11 edges each way and 11 x 11 vertices, each shared.
  EXPECT_EQ(edges.Extent(), 220);
  EXPECT_EQ(vertices.Extent(), 121);
  EXPECT_EQ(models().patches.face_count(), 100);
}

// The patches are the same surface: cold answers agree with the single
// face's at points over the whole surface and beyond its border, every
// fourth one over a cut line; the answers come from faces all over.
TEST(WavyPatches, SameClosestPointsAsTheUncutFace) {
  const Models& m = models();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> xy(-5, 105), z(-6, 12);
  std::vector<bool> seen(100, false);
  for (int i = 0; i < 400; ++i) {
    Vector3d p(xy(rng), xy(rng), z(rng));
    if (i % 4 == 0) p.x() = 10 * std::round(p.x() / 10);
    const auto a = m.face.closest_point(p, 1e9, nullptr);
    const auto b = m.patches.closest_point(p, 1e9, nullptr);
    ASSERT_TRUE(a && b) << p.transpose();
    EXPECT_LT((a->point - b->point).norm(), 1e-9)
        << p.transpose() << " face: " << geometry::to_string(a->type) << " at "
        << a->point.transpose() << ", patches: " << geometry::to_string(b->type) << " at "
        << b->point.transpose() << " on face " << b->face;
    EXPECT_NEAR(a->distance, b->distance, 1e-9) << p.transpose();
    if (a->type == ContactType::face && b->type == ContactType::face) {
      EXPECT_LT((a->normal - b->normal).norm(), 1e-9) << p.transpose();
    }
    seen[static_cast<std::size_t>(b->face)] = true;
  }
  EXPECT_GT(std::count(seen.begin(), seen.end(), true), 80);
}

TEST(WavyPatches, WrittenToStepAndReadBack) {
  const Handle(Geom_BSplineSurface) s = wavy_surface();
  BsplineSurfaceSpec spec;
  spec.degree_u = s->UDegree();
  spec.degree_v = s->VDegree();
  for (int i = 1; i <= s->NbUKnots(); ++i)
    for (int k = 0; k < s->UMultiplicity(i); ++k) spec.knots_u.push_back(s->UKnot(i));
  for (int i = 1; i <= s->NbVKnots(); ++i)
    for (int k = 0; k < s->VMultiplicity(i); ++k) spec.knots_v.push_back(s->VKnot(i));
  spec.count_u = s->NbUPoles();
  spec.count_v = s->NbVPoles();
  for (int i = 1; i <= spec.count_u; ++i)
    for (int j = 1; j <= spec.count_v; ++j) spec.poles.push_back(eig(s->Pole(i, j)));
  const fs::path dir =
      fs::temp_directory_path() / ("vcpost_patches_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "patches.step";
  write_bspline_patches_step(file, spec, 4, 3, "wavy 4 x 3");
  const BrepModel model = BrepModel::load_step(file);
  fs::remove_all(dir);
  EXPECT_EQ(model.face_count(), 12);
  const Models& m = models();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> xy(0, 100), z(-6, 12);
  for (int i = 0; i < 100; ++i) {
    const Vector3d p(xy(rng), xy(rng), z(rng));
    const auto a = m.face.closest_point(p, 1e9, nullptr);
    const auto b = model.closest_point(p, 1e9, nullptr);
    ASSERT_TRUE(a && b);
    EXPECT_LT((a->point - b->point).norm(), 1e-9) << p.transpose();
  }
}

// Warm answers along a walk against cold ones (no hint) at every point.
void expect_warm_equals_cold(const BrepModel& model, const std::vector<Vector3d>& walk,
                             int* face_changes) {
  ContactHint hint;
  int changes = 0, previous_face = -1;
  for (const Vector3d& p : walk) {
    const auto warm = model.closest_point(p, 1e9, &hint);
    const auto cold = model.closest_point(p, 1e9, nullptr);
    ASSERT_TRUE(warm && cold) << p.transpose();
    ASSERT_LT((warm->point - cold->point).norm(), 1e-9)
        << p.transpose() << " warm face " << warm->face << " cold face " << cold->face;
    ASSERT_NEAR(warm->distance, cold->distance, 1e-9) << p.transpose();
    if (cold->face != previous_face) ++changes;
    previous_face = cold->face;
  }
  EXPECT_GT(hint.warm_queries, walk.size() * 8 / 10);
  *face_changes = changes;
}

TEST(WarmStart, SingleFaceWalkGivesTheColdAnswers) {
  int changes = 0;
  expect_warm_equals_cold(models().face, random_walk(5000, 1), &changes);
}

TEST(WarmStart, HundredFaceWalkAcrossFaceBoundariesGivesTheColdAnswers) {
  int changes = 0;
  expect_warm_equals_cold(models().patches, random_walk(5000, 2), &changes);
  EXPECT_GT(changes, 50);  // the walk crosses many face boundaries
}

bool same_bits(const ModelContact& a, const ModelContact& b) {
  const auto eq = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  return eq(a.point, b.point) && eq(a.normal, b.normal) && eq(a.distance, b.distance) &&
         a.face == b.face && eq(a.uv, b.uv) && a.type == b.type &&
         a.curvature.has_value() == b.curvature.has_value() &&
         (!a.curvature ||
          (eq(a.curvature->k1, b.curvature->k1) && eq(a.curvature->k2, b.curvature->k2) &&
           eq(a.curvature->d1, b.curvature->d1)));
}

// The same 20 000 warm queries on two threads at once, each with its own
// hint, and on one thread: bit for bit the same answers.
void expect_threads_bitwise_equal(const BrepModel& model) {
  const std::vector<Vector3d> walk = random_walk(20000, 7);
  const auto run = [&](std::vector<ModelContact>& out) {
    ContactHint hint;
    out.resize(walk.size());
    for (std::size_t i = 0; i < walk.size(); ++i)
      out[i] = *model.closest_point(walk[i], 1e9, &hint);
  };
  std::vector<ModelContact> one, a, b;
  run(one);
  std::thread other([&] { run(b); });
  run(a);
  other.join();
  for (std::size_t i = 0; i < walk.size(); ++i) {
    ASSERT_TRUE(same_bits(one[i], a[i]) && same_bits(one[i], b[i])) << "query " << i;
  }
}

TEST(ThreadSafety, SingleFaceTwoThreadsBitForBit) { expect_threads_bitwise_equal(models().face); }
TEST(ThreadSafety, HundredFacesTwoThreadsBitForBit) {
  expect_threads_bitwise_equal(models().patches);
}

}  // namespace
}  // namespace vcpost::occt
