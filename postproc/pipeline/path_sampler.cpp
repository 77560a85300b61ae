#include "postproc/pipeline/path_sampler.h"

#include <algorithm>
#include <cmath>

#include "postproc/program/arc.h"

namespace vcpost::pipeline {

namespace {

// A move is cut into at most this many pieces, so one move never holds more
// than that many samples in memory whatever the spacing (longer moves get
// proportionally wider spacing: over 100 m at 1 um, over 50 km at 0.5 mm).
constexpr std::uint64_t kMaxPiecesPerMove = 100'000;

// d/du of program::arc_point: angle, radius and axis coordinate are linear in u.
Eigen::Vector3d arc_tangent(const program::ArcFeed& arc, double u) {
  const auto [i, j, k] = program::plane_axes(arc.plane);
  const double r0 = std::hypot(arc.start[i] - arc.centre[i], arc.start[j] - arc.centre[j]);
  const double r1 = std::hypot(arc.end[i] - arc.centre[i], arc.end[j] - arc.centre[j]);
  const double sweep = program::arc_sweep(arc);
  const double angle =
      std::atan2(arc.start[j] - arc.centre[j], arc.start[i] - arc.centre[i]) + sweep * u;
  const double r = r0 + (r1 - r0) * u;
  Eigen::Vector3d d;
  d[i] = (r1 - r0) * std::cos(angle) - r * sweep * std::sin(angle);
  d[j] = (r1 - r0) * std::sin(angle) + r * sweep * std::cos(angle);
  d[k] = arc.end[k] - arc.start[k];
  return d.normalized();
}

}  // namespace

PathSampler::PathSampler(double spacing) : spacing_(spacing) {}

void PathSampler::add(const program::Event& event, std::uint64_t move,
                      std::vector<PathSample>& out) {
  if (const auto* rapid = std::get_if<program::StraightTraverse>(&event)) {
    after_cut_ = false;
    last_end_ = rapid->end;
    return;
  }
  const auto* line = std::get_if<program::StraightFeed>(&event);
  const auto* arc = std::get_if<program::ArcFeed>(&event);
  if (!line && !arc) return;

  const Eigen::Vector3d start = line ? line->start : arc->start;
  const double length = line ? (line->end - line->start).norm() : program::arc_length(*arc);
  if (!(length > 0)) return;  // a zero-length move says nothing about direction
  const program::SourceRef source = line ? line->source : arc->source;
  auto point_at = [&](double u) -> Eigen::Vector3d {
    return line ? Eigen::Vector3d(line->start + u * (line->end - line->start))
                : program::arc_point(*arc, u);
  };
  auto direction_at = [&](double u) -> Eigen::Vector3d {
    if (line) return (line->end - line->start) / length;
    return arc_tangent(*arc, u);
  };

  // Most moves start exactly where the last one ended: no square roots then.
  const bool continues =
      after_cut_ && (start == last_end_ || (start - last_end_).norm() <= 1e-9 * (1 + start.norm()));
  const auto pieces = static_cast<std::uint64_t>(
      std::clamp(std::ceil(length / spacing_), 1.0, static_cast<double>(kMaxPiecesPerMove)));
  for (std::uint64_t i = continues ? 1 : 0; i <= pieces; ++i) {
    const double u = static_cast<double>(i) / static_cast<double>(pieces);
    out.push_back({point_at(u), direction_at(u), move, u, source});
  }
  after_cut_ = true;
  last_end_ = point_at(1);
}

}  // namespace vcpost::pipeline
