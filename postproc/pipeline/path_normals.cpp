#include "postproc/pipeline/path_normals.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <optional>

#include "postproc/pipeline/pass_tracker.h"

namespace vcpost::pipeline {

std::string_view to_string(NormalSource source) {
  switch (source) {
    case NormalSource::two_sided:
      return "two_sided";
    case NormalSource::one_sided:
      return "one_sided";
    case NormalSource::kept:
      return "kept";
  }
  return "?";
}

PathNormalCounts& PathNormalCounts::operator+=(const PathNormalCounts& other) {
  two_sided += other.two_sided;
  one_sided += other.one_sided;
  kept += other.kept;
  return *this;
}

PathNormalCounts count_sources(std::span<const PathNormal> normals) {
  PathNormalCounts counts;
  for (const PathNormal& n : normals) {
    switch (n.source) {
      case NormalSource::two_sided:
        ++counts.two_sided;
        break;
      case NormalSource::one_sided:
        ++counts.one_sided;
        break;
      case NormalSource::kept:
        ++counts.kept;
        break;
    }
  }
  return counts;
}

namespace {

using Eigen::Vector3d;

// The path runs on smoothly through a point when its segments turn by less
// than this (30 deg); a sharper turn is a corner (a zig-zag's turn onto a
// link), where each side has its own tangent.
constexpr double smooth_cos = 0.866;
// Points closer than this are one point, mm.
constexpr double same_point = 1e-9;
// A one-sided normal needs the chord to the neighbour nearly across the
// surface (|c.n| is half the turn between the passes) and the normals of
// the two passes within 30 deg of each other: beyond, the passes are too
// far apart for the surface between them to be one smooth piece.
constexpr double one_sided_max_turn_cos = 0.866;

bool smooth(const Vector3d& in, const Vector3d& out) {
  const double a = in.norm(), b = out.norm();
  return a > same_point && b > same_point && in.dot(out) >= smooth_cos * a * b;
}

// The previous point of the pass distinct from point i (none at the pass start).
std::optional<std::size_t> before(std::span<const Vector3d> p, std::span<const std::uint8_t> starts,
                                  std::size_t i) {
  for (std::size_t j = i; j > 0 && starts[j] == 0;) {
    --j;
    if ((p[j] - p[i]).norm() > same_point) return j;
  }
  return std::nullopt;
}
std::optional<std::size_t> after(std::span<const Vector3d> p, std::span<const std::uint8_t> starts,
                                 std::size_t i) {
  for (std::size_t j = i + 1; j < p.size() && starts[j] == 0; ++j) {
    if ((p[j] - p[i]).norm() > same_point) return j;
  }
  return std::nullopt;
}

// The unit tangent at point i, forward, to second order from i and the
// next two points on one side (j next to it, ahead or behind): with d1 at
// s1 and d2 at s2 (same sign, |s2| > |s1|), s2^2 d1 - s1^2 d2 = s1 s2 (s2 -
// s1) T. The chord to j where the path turns at j.
Vector3d one_sided(std::span<const Vector3d> p, std::span<const std::uint8_t> starts, std::size_t i,
                   std::size_t j, bool ahead) {
  const Vector3d d1 = p[j] - p[i];
  const double s1 = ahead ? d1.norm() : -d1.norm();
  const Vector3d along1 = ahead ? d1 : Vector3d(-d1);
  const auto k = ahead ? after(p, starts, j) : before(p, starts, j);
  if (k) {
    const Vector3d d2 = p[*k] - p[i];
    const Vector3d along2 = ahead ? Vector3d(p[*k] - p[j]) : Vector3d(p[j] - p[*k]);
    const double s2 = ahead ? d2.norm() : -d2.norm();
    if (smooth(along1, along2) && std::abs(s2) > std::abs(s1) * (1 + 1e-6)) {
      const Vector3d t = s2 * s2 * d1 - s1 * s1 * d2;
      const double sign = s1 * s2 * (s2 - s1) > 0 ? 1 : -1;
      return (sign * t).normalized();
    }
  }
  return along1.normalized();
}

// The unit tangent at point i along its pass, to second order: the
// derivative at i of the parabola through i and its two neighbours (d+ at
// arc a ahead, d- at b behind: d = s T + s^2 K / 2 + O(s^3) gives
// b^2 d+ - a^2 d- = ab (a + b) T), or of the one through i and the next two
// on one side (at a corner or a pass end: the side with the longer
// segment). Zero where the pass has no other point.
struct Tangent {
  Vector3d along = Vector3d::Zero();
  bool smooth = false;  // from both sides: the pass runs on smoothly through the point
};

Tangent tangent_at(std::span<const Vector3d> p, std::span<const std::uint8_t> starts,
                   std::size_t i) {
  const auto prev = before(p, starts, i);
  const auto next = after(p, starts, i);
  if (prev && next) {
    const Vector3d dm = p[*prev] - p[i], dp = p[*next] - p[i];
    if (smooth(-dm, dp)) {
      const double a = dp.norm(), b = dm.norm();
      return {(b * b * dp - a * a * dm).normalized(), true};
    }
  }
  // One side: d1 at s1, d2 at s2 (same sign, |s2| > |s1|): s2^2 d1 - s1^2 d2
  // = s1 s2 (s2 - s1) T.
  if (prev && next) {
    return {(p[*prev] - p[i]).norm() >= (p[*next] - p[i]).norm()
                ? one_sided(p, starts, i, *prev, false)
                : one_sided(p, starts, i, *next, true),
            false};
  }
  if (prev) return {one_sided(p, starts, i, *prev, false), false};
  if (next) return {one_sided(p, starts, i, *next, true), false};
  return {};
}

// A direction across the feed for the tracker's frame (its side and
// distances only): the vertical, or x on a steep feed, made perpendicular.
Vector3d across_feed(const Vector3d& feed) {
  Vector3d up = Vector3d::UnitZ() - feed.z() * feed;
  if (up.norm() < 0.1) up = Vector3d::UnitX() - feed.x() * feed;
  return up.normalized();
}

// The point of the nearest other pass abeam of a point: on the segment from
// point `from` to point `to` of the path, at `fraction` of the way.
struct Neighbour {
  Vector3d point = Vector3d::Zero();
  std::size_t from = 0, to = 0;
  double fraction = 1;
  bool found = false;
};

// The nearest earlier pass at every point, found as the points arrive in
// path order: a point is stepped once its tangent is settled (no later
// point changes it: the pass goes on by two distinct points, or ends).
class EarlierPasses {
 public:
  explicit EarlierPasses(const PathNormalSettings& settings)
      : tracker_(settings.search_radius, settings.min_path_gap, PassTracker::kPostMemory) {}

  // Steps the tracker over the points of `p` not stepped yet, up to the
  // first whose tangent is not settled (all of them when `all`).
  void track(std::span<const Vector3d> p, std::span<const std::uint8_t> starts, bool all) {
    while (tangents_.size() < p.size() && (all || settled(p, starts, tangents_.size())))
      step(p, starts, tangents_.size());
  }
  void reserve(std::size_t points) {
    index_of_.reserve(points);
    tangents_.reserve(points);
    out_.reserve(points);
  }
  std::vector<Tangent> take_tangents() { return std::move(tangents_); }
  std::vector<Neighbour> take_neighbours() { return std::move(out_); }

 private:
  static bool settled(std::span<const Vector3d> p, std::span<const std::uint8_t> starts,
                      std::size_t i) {
    const Vector3d* last = &p[i];
    int distinct = 0;
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      if (starts[j] != 0) return true;
      if ((p[j] - *last).norm() > same_point) {
        if (++distinct == 2) return true;
        last = &p[j];
      }
    }
    return false;
  }

  void step(std::span<const Vector3d> p, std::span<const std::uint8_t> starts, std::size_t i) {
    const Tangent& tangent = tangents_.emplace_back(tangent_at(p, starts, i));
    Neighbour& nb = out_.emplace_back();
    if (starts[i] != 0 && open_) tracker_.break_pass();
    const Vector3d& t = tangent.along;
    if (t.isZero()) {  // a lone point: no feed to look across
      if (open_) tracker_.break_pass();
      open_ = false;
      return;
    }
    open_ = true;
    const auto found = tracker_.step(p[i], across_feed(t), t);
    index_of_.push_back(i);
    if (!found) return;
    nb.found = true;
    nb.point = found->point;
    nb.to = index_of_[found->entry];
    nb.from = found->fraction < 1 && found->entry > 0 ? index_of_[found->entry - 1] : nb.to;
    nb.fraction = found->fraction;
  }

  PassTracker tracker_;
  std::vector<std::size_t> index_of_;  // the point of each tracker step
  std::vector<Tangent> tangents_;      // of the points stepped
  std::vector<Neighbour> out_;
  bool open_ = false;
};

// The nearest later pass at every point, from the earlier passes: a point
// whose earlier pass runs through point j lies on a later pass beside j
// (the nearest such point names it). A point none names takes the later
// pass named at the nearest point of its own pass that has one, within
// `reach` along the pass (a later pass sampled more sparsely names fewer
// points). That is a point of the later pass near the plane across the
// feed; crossing() follows the pass to the plane. As for the tracker, only
// a pass within 45 deg of the point's feed counts (not at a corner, whose
// feed turns onto a link).
std::vector<Neighbour> later_neighbours(std::span<const Neighbour> earlier,
                                        std::span<const Vector3d> p,
                                        std::span<const std::uint8_t> starts,
                                        std::span<const Tangent> tangents, double reach) {
  constexpr std::size_t unnamed = std::numeric_limits<std::size_t>::max();
  constexpr double far = std::numeric_limits<double>::infinity();
  const std::size_t n = p.size();
  std::vector<std::size_t> named(n, unnamed);  // the later point naming point j
  std::vector<double> across(n, far);          // and how far across it lies
  for (std::size_t i = 0; i < n; ++i) {
    const Neighbour& nb = earlier[i];
    if (!nb.found) continue;
    const double d = (p[i] - nb.point).norm();
    for (const std::size_t j : {nb.from, nb.to}) {
      if (d < across[j]) {
        across[j] = d;
        named[j] = i;
      }
    }
  }
  // The nearest point of the same pass that is named, either way along it.
  std::vector<std::size_t> source(n, unnamed);
  std::vector<double> along(n, far);
  std::size_t last = unnamed;
  double since = 0;
  for (std::size_t j = 0; j < n; ++j) {
    since = starts[j] != 0 || j == 0 ? 0 : since + (p[j] - p[j - 1]).norm();
    if (starts[j] != 0) last = unnamed;
    if (named[j] != unnamed) {
      last = j;
      since = 0;
    }
    if (last != unnamed && since <= reach) {
      source[j] = last;
      along[j] = since;
    }
  }
  last = unnamed;
  for (std::size_t k = n; k-- > 0;) {
    const bool pass_ends = k + 1 == n || starts[k + 1] != 0;
    since = pass_ends ? 0 : since + (p[k + 1] - p[k]).norm();
    if (pass_ends) last = unnamed;
    if (named[k] != unnamed) {
      last = k;
      since = 0;
    }
    if (last != unnamed && since <= reach && since < along[k]) source[k] = last;
  }
  std::vector<Neighbour> out(n);
  for (std::size_t j = 0; j < n; ++j) {
    if (source[j] == unnamed) continue;
    const std::size_t i = named[source[j]];
    if (std::abs(tangents[i].along.dot(tangents[j].along)) < PassTracker::kParallelCos) continue;
    out[j] = {p[i], i, i, 1, true};
  }
  return out;
}

// The neighbour's point on the path surface: its pass's points lie on it,
// the straight segment between two of them only within its sagitta (the
// CAM's chord tolerance, as much as the spacing of the passes' heights
// differ by on a 0.1 mm stepover). So the segment is followed as the cubic
// through its ends with their tangents (Hermite).
Vector3d on_surface(const Neighbour& nb, std::span<const Vector3d> p,
                    std::span<const std::uint8_t> starts, std::span<const Tangent> tangents) {
  if (!nb.found) return nb.point;
  if (nb.from == nb.to || nb.fraction >= 1 || nb.fraction <= 0) return nb.point;
  // The segment forward, lo -> hi, and its ends' tangents along it: at a
  // pass end or a corner the one-sided tangent of this segment's side.
  const std::size_t lo = std::min(nb.from, nb.to), hi = std::max(nb.from, nb.to);
  const double f = nb.from < nb.to ? nb.fraction : 1 - nb.fraction;
  const Vector3d ta = tangents[lo].smooth ? tangents[lo].along : one_sided(p, starts, lo, hi, true);
  const Vector3d tb =
      tangents[hi].smooth ? tangents[hi].along : one_sided(p, starts, hi, lo, false);
  const Vector3d& a = p[lo];
  const Vector3d& b = p[hi];
  const double length = (b - a).norm();
  const double f2 = f * f, f3 = f2 * f;
  return (2 * f3 - 3 * f2 + 1) * a + (f3 - 2 * f2 + f) * length * ta + (-2 * f3 + 3 * f2) * b +
         (f3 - f2) * length * tb;
}

// The neighbour's pass where it crosses the plane across the feed t
// through P: the tracker names a point of that pass nearest across, which
// may lie up to a tenth of its search radius along the feed (its ties are
// within 0.001 mm across, what ae needs), and there the surface has left
// the plane by half the feed's curvature times that offset squared (1 mm
// along on an R100 cylinder at 45 deg: 0.003 mm, 1 deg on a 0.1 mm
// stepover). So the pass is followed from there, segment by segment while
// it runs along the feed, to the segment that crosses the plane. None when
// it ends first (its end is abeam, not a crossing).
std::optional<Neighbour> crossing(const Neighbour& nb, const Vector3d& P, const Vector3d& t,
                                  std::span<const Vector3d> p,
                                  std::span<const std::uint8_t> starts) {
  constexpr int max_steps = 256;
  auto h = [&](std::size_t k) { return (p[k] - P).dot(t); };
  auto joined = [&](std::size_t a) {  // the segment a -> a + 1 belongs to the pass and runs along t
    if (a + 1 >= p.size() || starts[a + 1] != 0) return false;
    const Vector3d d = p[a + 1] - p[a];
    return std::abs(d.dot(t)) >= 0.5 * d.norm() && d.norm() > same_point;
  };
  std::size_t a = std::min(nb.from, nb.to);
  if (nb.from == nb.to) {
    if (a + 1 < p.size() && joined(a) && (h(a) <= 0) != (h(a + 1) <= 0)) {
    } else if (a > 0 && joined(a - 1)) {
      a -= 1;
    } else if (!joined(a)) {
      return std::nullopt;
    }
  }
  for (int step = 0; step < max_steps; ++step) {
    if (!joined(a)) return std::nullopt;
    const double ha = h(a), hb = h(a + 1);
    if ((ha <= 0) != (hb <= 0) || hb == 0) {
      Neighbour out;
      out.from = a;
      out.to = a + 1;
      out.fraction = ha == hb ? 1.0 : ha / (ha - hb);
      out.point = p[a] + out.fraction * (p[a + 1] - p[a]);
      out.found = true;
      return out;
    }
    // Towards the plane: the end of the segment nearer to it along the feed.
    const bool forward = std::abs(hb) < std::abs(ha);
    if (forward) {
      a += 1;
    } else {
      if (a == 0) return std::nullopt;
      a -= 1;
    }
  }
  return std::nullopt;
}

// The unit vector of v across the feed t (its part perpendicular to t).
Vector3d across(const Vector3d& v, const Vector3d& t) { return v - v.dot(t) * t; }

// Oriented out of the material: towards the tool, which is above (n_z >= 0).
Vector3d oriented(const Vector3d& n, const Vector3d& t) {
  const double up = n.dot(across_feed(t));
  return up < 0 ? Vector3d(-n) : n;
}

// Second order from the passes on both sides: the parabola across the
// passes through the point and its neighbours d1 (at s1 > 0) and d2 (at
// s2 < 0) has the tangent s2^2 d1 - s1^2 d2 (see tangent_at).
std::optional<Vector3d> two_sided(const Vector3d& t, const Vector3d& d1, const Vector3d& d2) {
  const Vector3d a1 = across(d1, t), a2 = across(d2, t);
  if (a1.dot(a2) >= 0) return std::nullopt;  // both on one side
  const double h1 = a1.norm(), h2 = a2.norm();
  if (h1 < same_point || h2 < same_point) return std::nullopt;
  const Vector3d w = h2 * h2 * a1 - h1 * h1 * a2;
  const Vector3d n = t.cross(w);
  if (n.norm() < same_point) return std::nullopt;
  return oriented(n.normalized(), t);
}

// One path's normals, step by step (estimate_path_normals).
class Estimate {
 public:
  Estimate(std::span<const Vector3d> points, std::span<const std::uint8_t> starts,
           const PathNormalSettings& settings, std::vector<Tangent> tangents,
           std::vector<Neighbour> earlier)
      : p_(points),
        starts_(starts),
        settings_(settings),
        tangents_(std::move(tangents)),
        earlier_(std::move(earlier)),
        later_(later_neighbours(earlier_, p_, starts_, tangents_, settings_.search_radius)) {}

  void find_normals() {
    tbb::parallel_for(blocks(p_.size()), [&](const auto& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) later_[i] = abeam(later_[i], i);
    });
    out_.assign(p_.size(), PathNormal{});
    tbb::parallel_for(blocks(p_.size()), [&](const auto& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        if (!earlier_[i].found || !later_[i].found) continue;
        const Neighbour earlier = abeam(earlier_[i], i);
        if (!earlier.found) continue;
        const auto normal = two_sided(tangents_[i].along, on_surface(earlier) - p_[i],
                                      on_surface(later_[i]) - p_[i]);
        if (normal) out_[i] = {*normal, NormalSource::two_sided};
      }
    });
    fill_kept([&](std::size_t i) { return one_sided_normal(i); });
    fill_kept([&](std::size_t i) {
      auto m = carried_normal(i, false);
      return m ? m : carried_normal(i, true);
    });
  }
  std::vector<PathNormal> take_normals() { return std::move(out_); }

  // After find_normals(): the earlier neighbour as the tracker found it
  // (for the width of cut, measured as the post's own tracker measures it:
  // a pass end abeam counts, where a normal needs the pass where it crosses
  // the plane) on the path surface, with the normal between those of its segment's ends (either
  // end's where the other has none, the point's own where neither has: a
  // ring closing on its own start, whose first points have no pass before
  // them, lies within ae of it).
  std::vector<EarlierPass> earlier_passes() const {
    std::vector<EarlierPass> passes(p_.size());
    tbb::parallel_for(blocks(p_.size()), [&](const auto& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        const Neighbour& nb = earlier_[i];
        if (!nb.found) continue;
        const PathNormal& to = out_[nb.to];
        const PathNormal& from = out_[nb.from];
        const bool has_to = to.source != NormalSource::kept;
        const bool has_from = from.source != NormalSource::kept;
        if (!has_to && !has_from && out_[i].source == NormalSource::kept) continue;
        const Vector3d m =
            !has_to && !has_from ? out_[i].normal
            : !has_from          ? to.normal
            : !has_to            ? from.normal
                      : Vector3d(nb.fraction * to.normal + (1 - nb.fraction) * from.normal);
        if (m.norm() < 0.5) continue;
        passes[i] = {on_surface(nb), m.normalized(), true};
      }
    });
    return passes;
  }

 private:
  static tbb::blocked_range<std::size_t> blocks(std::size_t n) {
    return tbb::blocked_range<std::size_t>(0, n, 4096);
  }

  Vector3d on_surface(const Neighbour& nb) const {
    return pipeline::on_surface(nb, p_, starts_, tangents_);
  }

  // Point i's neighbour moved to where its pass crosses the plane across
  // the feed (kept where it ends abeam).
  Neighbour abeam(const Neighbour& nb, std::size_t i) const {
    if (!nb.found) return nb;
    const Vector3d& t = tangents_[i].along;
    if (const auto crossed = crossing(nb, p_[i], t, p_, starts_)) return *crossed;
    const double along = std::abs((nb.point - p_[i]).dot(t));
    if (along > across(nb.point - p_[i], t).norm() ||
        along > PassTracker::kAbeamShare * settings_.search_radius) {
      return {};  // a pass end farther along the feed than across, or than abeam
    }
    return nb;
  }

  // The points without a normal yet given the one `find` returns (if any),
  // in parallel: `find` reads only normals found two-sided, which this
  // does not change.
  template <class Find>
  void fill_kept(Find&& find) {
    std::vector<std::size_t> kept;
    for (std::size_t i = 0; i < out_.size(); ++i) {
      if (out_[i].source == NormalSource::kept) kept.push_back(i);
    }
    std::vector<std::optional<Vector3d>> found(kept.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kept.size(), 256), [&](const auto& range) {
      for (std::size_t k = range.begin(); k != range.end(); ++k) found[k] = find(kept[k]);
    });
    for (std::size_t k = 0; k < kept.size(); ++k) {
      if (found[k]) out_[kept[k]] = {*found[k], NormalSource::one_sided};
    }
  }

  // The normal at a neighbour's point between those of its segment's ends,
  // both found two-sided.
  std::optional<Vector3d> normal_at(const Neighbour& nb) const {
    const PathNormal& to = out_[nb.to];
    const PathNormal& from = out_[nb.from];
    if (to.source != NormalSource::two_sided || from.source != NormalSource::two_sided)
      return std::nullopt;
    const Vector3d m = nb.fraction * to.normal + (1 - nb.fraction) * from.normal;
    if (m.norm() < 0.5) return std::nullopt;
    return m.normalized();
  }

  // One side: the chord c to the neighbour Q across the feed is
  // perpendicular to n_P + n_Q to second order (exactly on a circle), with
  // n_Q interpolated between the normals of its segment's ends, both found
  // two-sided: n_P = -(c.n_Q) c + sqrt(1 - (c.n_Q)^2) (t x c), turned to
  // n_Q. The nearer neighbour's where both give one.
  std::optional<Vector3d> one_sided_normal(std::size_t i) const {
    const Vector3d& t = tangents_[i].along;
    std::optional<Vector3d> best;
    double best_h = 0;
    const Neighbour earlier = abeam(earlier_[i], i);
    for (const Neighbour* nb : {&earlier, &later_[i]}) {
      if (!nb->found) continue;
      const Vector3d a = across(on_surface(*nb) - p_[i], t);
      const double h = a.norm();
      if (h < same_point || (best && h >= best_h)) continue;
      const auto nq = normal_at(*nb);
      if (!nq) continue;
      const Vector3d c = a / h;
      const double cn = -c.dot(*nq);
      const Vector3d e2 = t.cross(c);
      const double side = e2.dot(*nq) >= 0 ? 1 : -1;
      const Vector3d np = cn * c + side * std::sqrt(std::max(0.0, 1 - cn * cn)) * e2;
      if (np.dot(*nq) < one_sided_max_turn_cos) continue;
      best = np.normalized();
      best_h = h;
    }
    return best;
  }

  // A point no pass lies abeam of (a pass end, a zig-zag's turn onto its
  // link at the edge of the window): the normals of the two points before
  // it on its path (or after it), found from their neighbours, carried on
  // to it along the path as the line through them (second order where the
  // points are a sample step apart, as the normal turns smoothly).
  std::optional<Vector3d> carried_normal(std::size_t i, bool ahead) const {
    const std::size_t n = p_.size();
    std::size_t j1 = i, j2 = i;
    if (ahead) {
      if (i + 2 >= n || starts_[i + 1] != 0 || starts_[i + 2] != 0) return std::nullopt;
      j1 = i + 1;
      j2 = i + 2;
    } else {
      if (i < 2 || starts_[i] != 0 || starts_[i - 1] != 0) return std::nullopt;
      j1 = i - 1;
      j2 = i - 2;
    }
    if (out_[j1].source != NormalSource::two_sided || out_[j2].source != NormalSource::two_sided)
      return std::nullopt;
    const double s1 = (p_[j1] - p_[i]).norm();
    const double s12 = (p_[j2] - p_[j1]).norm();
    if (s12 < same_point || s1 > 2 * s12 || out_[j1].normal.dot(out_[j2].normal) < smooth_cos)
      return std::nullopt;
    const Vector3d m = out_[j1].normal + (s1 / s12) * (out_[j1].normal - out_[j2].normal);
    return m.normalized();
  }

  std::span<const Vector3d> p_;
  std::span<const std::uint8_t> starts_;
  const PathNormalSettings& settings_;
  std::vector<Tangent> tangents_;
  // earlier_ as the tracker found them, later_ where they cross the plane
  // across the feed (after find_normals()).
  std::vector<Neighbour> earlier_, later_;
  std::vector<PathNormal> out_;
};

}  // namespace

struct PathNormalEstimator::State {
  explicit State(const PathNormalSettings& s) : settings(s), earlier(std::in_place, s) {}
  PathNormalSettings settings;
  std::vector<Eigen::Vector3d> points;
  std::vector<std::uint8_t> starts;
  std::optional<EarlierPasses> earlier;
};

PathNormalEstimator::PathNormalEstimator(const PathNormalSettings& settings)
    : state_(std::make_unique<State>(settings)) {}
PathNormalEstimator::~PathNormalEstimator() = default;
PathNormalEstimator::PathNormalEstimator(PathNormalEstimator&&) noexcept = default;
PathNormalEstimator& PathNormalEstimator::operator=(PathNormalEstimator&&) noexcept = default;

void PathNormalEstimator::add(const Eigen::Vector3d& point, bool starts_pass) {
  state_->points.push_back(point);
  state_->starts.push_back(starts_pass ? 1 : 0);
}

void PathNormalEstimator::reserve(std::size_t points) {
  state_->points.reserve(points);
  state_->starts.reserve(points);
  state_->earlier->reserve(points);
}

void PathNormalEstimator::track() { state_->earlier->track(state_->points, state_->starts, false); }

std::vector<PathNormal> PathNormalEstimator::finish(std::vector<EarlierPass>* earlier_passes) {
  const std::unique_ptr<State> s = std::move(state_);  // its memory goes with the call
  s->earlier->track(s->points, s->starts, true);
  auto tangents = s->earlier->take_tangents();
  auto earlier = s->earlier->take_neighbours();
  s->earlier.reset();  // the pass tracker's memory, before the rest needs more
  Estimate estimate(s->points, s->starts, s->settings, std::move(tangents), std::move(earlier));
  estimate.find_normals();
  if (earlier_passes != nullptr) *earlier_passes = estimate.earlier_passes();
  return estimate.take_normals();
}

std::vector<PathNormal> estimate_path_normals(std::span<const Eigen::Vector3d> points,
                                              std::span<const std::uint8_t> starts,
                                              const PathNormalSettings& settings,
                                              std::vector<EarlierPass>* earlier_passes) {
  PathNormalEstimator estimator(settings);
  for (std::size_t i = 0; i < points.size(); ++i) estimator.add(points[i], starts[i] != 0);
  return estimator.finish(earlier_passes);
}

}  // namespace vcpost::pipeline
