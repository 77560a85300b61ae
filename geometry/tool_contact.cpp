#include "geometry/tool_contact.h"

#include <array>
#include <cmath>

namespace vcpost::geometry {

Eigen::Vector3d tool_origin(const Eigen::Vector3d& cl_point, const Tool& tool, ClPoint kind) {
  return kind == ClPoint::tip
             ? Eigen::Vector3d(cl_point + tool.corner_radius * Eigen::Vector3d::UnitZ())
             : cl_point;
}

namespace {

// The point of the disc |q| <= radius nearest to q.
Eigen::Vector2d onto_disc(const Eigen::Vector2d& q, double radius) {
  const double length = q.norm();
  return length > radius ? Eigen::Vector2d(q * (radius / length)) : q;
}

}  // namespace

BallContact tool_contact(const SurfaceModel& model, const Tool& tool, const Eigen::Vector3d& origin,
                         double tolerance, double search_margin, ContactHint* hint) {
  const double rc = tool.kind == ToolKind::flat ? 0.0 : tool.corner_radius;
  const double disc = tool.kind == ToolKind::flat ? tool.radius() : tool.flat_radius();
  if (tool.kind == ToolKind::ball || !(disc > 0)) {
    return ball_contact(model, origin, tool.radius(), tolerance, search_margin, hint);
  }
  const double reach = 2 * disc + rc + search_margin;
  const auto at = [&](const Eigen::Vector2d& q) {
    const Eigen::Vector3d centre = origin + Eigen::Vector3d(q.x(), q.y(), 0);
    return classify_ball_contact(centre, rc, tolerance, model.closest_point(centre, reach, hint));
  };
  // Minimise the distance over the disc. Its gradient is the contact
  // normal's horizontal part g; a step q - alpha g projected back onto the
  // disc, alpha by Barzilai-Borwein from the last two steps, very long at
  // first (on a plane the first step lands on the answer, the rim point
  // against g; on the rim a long step is the fixed point q = -R0 g/|g|).
  const double long_step = 1e3 * tool.radius();
  const double converged = 1e-10 * tool.radius();
  struct Found {
    BallContact contact;
    Eigen::Vector2d where;
  };
  const auto descend = [&](const Eigen::Vector2d& start) {
    // Two slots, the best answer so far and the latest, swapped, not copied.
    std::array<BallContact, 2> slot;
    std::array<Eigen::Vector2d, 2> where;
    int best = 0;
    where[0] = onto_disc(start, disc);
    slot[0] = at(where[0]);
    if (!slot[0].contact) return Found{slot[0], where[0]};
    Eigen::Vector2d q = where[0], g = slot[0].normal.head<2>();
    double alpha = long_step;
    for (int query = 1; query < 16; ++query) {
      const Eigen::Vector2d next = onto_disc(q - alpha * g, disc);
      if ((next - q).norm() <= converged) break;
      const int spare = 1 - best;
      slot[spare] = at(next);
      where[spare] = next;
      if (!slot[spare].contact) break;
      const Eigen::Vector2d s = next - q, y = slot[spare].normal.head<2>() - g;
      const double curvature = s.dot(y);
      alpha = curvature > 0 ? s.squaredNorm() / curvature : long_step;
      q = next;
      g = slot[spare].normal.head<2>();
      if (slot[spare].distance_error < slot[best].distance_error) best = spare;
    }
    return Found{slot[best], where[best]};
  };
  Found found = descend(hint ? hint->rim : Eigen::Vector2d::Zero());
  // Over a valley the distance has a minimum on each flank, and a descent
  // warm-started on the flank the tool last touched stops on it, lifted,
  // while the tool rests on the other. A lifted answer is checked from the
  // opposite rim point and from the centre; the least distance wins.
  if (found.contact.contact && found.contact.distance_error > tolerance) {
    const double length = found.where.norm();
    const Eigen::Vector2d opposite =
        length > 0 ? Eigen::Vector2d(-disc / length * found.where) : Eigen::Vector2d(disc, 0);
    for (const Eigen::Vector2d& start : {opposite, Eigen::Vector2d(Eigen::Vector2d::Zero())}) {
      const Found other = descend(start);
      if (other.contact.contact && other.contact.distance_error < found.contact.distance_error)
        found = other;
      if (found.contact.distance_error <= tolerance) break;
    }
  }
  if (hint) hint->rim = found.where;
  return found.contact;
}

}  // namespace vcpost::geometry
