#include "postproc/pipeline/point_evaluator.h"

#include <algorithm>
#include <cmath>

#include "geometry/rigid_transform.h"
#include "geometry/tool_contact.h"

namespace vcpost::pipeline {

std::string_view to_string(AeSource source) {
  switch (source) {
    case AeSource::measured:
      return "measured";
    case AeSource::given:
      return "given";
    case AeSource::first_pass:
      return "first_pass";
  }
  return "?";
}

std::string_view to_string(ApSource source) {
  switch (source) {
    case ApSource::given:
      return "given";
    case ApSource::stock:
      return "stock";
    case ApSource::clamped:
      return "clamped";
    case ApSource::air:
      return "air";
  }
  return "?";
}

PointEvaluator::PointEvaluator(const geometry::SurfaceModel& model, PointSettings settings)
    : model_(model),
      settings_(settings),
      cutting_points_(settings.cutting_points || settings.policy == DiameterPolicy::tangent
                          ? geometry::CuttingPointsWanted::yes
                          : geometry::CuttingPointsWanted::no),
      tracker_(settings.tool.diameter, 4 * settings.tool.diameter, PassTracker::kPostMemory) {}

PointResult PointEvaluator::evaluate(const PathSample& sample) {
  PointResult out;
  out.contact = contact(sample, hint_);
  place(sample, out);
  engage(sample, out);
  return out;
}

geometry::BallContact PointEvaluator::contact(const PathSample& sample,
                                              geometry::ContactHint& hint) const {
  const geometry::Tool& tool = settings_.tool;
  const Eigen::Vector3d origin = geometry::tool_origin(sample.point, tool, settings_.cl_point);
  if (sample.frame == nullptr)
    return geometry::tool_contact(model_, tool, origin, settings_.contact_tolerance, tool.diameter,
                                  &hint);
  // A tilted frame: the tool axis is its +z, so the model is turned into
  // it and everything after contact is measured there (MODELS.md 5). The
  // view is a thin decorator, cheaper to make here than to look up.
  const std::shared_ptr<const geometry::SurfaceModel> base(std::shared_ptr<void>(), &model_);
  const geometry::TransformedModel turned(base, *sample.frame);
  return geometry::tool_contact(turned, tool, origin, settings_.contact_tolerance, tool.diameter,
                                &hint);
}

geometry::BallContact PointEvaluator::contact(const PathSample& sample,
                                              const PathNormal& normal) const {
  geometry::BallContact out;
  // No normal (a pass end, a link, a lone pass): like a point lifted off
  // the surface, no target here; a section with none keeps its S.
  if (normal.source == NormalSource::kept) {
    out.status = geometry::BallStatus::lifted;
    out.center = geometry::tool_origin(sample.point, settings_.tool, settings_.cl_point);
    return out;
  }
  const geometry::Tool& tool = settings_.tool;
  const Eigen::Vector3d& n = normal.normal;
  Eigen::Vector3d center = geometry::tool_origin(sample.point, tool, settings_.cl_point);
  const Eigen::Vector3d level(n.x(), n.y(), 0);
  if (tool.flat_radius() > 0 && level.norm() > 1e-9)
    center -= tool.flat_radius() / level.norm() * level;
  out.status = geometry::BallStatus::touching;
  out.center = center;
  out.normal = n;
  geometry::ModelContact contact;
  contact.point = center - tool.corner_radius * n;
  contact.normal = n;
  contact.distance = tool.corner_radius;
  out.contact = contact;
  return out;
}

namespace {
// A level move (Z constant) along a level line of the surface (Z-level
// passes) keeps the tool's end face parallel to the feed, so its feed on
// the surface is the tangent plane's level direction, along the move.
// Projected onto the tangent plane, its chord, which cuts across the
// curved level line it follows by half the chord's turn, left the feed
// that much out of level (|F_z| 3e-3 on 0.6 mm chords round an R40
// dome): a bull-nose's face seemed to lead or trail, and the engine took
// the general route for a level cut. Along the level line means within
// 0.1 rad of it (the chord of a contour turning up to 0.2 rad): a level
// move across it (a raster's chord over a crest, its ends' Z rounded
// equal), and any other move, is projected onto the tangent plane. Zero
// where neither gives a direction (a move along the normal).
Eigen::Vector3d feed_on_surface(const Eigen::Vector3d& direction, const Eigen::Vector3d& n) {
  const Eigen::Vector3d level(-n.y(), n.x(), 0);  // z x n
  const double across = level.norm();             // |n_xy|
  const double off_level = direction.dot(n);      // |n_xy| sin(angle to the level line)
  if (direction.z() == 0 && across > 1e-9 && std::abs(off_level) <= 0.1 * across)
    return (level.dot(direction) >= 0 ? 1 / across : -1 / across) * level;
  const Eigen::Vector3d tangent = direction - off_level * n;
  return tangent.norm() > 1e-9 ? Eigen::Vector3d(tangent.normalized()) : Eigen::Vector3d::Zero();
}

bool cuts(const geometry::BallContact& contact) {
  return contact.status == geometry::BallStatus::touching ||
         contact.status == geometry::BallStatus::gouging;
}
}  // namespace

void PointEvaluator::place(const PathSample& sample, PointResult& out) {
  if (sample.frame != frame_) {
    // Another working frame: the passes cut so far lie in other coordinates.
    frame_ = sample.frame;
    tracker_ =
        PassTracker(settings_.tool.diameter, 4 * settings_.tool.diameter, PassTracker::kPostMemory);
    had_contact_ = false;
  }
  if (!cuts(out.contact)) {
    if (had_contact_) tracker_.break_pass();
    had_contact_ = false;
    return;
  }
  had_contact_ = true;

  const Eigen::Vector3d& n = out.contact.normal;
  out.feed = feed_on_surface(sample.direction, n);
  // The passes are followed by the points the model shifts by ae: the
  // previous pass is this tool moved by ae across the feed. A ball's
  // contact point moves with its centre; a bull-nose's or flat mill's goes
  // round the rim as the normal turns, up to 2 R0 across the pass, so those
  // are followed by the tool's own position (on the wavy raster their
  // contact points gave ae 0.016-0.1 mm for a 0.077 mm stepover, and the
  // tracker looked at 400 runs a step instead of 6).
  const auto neighbour =
      out.feed.isZero() ? std::nullopt : tracker_.step(tracked(sample, out.contact), n, out.feed);
  set_ae(neighbour, out);
}

Eigen::Vector3d PointEvaluator::tracked(const PathSample& sample,
                                        const geometry::BallContact& contact) const {
  const geometry::Tool& tool = settings_.tool;
  return tool.kind == geometry::ToolKind::ball
             ? contact.contact->point
             : geometry::tool_origin(sample.point, tool, settings_.cl_point);
}

void PointEvaluator::place(const PathSample& sample, PointResult& out,
                           const EarlierPass& earlier) const {
  if (!cuts(out.contact)) return;
  const Eigen::Vector3d& n = out.contact.normal;
  out.feed = feed_on_surface(sample.direction, n);
  std::optional<NeighbourPass> neighbour;
  if (earlier.found && !out.feed.isZero()) {
    // The tracker's measure (pass_tracker.h) on the earlier pass's point:
    // the distance across the feed between the points the passes follow.
    PathSample beside = sample;
    beside.point = earlier.point;
    const geometry::BallContact there =
        contact(beside, PathNormal{earlier.normal, NormalSource::two_sided});
    if (there.contact) {
      const Eigen::Vector3d d = tracked(beside, there) - tracked(sample, out.contact);
      const double across = (d - d.dot(out.feed) * out.feed).norm();
      if (across > 1e-9 && across <= settings_.tool.diameter) {
        neighbour = NeighbourPass{
            across, n.cross(out.feed).dot(d) >= 0 ? geometry::Side::left : geometry::Side::right,
            earlier.point};
      }
    }
  }
  set_ae(neighbour, out);
}

void PointEvaluator::set_ae(const std::optional<NeighbourPass>& neighbour, PointResult& out) const {
  if (settings_.ae && (settings_.ae_override || !neighbour)) {
    out.ae = *settings_.ae;
    out.ae_source = AeSource::given;
  } else if (neighbour) {
    out.ae = neighbour->ae;
    out.ae_source = AeSource::measured;
  } else {
    out.ae = settings_.tool.diameter;  // no pass beside this one: the whole leading half cuts
    out.ae_source = AeSource::first_pass;
  }
  if (neighbour) out.side = neighbour->side;
}

void PointEvaluator::engage(const PathSample& sample, PointResult& out) const {
  if (!cuts(out.contact)) return;
  out.ap = settings_.ap;
  // A tilted frame's points: the stock is a height field along the
  // machine's z, not the frame's tool axis.
  if (material_ != nullptr && sample.frame == nullptr && out.contact.contact) {
    const double limit = kMaxApShare * settings_.tool.diameter;
    const double depth = material_->depth_along(out.contact.contact->point, out.contact.normal,
                                                settings_.tool.diameter);
    if (!(depth >= air_mm_)) {
      out.ap = 0;
      out.ap_source = ApSource::air;
      return;
    }
    out.ap = std::min(depth, limit);
    out.ap_source = depth > limit ? ApSource::clamped : ApSource::stock;
  }
  const geometry::CutSetup setup{out.ap, out.ae, out.contact.normal,
                                 out.feed.isZero() ? sample.direction : out.feed, out.side};
  out.engagement = geometry::evaluate_engagement(settings_.tool, setup, cutting_points_);
  const auto& e = *out.engagement;
  out.d_ref = geometry::reference_diameter(
      settings_.policy, e, [&] { return geometry::engaged_mean_diameter(settings_.tool, setup); });
  if (out.d_ref) out.target_rpm = geometry::target_rpm(settings_.vc, *out.d_ref);
}

}  // namespace vcpost::pipeline
