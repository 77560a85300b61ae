// The paths of Klartext's contour approach and departure (APPR, DEP) in the
// working plane, as the TNC user's manual describes them: from the starting
// point PS through an auxiliary point PH to the first contour point PA, and
// from the last contour point PE to the end point PN. Points are those of
// the programmed contour (the tool radius is not applied, as nowhere in the
// reader); `side` is the radius compensation's: +1 RL (the tool left of the
// contour, the approach from the left), -1 RR, 0 none. Geometry only; the
// interpreter turns a path into events (docs/heidenhain.md).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

namespace vcpost::heidenhain {

// `d` turned by +90 degrees: the normal on the left of a direction.
inline Eigen::Vector2d left_normal(const Eigen::Vector2d& d) { return {-d.y(), d.x()}; }

enum class ContourLink : std::uint8_t {
  line_tangent,    // LT: on the tangent's extension, LEN from the contour
  line_normal,     // LN: on the normal, LEN from the contour
  circle_tangent,  // CT: an arc of radius R and centre angle CCA
  line_circle,     // LCT: a line tangent to an arc of radius R
};

// An approach or a departure in the plane: a straight piece and an arc, in
// the order they are run.
struct LinkPath {
  // APPR: PS -> auxiliary (a line), then auxiliary -> PA (a line, or the arc
  // when `centre` is set). DEP: PE -> auxiliary (a line, or the arc), then
  // auxiliary -> PN (a line) for LCT; PN == auxiliary for LT, LN, CT.
  Eigen::Vector2d auxiliary = Eigen::Vector2d::Zero();
  std::optional<Eigen::Vector2d> centre;
  int rotation = 0;                               // the arc's: +1 counterclockwise, -1 clockwise
  Eigen::Vector2d end = Eigen::Vector2d::Zero();  // DEP: PN
};

struct LinkInput {
  ContourLink link = ContourLink::line_tangent;
  int side = 0;       // +1 RL, -1 RR, 0 R0
  double len = 0;     // LT, LN
  double radius = 0;  // CT, LCT: R as written (its sign picks the side)
  double cca = 0;     // CT: centre angle, degrees
};

// APPR: the path from `start` (PS) to `first` (PA), whose contour goes on in
// direction `tangent` (unit). An empty path and `why` set when none exists.
std::optional<LinkPath> approach_path(const LinkInput& in, const Eigen::Vector2d& start,
                                      const Eigen::Vector2d& first, const Eigen::Vector2d& tangent,
                                      std::string& why);

// DEP: the path from `last` (PE), where the contour ran in direction
// `tangent`, to PN (`end`, given for LCT only).
std::optional<LinkPath> departure_path(const LinkInput& in, const Eigen::Vector2d& last,
                                       const Eigen::Vector2d& tangent, const Eigen::Vector2d& end,
                                       std::string& why);

}  // namespace vcpost::heidenhain
