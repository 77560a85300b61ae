// The local frame of one cutting situation, shared by the tool engines.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "geometry/engagement.h"

namespace vcpost::geometry {

// F = unit(feed projected onto the tangent plane), S0 = N x F (points to the
// left looking along F with N up), N = unit normal. A point P has the frame
// coordinates a = F.P, b = S0.P, c = N.P.
struct CutFrame {
  Eigen::Vector3d feed, side, normal;
  double sigma;  // +1: previous pass on the left (at +ae S0), -1: on the right
};

// Flags for input the engines cannot evaluate (zero or negative ap/ae,
// ap >= D, undercut, feed along the normal, zero vectors). When a flag that
// makes the cut meaningless is set, `frame` is empty.
struct CutCheck {
  EngagementFlags flags;
  std::optional<CutFrame> frame;
  bool rim_exists = false;  // the stock plane cuts the tool: cutting points exist
  bool can_engage = false;  // also ae > 0: an engaged zone of positive area may exist
};

CutCheck check_cut(const Tool& tool, const CutSetup& setup);

}  // namespace vcpost::geometry
