#include "postproc/pipeline/pass_tracker.h"

#include <cmath>

namespace vcpost::pipeline {
namespace {
constexpr double parallel_cos = 0.70710678118654752;  // cos 45 deg
}

PassTracker::PassTracker(double search_radius, double min_path_gap, std::size_t memory)
    : radius_(search_radius),
      min_gap_(min_path_gap),
      cell_(search_radius / 16),
      abeam_(0.1 * search_radius),
      memory_(memory) {
  ring_.reserve(memory);
}

void PassTracker::break_pass() { pass_open_ = false; }

PassTracker::Key PassTracker::key_of(std::int64_t x, std::int64_t y, std::int64_t z) const {
  // 21 bits per axis: cells wrap beyond 2^21 cells (kilometres), harmless for a hash.
  const auto part = [](std::int64_t v) { return static_cast<std::uint64_t>(v) & 0x1FFFFF; };
  return part(x) | (part(y) << 21) | (part(z) << 42);
}

PassTracker::Key PassTracker::key_of(const Eigen::Vector3d& p) const {
  return key_of(static_cast<std::int64_t>(std::floor(p.x() / cell_)),
                static_cast<std::int64_t>(std::floor(p.y() / cell_)),
                static_cast<std::int64_t>(std::floor(p.z() / cell_)));
}

const PassTracker::Entry* PassTracker::entry(std::uint64_t sequence) const {
  if (sequence >= next_ || next_ - sequence > ring_.size()) return nullptr;  // forgotten
  return &ring_[sequence % memory_];
}

std::optional<NeighbourPass> PassTracker::step(const Eigen::Vector3d& cc,
                                               const Eigen::Vector3d& normal,
                                               const Eigen::Vector3d& feed) {
  const Entry* last = next_ > 0 ? entry(next_ - 1) : nullptr;
  const bool turned = last && last->feed.dot(feed) < parallel_cos;
  if (!pass_open_ || turned) {
    ++pass_;
    pass_open_ = true;
  }
  Entry current{cc, feed, 0, pass_, false};
  if (last) current.path = last->path + (cc - last->point).norm();
  current.joined = last && last->pass == pass_;
  if (current.joined) max_segment_ = std::max(max_segment_, (cc - last->point).norm());
  auto found = nearest(current, normal);
  if (found) last_ae_ = found->ae;
  add(current);
  return found;
}

void PassTracker::add(const Entry& e) {
  if (ring_.size() < memory_) {
    ring_.push_back(e);
  } else {
    ring_[next_ % memory_] = e;
  }
  grid_[key_of(e.point)].push_back(next_++);
  if (next_ - compacted_at_ >= memory_) compact();
}

// Drops forgotten sequence numbers from the grid, so it stays bounded.
void PassTracker::compact() {
  for (auto it = grid_.begin(); it != grid_.end();) {
    auto& cell = it->second;
    std::erase_if(cell, [&](std::uint64_t s) { return entry(s) == nullptr; });
    it = cell.empty() ? grid_.erase(it) : std::next(it);
  }
  compacted_at_ = next_;
}

std::optional<NeighbourPass> PassTracker::nearest(const Entry& current,
                                                  const Eigen::Vector3d& normal) const {
  const Eigen::Vector3d& cc = current.point;
  const Eigen::Vector3d& feed = current.feed;
  const Eigen::Vector3d left = normal.cross(feed);
  std::optional<NeighbourPass> best;
  auto consider = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - cc;
    const double across = std::sqrt(std::pow(left.dot(d), 2) + std::pow(normal.dot(d), 2));
    if (across > radius_ || across <= 1e-9 || (best && across >= best->ae)) return;
    best = NeighbourPass{across, left.dot(d) >= 0 ? geometry::Side::left : geometry::Side::right, p};
  };
  auto scan_cell = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    const auto cell = grid_.find(key_of(x, y, z));
    if (cell == grid_.end()) return;
    for (const std::uint64_t s : cell->second) {
      const Entry* e = entry(s);
      if (!e || std::abs(e->feed.dot(feed)) < parallel_cos) continue;
      const bool earlier = e->pass != current.pass || current.path - e->path > min_gap_;
      if (!earlier) continue;
      // Where that pass crosses the plane across the feed through CC:
      // on the segment from its previous point, if it crosses there.
      const Entry* before = e->joined ? entry(s - 1) : nullptr;
      const double h1 = feed.dot(e->point - cc);
      if (before) {
        const double h0 = feed.dot(before->point - cc);
        if ((h0 <= 0) != (h1 <= 0) || h1 == 0) {
          const double t = h0 / (h0 - h1);
          consider(before->point + t * (e->point - before->point));
          continue;
        }
      }
      // A pass end, or the crossing lies on another segment: only a point
      // almost abeam counts on its own.
      if (std::abs(h1) <= abeam_) consider(e->point);
    }
  };
  // Search outwards: every candidate found within a cube of half-width
  // r + slack is a point or crossing within r + slack of CC, so once the
  // best lies within r no farther candidate can beat it. Most points find
  // their neighbour at about the last width of cut, in a handful of cells.
  const double slack = std::max(max_segment_, abeam_);
  for (double r = std::max(cell_, 2 * last_ae_);; r *= 2) {
    const double reach = std::min(r, radius_) + slack;
    const auto lo = [&](double v) { return static_cast<std::int64_t>(std::floor((v - reach) / cell_)); };
    const auto hi = [&](double v) { return static_cast<std::int64_t>(std::floor((v + reach) / cell_)); };
    best.reset();
    for (std::int64_t x = lo(cc.x()); x <= hi(cc.x()); ++x) {
      for (std::int64_t y = lo(cc.y()); y <= hi(cc.y()); ++y) {
        for (std::int64_t z = lo(cc.z()); z <= hi(cc.z()); ++z) scan_cell(x, y, z);
      }
    }
    if ((best && best->ae <= r) || r >= radius_) break;
  }
  return best;
}

}  // namespace vcpost::pipeline
