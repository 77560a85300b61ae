// BrepModel against OpenCASCADE's own answers and constructions with known
// truth: a B-spline face written to STEP and read back (CC within 1e-5 mm,
// N within 1e-5 rad of a dense search refined by GeomAPI_ProjectPointOnSurf),
// trims, edges and vertices of B-rep solids, inch files, the shared real
// STEP files (against BRepExtrema_DistShapeShape), and bad input.
#include "geometry/occt/brep_model.h"

#include <gtest/gtest.h>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GC_MakeCircle.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom_Surface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <StepData_StepModel.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Compound.hxx>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gp_Circ.hxx>
#include <iostream>
#include <numbers>
#include <random>
#include <thread>

#include "geometry/occt/sample_shapes.h"
#include "geometry/occt/shape_model.h"

namespace vcpost::occt {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector2d;
using Eigen::Vector3d;
using geometry::BallStatus;
using geometry::ContactHint;
using geometry::ContactType;
using geometry::ModelContact;

Vector3d eig(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
double angle_between(const Vector3d& a, const Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

fs::path temp_dir() {
  const fs::path dir =
      fs::temp_directory_path() / ("vcpost_occt_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

// The temporary folder goes when the suite ends.
class TempDirCleanup : public ::testing::Environment {
 public:
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(temp_dir(), ignored);
  }
};
::testing::Environment* const kTempDirCleanup =
    ::testing::AddGlobalTestEnvironment(new TempDirCleanup);

fs::path write_step(const TopoDS_Shape& shape, const std::string& name, const char* unit = "MM") {
  const fs::path path = temp_dir() / name;
  STEPControl_Controller::Init();  // registers write.step.unit
  Interface_Static::SetCVal("write.step.unit", unit);
  STEPControl_Writer writer;
  writer.Model(true)->SetWriteLengthUnit(std::string(unit) == "INCH" ? 25.4 : 1);
  EXPECT_EQ(writer.Transfer(shape, STEPControl_AsIs), IFSelect_RetDone);
  EXPECT_EQ(writer.Write(path.string().c_str()), IFSelect_RetDone);
  Interface_Static::SetCVal("write.step.unit", "MM");
  return path;
}

// The independent truth on a surface: the nearest node of a 400 x 400 grid,
// then OpenCASCADE's projection from there (its own Newton/extrema code).
struct Truth {
  Vector3d point, normal;
  double k_max = 0, k_min = 0;
  Vector3d dir_of_occt_max, dir_of_occt_min;
};
Truth surface_truth(const Handle(Geom_Surface) & surface, const Vector3d& p) {
  double u0, u1, v0, v1;
  surface->Bounds(u0, u1, v0, v1);
  constexpr int n = 400;
  double best = 1e300, bu = 0, bv = 0;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const double u = u0 + (u1 - u0) * i / n, v = v0 + (v1 - v0) * j / n;
      const double d = (eig(surface->Value(u, v)) - p).squaredNorm();
      if (d < best) {
        best = d;
        bu = u;
        bv = v;
      }
    }
  }
  GeomAPI_ProjectPointOnSurf projector;
  projector.Init(surface, u0, u1, v0, v1);
  projector.Perform(gp_Pnt(p.x(), p.y(), p.z()));
  EXPECT_TRUE(projector.IsDone());
  double pu = bu, pv = bv;
  if (projector.NbPoints() > 0) projector.LowerDistanceParameters(pu, pv);
  // Keep whichever is nearer (the projector can miss when the grid is right).
  if ((eig(surface->Value(pu, pv)) - p).squaredNorm() > best) {
    pu = bu;
    pv = bv;
  }
  GeomLProp_SLProps props(surface, pu, pv, 2, 1e-9);
  Truth t;
  t.point = eig(surface->Value(pu, pv));
  const gp_Dir dir = props.Normal();
  t.normal = {dir.X(), dir.Y(), dir.Z()};
  // OCCT's curvatures are signed against its normal (concave-positive seen
  // from it); ours are convex-positive.
  t.k_max = -props.MinCurvature();
  t.k_min = -props.MaxCurvature();
  gp_Dir dmax, dmin;
  props.CurvatureDirections(dmax, dmin);
  t.dir_of_occt_max = {dmax.X(), dmax.Y(), dmax.Z()};
  t.dir_of_occt_min = {dmin.X(), dmin.Y(), dmin.Z()};
  return t;
}

class WavyFace : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    face_ = new TopoDS_Face(wavy_bspline_face());
    model_ = new BrepModel(BrepModel::load_step(write_step(*face_, "wavy.step"), {}));
  }
  static void TearDownTestSuite() {
    delete model_;
    delete face_;
  }
  static TopoDS_Face* face_;
  static BrepModel* model_;
};
TopoDS_Face* WavyFace::face_ = nullptr;
BrepModel* WavyFace::model_ = nullptr;

TEST_F(WavyFace, ReadBackAsOneFaceInMillimetres) {
  EXPECT_EQ(model_->face_count(), 1);
  EXPECT_EQ(model_->info().length_unit, "millimetre");
  // Bounds hold the face, grown by the tessellation margin only.
  const Eigen::AlignedBox3d box = model_->bounds();
  EXPECT_LE(box.min().x(), 0);
  EXPECT_NEAR(box.min().x(), 0, 0.5);
  EXPECT_GE(box.max().x(), 100);
  EXPECT_NEAR(box.max().x(), 100, 0.5);
}

// Random points up to 8 mm off the surface: CC within 1e-5 mm and N within
// 1e-5 rad of the truth, principal curvatures within 1e-6 /mm.
TEST_F(WavyFace, ClosestPointsMatchDenseSearchAndOcctProjection) {
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(*face_);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> xy(5, 95), dz(-8, 8);
  for (int i = 0; i < 40; ++i) {
    const Vector3d p(xy(rng), xy(rng), dz(rng));
    const auto c = model_->closest_point(p, 1e9, nullptr);
    ASSERT_TRUE(c);
    const Truth truth = surface_truth(surface, p);
    EXPECT_LT((c->point - truth.point).norm(), 1e-5) << "at " << p.transpose();
    // Our face normal is out of the material (+z side here).
    const Vector3d expected_n = truth.normal.z() > 0 ? truth.normal : Vector3d(-truth.normal);
    EXPECT_LT(angle_between(c->normal, expected_n), 1e-5);
    EXPECT_NEAR(c->distance, (p - truth.point).norm(), 1e-5);
    ASSERT_TRUE(c->curvature);
    const double sign = truth.normal.z() > 0 ? 1 : -1;
    const double k1 = sign > 0 ? truth.k_max : -truth.k_min;
    const double k2 = sign > 0 ? truth.k_min : -truth.k_max;
    EXPECT_NEAR(c->curvature->k1, k1, 1e-6);
    EXPECT_NEAR(c->curvature->k2, k2, 1e-6);
    // Directions: ours are convex-positive against our normal, OCCT's
    // concave-positive against its own, so k1 pairs with OCCT's minimum
    // when the normals agree and with its maximum when they are opposite.
    const Vector3d d1 = sign > 0 ? truth.dir_of_occt_min : truth.dir_of_occt_max;
    if (k1 - k2 > 1e-4) {
      EXPECT_NEAR(std::abs(c->curvature->d1.dot(d1)), 1, 1e-8);
    }
    EXPECT_NEAR(c->curvature->d1.cross(c->curvature->d2).dot(c->normal), 1, 1e-12);
    EXPECT_EQ(c->type, ContactType::face);
  }
}

// Ball centres placed R along the normal from known surface points: the CC
// is that point (R is below the smallest concave radius of curvature here).
TEST_F(WavyFace, BallCentresOffsetAlongTheNormalGiveTheirFootPoint) {
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(*face_);
  const double radius = 3;
  ContactHint hint;
  for (int i = 0; i <= 200; ++i) {
    const double u = 0.1 + 0.8 * i / 200.0, v = 0.37;
    GeomLProp_SLProps props(surface, u, v, 1, 1e-9);
    const Vector3d foot = eig(props.Value());
    Vector3d n(props.Normal().X(), props.Normal().Y(), props.Normal().Z());
    if (n.z() < 0) n = -n;
    const auto ball = geometry::ball_contact(*model_, foot + radius * n, radius, 1e-7, 1, &hint);
    ASSERT_EQ(ball.status, BallStatus::touching) << i;
    EXPECT_LT((ball.contact->point - foot).norm(), 1e-7);
    EXPECT_LT(angle_between(ball.normal, n), 1e-7);
    EXPECT_NEAR(ball.contact->uv.x(), u, 1e-7);
  }
  EXPECT_GE(hint.warm_queries, 200u);  // all but the first come from the hint
}

// Warm queries along a path give the cold answers.
TEST_F(WavyFace, WarmAndColdAgreeAlongAPath) {
  ContactHint hint;
  for (int i = 0; i <= 300; ++i) {
    const Vector3d p(2 + 96.0 * i / 300, 30 + 20 * std::sin(i / 40.0), 6);
    const auto warm = model_->closest_point(p, 1e9, &hint);
    const auto cold = model_->closest_point(p, 1e9, nullptr);
    ASSERT_TRUE(warm && cold);
    EXPECT_LT((warm->point - cold->point).norm(), 1e-9) << i;
  }
}

// A hint that asks for no curvatures gets the same answers without them
// (the post job without a report); one that asks gets them as a cold query.
TEST_F(WavyFace, CurvaturesOnlyWhenTheHintAsksForThem) {
  ContactHint without, with;
  without.curvature = false;
  for (int i = 0; i <= 100; ++i) {
    const Vector3d p(2 + 96.0 * i / 100, 30 + 20 * std::sin(i / 20.0), 6);
    const auto bare = model_->closest_point(p, 1e9, &without);
    const auto full = model_->closest_point(p, 1e9, &with);
    const auto cold = model_->closest_point(p, 1e9, nullptr);
    ASSERT_TRUE(bare && full && cold);
    EXPECT_FALSE(bare->curvature) << i;
    ASSERT_TRUE(full->curvature && cold->curvature) << i;
    EXPECT_EQ(bare->point, full->point) << i;
    EXPECT_EQ(bare->normal, full->normal) << i;
    EXPECT_EQ(bare->uv, full->uv) << i;
    EXPECT_NEAR(full->curvature->k1, cold->curvature->k1, 1e-9) << i;
    EXPECT_NEAR(full->curvature->k2, cold->curvature->k2, 1e-9) << i;
  }
}

TEST_F(WavyFace, OutsideTheFaceTheEdgeOrCornerIsTheContact) {
  // Beyond x = 100 the boundary curve at u = 1 is nearest; beyond both
  // x = 100 and y = 0, the corner pole (100, 0, z).
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(*face_);
  const auto edge = model_->closest_point({110, 50, 0}, 1e9, nullptr);
  ASSERT_TRUE(edge);
  EXPECT_EQ(edge->type, ContactType::edge);
  EXPECT_NEAR(edge->point.x(), 100, 1e-9);
  EXPECT_NEAR(edge->uv.x(), 1, 1e-9);
  // Independent: the closest point of the boundary curve u = 1 by a fine
  // scan refined by golden-section search.
  double lo = 0, hi = 1;
  const auto dist = [&](double v) {
    return (eig(surface->Value(1, v)) - Vector3d(110, 50, 0)).norm();
  };
  double best_v = 0;
  for (int i = 0; i <= 10000; ++i) {
    if (dist(i / 1e4) < dist(best_v)) best_v = i / 1e4;
  }
  lo = std::max(0.0, best_v - 1e-4);
  hi = std::min(1.0, best_v + 1e-4);
  for (int i = 0; i < 100; ++i) {
    const double a = lo + (hi - lo) * 0.382, b = lo + (hi - lo) * 0.618;
    (dist(a) < dist(b) ? hi : lo) = dist(a) < dist(b) ? b : a;
  }
  EXPECT_LT((edge->point - eig(surface->Value(1, (lo + hi) / 2))).norm(), 1e-5);
  const auto corner = model_->closest_point({120, -30, 0}, 1e9, nullptr);
  ASSERT_TRUE(corner);
  EXPECT_EQ(corner->type, ContactType::vertex);
  EXPECT_LT((corner->point - eig(surface->Value(1, 0))).norm(), 1e-9);
}

TEST_F(WavyFace, SearchDistanceAndThreads) {
  EXPECT_FALSE(model_->closest_point({50, 50, 40}, 10, nullptr));
  // Two threads, each with its own hint, give the single-thread answers.
  std::vector<Vector3d> points;
  for (int i = 0; i < 2000; ++i)
    points.emplace_back(3 + 0.047 * i, 50 + 10 * std::cos(i * 0.01), 7);
  std::vector<Vector3d> expected(points.size()), got(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    expected[i] = model_->closest_point(points[i], 1e9, nullptr)->point;
  }
  auto run = [&](std::size_t begin, std::size_t end) {
    ContactHint hint;
    for (std::size_t i = begin; i < end; ++i)
      got[i] = model_->closest_point(points[i], 1e9, &hint)->point;
  };
  std::thread a(run, 0, 1000), b(run, 1000, 2000);
  a.join();
  b.join();
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_LT((got[i] - expected[i]).norm(), 1e-9);
}

// An open face says nothing of its material: by default it is turned to
// face +z (where a 3-axis tool comes from); the option keeps it as it is.
TEST(BrepModel, OpenFacesAreOrientedUpUnlessAskedNotTo) {
  const TopoDS_Shape down = wavy_bspline_face().Reversed();
  const auto up_normal = model_from_shape(down).closest_point({50, 50, 20}, 1e9, nullptr);
  ASSERT_TRUE(up_normal);
  EXPECT_GT(up_normal->normal.z(), 0.5);
  BrepOptions keep;
  keep.orient_open_faces_up = false;
  const auto as_is = model_from_shape(down, keep).closest_point({50, 50, 20}, 1e9, nullptr);
  ASSERT_TRUE(as_is);
  EXPECT_LT((as_is->normal + up_normal->normal).norm(), 1e-12);
  // Curvatures follow the normal: their signs flip with it.
  EXPECT_NEAR(as_is->curvature->k1, -up_normal->curvature->k2, 1e-12);
  // A solid keeps its outward normals, even on its bottom face.
  const auto bottom = model_from_shape(BRepPrimAPI_MakeBox(10, 10, 10).Shape())
                          .closest_point({5, 5, -3}, 1e9, nullptr);
  EXPECT_LT((bottom->normal + Vector3d::UnitZ()).norm(), 1e-12);
}

TEST(BrepModel, TrimmedFaceWithAHoleGivesTheHoleEdge) {
  // A 100 x 100 plate at z = 0 with a hole of radius 10 at (50, 50).
  const TopoDS_Wire outer = BRepBuilderAPI_MakePolygon(gp_Pnt(0, 0, 0), gp_Pnt(100, 0, 0),
                                                       gp_Pnt(100, 100, 0), gp_Pnt(0, 100, 0), true)
                                .Wire();
  BRepBuilderAPI_MakeFace make(gp_Pln(gp::Origin(), gp::DZ()), outer);
  const gp_Circ circle(gp_Ax2(gp_Pnt(50, 50, 0), gp::DZ()), 10);
  TopoDS_Wire hole = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(circle).Edge()).Wire();
  hole.Reverse();
  make.Add(hole);
  const BrepModel model = model_from_shape(make.Face());
  const auto over_hole = model.closest_point({53, 50, 4}, 1e9, nullptr);
  ASSERT_TRUE(over_hole);
  EXPECT_EQ(over_hole->type, ContactType::edge);
  EXPECT_LT((over_hole->point - Vector3d(60, 50, 0)).norm(), 1e-9);
  EXPECT_NEAR(over_hole->distance, std::sqrt(65.0), 1e-9);
  const auto on_plate = model.closest_point({65, 50, 4}, 1e9, nullptr);
  ASSERT_TRUE(on_plate);
  EXPECT_EQ(on_plate->type, ContactType::face);
  EXPECT_LT((on_plate->point - Vector3d(65, 50, 0)).norm(), 1e-9);
  EXPECT_NEAR(std::abs(on_plate->normal.z()), 1, 1e-12);
  // Diagonal over the hole: nearest hole point along the ray from its centre.
  const Vector3d q(50 + 3, 50 + 4, 2);
  const auto diag = model.closest_point(q, 1e9, nullptr);
  ASSERT_TRUE(diag);
  EXPECT_LT((diag->point - Vector3d(56, 58, 0)).norm(), 1e-9);
}

TEST(BrepModel, BoxEdgeAndVertexContacts) {
  const BrepModel model = model_from_shape(BRepPrimAPI_MakeBox(100, 100, 100).Shape());
  EXPECT_EQ(model.face_count(), 6);
  const double radius = 5;
  const Vector3d dir(std::cos(std::numbers::pi / 6), 0, std::sin(std::numbers::pi / 6));
  const auto edge = geometry::ball_contact(model, Vector3d(100, 40, 100) + radius * dir, radius,
                                           1e-9, 1, nullptr);
  ASSERT_EQ(edge.status, BallStatus::touching);
  EXPECT_EQ(edge.contact->type, ContactType::edge);
  EXPECT_LT((edge.contact->point - Vector3d(100, 40, 100)).norm(), 1e-9);
  EXPECT_LT(angle_between(edge.normal, dir), 1e-9);
  const Vector3d diag = Vector3d(1, 1, 1).normalized();
  const auto vertex = geometry::ball_contact(model, Vector3d(100, 100, 100) + radius * diag, radius,
                                             1e-9, 1, nullptr);
  ASSERT_EQ(vertex.status, BallStatus::touching);
  EXPECT_EQ(vertex.contact->type, ContactType::vertex);
  EXPECT_LT((vertex.contact->point - Vector3d(100, 100, 100)).norm(), 1e-9);
  EXPECT_LT(angle_between(vertex.normal, diag), 1e-9);
  // Face normals of a solid point out of it.
  const auto top = model.closest_point({30, 30, 120}, 1e9, nullptr);
  EXPECT_LT((top->normal - Vector3d::UnitZ()).norm(), 1e-12);
  const auto side = model.closest_point({-7, 30, 40}, 1e9, nullptr);
  EXPECT_LT((side->normal + Vector3d::UnitX()).norm(), 1e-12);
  // Inside the box, 3 mm under the top: a gouge of R + 3.
  const auto inside = geometry::ball_contact(model, {50, 50, 97}, radius, 1e-6, 1, nullptr);
  EXPECT_EQ(inside.status, BallStatus::gouging);
  EXPECT_NEAR(inside.distance_error, -8, 1e-9);
}

TEST(BrepModel, BallInAConcaveCornerTouchesBothFaces) {
  // An L profile in xz extruded along y: floor z = 20 for x in [20, 100],
  // wall x = 20 for z in [20, 100]; the concave corner runs along y.
  BRepBuilderAPI_MakePolygon poly;
  for (const auto& [x, z] : std::vector<std::pair<double, double>>{
           {0, 0}, {100, 0}, {100, 20}, {20, 20}, {20, 100}, {0, 100}}) {
    poly.Add(gp_Pnt(x, 0, z));
  }
  poly.Close();
  const TopoDS_Shape solid =
      BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(poly.Wire()).Face(), gp_Vec(0, 60, 0)).Shape();
  const BrepModel model = model_from_shape(solid);
  const double radius = 5;
  const auto both = geometry::ball_contact(model, {25, 30, 25}, radius, 1e-9, 1, nullptr);
  ASSERT_EQ(both.status, BallStatus::touching);
  EXPECT_NEAR(both.distance_error, 0, 1e-9);
  const bool on_floor = std::abs(both.contact->point.z() - 20) < 1e-9;
  if (on_floor) {
    EXPECT_LT((both.contact->point - Vector3d(25, 30, 20)).norm(), 1e-9);
    EXPECT_LT((both.normal - Vector3d::UnitZ()).norm(), 1e-9);
  } else {
    EXPECT_LT((both.contact->point - Vector3d(20, 30, 25)).norm(), 1e-9);
    EXPECT_LT((both.normal - Vector3d::UnitX()).norm(), 1e-9);
  }
  // 0.5 mm higher: only the wall touches; the floor is 5.5 mm away.
  const auto wall = geometry::ball_contact(model, {25, 30, 25.5}, radius, 1e-9, 1, nullptr);
  ASSERT_EQ(wall.status, BallStatus::touching);
  EXPECT_LT((wall.contact->point - Vector3d(20, 30, 25.5)).norm(), 1e-9);
  EXPECT_LT((wall.contact->normal - Vector3d::UnitX()).norm(), 1e-9);
}

// Analytic B-rep faces against closed form: a solid sphere (convex,
// k = +1/r, seam and poles) and a cylindrical hole (concave, k = -1/r).
TEST(BrepModel, SphereAndCylindricalHoleAgainstClosedForm) {
  const BrepModel sphere = model_from_shape(BRepPrimAPI_MakeSphere(gp_Pnt(1, 2, 3), 20).Shape());
  std::mt19937 rng(9);
  std::normal_distribution<double> gauss;
  ContactHint hint;
  for (int i = 0; i < 200; ++i) {
    const Vector3d dir = Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const double r = i % 2 == 0 ? 26 : 13;  // outside and inside
    const Vector3d p = Vector3d(1, 2, 3) + r * dir;
    const auto c = sphere.closest_point(p, 1e9, i % 3 == 0 ? nullptr : &hint);
    ASSERT_TRUE(c);
    EXPECT_LT((c->point - (Vector3d(1, 2, 3) + 20 * dir)).norm(), 1e-9) << i;
    EXPECT_LT(angle_between(c->normal, dir), 1e-9);
    EXPECT_NEAR(c->curvature->k1, 1.0 / 20, 1e-9);
    EXPECT_NEAR(c->curvature->k2, 1.0 / 20, 1e-9);
  }
  const auto pole = sphere.closest_point({1, 2, 50}, 1e9, nullptr);
  ASSERT_TRUE(pole);
  EXPECT_LT((pole->point - Vector3d(1, 2, 23)).norm(), 1e-9);
  EXPECT_LT(angle_between(pole->normal, Vector3d::UnitZ()), 1e-6);
  EXPECT_NEAR(pole->curvature->k1, 1.0 / 20, 1e-6);
  EXPECT_NEAR(pole->curvature->k2, 1.0 / 20, 1e-6);

  // A 100 mm cube with a vertical hole of radius 15 through its middle.
  const TopoDS_Shape block = BRepAlgoAPI_Cut(
      BRepPrimAPI_MakeBox(100, 100, 100).Shape(),
      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(50, 50, -10), gp::DZ()), 15, 120).Shape());
  const BrepModel holed = model_from_shape(block);
  const auto wall = holed.closest_point({50 + 5, 50, 40}, 1e9, nullptr);
  ASSERT_TRUE(wall);
  EXPECT_LT((wall->point - Vector3d(65, 50, 40)).norm(), 1e-9);
  EXPECT_LT(angle_between(wall->normal, -Vector3d::UnitX()), 1e-9);  // into the hole
  EXPECT_NEAR(wall->curvature->k1, 0, 1e-9);
  EXPECT_NEAR(wall->curvature->k2, -1.0 / 15, 1e-9);
  // The rim of the hole at the top: an edge contact.
  const auto rim = holed.closest_point({50, 50 + 10, 104}, 1e9, nullptr);
  ASSERT_TRUE(rim);
  EXPECT_EQ(rim->type, ContactType::edge);
  EXPECT_LT((rim->point - Vector3d(50, 65, 100)).norm(), 1e-9);
}

TEST(BrepModel, InchFileIsConvertedToMillimetres) {
  // A 1 x 2 x 3 inch box written in inches: the file says INCH and holds
  // 1., 2., 3.; read back it is 25.4 x 50.8 x 76.2 mm.
  const fs::path path =
      write_step(BRepPrimAPI_MakeBox(25.4, 50.8, 76.2).Shape(), "inch_box.step", "INCH");
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_NE(text.find("INCH"), std::string::npos);
  ASSERT_NE(text.find("(1.,2.,3.)"), std::string::npos) << "no inch coordinates in the file";
  const BrepModel model = BrepModel::load_step(path);
  EXPECT_EQ(model.info().length_unit, "INCH");
  const auto c = model.closest_point({100, 10, 10}, 1e9, nullptr);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->point.x(), 25.4, 1e-9);
  const auto top = model.closest_point({10, 10, 100}, 1e9, nullptr);
  EXPECT_NEAR(top->point.z(), 76.2, 1e-9);
}

// Every shared STEP file loads (or is refused with a ModelError); loaded
// ones agree with BRepExtrema_DistShapeShape on the distance of a few
// points to the whole shape.
TEST(BrepModel, SharedStepFilesLoadAndAgreeWithBRepExtrema) {
  const fs::path dir = fs::path(VCPOST_SHARED_DATA_DIR) / "step";
  if (!fs::exists(dir)) GTEST_SKIP() << dir << " is absent";
  int loaded = 0, refused = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".stp" && ext != ".step") continue;
    SCOPED_TRACE(entry.path().filename().string());
    std::optional<BrepModel> model;
    try {
      model.emplace(BrepModel::load_step(entry.path()));
    } catch (const ModelError& error) {
      // OCCT 7.6 transfers no shape from the NIST AP242 file (bug 29241):
      // a refusal must say so with the no-faces code and the path.
      EXPECT_EQ(error.code(), Code::E4105) << error.what();
      EXPECT_NE(std::string(error.what()).find(entry.path().string()), std::string::npos);
      std::cout << "refused (allowed): " << error.what() << "\n";
      ++refused;
      continue;
    }
    ++loaded;
    EXPECT_GT(model->face_count(), 0);
    STEPControl_Reader reader;
    ASSERT_EQ(reader.ReadFile(entry.path().string().c_str()), IFSelect_RetDone);
    reader.TransferRoots();
    // The faces only: against a solid, BRepExtrema gives 0 for inner points.
    TopTools_IndexedMapOfShape face_map;
    TopExp::MapShapes(reader.OneShape(), TopAbs_FACE, face_map);
    TopoDS_Compound faces;
    BRep_Builder builder;
    builder.MakeCompound(faces);
    for (int f = 1; f <= face_map.Extent(); ++f) builder.Add(faces, face_map(f));
    const TopoDS_Shape& shape = faces;
    const Eigen::AlignedBox3d box = model->bounds();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> t(-0.1, 1.1);
    ContactHint hint;
    for (int i = 0; i < 6; ++i) {
      const Vector3d p = box.min() + Vector3d(t(rng), t(rng), t(rng)).cwiseProduct(box.sizes());
      const auto c = model->closest_point(p, 1e9, &hint);
      ASSERT_TRUE(c);
      BRepExtrema_DistShapeShape extrema(BRepBuilderAPI_MakeVertex(gp_Pnt(p.x(), p.y(), p.z())),
                                         shape);
      ASSERT_TRUE(extrema.IsDone());
      EXPECT_NEAR(c->distance, extrema.Value(), 1e-5) << "at " << p.transpose();
      EXPECT_NEAR((p - c->point).norm(), c->distance, 1e-9);
    }
  }
  EXPECT_GE(loaded, 7);
  EXPECT_LE(refused, 1);
}

// A path across many trimmed B-spline and planar faces of a real part:
// warm queries (one hint per thread, two threads) give the cold distances.
TEST(BrepModel, WarmPathAcrossFacesOfARealPartMatchesColdQueries) {
  const fs::path path = fs::path(VCPOST_SHARED_DATA_DIR) / "step" / "bug27693_cornetta-step.stp";
  if (!fs::exists(path)) GTEST_SKIP() << path << " is absent";
  const BrepModel model = BrepModel::load_step(path);
  ASSERT_EQ(model.face_count(), 110);
  const Eigen::AlignedBox3d box = model.bounds();
  std::vector<Vector3d> points;
  for (int pass = 0; pass < 4; ++pass) {
    for (int i = 0; i <= 1000; ++i) {
      const double t = i / 1000.0;
      points.push_back(
          box.min() +
          Vector3d(t, 0.2 + 0.2 * pass, 0.5 + 0.45 * std::sin(6 * t)).cwiseProduct(box.sizes()));
    }
  }
  std::vector<double> cold(points.size()), warm(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    cold[i] = model.closest_point(points[i], 1e9, nullptr)->distance;
  }
  std::vector<ContactHint> hints(2);
  auto run = [&](int k) {
    const std::size_t half = points.size() / 2;
    for (std::size_t i = half * k; i < (k == 0 ? half : points.size()); ++i) {
      warm[i] = model.closest_point(points[i], 1e9, &hints[k])->distance;
    }
  };
  std::thread a(run, 0), b(run, 1);
  a.join();
  b.join();
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_NEAR(warm[i], cold[i], 1e-9) << i;
  EXPECT_GT(hints[0].warm_queries + hints[1].warm_queries, points.size() * 9 / 10);
}

// A warm start from a query far away (a new tool's first point after the
// last point of the tool before, across the dome) is not trusted: from
// there Newton's method stopped on the far side of the sphere, 0.0545 mm
// too far, and the first point of the second ball section was "lifted".
// The dome is a sphere of radius 40 about the origin (samples/README.md):
// the closest point to c is 40 c / |c|, |c| = 45 here.
TEST(BrepModel, WarmStartFromAFarQueryFindsTheGlobalClosestPoint) {
  const BrepModel dome =
      BrepModel::load_step(fs::path(VCPOST_SOURCE_DIR) / "samples" / "dome.step");
  const Vector3d far(10.351265, 42, 12.403681), c(-10.351265, -42, 12.403681);
  ContactHint hint;
  hint.curvature = false;
  ASSERT_TRUE(dome.closest_point(far, 15, &hint));
  const auto contact = dome.closest_point(c, 15, &hint);
  ASSERT_TRUE(contact);
  EXPECT_NEAR(contact->distance, c.norm() - 40, 1e-9);
  EXPECT_LT((contact->point - 40 * c.normalized()).norm(), 1e-9);
  // Near the previous query the warm start still answers.
  const std::uint64_t warm = hint.warm_queries;
  ASSERT_TRUE(dome.closest_point(c + Vector3d(0.5, 0, 0), 15, &hint));
  EXPECT_EQ(hint.warm_queries, warm + 1);
}

void expect_error(const fs::path& path, Code code, const std::string& words) {
  try {
    (void)BrepModel::load_step(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const ModelError& error) {
    EXPECT_EQ(error.code(), code) << error.what();
    const std::string what = error.what();
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    EXPECT_NE(what.find(std::string(to_string(code))), std::string::npos) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
}

TEST(BrepModel, BadInputGetsTypedErrorsWithStableCodes) {
  const fs::path dir = temp_dir();
  expect_error(dir / "missing.step", Code::E4101, "no such file");
  expect_error(dir, Code::E4102, "directory");
  std::ofstream(dir / "empty.step").close();
  expect_error(dir / "empty.step", Code::E4103, "empty");
  std::ofstream(dir / "garbage.step") << "solid stl\nfacet normal 0 0 1\n";
  expect_error(dir / "garbage.step", Code::E4104, "not a STEP file");
  std::ofstream(dir / "points.step")
      << "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n"
         "FILE_NAME('p','2024-01-01T00:00:00',(''),(''),'','','');\n"
         "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n"
         "#1=CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;\nEND-ISO-10303-21;\n";
  expect_error(dir / "points.step", Code::E4105, "no");
  // A wire (curves only) is a valid STEP model without faces.
  const fs::path wire = write_step(
      BRepBuilderAPI_MakePolygon(gp_Pnt(0, 0, 0), gp_Pnt(10, 0, 0), gp_Pnt(10, 10, 0)).Wire(),
      "wire.step");
  expect_error(wire, Code::E4105, "no");
  // Unreadable: only meaningful when not running as root.
  const fs::path locked = dir / "locked.step";
  std::ofstream(locked) << "ISO-10303-21;\n";
  fs::permissions(locked, fs::perms::none);
  if (!std::ifstream(locked).is_open()) {
    expect_error(locked, Code::E4102, "cannot be opened");
  }
  fs::permissions(locked, fs::perms::owner_all);
}

}  // namespace
}  // namespace vcpost::occt
