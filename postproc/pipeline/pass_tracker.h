// The width of cut ae and the side of the previous pass, measured from the
// toolpath itself (MODELS.md section 1): the distance across the feed from
// the current contact point CC to the nearest contact point of an earlier
// neighbouring pass. Works for raster, zig-zag, offset, spiral and Z-level
// patterns, because it only asks where earlier cuts ran, not how the path
// was generated.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/engagement.h"

namespace vcpost::pipeline {

struct NeighbourPass {
  double ae = 0;                                    // across the feed, mm
  geometry::Side side = geometry::Side::left;       // where it lies, looking along F with N up
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // the point of that pass abeam of CC
  // Where that point lies on the recorded path: on the segment from the
  // point recorded before `entry` to it, at `fraction` of the way (1: the
  // recorded point itself). entry counts the steps of the tracker from 0.
  std::uint64_t entry = 0;
  double fraction = 1;
};

// Remembers the contact points of the recent path in a spatial hash.
// A point counts as an earlier pass when it lies on a stretch of path that
// ran roughly parallel to the current feed (within 45 deg, either way) and
// either belongs to another pass (passes are split by rapids, lost contact
// and turns of more than 45 deg) or lies more than `min_path_gap` mm back
// along the path (spirals never turn).
//
// The candidates from an earlier pass are where it crosses the plane across
// the feed through CC, and its pass ends within 0.1 search radius of that
// plane along the feed whose stretch of pass does not cross it within that
// distance (its other points are not: where a pass leans across the feed,
// they lie nearer than the pass does); the nearest candidate across the
// feed wins (ties within 1e-10 mm: any one).
// Earlier passes are those of the newest three through each grid cell
// (retraced or very close passes crowd a cell; the nearest is among the
// newest), so a step costs about the same whatever the passes' spacing.
//
// Cost: the grid indexes short runs of consecutive points (at most 16, and
// a sixteenth of the search radius long), each with a bounding capsule and
// a box of offsets from its axis, so a step looks at a few runs of the
// nearest passes and not at points one by one: on a straight pass one
// point of one run decides; on a curved one the points of a few runs. The
// runs near a step are listed once for the next several steps (while the
// list provably covers their reach, bounded by how far the feed turned and
// CC moved), so most steps do not walk the grid at all.
// Memory: O(`memory`, the points kept), about 100-250 bytes a point.
class PassTracker {
 public:
  // The points a tracker of the post keeps: a few passes of a large
  // program, its memory bounded whatever the program's length.
  static constexpr std::size_t kPostMemory = std::size_t{1} << 20;
  // A stretch of path runs along the feed when it turns from it by at most
  // 45 deg (either way).
  static constexpr double kParallelCos = 0.70710678118654752;
  // A pass end counts as abeam within this share of the search radius
  // along the feed.
  static constexpr double kAbeamShare = 0.1;

  // search_radius: farthest neighbour considered, mm (a pass farther than
  // the tool diameter removed nothing this pass would cut).
  // memory: how many recent points are kept (older ones are forgotten),
  // so memory does not grow with program length.
  // REQUIRES: search_radius > 0, min_path_gap >= 0, memory >= 1.
  PassTracker(double search_radius, double min_path_gap, std::size_t memory);

  // Starts a new pass (after a rapid, or where contact was lost).
  void break_pass();

  // Records the contact point of the next sample (in path order) and returns
  // the earlier pass nearest across the feed from it, within the search
  // radius. normal and feed: unit and perpendicular, feed in the tangent plane.
  std::optional<NeighbourPass> step(const Eigen::Vector3d& cc, const Eigen::Vector3d& normal,
                                    const Eigen::Vector3d& feed);

 private:
  struct Entry {
    Eigen::Vector3d point;
    Eigen::Vector3d feed;
    double path = 0;  // cumulative path length along the contact points, mm
    std::uint64_t pass = 0;
    bool joined = false;  // continues the previous entry (same pass, consecutive)
  };
  // Consecutive entries of one pass, at most about a cell long. Every point
  // of its segments lies within `radius` of the axis a-b (a convex capsule)
  // and within a box of offsets from it, which bound how near across the
  // feed and how far along it they can be.
  struct Run {
    Eigen::Vector3d a = Eigen::Vector3d::Zero();  // the entry before the first
                                                  // (joined), or the first
    Eigen::Vector3d b = Eigen::Vector3d::Zero();  // the last entry
    double radius = -1;                           // < 0 while the run is open (no capsule yet)
    std::uint64_t end = 0;                        // one past its last entry
    std::uint64_t mark = 0;   // the last search (or listing of nearby runs) that looked at it
    std::uint64_t first = 0;  // sequence of its first entry
    std::uint64_t pass = 0;   // the pass it belongs to
    // Every point of its segments is a + t (b - a) + o, 0 <= t <= 1, with
    // the offset o in the box offset_low..offset_high (and |o| <= radius);
    // floats rounded outwards (runs are many: memory and cache).
    Eigen::Vector3f offset_low = Eigen::Vector3f::Zero();
    Eigen::Vector3f offset_high = Eigen::Vector3f::Zero();
  };
  // The closed runs that may come within reach of an earlier step (a little
  // farther than its own), once each, with copies of their capsules side by
  // side (a closed run's capsule does not change): a later step whose reach
  // the list covers (nearby_covers) bounds them from here before reading
  // any run.
  struct Nearby {
    std::vector<std::uint64_t> id;
    std::vector<std::uint64_t> end;  // one past the last entry of the run
    std::array<std::vector<double>, 3> a, b;
    std::vector<double> radius;
    void clear();
    void push(std::uint64_t run_id, const Run& r);
  };
  // A node of a cell's list of runs, newest first; `run` is the run's
  // sequence modulo 2^32 (live runs span far fewer).
  struct Node {
    std::uint32_t run;
    std::uint32_t next;
  };
  static constexpr std::uint32_t none = ~std::uint32_t{0};
  // 4 x 4 x 4 cells: which of them hold runs, and the heads of their lists,
  // so one hash lookup serves 64 cells and empty cells cost a bit test.
  struct Block {
    std::uint64_t occupied = 0;
    std::uint32_t heads[64] = {};
  };
  // Open addressing with linear probing: block key -> Block, no allocation
  // per lookup; keys use 63 bits, so all ones marks an empty slot.
  class BlockMap {
   public:
    using Key = std::uint64_t;
    static constexpr Key empty = ~Key{0};
    const Block* find(Key key) const;
    Block& insert(Key key);  // a new block has no cell occupied
    std::size_t size() const { return size_; }
    void reserve(std::size_t blocks);
    template <class F>
    void for_each(F&& f) const {
      for (std::size_t i = 0; i < keys_.size(); ++i) {
        if (keys_[i] != empty) f(keys_[i], values_[i]);
      }
    }

   private:
    std::size_t slot(Key key) const;
    void grow();
    std::vector<Key> keys_;
    std::vector<Block> values_;
    std::size_t size_ = 0;
  };
  using Key = std::uint64_t;
  static Key key_of(std::int64_t x, std::int64_t y, std::int64_t z);

  const Entry* entry(std::uint64_t sequence) const;
  std::uint64_t kept() const { return std::min<std::uint64_t>(next_, memory_); }
  std::uint64_t oldest() const { return next_ - kept(); }  // oldest kept sequence
  Run& run(std::uint64_t sequence) { return runs_[sequence & mask_]; }
  std::uint64_t run_of(std::uint32_t low) const;
  bool run_alive(std::uint64_t sequence) const;

  void add(const Entry& e);
  void extend_run(const Entry& e, const std::optional<Eigen::Vector3d>& before);
  void close_run();
  void register_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& q, std::uint64_t run);
  void register_cell(std::int64_t x, std::int64_t y, std::int64_t z, std::uint64_t run);
  void compact();
  template <class F>
  void for_each_list(const std::array<std::int64_t, 3>& lo, const std::array<std::int64_t, 3>& hi,
                     F&& on_list) const;
  void fill_nearby(const Eigen::Vector3d& cc, const Eigen::Vector3d& normal,
                   const Eigen::Vector3d& feed, double across, double behind, double ahead);
  bool nearby_covers(const Eigen::Vector3d& cc, const Eigen::Vector3d& feed, double across,
                     double along) const;
  std::optional<NeighbourPass> nearest(const Entry& current, const Eigen::Vector3d& normal);
  // The steps of nearest(), on the state of one search.
  struct Search;
  void search_warm(Search& s);
  void search_outwards(Search& s);
  void scan_cell(Search& s, std::uint32_t head);
  void scan_nearby(Search& s);
  void look_at(Search& s, std::uint64_t id, Run& r);
  void evaluate(Search& s, std::uint64_t id, bool flat, std::uint64_t start = 0);
  bool evaluate_range(Search& s, std::uint64_t id, bool flat, std::uint64_t from,
                      std::uint64_t end) const;
  bool consider(Search& s, const Eigen::Vector3d& p, double fraction) const;
  bool stretch_crosses(const Search& s, std::uint64_t i, bool forward) const;
  std::optional<std::pair<double, bool>> measure(const Search& s, const Run& r, double worst) const;
  double worst(const Search& s) const;

  double radius_, min_gap_;
  double cell_;         // grid cell edge, mm: a sixteenth of the search radius
  double abeam_;        // how far along the feed a pass end still counts as abeam, mm
  double last_ae_ = 0;  // the last width of cut found: where the next search starts
  std::size_t memory_;
  std::size_t mask_;         // ring slots - 1: memory rounded up to a power of two, - 1
  std::vector<Entry> ring_;  // the last entries, by sequence & mask (the last `memory` count)
  std::uint64_t next_ = 0;   // sequence number of the next entry
  std::uint64_t pass_ = 0;
  std::uint64_t pass_start_ = 0;  // first entry of the current pass
  std::uint64_t cutoff_ = 0;      // entries from here on are not earlier passes
  bool pass_open_ = false;

  std::vector<Run> runs_;       // the last runs, by sequence & mask
  std::uint64_t run_next_ = 0;  // sequence number of the next run
  bool run_open_ = false;       // run_next_ - 1 still takes entries
  BlockMap blocks_;
  std::vector<Node> nodes_;
  std::size_t live_nodes_ = 0;      // nodes kept by the last compaction
  std::uint64_t compacted_at_ = 0;  // next_ at the last compaction
  std::uint64_t search_ = 0;        // number of searches and listings so far (marks runs seen)
  struct Candidate {
    double low;  // no candidate of the run lies nearer across the feed
    std::uint64_t run;
    bool flat;  // nor farther than low + tie
  };
  std::vector<Candidate> candidates_;  // runs to evaluate in a search, reused
  std::uint64_t run_cut_ = 0;          // runs from here on lie wholly at or after the cutoff
  std::optional<std::uint64_t> warm_;  // the run that held the last neighbour
  std::uint64_t warm_entry_ = 0;       // and the entry that gave it
  std::array<std::int64_t, 7> last_box_{0, 0, 0, -1, -1, -1, -1};  // cells and run last listed
  Nearby nearby_;
  Eigen::Vector3d nearby_cc_ = Eigen::Vector3d::Zero();  // the step it was listed for
  Eigen::Vector3d nearby_feed_ = Eigen::Vector3d::UnitX();
  double nearby_across_ = 0;  // its reach across that feed, mm
  double nearby_behind_ = 0,
         nearby_ahead_ = 0;        // and along it, back and forth, mm
  std::uint64_t nearby_from_ = 0;  // runs from here on were open or new: looked at directly
  bool nearby_valid_ = false;
};

}  // namespace vcpost::pipeline
