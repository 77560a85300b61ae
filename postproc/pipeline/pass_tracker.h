// The width of cut ae and the side of the previous pass, measured from the
// toolpath itself (MODELS.md section 1): the distance across the feed from
// the current contact point CC to the nearest contact point of an earlier
// neighbouring pass. Works for raster, zig-zag, offset, spiral and Z-level
// patterns, because it only asks where earlier cuts ran, not how the path
// was generated.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "geometry/engagement.h"

namespace vcpost::pipeline {

struct NeighbourPass {
  double ae = 0;                                  // across the feed, mm
  geometry::Side side = geometry::Side::left;     // where it lies, looking along F with N up
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // the point of that pass abeam of CC
};

// Remembers the contact points of the recent path in a spatial hash.
// A point counts as an earlier pass when it lies on a stretch of path that
// ran roughly parallel to the current feed (within 45 deg, either way) and
// either belongs to another pass (passes are split by rapids, lost contact
// and turns of more than 45 deg) or lies more than `min_path_gap` mm back
// along the path (spirals never turn).
class PassTracker {
 public:
  // search_radius: farthest neighbour considered, mm (a pass farther than
  // the tool diameter removed nothing this pass would cut).
  // memory: how many recent points are kept (older ones are forgotten),
  // so memory does not grow with program length.
  PassTracker(double search_radius, double min_path_gap, std::size_t memory);

  // Starts a new pass (after a rapid, or where contact was lost).
  void break_pass();

  // Records the contact point of the next sample (in path order) and returns
  // the earlier pass nearest across the feed from it, within the search
  // radius. normal and feed: unit, feed in the tangent plane.
  std::optional<NeighbourPass> step(const Eigen::Vector3d& cc, const Eigen::Vector3d& normal,
                                    const Eigen::Vector3d& feed);

 private:
  struct Entry {
    Eigen::Vector3d point;
    Eigen::Vector3d feed;
    double path = 0;      // cumulative path length along the contact points, mm
    std::uint64_t pass = 0;
    bool joined = false;  // continues the previous entry (same pass, consecutive)
  };
  using Key = std::uint64_t;
  Key key_of(const Eigen::Vector3d& p) const;
  Key key_of(std::int64_t x, std::int64_t y, std::int64_t z) const;
  const Entry* entry(std::uint64_t sequence) const;
  std::optional<NeighbourPass> nearest(const Entry& current, const Eigen::Vector3d& normal) const;
  void add(const Entry& e);
  void compact();

  double radius_, min_gap_;
  double cell_;   // grid cell edge, mm: a sixteenth of the search radius
  double abeam_;  // how far along the feed a pass end still counts as abeam, mm
  double max_segment_ = 0;  // longest step between consecutive points of a pass so far
  double last_ae_ = 0;      // the last width of cut found: where the next search starts
  std::size_t memory_;
  std::vector<Entry> ring_;                // the last `memory` entries, by sequence % memory
  std::uint64_t next_ = 0;                 // sequence number of the next entry
  std::uint64_t pass_ = 0;
  bool pass_open_ = false;
  std::unordered_map<Key, std::vector<std::uint64_t>> grid_;  // cell -> sequence numbers
  std::uint64_t compacted_at_ = 0;
};

}  // namespace vcpost::pipeline
