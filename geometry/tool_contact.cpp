#include "geometry/tool_contact.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include "geometry/small_angle.h"

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

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// The angle from a to b, in (-pi, pi].
double turn(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return atan2_small(cross(a, b), a.dot(b));
}

// q turned by `angle` (by the small angles' series up to half a radian).
Eigen::Vector2d rotated(const Eigen::Vector2d& q, double angle) {
  const auto [x, y] = geometry::rotated(q.x(), q.y(), angle);
  return {x, y};
}

// On the rim the minimum lies where the rim point q faces -g (g the
// distance's gradient there): q = -R0 g/|g|. Its angle is found as the root
// of the angle from q to -g, which falls through zero there (the distance
// along the rim has its minimum), by secant steps from the last two rim
// points met: superlinear where the fixed-point step q <- -R0 g/|g| (what
// a long gradient step projected onto the disc amounts to) converges only
// linearly, slowly where the rim angle turns fast with the normal.
class RimSecant {
 public:
  // `slope`: the residual's slope in angle known from a nearby solve, 0 if none.
  explicit RimSecant(double slope) : slope_(slope) {}

  // The rim point to try after q (on the rim, g pointing into the disc).
  // (The turns and the rotation by the small angles' series: libm's
  // atan2, cos and sin took a fifth of a bull-nose contact.)
  Eigen::Vector2d next(const Eigen::Vector2d& q, const Eigen::Vector2d& g) {
    const double residual = turn(q, -g);
    if (known_) slope_ = (residual - residual_) / turn(last_, q);
    // The residual falls through a minimum; with no slope, or a rising one
    // (a maximum, or round-off at the root), the fixed-point step.
    const double step = slope_ < 0 ? std::clamp(-residual / slope_, -max_step, max_step) : residual;
    known_ = true;
    last_ = q;
    residual_ = residual;
    return rotated(q, step);
  }

  // The last slope met, 0 if none.
  double slope() const { return slope_ < 0 ? slope_ : 0; }

 private:
  static constexpr double max_step = 1.0;  // rad: a secant through a flat residual goes far
  bool known_ = false;
  Eigen::Vector2d last_ = Eigen::Vector2d::Zero();  // the last rim point
  double slope_ = 0, residual_ = 0;
};

bool on_rim(const Eigen::Vector2d& q, double radius) { return q.norm() >= (1 - 1e-12) * radius; }

// A contact found on the core disc: where (relative to the disc's centre)
// and the rim solve's last slope.
struct Found {
  BallContact contact;
  Eigen::Vector2d where;
  double rim_slope = 0;
};

// The distance minimised over the core disc of a bull-nose or flat end mill
// from one start or another; what the starts share.
class DiscSearch {
 public:
  DiscSearch(const SurfaceModel& model, const Tool& tool, const Eigen::Vector3d& origin, double rc,
             double disc, double tolerance, double search_margin, ContactHint* hint)
      : model_(model),
        origin_(origin),
        rc_(rc),
        disc_(disc),
        tolerance_(tolerance),
        reach_(2 * disc + rc + search_margin),
        smooth_(!model.faceted()),
        hint_(hint),
        long_step_(1e3 * tool.radius()),
        converged_(1e-10 * tool.radius()),
        rim_converged_(1e-8 * tool.radius()),
        round_off_(1e-12 * tool.radius()) {}

  // Over a valley the distance has a minimum on each flank, and a descent
  // warm-started on the flank the tool last touched stops on it, lifted,
  // while the tool rests on the other. Lifted means, on a smooth surface, by
  // a tenth of the tolerance: on the wavy raster 200 of 200,912 contacts
  // stopped on the wrong flank lifted by 1e-3 to 1e-2 mm, within the
  // tolerance, where the CL points touch within 1e-6 mm; a CAM program's
  // coordinates rounded to 1e-3 mm lift it by up to 5e-4 mm, which does not
  // send every point through the retries. On a mesh, by the tolerance: its
  // facets stand off the CAD surface the program was made on by their
  // chordal error (a tenth took the wavy raster over its 100 k-triangle STL
  // from 4.52 to 5.00 queries a point).
  bool lifted(const Found& found) const {
    const double lifted = smooth_ ? 0.1 * tolerance_ : tolerance_;
    return found.contact.contact && found.contact.distance_error > lifted;
  }

  // Minimise the distance over the disc. Its gradient is the contact
  // normal's horizontal part g; a step q - alpha g projected back onto the
  // disc, alpha by Barzilai-Borwein from the last two steps, very long at
  // first (on a plane the first step lands on the answer, the rim point
  // against g; on the rim a long step is the fixed point q = -R0 g/|g|).
  // rim_slope: as RimSecant's.
  Found descend(const Eigen::Vector2d& start, double rim_slope) const {
    // Two slots, the best answer so far and the latest, swapped, not copied.
    std::array<BallContact, 2> slot;
    std::array<Eigen::Vector2d, 2> where;
    int best = 0;
    where[0] = onto_disc(start, disc_);
    slot[0] = at(where[0], reach_);
    if (!slot[0].contact) return Found{slot[0], where[0]};
    Eigen::Vector2d q = where[0], g = slot[0].normal.head<2>();
    double alpha = long_step_;
    RimSecant rim(rim_slope);
    int latest = 0;
    for (int query = 1; query < 16; ++query) {
      const bool secant = smooth_ && on_rim(q, disc_) && q.dot(g) < 0;
      const Eigen::Vector2d next = secant ? rim.next(q, g) : onto_disc(q - alpha * g, disc_);
      if ((next - q).norm() <= (secant ? rim_converged_ : converged_)) {
        if (smooth_ && slot[latest].distance_error <= slot[best].distance_error + round_off_)
          best = latest;
        break;
      }
      const int spare = 1 - best;
      latest = spare;
      slot[spare] = at(next, reach_);
      where[spare] = next;
      if (!slot[spare].contact) break;
      const Eigen::Vector2d s = next - q, y = slot[spare].normal.head<2>() - g;
      const double curvature = s.dot(y);
      alpha = curvature > 0 ? s.squaredNorm() / curvature : long_step_;
      q = next;
      g = slot[spare].normal.head<2>();
      if (slot[spare].distance_error < slot[best].distance_error) best = spare;
    }
    return Found{slot[best], where[best], rim.slope()};
  }

  // A lifted answer checked from the opposite rim point and from the
  // centre (the other flank of a valley); the least distance wins.
  Found from_opposite_and_centre(Found found) const {
    const double length = found.where.norm();
    const Eigen::Vector2d opposite =
        length > 0 ? Eigen::Vector2d(-disc_ / length * found.where) : Eigen::Vector2d(disc_, 0);
    for (const Eigen::Vector2d& start : {opposite, Eigen::Vector2d(Eigen::Vector2d::Zero())}) {
      const Found other = descend(start, 0);
      if (other.contact.contact && other.contact.distance_error < found.contact.distance_error)
        found = other;
      if (!lifted(found)) break;
    }
    return found;
  }

  // Still lifted: the least distance may be against a face beyond the rim
  // that none of those starts leads to (a pocket's wall beside the tool,
  // seen from the centre and the opposite rim point only as the floor below,
  // whose distance has no gradient across the disc). The rim is sampled
  // every 22.5 degrees and searched again from its lowest sample: a plane
  // the rim comes nearer to than the answer by more than R0 (1 - cos 11.25
  // deg) is nearer than the answer at the sample facing it.
  Found from_lowest_rim_point(Found found) const {
    constexpr int kRimSamples = 16;
    // Only surface nearer than the answer matters: the samples search no
    // farther (most of a lifted path's samples then find nothing, fast).
    const double nearer = found.contact.distance_error + rc_;
    std::optional<Found> lowest;
    for (int k = 0; k < kRimSamples; ++k) {
      const double angle = 2 * std::numbers::pi * k / kRimSamples;
      const Eigen::Vector2d q(disc_ * std::cos(angle), disc_ * std::sin(angle));
      BallContact sample = at(q, nearer);
      if (sample.contact && (!lowest || sample.distance_error < lowest->contact.distance_error)) {
        lowest = Found{std::move(sample), q};
      }
    }
    if (lowest) {
      Found other = descend(lowest->where, 0);
      if (!other.contact.contact || lowest->contact.distance_error < other.contact.distance_error)
        other = std::move(*lowest);
      if (other.contact.distance_error < found.contact.distance_error) found = std::move(other);
    }
    return found;
  }

 private:
  // The ball of radius rc at disc point q against the surface within `search`.
  BallContact at(const Eigen::Vector2d& q, double search) const {
    const Eigen::Vector3d centre = origin_ + Eigen::Vector3d(q.x(), q.y(), 0);
    return classify_ball_contact(centre, rc_, tolerance_,
                                 model_.closest_point(centre, search, hint_));
  }

  const SurfaceModel& model_;
  const Eigen::Vector3d& origin_;
  const double rc_, disc_, tolerance_;
  const double reach_;  // from each disc point
  // On a smooth surface the rim residual is smooth and secant steps find its
  // root. On a mesh it is piecewise (a normal per facet) and the distance
  // along the rim has shallow minima a facet apart, which secant steps jump
  // between: there the gradient steps alone, as they always were.
  const bool smooth_;
  ContactHint* const hint_;
  const double long_step_;
  const double converged_;
  // Secant steps on the rim converge superlinearly: the point a step
  // leaves is off the root by about the step, so a step below 1e-8 R ends
  // the solve with the rim point within about 1e-8 R (5e-8 mm on a 10 mm
  // tool; the distance, at its minimum, within round-off). Gradient steps
  // converge only linearly and go on to `converged_`.
  const double rim_converged_;
  // Distances met this close are equal for all we know: the converged
  // point wins over one lower by round-off only (up to 1e-8 rad away
  // along the rim, where the distance is flat).
  const double round_off_;
};

// The rim angle turns smoothly along a path over a smooth face: a rim
// contact's next one is first sought that much further round, the turn
// changed as it changed last time, but by a tenth of the turn at most:
// where the turn changes fast (over a valley) the extrapolation
// overshoots into the other flank's basin (unbounded, 32 of the
// generator's 200,912 bull-nose contacts landed more than 1e-3 mm off
// its exact ones, 25 without the change, 23 with it bounded).
double turn_ahead(const ContactHint& hint) {
  return hint.rim_slope < 0
             ? hint.rim_turn + std::clamp(hint.rim_turn_change, -0.1 * std::abs(hint.rim_turn),
                                          0.1 * std::abs(hint.rim_turn))
             : 0;
}

// What the next contact's first guess starts from (ContactHint's rim fields).
void remember(ContactHint& hint, const Found& found, double disc) {
  const bool rim_to_rim = on_rim(hint.rim, disc) && on_rim(found.where, disc);
  const double last_turn =
      std::exchange(hint.rim_turn, rim_to_rim ? turn(hint.rim, found.where) : 0);
  hint.rim_turn_change = rim_to_rim && last_turn != 0 ? hint.rim_turn - last_turn : 0;
  hint.rim_slope = found.rim_slope;
  hint.rim = found.where;
}

}  // namespace

BallContact tool_contact(const SurfaceModel& model, const Tool& tool, const Eigen::Vector3d& origin,
                         double tolerance, double search_margin, ContactHint* hint) {
  const double rc = tool.kind == ToolKind::flat ? 0.0 : tool.corner_radius;
  const double disc = tool.kind == ToolKind::flat ? tool.radius() : tool.flat_radius();
  if (tool.kind == ToolKind::ball || !(disc > 0)) {
    return ball_contact(model, origin, tool.radius(), tolerance, search_margin, hint);
  }
  const DiscSearch search(model, tool, origin, rc, disc, tolerance, search_margin, hint);
  Found found = hint ? search.descend(rotated(hint->rim, turn_ahead(*hint)), hint->rim_slope)
                     : search.descend(Eigen::Vector2d::Zero(), 0);
  if (search.lifted(found)) found = search.from_opposite_and_centre(std::move(found));
  if (search.lifted(found)) found = search.from_lowest_rim_point(std::move(found));
  if (hint) remember(*hint, found, disc);
  return found.contact;
}

}  // namespace vcpost::geometry
