// PLANE PROJECTED, POINTS and AXIAL: the tilted frame each gives, worked
// out by hand (c = sqrt(1/2)), and checked against the SPATIAL angle that
// one projection or axis angle alone stands for. Tolerance 1e-12.
#include "postproc/heidenhain/plane_forms.h"

#include <gtest/gtest.h>

#include <cmath>

#include "postproc/program/working_frame.h"
#include "tests/postproc/heidenhain/klartext_support.h"

namespace vcpost::heidenhain {
namespace {

using program::Event;
using testing::error_of;
using testing::run;

// The rotation of the (last) WorkingFrame the program gives.
Eigen::Matrix3d frame_of(const std::string& plane) {
  const auto events = run("BEGIN PGM T MM\n" + plane + "\nL X+1 Y+2 Z+3 FMAX\nEND PGM T MM\n");
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  for (const Event& e : events)
    if (const auto* f = std::get_if<program::WorkingFrame>(&e)) r = f->rotation;
  return r;
}

void expect_matrix(const Eigen::Matrix3d& got, const Eigen::Matrix3d& want) {
  EXPECT_TRUE(got.isApprox(want, 1e-12)) << got << "\nwanted\n" << want;
}

TEST(KlartextPlaneForms, ProjectedAnglesAloneAreSpatialAngles) {
  expect_matrix(frame_of("PLANE PROJECTED PROPR+30 PROMIN+0 ROT+0 STAY"),
                program::spatial_angles(0, 30, 0));
  expect_matrix(frame_of("PLANE PROJECTED PROPR+0 PROMIN+20 ROT+0 STAY"),
                program::spatial_angles(20, 0, 0));
  expect_matrix(frame_of("PLANE PROJECTED PROPR+0 PROMIN+0 ROT+25 STAY"),
                program::spatial_angles(0, 0, 25));
}

// PROPR+45 PROMIN+45: x = Ry(45) X = (c, 0, -c), Rx(45) Y = (0, c, c),
// z = x cross that, normalised: (1, -1, 1)/sqrt3; y = z cross x =
// (1, 2, 1)/sqrt6. ROT+90 turns x onto y: x'' = y, y'' = -x.
TEST(KlartextPlaneForms, ProjectedBothAnglesAndRotation) {
  const double c = std::sqrt(0.5), s3 = std::sqrt(3.0), s6 = std::sqrt(6.0);
  Eigen::Matrix3d want;
  want.col(0) << c, 0, -c;
  want.col(1) << 1 / s6, 2 / s6, 1 / s6;
  want.col(2) << 1 / s3, -1 / s3, 1 / s3;
  expect_matrix(frame_of("PLANE PROJECTED PROPR+45 PROMIN+45 ROT+0 STAY"), want);
  Eigen::Matrix3d turned;
  turned.col(0) = want.col(1);
  turned.col(1) = -want.col(0);
  turned.col(2) = want.col(2);
  expect_matrix(frame_of("PLANE PROJECTED PROPR+45 PROMIN+45 ROT+90 STAY"), turned);
  // The plane's trace in YZ is at PROMIN from Y: the in-plane direction
  // with x = 0 is (0, 1, 1)/sqrt2.
  EXPECT_NEAR(want.col(2).dot(Eigen::Vector3d(0, c, c)), 0, 1e-12);
  EXPECT_EQ(error_of("BEGIN PGM T MM\nPLANE PROJECTED PROPR+90 PROMIN+90 ROT+0 STAY\n"),
            Code::E3320);
}

// POINTS (0,0,0), (10,0,0), (0,10,10): x = (1,0,0), z from (10,0,0) x
// (0,10,10) = (0,-100,100): (0,-c,c), y = (0,c,c): SPATIAL SPA+45.
TEST(KlartextPlaneForms, PointsAndAxial) {
  expect_matrix(frame_of("PLANE POINTS P1X+0 P1Y+0 P1Z+0 P2X+10 P2Y+0 P2Z+0 P3X+0 P3Y+10 "
                         "P3Z+10 STAY"),
                program::spatial_angles(45, 0, 0));
  // The same plane from points elsewhere: only directions count.
  expect_matrix(frame_of("PLANE POINTS P1X+5 P1Y+5 P1Z+5 P2X+25 P2Y+5 P2Z+5 P3X+7 P3Y+15 "
                         "P3Z+15 STAY"),
                program::spatial_angles(45, 0, 0));
  expect_matrix(frame_of("PLANE AXIAL B+30 STAY"), program::spatial_angles(0, 30, 0));
  expect_matrix(frame_of("PLANE AXIAL A-90 C+0 STAY"), program::spatial_angles(-90, 0, 0));
  EXPECT_EQ(error_of("BEGIN PGM T MM\nPLANE POINTS P1X+0 P1Y+0 P1Z+0 P2X+10 P2Y+0 P2Z+0 "
                     "P3X+20 P3Y+0 P3Z+0 STAY\n"),
            Code::E3320);  // on one line
  EXPECT_EQ(error_of("BEGIN PGM T MM\nPLANE AXIAL A+10 C+20 STAY\n"), Code::E3320);
}

}  // namespace
}  // namespace vcpost::heidenhain
