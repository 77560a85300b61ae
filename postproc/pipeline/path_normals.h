// Surface normals from the toolpath alone, for posting without a model
// (docs/models.md §5, "Normals without a model"): the path of any fixed
// point of the tool (a ball's centre, its tip, a bull-nose's core disc
// centre) lies on the finished surface offset by the tool, whose normal at
// a point is the model's normal at the contact. The passes sample that path
// surface; the normal is found from the feed tangent and the neighbouring
// passes.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

namespace vcpost::pipeline {

// How the normal at a point was found.
enum class NormalSource : std::uint8_t {
  // The passes on both sides and the pass's own curvature: a parabola
  // across the passes and one along the pass through the point (second
  // order, whatever the spacings on either side).
  two_sided,
  // A pass on one side only (a first or last pass) whose own normal was
  // found two-sided: the chord to it is perpendicular to the mean of both
  // normals (second order). Or a point with no pass abeam (a pass end):
  // the normals of the two points beside it on its path carried on to it.
  one_sided,
  // No pass near enough, or none found two-sided (isolated moves, a lone
  // pass): no normal; the program's S stays.
  kept,
};
std::string_view to_string(NormalSource source);

struct PathNormal {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, n_z >= 0; meaningless when kept
  NormalSource source = NormalSource::kept;
};

// The nearest earlier pass beside a point as the forward pass tracker
// found it (where it crosses the plane across the feed, or a pass end
// abeam: the post's own tracker's rule), what its width of cut is measured
// to: that point on the path surface, and the normal there.
struct EarlierPass {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  bool found = false;  // none, or no normal there nor at the point
};

struct PathNormalCounts {
  std::uint64_t two_sided = 0, one_sided = 0, kept = 0;
  PathNormalCounts& operator+=(const PathNormalCounts& other);
};

struct PathNormalSettings {
  // Farthest neighbouring pass, mm (the tool's diameter: a pass farther
  // away removed nothing this one cuts).
  double search_radius = 10;
  // A stretch of the same pass at least this far back along the path
  // counts as another pass (a spiral's previous turn), mm.
  double min_path_gap = 40;
};

// Normals at `points`, one path in path order (a tool's fixed point at
// every sample; one tool: one offset surface). starts[i] != 0: a new pass
// starts at point i (a rapid or lost contact came before). The steps:
// tangents along the passes, the nearest earlier pass of each point by a
// pass tracker, the nearest later one from those (a point whose earlier
// pass is near point j lies on a later pass beside j), the normals. All
// but the tracker run on the calling thread's task arena in parallel.
// REQUIRES: starts.size() == points.size(), search_radius > 0.
// With `earlier` given: also the nearest earlier pass of every point
// (the width of cut without a second tracker).
std::vector<PathNormal> estimate_path_normals(std::span<const Eigen::Vector3d> points,
                                              std::span<const std::uint8_t> starts,
                                              const PathNormalSettings& settings,
                                              std::vector<EarlierPass>* earlier = nullptr);

// The normals of one path whose points arrive in path order (a program
// being read): the pass tracker, which needs path order, steps over each
// point as soon as no later point can change its tangent, so track() runs
// beside the reading; the rest runs in parallel at finish().
// estimate_path_normals() is add() of every point, then finish().
class PathNormalEstimator {
 public:
  explicit PathNormalEstimator(const PathNormalSettings& settings);
  ~PathNormalEstimator();
  PathNormalEstimator(PathNormalEstimator&&) noexcept;
  PathNormalEstimator& operator=(PathNormalEstimator&&) noexcept;

  // The next point of the path; starts_pass: a new pass starts at it (a
  // rapid or lost contact came before).
  void add(const Eigen::Vector3d& point, bool starts_pass);
  // Room for about this many points (a guess: fewer or more may come).
  void reserve(std::size_t points);
  // Steps the tracker over the points added whose tangents are settled.
  void track();
  // All points added: their normals, and with `earlier` given, their
  // nearest earlier passes. Once.
  std::vector<PathNormal> finish(std::vector<EarlierPass>* earlier = nullptr);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

PathNormalCounts count_sources(std::span<const PathNormal> normals);

}  // namespace vcpost::pipeline
