#include "postproc/pipeline/pass_tracker.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

namespace vcpost::pipeline {
namespace {
// Runs end after this many entries, or a cell length from their start.
// (32 read 1.6 times the points a step on a dense raster over an STL, whose
// contact points of neighbouring passes often lie within ae of each other
// on the facets, and was no faster elsewhere.)
constexpr std::uint64_t run_points = 16;
// The earlier passes a cell's list is read for, newest first: passes
// retraced or a hair apart pile hundreds into one cell (a row retraced 1000
// times, a raster at ae 0.005 mm with a 10 mm tool), and every step read
// them all. Passes a cell apart or more never fill it; where they do, the
// nearest pass is among the newest (the previous pass of a raster, the last
// retraces of a row, the jitter of their contact points apart).
constexpr std::uint64_t cell_passes = 3;

// Counts the passes of a cell's list as it is walked, newest first (a
// pass's runs lie together there: passes run one after the other).
class CellPasses {
 public:
  // Whether a run of `pass` lies beyond the newest cell_passes passes.
  bool full(std::uint64_t pass) {
    if (pass != last_ || count_ == 0) {
      last_ = pass;
      ++count_;
    }
    return count_ > cell_passes;
  }

 private:
  std::uint64_t last_ = 0, count_ = 0;
};
// Candidates nearer than the best by no more than this are ties, mm: a run
// of a straight pass is skipped once one of its twins gave the same ae.
constexpr double tie = 1e-10;
// Cell corners are widened by this when a segment is registered, mm, so a
// point computed on a cell boundary is not lost to rounding.
constexpr double cell_margin = 1e-9;

// Cell index of a coordinate; the grid is shifted by an odd fraction of a
// cell so that round coordinates (a floor at z = 0, a pass at y = 10) do not
// lie on cell faces, where they would be listed in two cells.
std::int64_t cell_index(double v, double cell) {
  return static_cast<std::int64_t>(std::floor(v / cell + 0.3819660112501051));
}

// A step whose box reaches at most this many cells across the feed takes
// its runs from a list of the runs near an earlier step (when it still
// covers it). A new list reaches farther across by this fraction of the
// reach, or of the step along the path if longer (contact points wander
// across the feed by about that much); ahead along the feed (where the
// path goes) by this fraction of the abeam allowance, or this many steps
// of the path if longer; behind by a little only.
constexpr double nearby_reach = 2;
constexpr double nearby_across = 0.5;
constexpr double nearby_ahead = 1;
constexpr double nearby_steps = 12;
constexpr double nearby_behind = 0.05;
// Room for rounding in the bounds from the list's copies, mm (their
// differences are taken in another order than in measure()).
constexpr double nearby_slack = 1e-9;

// The cells of the box around the points within `across` of cc across the
// unit `feed` and within `along` of it along the feed.
inline void cells_around(const Eigen::Vector3d& cc, const Eigen::Vector3d& feed, double across,
                         double along, double cell, std::array<std::int64_t, 3>& lo,
                         std::array<std::int64_t, 3>& hi) {
  for (int i = 0; i < 3; ++i) {
    const double f = feed[i];
    const double half = across * std::sqrt(std::max(0.0, 1 - f * f)) + along * std::abs(f);
    lo[static_cast<std::size_t>(i)] = cell_index(cc[i] - half, cell);
    hi[static_cast<std::size_t>(i)] = cell_index(cc[i] + half, cell);
  }
}

// Distance from the origin to the 2-D segment p-q.
double distance_to_segment(double px, double py, double qx, double qy) {
  const double dx = qx - px, dy = qy - py;
  const double length2 = dx * dx + dy * dy;
  double t = length2 > 0 ? -(px * dx + py * dy) / length2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  const double x = px + t * dx, y = py + t * dy;
  return std::sqrt(x * x + y * y);
}
// A float at or below v, and one at or above it: moved away by more than
// the rounding to float (half a float ulp, under 6e-8 of |v|) first.
float down(double v) { return static_cast<float>(v - std::abs(v) * 2.4e-7); }
float up(double v) { return static_cast<float>(v + std::abs(v) * 2.4e-7); }

// The range of v . o over the offsets o of the box low..high.
std::pair<double, double> spread(const Eigen::Vector3d& v, const Eigen::Vector3f& low,
                                 const Eigen::Vector3f& high) {
  double from = 0, to = 0;
  for (int i = 0; i < 3; ++i) {
    const double p = v[i] * double{low[i]}, q = v[i] * double{high[i]};
    from += std::min(p, q);
    to += std::max(p, q);
  }
  return {from, to};
}
}  // namespace

// ---- BlockMap ---------------------------------------------------------------

std::size_t PassTracker::BlockMap::slot(Key key) const {
  // Fibonacci hashing of the packed cell coordinates.
  const auto shift = 64 - std::countr_zero(keys_.size());
  return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> shift);
}

const PassTracker::Block* PassTracker::BlockMap::find(Key key) const {
  if (keys_.empty()) return nullptr;
  const std::size_t mask = keys_.size() - 1;
  for (std::size_t i = slot(key);; i = (i + 1) & mask) {
    if (keys_[i] == key) return &values_[i];
    if (keys_[i] == empty) return nullptr;
  }
}

void PassTracker::BlockMap::reserve(std::size_t blocks) {
  std::size_t capacity = 16;
  while (capacity < 2 * blocks) capacity *= 2;
  keys_.assign(capacity, empty);
  values_.assign(capacity, Block{});
  size_ = 0;
}

void PassTracker::BlockMap::grow() {
  std::vector<Key> keys = std::move(keys_);
  std::vector<Block> values = std::move(values_);
  reserve(std::max<std::size_t>(16, keys.size()));  // twice the slots
  const std::size_t mask = keys_.size() - 1;
  for (std::size_t j = 0; j < keys.size(); ++j) {
    if (keys[j] == empty) continue;
    std::size_t i = slot(keys[j]);
    while (keys_[i] != empty) i = (i + 1) & mask;
    keys_[i] = keys[j];
    values_[i] = values[j];
    ++size_;
  }
}

PassTracker::Block& PassTracker::BlockMap::insert(Key key) {
  if (2 * (size_ + 1) > keys_.size()) grow();  // load factor at most 1/2
  const std::size_t mask = keys_.size() - 1;
  std::size_t i = slot(key);
  for (; keys_[i] != empty; i = (i + 1) & mask) {
    if (keys_[i] == key) return values_[i];
  }
  keys_[i] = key;
  values_[i].occupied = 0;
  ++size_;
  return values_[i];
}

// ---- PassTracker ------------------------------------------------------------

PassTracker::PassTracker(double search_radius, double min_path_gap, std::size_t memory)
    : radius_(search_radius),
      min_gap_(min_path_gap),
      cell_(search_radius / 16),
      abeam_(kAbeamShare * search_radius),
      memory_(std::max<std::size_t>(memory, 1)),
      mask_(std::bit_ceil(memory_) - 1) {
  // The whole ring at once: pages never written cost no memory (the kernel
  // maps them on first use), while growing by doubling copied every entry
  // and touched twice the pages.
  ring_.reserve(mask_ + 1);
  runs_.reserve(mask_ + 1);
  candidates_.reserve(64);
}

void PassTracker::break_pass() { pass_open_ = false; }

PassTracker::Key PassTracker::key_of(std::int64_t x, std::int64_t y, std::int64_t z) {
  // 21 bits per axis: blocks wrap beyond 2^21 (kilometres); a wrapped block
  // only adds runs that the distance bounds then reject.
  const auto part = [](std::int64_t v) { return static_cast<std::uint64_t>(v) & 0x1FFFFF; };
  return part(x) | (part(y) << 21) | (part(z) << 42);
}

const PassTracker::Entry* PassTracker::entry(std::uint64_t sequence) const {
  if (sequence >= next_ || next_ - sequence > kept()) return nullptr;  // forgotten
  return &ring_[sequence & mask_];
}

std::uint64_t PassTracker::run_of(std::uint32_t low) const {
  const std::uint64_t newest = run_next_ - 1;
  return newest - static_cast<std::uint32_t>(static_cast<std::uint32_t>(newest) - low);
}

bool PassTracker::run_alive(std::uint64_t sequence) const {
  if (sequence >= run_next_ || run_next_ - sequence > runs_.size()) return false;  // overwritten
  return runs_[sequence & mask_].end > oldest();  // its last entry is kept
}

std::optional<NeighbourPass> PassTracker::step(const Eigen::Vector3d& cc,
                                               const Eigen::Vector3d& normal,
                                               const Eigen::Vector3d& feed) {
  const Entry* last = next_ > 0 ? entry(next_ - 1) : nullptr;
  const bool turned = last && last->feed.dot(feed) < kParallelCos;
  if (!pass_open_ || turned) {
    ++pass_;
    pass_open_ = true;
    pass_start_ = next_;
  }
  Entry current{cc, feed, 0, pass_, false};
  if (last) current.path = last->path + (cc - last->point).norm();
  current.joined = last && last->pass == pass_;
  // Entries of this pass less than the path gap back are no earlier pass;
  // path length only grows, so that boundary only moves forward.
  cutoff_ = std::max(cutoff_, pass_start_);
  for (; cutoff_ < next_; ++cutoff_) {
    const Entry* e = entry(cutoff_);
    if (e && !(current.path - e->path > min_gap_)) break;
  }
  auto found = nearest(current, normal);
  if (found) last_ae_ = found->ae;
  add(current);
  return found;
}

void PassTracker::add(const Entry& e) {
  // The run first: closing one reads entries that e may overwrite.
  std::optional<Eigen::Vector3d> before;
  if (e.joined) before = ring_[(next_ - 1) & mask_].point;
  extend_run(e, before);
  if (ring_.size() <= mask_) {
    ring_.push_back(e);
  } else {
    ring_[next_ & mask_] = e;
  }
  ++next_;
  if (next_ - compacted_at_ >= memory_ && nodes_.size() > 2 * live_nodes_ + 4096) compact();
}

void PassTracker::extend_run(const Entry& e, const std::optional<Eigen::Vector3d>& before) {
  const bool fits = run_open_ && e.joined && next_ - run(run_next_ - 1).first < run_points &&
                    (e.point - run(run_next_ - 1).a).norm() <= cell_;
  if (!fits) {
    close_run();
    Run fresh;
    fresh.a = before ? *before : e.point;
    fresh.first = next_;
    fresh.pass = e.pass;
    if (runs_.size() <= mask_) {
      runs_.push_back(fresh);
    } else {
      run(run_next_) = fresh;
    }
    ++run_next_;
    run_open_ = true;
  }
  Run& r = run(run_next_ - 1);
  r.b = e.point;
  r.end = next_ + 1;
  register_segment(before ? *before : e.point, e.point, run_next_ - 1);
}

// Fixes the capsule of the open run: the largest distance of its points
// from the axis a-b (segments between them lie inside: it is convex).
void PassTracker::close_run() {
  if (!run_open_) return;
  run_open_ = false;
  Run& r = run(run_next_ - 1);
  const Eigen::Vector3d axis = r.b - r.a;
  const double length2 = axis.squaredNorm();
  double radius = 0;
  Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();
  for (std::uint64_t s = std::max(r.first, oldest()); s < r.end; ++s) {
    const Eigen::Vector3d d = ring_[s & mask_].point - r.a;
    const double t = length2 > 0 ? std::clamp(d.dot(axis) / length2, 0.0, 1.0) : 0.0;
    const Eigen::Vector3d offset = d - t * axis;
    radius = std::max(radius, offset.norm());
    low = low.cwiseMin(offset);
    high = high.cwiseMax(offset);
  }
  const double rounding = radius * 1e-12 + 1e-12;  // of the distances above
  r.radius = radius + rounding;
  for (int i = 0; i < 3; ++i) {
    r.offset_low[i] = down(low[i] - rounding);
    r.offset_high[i] = up(high[i] + rounding);
  }
}

// Registers `run` in every cell the segment p-q passes through: the segment
// is cut into pieces no longer than a cell along any axis, and each piece
// marks the cells of its bounding box (at most 2 x 2 x 2).
void PassTracker::register_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                   std::uint64_t run) {
  const Eigen::Vector3d d = q - p;
  const double longest = d.cwiseAbs().maxCoeff();
  const auto pieces =
      std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(longest / cell_)));
  if (pieces == 1) {
    // Most steps stay in the cells of the last one: nothing new to list.
    const Eigen::Vector3d lo = p.cwiseMin(q).array() - cell_margin;
    const Eigen::Vector3d hi = p.cwiseMax(q).array() + cell_margin;
    const std::array<std::int64_t, 7> box{cell_index(lo.x(), cell_),     cell_index(lo.y(), cell_),
                                          cell_index(lo.z(), cell_),     cell_index(hi.x(), cell_),
                                          cell_index(hi.y(), cell_),     cell_index(hi.z(), cell_),
                                          static_cast<std::int64_t>(run)};
    if (box == last_box_) return;
    last_box_ = box;
    for (std::int64_t x = box[0]; x <= box[3]; ++x) {
      for (std::int64_t y = box[1]; y <= box[4]; ++y) {
        for (std::int64_t z = box[2]; z <= box[5]; ++z) register_cell(x, y, z, run);
      }
    }
    return;
  }
  last_box_.back() = -1;
  Eigen::Vector3d from = p;
  for (std::int64_t k = 1; k <= pieces; ++k) {
    const Eigen::Vector3d to =
        k == pieces
            ? q
            : Eigen::Vector3d(p + d * (static_cast<double>(k) / static_cast<double>(pieces)));
    const Eigen::Vector3d lo = from.cwiseMin(to).array() - cell_margin;
    const Eigen::Vector3d hi = from.cwiseMax(to).array() + cell_margin;
    for (std::int64_t x = cell_index(lo.x(), cell_); x <= cell_index(hi.x(), cell_); ++x) {
      for (std::int64_t y = cell_index(lo.y(), cell_); y <= cell_index(hi.y(), cell_); ++y) {
        for (std::int64_t z = cell_index(lo.z(), cell_); z <= cell_index(hi.z(), cell_); ++z) {
          register_cell(x, y, z, run);
        }
      }
    }
    from = to;
  }
}

void PassTracker::register_cell(std::int64_t x, std::int64_t y, std::int64_t z, std::uint64_t run) {
  Block& block = blocks_.insert(key_of(x >> 2, y >> 2, z >> 2));
  const auto bit = static_cast<unsigned>((x & 3) | ((y & 3) << 2) | ((z & 3) << 4));
  std::uint32_t& head = block.heads[bit];
  const auto low = static_cast<std::uint32_t>(run);
  if (!(block.occupied >> bit & 1)) {
    block.occupied |= std::uint64_t{1} << bit;
    head = none;
  } else if (nodes_[head].run == low) {
    return;  // the run is already listed here (a run registers all at once)
  }
  nodes_.push_back({low, head});
  head = static_cast<std::uint32_t>(nodes_.size() - 1);
}

// Drops forgotten runs from the cell lists (and empty cells and blocks), so
// the grid stays bounded; lists are newest first, so each is cut at its
// first forgotten run.
void PassTracker::compact() {
  std::vector<std::pair<Key, Block>> kept;
  std::vector<Node> nodes;
  nodes.reserve(nodes_.size() / 2);
  blocks_.for_each([&](Key key, const Block& block) {
    Block fresh;
    for (std::uint64_t bits = block.occupied; bits != 0; bits &= bits - 1) {
      const auto bit = static_cast<unsigned>(std::countr_zero(bits));
      // Links by index: push_back may move `nodes`, so no pointer into it.
      fresh.heads[bit] = none;
      std::uint32_t last = none;
      for (std::uint32_t n = block.heads[bit]; n != none; n = nodes_[n].next) {
        if (!run_alive(run_of(nodes_[n].run))) break;
        nodes.push_back({nodes_[n].run, none});
        const auto added = static_cast<std::uint32_t>(nodes.size() - 1);
        (last == none ? fresh.heads[bit] : nodes[last].next) = added;
        last = added;
      }
      if (fresh.heads[bit] != none) fresh.occupied |= std::uint64_t{1} << bit;
    }
    if (fresh.occupied) kept.emplace_back(key, fresh);
  });
  blocks_.reserve(kept.size());
  for (const auto& [key, block] : kept) blocks_.insert(key) = block;
  nodes_ = std::move(nodes);
  live_nodes_ = nodes_.size();
  compacted_at_ = next_;
}

// Walks the lists of the cells lo..hi (inclusive cell indices): calls
// on_list(head) for each occupied cell.
template <class F>
void PassTracker::for_each_list(const std::array<std::int64_t, 3>& lo,
                                const std::array<std::int64_t, 3>& hi, F&& on_list) const {
  for (std::int64_t bx = lo[0] >> 2; bx <= hi[0] >> 2; ++bx) {
    for (std::int64_t by = lo[1] >> 2; by <= hi[1] >> 2; ++by) {
      for (std::int64_t bz = lo[2] >> 2; bz <= hi[2] >> 2; ++bz) {
        const Block* block = blocks_.find(key_of(bx, by, bz));
        if (!block) continue;
        // The cells of the box inside this block, as bits of `occupied`.
        const auto span = [](std::int64_t l, std::int64_t h, std::int64_t base) {
          const auto from = static_cast<unsigned>(std::max(l, base) - base);
          const auto to = static_cast<unsigned>(std::min(h, base + 3) - base);
          return ((1u << (to + 1)) - 1) & ~((1u << from) - 1);  // bits from..to of 4
        };
        const unsigned xs = span(lo[0], hi[0], 4 * bx), ys = span(lo[1], hi[1], 4 * by),
                       zs = span(lo[2], hi[2], 4 * bz);
        // Spread the y bits 4 apart and the z bits 16 apart: the products
        // then lay the x bits on every wanted row (no carries).
        const std::uint64_t y_rows = (ys & 1) | (ys & 2) << 3 | (ys & 4) << 6 | (ys & 8) << 9;
        const std::uint64_t z_planes = std::uint64_t{zs & 1} | std::uint64_t{zs & 2} << 15 |
                                       std::uint64_t{zs & 4} << 30 | std::uint64_t{zs & 8} << 45;
        const std::uint64_t wanted = xs * y_rows * z_planes;
        for (std::uint64_t bits = block->occupied & wanted; bits != 0; bits &= bits - 1) {
          on_list(block->heads[std::countr_zero(bits)]);
        }
      }
    }
  }
}

// Lists the closed runs that may come within `across` of cc across the
// feed and from `behind` back to `ahead` on along it, once each, with
// copies of their capsules side by side, for the searches of the next
// steps.
void PassTracker::fill_nearby(const Eigen::Vector3d& cc, const Eigen::Vector3d& normal,
                              const Eigen::Vector3d& feed, double across, double behind,
                              double ahead) {
  // Marks the runs listed with a number of its own, as if a search: the
  // search that asked for the list takes another one after it.
  const std::uint64_t listing = ++search_;
  nearby_.clear();
  const std::uint64_t kept = oldest();
  const std::uint64_t run_floor = run_next_ - runs_.size();
  const std::uint64_t open = run_open_ ? run_next_ - 1 : run_next_;
  const Eigen::Vector3d left = normal.cross(feed);
  std::array<std::int64_t, 3> lo{}, hi{};
  cells_around(cc + 0.5 * (ahead - behind) * feed, feed, across, 0.5 * (ahead + behind), cell_, lo,
               hi);
  for_each_list(lo, hi, [&](std::uint32_t head) {
    CellPasses earlier;
    for (std::uint32_t n = head; n != none; n = nodes_[n].next) {
      const std::uint64_t id = run_of(nodes_[n].run);
      if (id >= open) continue;   // still growing: looked at directly
      if (id < run_floor) break;  // overwritten: older ones are too
      Run& r = run(id);
      if (r.end <= kept) break;                          // forgotten: older ones are too
      if (id < run_cut_ && earlier.full(r.pass)) break;  // crowded: the newest passes only
      if (r.mark == listing) continue;
      r.mark = listing;
      // measure()'s bounds, for the list's reach.
      const Eigen::Vector3d da = r.a - cc, db = r.b - cc;
      const double ha = feed.dot(da), hb = feed.dot(db);
      const double radius = r.radius + nearby_slack;
      if (std::min(ha, hb) - radius > ahead || std::max(ha, hb) + radius < -behind) continue;
      const double xa = left.dot(da), xb = left.dot(db), ya = normal.dot(da), yb = normal.dot(db);
      if (std::min(xa, xb) - radius > across || std::max(xa, xb) + radius < -across ||
          std::min(ya, yb) - radius > across || std::max(ya, yb) + radius < -across) {
        continue;
      }
      nearby_.push(id, r);
    }
  });
  nearby_cc_ = cc;
  nearby_feed_ = feed;
  nearby_across_ = across;
  nearby_behind_ = behind;
  nearby_ahead_ = ahead;
  nearby_from_ = open;
  nearby_valid_ = true;
}

// Whether every point within `across` of cc across the feed and within
// `along` along it lies within the list's reach of its step. With f' and
// P' the list's feed and the projection across it, D = |f - f'| and such a
// point p = cc + a f + u (|a| <= along, u across f, |u| <= across):
// |P'f| <= D and |f'.u| = |(f' - f).u| <= D across, so
//   |P'(p - cc')| <= across + D along + |P'(cc - cc')|,
//   |f'.(p - cc')| <= along + D across + |f'.(cc - cc')|.
bool PassTracker::nearby_covers(const Eigen::Vector3d& cc, const Eigen::Vector3d& feed,
                                double across, double along) const {
  if (!nearby_valid_) return false;
  const double turn = (feed - nearby_feed_).norm();
  const Eigen::Vector3d moved = cc - nearby_cc_;
  const double ahead = nearby_feed_.dot(moved);
  const double aside = (moved - ahead * nearby_feed_).norm();
  const double reach_along = along + turn * across + nearby_slack;
  return across + turn * along + aside + nearby_slack <= nearby_across_ &&
         ahead + reach_along <= nearby_ahead_ && ahead - reach_along >= -nearby_behind_;
}

void PassTracker::Nearby::clear() {
  id.clear();
  end.clear();
  for (auto& v : a) v.clear();
  for (auto& v : b) v.clear();
  radius.clear();
}

void PassTracker::Nearby::push(std::uint64_t run_id, const Run& r) {
  id.push_back(run_id);
  end.push_back(r.end);
  for (int i = 0; i < 3; ++i) {
    a[i].push_back(r.a[i]);
    b[i].push_back(r.b[i]);
  }
  radius.push_back(r.radius);
}

// One call of nearest(): the current point's frame across the feed, the
// runs and entries still to be looked at, and the best candidate so far.
struct PassTracker::Search {
  Search(const Entry& entry, const Eigen::Vector3d& surface_normal, std::uint64_t oldest_kept,
         std::uint64_t first_run, double radius)
      : current(entry),
        cc(entry.point),
        feed(entry.feed),
        normal(surface_normal),
        left(surface_normal.cross(entry.feed)),
        kept(oldest_kept),
        run_floor(first_run),
        limit2(radius * radius * (1 + 1e-15)) {}

  const Entry& current;
  const Eigen::Vector3d& cc;
  const Eigen::Vector3d& feed;
  const Eigen::Vector3d& normal;
  const Eigen::Vector3d left;
  const std::uint64_t kept;       // the oldest kept entry
  const std::uint64_t run_floor;  // older runs are overwritten
  std::optional<NeighbourPass> best;
  std::uint64_t evaluating = 0,
                best_run = 0;                          // the run being evaluated, the best one's
  std::uint64_t evaluating_entry = 0, best_entry = 0;  // the same for entries
  // Squared distance across beyond which a candidate cannot be the best:
  // a little more than the best's square (or the radius's), so that what
  // passes it is compared exactly and nothing nearer is lost to rounding.
  double limit2;
};

std::optional<NeighbourPass> PassTracker::nearest(const Entry& current,
                                                  const Eigen::Vector3d& normal) {
  const std::uint64_t kept = oldest();
  if (cutoff_ <= kept) return std::nullopt;  // everything kept belongs to this pass
  ++search_;
  const std::uint64_t run_floor = run_next_ - runs_.size();  // older runs are overwritten
  // Runs from run_cut_ on start at or after the cutoff: this pass, too close
  // behind.
  run_cut_ = std::max(run_cut_, run_floor);
  while (run_cut_ < run_next_ && run(run_cut_).first < cutoff_) ++run_cut_;
  Search s(current, normal, kept, run_floor, radius_);
  search_warm(s);
  search_outwards(s);
  warm_.reset();
  if (s.best) {
    warm_ = s.best_run;
    warm_entry_ = s.best_entry;
  }
  return s.best;
}

// Returns whether the candidate was compared with the best (it lies
// within the search radius and is not CC itself).
bool PassTracker::consider(Search& s, const Eigen::Vector3d& p, double fraction) const {
  const Eigen::Vector3d d = p - s.cc;
  const double across = std::sqrt(std::pow(s.left.dot(d), 2) + std::pow(s.normal.dot(d), 2));
  if (across > radius_ || across <= 1e-9) return false;
  if (s.best && across >= s.best->ae) return true;
  s.best = NeighbourPass{across, s.left.dot(d) >= 0 ? geometry::Side::left : geometry::Side::right,
                         p, s.evaluating_entry, fraction};
  s.best_run = s.evaluating;
  s.best_entry = s.evaluating_entry;
  s.limit2 = across * across * (1 + 1e-15);
  return true;
}

namespace {
// Whether the segment from a point at h_from along the feed (from the
// plane across it through CC) to one at h_to crosses that plane (the end
// point on it counts, the start point does not: a crossing at a shared
// point is the segment's before it).
bool crosses(double h_from, double h_to) { return (h_from <= 0) != (h_to <= 0) || h_to == 0; }
}  // namespace

// Whether the stretch of earlier pass that ends at entry i (its first
// entry, looking forward, or its last, looking back) crosses the plane
// across the feed through CC on a segment of its own that evaluate_range
// takes, before it leaves the abeam allowance along the feed.
bool PassTracker::stretch_crosses(const Search& s, std::uint64_t i, bool forward) const {
  const auto h = [&](std::uint64_t j) { return s.feed.dot(ring_[j & mask_].point - s.cc); };
  // The segment into entry j is the pass's (and a candidate's) when j is
  // joined to a kept entry, before the cutoff and parallel.
  const auto takes = [&](std::uint64_t j) {
    const Entry& e = ring_[j & mask_];
    return j < cutoff_ && j > s.kept && e.joined && std::abs(e.feed.dot(s.feed)) >= kParallelCos;
  };
  if (forward) {
    double h_from = h(i);
    for (std::uint64_t j = i + 1; takes(j); ++j) {
      const double h_to = h(j);
      if (crosses(h_from, h_to)) return true;
      if (std::abs(h_to) > abeam_) return false;
      h_from = h_to;
    }
  } else {
    double h_to = h(i);
    for (std::uint64_t j = i; takes(j); --j) {
      const double h_from = h(j - 1);
      if (crosses(h_from, h_to)) return true;
      if (std::abs(h_from) > abeam_) return false;
      h_to = h_from;
    }
  }
  return false;
}

// The candidate of an entry of an earlier, roughly parallel pass: where
// that pass crosses the plane across the feed through CC, on the segment
// from its previous point; or, at an end of a stretch of pass that does
// not reach the plane, the end point itself if almost abeam. A point
// inside a stretch is no candidate on its own, nor is the end of one that
// crosses the plane within the abeam allowance: where the pass leans
// across the feed (a ball's contact track on a surface whose slope turns)
// or bends towards CC (an offset contour inside the last), its points
// ahead or behind lie nearer than the pass does across the feed.
// flat: all candidates of the run lie within `tie` of each other across
// the feed, so the first one compared stands for all.
// Evaluates the entries from..to (sequences) of run id.
bool PassTracker::evaluate_range(Search& s, std::uint64_t id, bool flat, std::uint64_t from,
                                 std::uint64_t end) const {
  const Eigen::Vector3d& cc = s.cc;
  const Eigen::Vector3d& feed = s.feed;
  s.evaluating = id;
  // h of the entry before: the same expression as h1 of that entry, so
  // it is carried from one entry to the next.
  double h0 = from > s.kept && from < end ? feed.dot(ring_[(from - 1) & mask_].point - cc) : 0.0;
  for (std::uint64_t i = from; i < end; ++i) {
    const Entry& e = ring_[i & mask_];
    const double h1 = feed.dot(e.point - cc);
    const double h_before = h0;
    h0 = h1;
    if (std::abs(e.feed.dot(feed)) < kParallelCos) continue;
    s.evaluating_entry = i;
    const bool has_before = e.joined && i > s.kept;  // the entry before is kept
    if (has_before && crosses(h_before, h1)) {
      const Eigen::Vector3d& before = ring_[(i - 1) & mask_].point;
      // h0 == h1 == 0: the segment lies in the plane
      const double t = h_before == h1 ? 1.0 : h_before / (h_before - h1);
      if (consider(s, before + t * (e.point - before), t) && flat) return true;
      continue;
    }
    if (std::abs(h1) > abeam_) continue;
    // The entry after continues the stretch when the segment into it is
    // one evaluate_range takes.
    const Entry* after = i + 1 < cutoff_ ? &ring_[(i + 1) & mask_] : nullptr;
    const bool has_after =
        after != nullptr && after->joined && std::abs(after->feed.dot(feed)) >= kParallelCos;
    if (has_before == has_after) {
      if (has_before) continue;  // inside a stretch: its crossing is the candidate
    } else if (stretch_crosses(s, i, has_after)) {
      continue;  // an end of a stretch that reaches the plane nearby
    }
    if (!flat) {
      // Only a nearer candidate matters here, and most are not.
      const Eigen::Vector3d d = e.point - cc;
      const double x = s.left.dot(d), y = s.normal.dot(d);
      if (x * x + y * y > s.limit2) continue;
    }
    if (consider(s, e.point, 1.0) && flat) return true;
  }
  return false;
}

// Evaluates run id, from its entry `start` on first when that lies in it
// (where the last neighbour was: the best comes soon, and the bound on
// the others is tight from there on).
void PassTracker::evaluate(Search& s, std::uint64_t id, bool flat, std::uint64_t start) {
  const Run& r = run(id);
  const std::uint64_t end = std::min(r.end, cutoff_);
  const std::uint64_t first = std::max(r.first, s.kept);
  if (start <= first || start >= end) {
    evaluate_range(s, id, flat, first, end);
  } else if (!evaluate_range(s, id, flat, start, end)) {
    evaluate_range(s, id, flat, first, start);
  }
}

// Bounds of a closed run across the feed (lowest, highest); none when
// all of it lies beyond the abeam allowance along the feed.
// flat: whether the highest bound lies within `tie` of the lowest. Runs
// whose lowest bound is no better than `worst` are left out.
std::optional<std::pair<double, bool>> PassTracker::measure(const Search& s, const Run& r,
                                                            double worst) const {
  const Eigen::Vector3d& left = s.left;
  const Eigen::Vector3d& normal = s.normal;
  const Eigen::Vector3d da = r.a - s.cc, db = r.b - s.cc;
  const double ha = s.feed.dot(da), hb = s.feed.dot(db);
  if (std::min(ha, hb) - r.radius > abeam_ || std::max(ha, hb) + r.radius < -abeam_) {
    return std::nullopt;
  }
  const double xa = left.dot(da), ya = normal.dot(da), xb = left.dot(db), yb = normal.dot(db);
  // Each coordinate across bounds the distance: no division, no root.
  if (std::min(xa, xb) - r.radius > worst || std::max(xa, xb) + r.radius < -worst ||
      std::min(ya, yb) - r.radius > worst || std::max(ya, yb) + r.radius < -worst) {
    return std::nullopt;
  }
  // The same with the box of offsets instead of the ball: on a curved
  // pass the points leave the axis mostly along the normal, which
  // changes the distance across little where the pass lies beside CC.
  double boxed = 0;  // (on a straight run the ball is as tight)
  if (r.radius > tie) {
    const auto [xl, xh] = spread(left, r.offset_low, r.offset_high);
    const auto [yl, yh] = spread(normal, r.offset_low, r.offset_high);
    const double gap_x = std::max({0.0, std::min(xa, xb) + xl, -(std::max(xa, xb) + xh)});
    const double gap_y = std::max({0.0, std::min(ya, yb) + yl, -(std::max(ya, yb) + yh)});
    boxed = std::sqrt(gap_x * gap_x + gap_y * gap_y);
    if (boxed > worst) return std::nullopt;
  }
  const double low = std::max(boxed, distance_to_segment(xa, ya, xb, yb) - r.radius);
  if (low > worst) return std::nullopt;
  // The distance to a line is convex along the axis: largest at an end.
  const double high = std::sqrt(std::max(xa * xa + ya * ya, xb * xb + yb * yb)) + r.radius;
  return std::pair{low, high - low <= tie};
}

// How far across a run may lie and still hold a better candidate.
double PassTracker::worst(const Search& s) const {
  return s.best ? std::min(radius_, s.best->ae - tie) : radius_;
}

// A run that may hold a candidate nearer than the best so far: the open
// run (no capsule yet) is evaluated at once, a closed one collected.
void PassTracker::look_at(Search& s, std::uint64_t id, Run& r) {
  if (r.mark == search_) return;
  r.mark = search_;
  if (r.radius < 0) {
    evaluate(s, id, false);
    return;
  }
  const auto bounds = measure(s, r, worst(s));
  if (bounds) candidates_.push_back({bounds->first, id, bounds->second});
}

// The runs of a cell's list that are earlier passes and still kept.
void PassTracker::scan_cell(Search& s, std::uint32_t head) {
  CellPasses earlier;
  for (std::uint32_t n = head; n != none; n = nodes_[n].next) {
    const std::uint64_t id = run_of(nodes_[n].run);
    if (id >= run_cut_) continue;  // all of it is this pass, too close behind
    if (id < s.run_floor) break;   // overwritten: older ones are too
    Run& r = run(id);
    if (r.end <= s.kept) break;       // forgotten: older ones are too
    if (earlier.full(r.pass)) break;  // crowded: the newest passes only
    look_at(s, id, r);
  }
}

// The runs listed near the last searches: the same bounds as measure's,
// from the copies side by side, before a run itself is read (with room
// for rounding: the copies are exact, the differences are taken
// differently); then the runs begun since they were listed.
void PassTracker::scan_nearby(Search& s) {
  const Eigen::Vector3d& cc = s.cc;
  const Eigen::Vector3d& feed = s.feed;
  const Eigen::Vector3d& left = s.left;
  const Eigen::Vector3d& normal = s.normal;
  const double fc = feed.dot(cc), lc = left.dot(cc), nc = normal.dot(cc);
  const std::size_t count = nearby_.id.size();
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint64_t id = nearby_.id[i];
    if (id >= run_cut_ || nearby_.end[i] <= s.kept) continue;
    const double ax = nearby_.a[0][i], ay = nearby_.a[1][i], az = nearby_.a[2][i];
    const double bx = nearby_.b[0][i], by = nearby_.b[1][i], bz = nearby_.b[2][i];
    const double rad = nearby_.radius[i] + nearby_slack;
    const double ha = feed.x() * ax + feed.y() * ay + feed.z() * az - fc;
    const double hb = feed.x() * bx + feed.y() * by + feed.z() * bz - fc;
    if (std::min(ha, hb) - rad > abeam_ || std::max(ha, hb) + rad < -abeam_) continue;
    const double w = worst(s);
    const double xa = left.x() * ax + left.y() * ay + left.z() * az - lc;
    const double xb = left.x() * bx + left.y() * by + left.z() * bz - lc;
    if (std::min(xa, xb) - rad > w || std::max(xa, xb) + rad < -w) continue;
    const double ya = normal.x() * ax + normal.y() * ay + normal.z() * az - nc;
    const double yb = normal.x() * bx + normal.y() * by + normal.z() * bz - nc;
    if (std::min(ya, yb) - rad > w || std::max(ya, yb) + rad < -w) continue;
    look_at(s, id, run(id));
  }
  for (std::uint64_t id = std::max(nearby_from_, s.run_floor); id < run_next_ && id < run_cut_;
       ++id) {
    Run& r = run(id);
    if (r.end > s.kept) look_at(s, id, r);
  }
}

// The run that held the last neighbour most likely holds this one: with
// its candidates first, the bounds below skip most other runs at once.
// Its neighbours on the path next, while nothing is found (the neighbour
// moves on to them along the pass, either way).
void PassTracker::search_warm(Search& s) {
  if (!warm_) return;
  for (const std::uint64_t id : {*warm_, *warm_ - 1, *warm_ + 1}) {
    if (s.best || id < s.run_floor || id >= run_cut_ || run(id).end <= s.kept) continue;
    Run& r = run(id);
    if (r.mark == search_) continue;
    r.mark = search_;
    // A run whose points leave its axis by more than the tie is not flat
    // (measure() would only say so): its candidates are looked at anyway.
    if (r.radius < 0 || r.radius > tie) {
      evaluate(s, id, false, warm_entry_);
    } else if (const auto bounds = measure(s, r, radius_)) {
      evaluate(s, id, bounds->second, warm_entry_);
    }
  }
}

// Search outwards: a candidate within r of CC across the feed and within
// the abeam allowance along it lies in the box below, and so does a cell
// listing its run. Once the best lies within r, nothing outside beats it.
void PassTracker::search_outwards(Search& s) {
  const Eigen::Vector3d& cc = s.cc;
  const Eigen::Vector3d& feed = s.feed;
  double r = s.best ? s.best->ae : last_ae_ > 0 ? 1.125 * last_ae_ : cell_;
  for (bool first = true;; first = false) {
    const double reach = std::min(r, radius_);
    // The first search of a step looks at the runs listed for an earlier
    // step while they cover its reach; a new list reaches a little farther
    // across and along the feed, so the next steps can use it too.
    const bool small = first && reach <= nearby_reach * cell_;
    bool listed = small && nearby_covers(cc, feed, reach, abeam_);
    if (small && !listed) {
      // Steps longer than a cell (long moves of a program read without a
      // model: 10 mm on NX's finishing profile) would stretch the list's
      // box with them, across as well, to hundreds of thousands of cells;
      // such steps outrun any list, each takes one of its own.
      const Entry* last = next_ > 0 ? entry(next_ - 1) : nullptr;
      const double step =
          last && s.current.joined ? std::min(s.current.path - last->path, cell_) : 0.0;
      fill_nearby(cc, s.normal, feed, reach + nearby_across * std::max(reach, step),
                  abeam_ * (1 + nearby_behind),
                  abeam_ + std::max(nearby_ahead * abeam_, nearby_steps * step));
      // (the runs looked at before count as not looked at: the warm ones
      // may be looked at again, to no effect)
      ++search_;
      listed = true;
    }
    if (listed) {
      scan_nearby(s);
    } else {
      std::array<std::int64_t, 3> lo{}, hi{};
      cells_around(cc, feed, reach, abeam_, cell_, lo, hi);
      for_each_list(lo, hi, [&](std::uint32_t head) { scan_cell(s, head); });
    }
    // Nearest bound first: once a run's bound is no better than the best,
    // neither is any later one.
    std::sort(candidates_.begin(), candidates_.end(),
              [](const Candidate& x, const Candidate& y) { return x.low < y.low; });
    for (const Candidate& c : candidates_) {
      if (s.best && c.low > s.best->ae - tie) break;
      evaluate(s, c.run, c.flat);
    }
    candidates_.clear();
    if ((s.best && s.best->ae <= reach) || r >= radius_) break;
    // Nothing at all within r: go to the whole radius at once.
    r = s.best ? 2 * r : radius_;
  }
}

}  // namespace vcpost::pipeline
