#include "geometry/model.h"

#include <cmath>

namespace vcpost::geometry {

std::string_view to_string(ContactType type) {
  switch (type) {
    case ContactType::face:
      return "face";
    case ContactType::edge:
      return "edge";
    case ContactType::vertex:
      return "vertex";
  }
  return "?";
}

std::string_view to_string(BallStatus status) {
  switch (status) {
    case BallStatus::touching:
      return "touching";
    case BallStatus::lifted:
      return "lifted";
    case BallStatus::gouging:
      return "gouging";
    case BallStatus::missed:
      return "missed";
  }
  return "?";
}

Eigen::Vector3d ball_center(const Eigen::Vector3d& cl_point, double radius, ClPoint kind,
                            const Eigen::Vector3d& axis) {
  return kind == ClPoint::tip ? Eigen::Vector3d(cl_point + radius * axis) : cl_point;
}

BallContact classify_ball_contact(const Eigen::Vector3d& center, double radius, double tolerance,
                                  const std::optional<ModelContact>& contact) {
  BallContact out;
  out.center = center;
  out.contact = contact;
  if (!contact) return out;
  const Eigen::Vector3d offset = center - contact->point;
  const double length = offset.norm();
  // C behind the surface means the ball's centre is in the material: a gouge
  // deeper than R, which |C - CC| alone would report as lifted.
  const bool behind = offset.dot(contact->normal) < 0;
  // Below this the direction of C - CC is noise; the surface normal is exact.
  const double tiny = 1e-12 * std::max(1.0, radius);
  if (behind || length <= tiny) {
    out.normal = contact->normal;
    out.distance_error = -length - radius;
  } else {
    out.normal = offset / length;
    out.distance_error = length - radius;
  }
  if (std::abs(out.distance_error) <= tolerance) {
    out.status = BallStatus::touching;
  } else {
    out.status = out.distance_error > 0 ? BallStatus::lifted : BallStatus::gouging;
  }
  return out;
}

BallContact ball_contact(const SurfaceModel& model, const Eigen::Vector3d& center, double radius,
                         double tolerance, double search_margin, ContactHint* hint) {
  return classify_ball_contact(center, radius, tolerance,
                               model.closest_point(center, radius + search_margin, hint));
}

}  // namespace vcpost::geometry
