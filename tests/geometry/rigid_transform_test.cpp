// The rigid-transform decorator: turns and shifts checked against points
// worked out by hand on analytic surfaces (1e-9), the step order, the
// matrix form and its refusals, and the shared Heidenhain set-ups' design
// STL placed as their VERICUT projects place it, against each set-up's BLK
// FORM.
#include "geometry/rigid_transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "geometry/analytic_surfaces.h"
#include "geometry/mesh/mesh_model.h"
#include "geometry/mesh/stl_reader.h"

namespace vcpost::geometry {
namespace {

using Eigen::Vector3d;
namespace fs = std::filesystem;
constexpr double kTol = 1e-9;

void expect_near(const Vector3d& actual, const Vector3d& expected, double tol) {
  EXPECT_LE((actual - expected).norm(), tol)
      << "actual " << actual.transpose() << "\nexpected " << expected.transpose();
}

std::shared_ptr<const SurfaceModel> model_of(AnalyticSurface surface) {
  return std::make_shared<AnalyticModel>(std::vector<AnalyticSurface>{std::move(surface)});
}

TEST(RigidTransform, StepsApplyInTheOrderWritten) {
  // (1, 0, 0) turned 90 about X stays; then 90 about Z: (0, 1, 0).
  expect_near(parse_rigid_transform("rx=90,rz=90").apply({1, 0, 0}), {0, 1, 0}, kTol);
  // The other order: about Z first to (0, 1, 0), then about X to (0, 0, 1).
  expect_near(parse_rigid_transform("rz=90, rx=90").apply({1, 0, 0}), {0, 0, 1}, kTol);
  // Set-up B of the Heidenhain part: (1, 2, 3) -> X180 (1, -2, -3) -> Z180
  // (-1, 2, -3) -> lifted 25.25: (-1, 2, 22.25).
  expect_near(parse_rigid_transform("RX=180,rz=180,z=25.25").apply({1, 2, 3}), {-1, 2, 22.25},
              kTol);
  // Set-up A: -90 about Z takes +X to -Y.
  const RigidTransform a = parse_rigid_transform("rz=-90");
  expect_near(a.apply({1, 0, 0}), {0, -1, 0}, 0);  // quarter turns are exact
  expect_near(a.apply({0, 1, 0}), {1, 0, 0}, 0);
  // 30 degrees about Y: +X goes to (cos 30, 0, -sin 30).
  expect_near(parse_rigid_transform("ry=30").apply({1, 0, 0}), {std::sqrt(3.0) / 2, 0, -0.5}, kTol);
  // Shifts and turns do not commute: shift then turn moves the shift too.
  expect_near(parse_rigid_transform("x=10,rz=90").apply({0, 0, 0}), {0, 10, 0}, kTol);
  expect_near(parse_rigid_transform("rz=90,x=10").apply({0, 0, 0}), {10, 0, 0}, kTol);
}

TEST(RigidTransform, MatrixFormEqualsTheStepsAndReadsBack) {
  const RigidTransform steps = parse_rigid_transform("rx=180,rz=180,z=25.25");
  // Rz(180) Rx(180) = diag(-1, 1, -1) by hand.
  const RigidTransform matrix =
      parse_rigid_transform("matrix=-1,0,0,0, 0,1,0,0, 0,0,-1,25.25, 0,0,0,1");
  EXPECT_LE((steps.rotation - matrix.rotation).cwiseAbs().maxCoeff(), kTol);
  expect_near(steps.shift, matrix.shift, kTol);
  // A turn typed with 6 decimals (cos 45 = 0.707107) is taken, made orthonormal.
  const RigidTransform typed = parse_rigid_transform(
      "matrix=0.707107,-0.707107,0,1, 0.707107,0.707107,0,2, 0,0,1,3, 0,0,0,1");
  EXPECT_LE((typed.rotation - parse_rigid_transform("rz=45").rotation).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_NEAR(typed.rotation.determinant(), 1, 1e-12);
  // to_string reads back to the same transform.
  const RigidTransform odd = parse_rigid_transform("rx=17,ry=-33,rz=71,x=5,y=-6,z=7");
  const RigidTransform back = parse_rigid_transform(to_string(odd));
  EXPECT_LE((odd.rotation - back.rotation).cwiseAbs().maxCoeff(), 1e-9);
  expect_near(odd.shift, back.shift, 1e-8);
  EXPECT_EQ(to_string(RigidTransform{}), "identity");
  // inverse() undoes it.
  expect_near(odd.inverse().apply(odd.apply({1, 2, 3})), {1, 2, 3}, 1e-12);
}

void expect_refused(const std::string& text, Code code, const std::string& words) {
  try {
    parse_rigid_transform(text);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const TransformError& e) {
    EXPECT_EQ(e.code(), code) << text << ": " << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(RigidTransform, RefusesBadTextAndMatricesThatAreNotRigid) {
  expect_refused("", Code::E4110, "empty step");
  expect_refused("rz=-90,", Code::E4110, "empty step");
  expect_refused("rz", Code::E4110, "expected rx=DEG");
  expect_refused("rq=5", Code::E4110, "unknown step");
  expect_refused("rz=ninety", Code::E4110, "not a number");
  expect_refused("rz=nan", Code::E4110, "not a number");
  expect_refused("z=1e6", Code::E4110, "beyond 100000");
  expect_refused("matrix=1,0,0,0", Code::E4110, "16 numbers");
  // Scaled by 2, sheared, mirrored (det -1), projective.
  expect_refused("matrix=2,0,0,0,0,2,0,0,0,0,2,0,0,0,0,1", Code::E4111, "not orthonormal");
  expect_refused("matrix=1,0.1,0,0,0,1,0,0,0,0,1,0,0,0,0,1", Code::E4111, "not orthonormal");
  expect_refused("matrix=-1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1", Code::E4111, "mirrors");
  expect_refused("matrix=1,0,0,0,0,1,0,0,0,0,1,0,0,0.5,0,1", Code::E4111, "last row");
}

TEST(TransformedModel, SphereTurnedAndShiftedAnswersInTheProgramFrame) {
  SpherePatch sphere;
  sphere.center = {10, 0, 0};
  sphere.radius = 5;
  sphere.max_polar = 4;
  // Turned 90 about Z, then lifted 3: the centre at (0, 10, 3).
  const TransformedModel placed(model_of(sphere), parse_rigid_transform("rz=90,z=3"));
  ContactHint hint;
  const auto c = placed.closest_point({0, 20, 3}, 100, &hint);
  ASSERT_TRUE(c);
  expect_near(c->point, {0, 15, 3}, kTol);
  expect_near(c->normal, {0, 1, 0}, kTol);
  EXPECT_NEAR(c->distance, 5, kTol);
  ASSERT_TRUE(c->curvature);
  EXPECT_NEAR(c->curvature->k1, 0.2, kTol);
  EXPECT_NEAR(c->curvature->k2, 0.2, kTol);
  // The search distance is the program frame's too: 5 mm away, 4.9 finds nothing.
  EXPECT_FALSE(placed.closest_point({0, 20, 3}, 4.9, nullptr));
  const Eigen::AlignedBox3d box = placed.bounds();
  expect_near(box.min(), {-5, 5, -2}, kTol);
  expect_near(box.max(), {5, 15, 8}, kTol);
}

// A base that answers with its own plane z = 0 and keeps the hint's query
// point as the B-rep model does, recording what it saw.
class RecordingModel final : public SurfaceModel {
 public:
  mutable Vector3d seen_point = Vector3d::Zero(), seen_hint_query = Vector3d::Zero();
  std::optional<ModelContact> closest_point(const Vector3d& point, double /*max_distance*/,
                                            ContactHint* hint) const override {
    seen_point = point;
    if (hint) {
      seen_hint_query = hint->query;
      hint->query = point;
    }
    ModelContact c;
    c.point = {point.x(), point.y(), 0};
    c.distance = std::abs(point.z());
    return c;
  }
  Eigen::AlignedBox3d bounds() const override { return {}; }
  int face_count() const override { return 1; }
};

TEST(TransformedModel, HintsKeepTheProgramFramesQueryPoint) {
  const auto base = std::make_shared<RecordingModel>();
  const RigidTransform t = parse_rigid_transform("rz=90,x=5");
  const TransformedModel placed(base, t);
  ContactHint hint;
  ASSERT_TRUE(placed.closest_point({5, 2, 3}, 10, &hint));
  // The base saw the query in its frame: (5, 2, 3) less the shift, turned back.
  expect_near(base->seen_point, {2, 0, 3}, 1e-12);
  // The caller sees the hint's query point in the program's frame ...
  expect_near(hint.query, {5, 2, 3}, 1e-12);
  // ... and the base sees it in its own on the next query.
  ASSERT_TRUE(placed.closest_point({5, 3, 3}, 10, &hint));
  expect_near(base->seen_hint_query, {2, 0, 3}, 1e-12);
  expect_near(hint.query, {5, 3, 3}, 1e-12);
}

TEST(TransformedModel, CylinderCurvatureDirectionsTurnWithIt) {
  // A cylinder of radius 3 along X through the origin, turned 90 about Z
  // and lifted 5: its axis along Y at z = 5.
  CylinderPatch cylinder;
  cylinder.axis = Vector3d::UnitX();
  cylinder.reference = Vector3d::UnitY();
  cylinder.radius = 3;
  cylinder.h_min = -50;
  cylinder.h_max = 50;
  const TransformedModel placed(model_of(cylinder), parse_rigid_transform("rz=90,z=5"));
  const Vector3d query(2, 7, 15);
  const auto c = placed.closest_point(query, 100, nullptr);
  ASSERT_TRUE(c);
  // By hand: from the axis point (0, 7, 5) towards the query, 3 mm out.
  const Vector3d out = Vector3d(2, 0, 10).normalized();
  expect_near(c->point, Vector3d(0, 7, 5) + 3 * out, kTol);
  expect_near(c->normal, out, kTol);
  EXPECT_NEAR(c->distance, std::sqrt(104.0) - 3, kTol);
  ASSERT_TRUE(c->curvature);
  EXPECT_NEAR(c->curvature->k1, 1.0 / 3, kTol);
  EXPECT_NEAR(c->curvature->k2, 0, kTol);
  // The straight direction is the placed axis, Y; the curved one goes round it.
  EXPECT_NEAR(std::abs(c->curvature->d2.dot(Vector3d::UnitY())), 1, kTol);
  EXPECT_NEAR(c->curvature->d1.dot(out), 0, kTol);
  EXPECT_NEAR(c->curvature->d1.dot(Vector3d::UnitY()), 0, kTol);
  expect_near(c->curvature->d1.cross(c->curvature->d2), c->normal, kTol);
}

TEST(TransformedModel, PlaneTurnedOverFacesDown) {
  PlanePatch plane;
  plane.u_min = plane.v_min = -10;
  plane.u_max = plane.v_max = 10;
  const TransformedModel placed(model_of(plane), parse_rigid_transform("rx=180"));
  const auto c = placed.closest_point({1, 2, -3}, 10, nullptr);
  ASSERT_TRUE(c);
  expect_near(c->point, {1, 2, 0}, kTol);
  expect_near(c->normal, {0, 0, -1}, kTol);
  EXPECT_NEAR(c->distance, 3, kTol);
}

TEST(TransformedModel, AnyTurnAgreesWithTheBaseQueriedInItsFrame) {
  TorusSurface torus;
  torus.major = 8;
  torus.minor = 2;
  const auto base = model_of(torus);
  const RigidTransform t = parse_rigid_transform("rx=23,ry=-41,rz=112,x=4,y=-5,z=6");
  const TransformedModel placed(base, t);
  for (const Vector3d& q : {Vector3d(9, 1, 3), Vector3d(-4, 7, -2), Vector3d(0.5, -9, 1)}) {
    const Vector3d p = t.apply(q);
    const auto inside = base->closest_point(q, 100, nullptr);
    const auto outside = placed.closest_point(p, 100, nullptr);
    ASSERT_TRUE(inside && outside);
    expect_near(outside->point, t.apply(inside->point), 1e-12);
    expect_near(outside->normal, t.rotation * inside->normal, 1e-12);
    EXPECT_NEAR(outside->distance, inside->distance, 1e-12);
    EXPECT_EQ(outside->face, inside->face);
    EXPECT_NEAR(outside->curvature->k1, inside->curvature->k1, 1e-12);
  }
}

// The BLK FORM of a Heidenhain program: its two corners.
Eigen::AlignedBox3d blk_form(const fs::path& program) {
  std::ifstream in(program);
  std::string line;
  const std::regex corner(R"(BLK FORM 0\.[12].*X([-+.\d]+) +Y([-+.\d]+) +Z([-+.\d]+))");
  Eigen::AlignedBox3d box;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, corner))
      box.extend(Vector3d(std::stod(m[1]), std::stod(m[2]), std::stod(m[3])));
  }
  return box;
}

TEST(TransformedModel, HeidenhainDesignStlPlacedAsItsVericutProjectsFitsEachBlkForm) {
  const fs::path dir = fs::path(VCPOST_SHARED_DATA_DIR) / "corpus" / "heidenhain";
  if (!fs::exists(dir)) GTEST_SKIP() << "shared data absent: " << dir;
  const auto stl =
      std::make_shared<mesh::MeshModel>(mesh::read_stl_file(dir / "W5246NS01007_design.stl"));
  struct Setup {
    const char* program;
    const char* transform;  // the .vcproject's design STL against its NCS
  };
  // A: STL Rotation K=-90 at Z 192.25, NCS at Z 192.25. B: STL Rotation
  // I=-180 K=180 at Z 217.5, NCS at Z 239.5: lowered 22.
  for (const Setup& s : {Setup{"W5246NS01007A/W5246NS01007A8.h", "rz=-90"},
                         Setup{"W5246NS01007B/W5246NS01007B2.h", "rx=-180,rz=180,z=-22"}}) {
    SCOPED_TRACE(s.program);
    const Eigen::AlignedBox3d stock = blk_form(dir / s.program);
    ASSERT_FALSE(stock.isEmpty());
    const Eigen::AlignedBox3d placed =
        TransformedModel(stl, parse_rigid_transform(s.transform)).bounds();
    // The part lies in its stock, each face within the 0.25 mm the CAM left
    // around it (A's stock is 0.25 mm thicker at top and bottom).
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_GE(placed.min()[axis], stock.min()[axis] - 1e-6) << "axis " << axis;
      EXPECT_LE(placed.max()[axis], stock.max()[axis] + 1e-6) << "axis " << axis;
      EXPECT_LE(placed.min()[axis] - stock.min()[axis], 0.25 + 1e-6) << "axis " << axis;
      EXPECT_LE(stock.max()[axis] - placed.max()[axis], 0.25 + 1e-6) << "axis " << axis;
    }
  }
}

}  // namespace
}  // namespace vcpost::geometry
