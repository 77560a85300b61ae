// Samples along the cutting moves: the points where contact and working
// diameter are evaluated.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "geometry/rigid_transform.h"
#include "postproc/program/events.h"

namespace vcpost::pipeline {

struct PathSample {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // programmed (CL) point, mm
  Eigen::Vector3d direction =
      Eigen::Vector3d::UnitX();  // unit motion direction (arc tangent on arcs)
  std::uint64_t move = 0;        // index of the motion event it lies on
  double fraction = 1;           // position along that move, (0, 1]; 0 = its start
  program::SourceRef source;     // the block (record) of that move
  // A tilted working frame's (3+2): point and direction are in its
  // coordinates, and this places the program frame's model in them (the
  // inverse of program::WorkingFrame); null in the untilted program. Owned
  // by the reader, which keeps every frame it met.
  const geometry::RigidTransform* frame = nullptr;
};

// Splits cutting moves (straight and arc feeds) into samples no further
// apart than `spacing` mm: every move gives its end point and evenly spaced
// intermediate points, and its start point too when it does not continue a
// cutting move (after a rapid, at the program's start). Rapids give none.
class PathSampler {
 public:
  // REQUIRES: spacing > 0.
  explicit PathSampler(double spacing);

  // Appends the samples of `event`; `move` is its index among the motion
  // events (counted by the caller), stored in the samples.
  void add(const program::Event& event, std::uint64_t move, std::vector<PathSample>& out);

 private:
  double spacing_;
  bool after_cut_ = false;
  Eigen::Vector3d last_end_ = Eigen::Vector3d::Constant(NAN);
};

}  // namespace vcpost::pipeline
