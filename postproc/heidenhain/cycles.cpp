#include "postproc/heidenhain/cycles.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vcpost::heidenhain {

namespace {

// The control's advanced stop distance above the last depth when the tool
// goes back down into a hole (a machine setting; 0.2 mm assumed).
constexpr double kAdvancedStop = 0.2;

class HoleWriter {
 public:
  HoleWriter(const DrillHole& h, std::vector<program::Event>& events)
      : h_(h), events_(events), at_(h.start) {}

  void traverse(double z) {
    const Eigen::Vector3d end(at_.x(), at_.y(), z);
    events_.emplace_back(program::StraightTraverse{at_, end, h_.source});
    at_ = end;
    ++moves_;
  }
  void feed(double z, double rate) {
    if (rate != rate_) {
      events_.emplace_back(program::SetFeedRate{rate, program::FeedMode::per_minute, h_.source});
      rate_ = rate;
    }
    const Eigen::Vector3d end(at_.x(), at_.y(), z);
    events_.emplace_back(program::StraightFeed{at_, end, h_.source});
    at_ = end;
    ++moves_;
  }
  // An arc in the plane about `centre` to `end` (a full turn when `end` is
  // where the tool is in the plane).
  void arc(const Eigen::Vector2d& centre, const Eigen::Vector3d& end, int rotation, double rate) {
    if (rate != rate_) {
      events_.emplace_back(program::SetFeedRate{rate, program::FeedMode::per_minute, h_.source});
      rate_ = rate;
    }
    events_.emplace_back(program::ArcFeed{at_, end,
                                          Eigen::Vector3d(centre.x(), centre.y(), at_.z()),
                                          program::Plane::xy, rotation, h_.source});
    at_ = end;
    ++moves_;
  }
  void dwell(double seconds) {
    if (seconds > 0) events_.emplace_back(program::Dwell{seconds, h_.source});
  }
  void spindle(bool ccw) {
    events_.emplace_back(program::SpindleOn{
        ccw ? program::SpindleDirection::counterclockwise : program::SpindleDirection::clockwise,
        h_.source});
  }
  void restore_feed() {
    if (h_.restore_feed > 0 && rate_ != 0 && rate_ != h_.restore_feed)
      events_.emplace_back(
          program::SetFeedRate{h_.restore_feed, program::FeedMode::per_minute, h_.source});
  }
  // Back to the hole's axis at the feed, at the same height.
  void centre(double rate) {
    const Eigen::Vector3d end(h_.start.x(), h_.start.y(), at_.z());
    if ((end - at_).norm() < 1e-12) return;
    if (rate != rate_) {
      events_.emplace_back(program::SetFeedRate{rate, program::FeedMode::per_minute, h_.source});
      rate_ = rate;
    }
    events_.emplace_back(program::StraightFeed{at_, end, h_.source});
    at_ = end;
    ++moves_;
  }
  double z() const { return at_.z(); }
  const Eigen::Vector3d& at() const { return at_; }
  std::uint32_t moves() const { return moves_; }

 private:
  const DrillHole& h_;
  std::vector<program::Event>& events_;
  Eigen::Vector3d at_;
  double rate_ = 0;
  std::uint32_t moves_ = 0;
};

// Pecks from the surface to the bottom (200 203 205): each plunge at the
// feed, then a chip break (203: back by Q256) or a retract to the clearance
// and back down to the advanced stop distance above the depth reached.
void pecks(const DrillHole& h, HoleWriter& w, double clear, double bottom) {
  const double retract_feed = h.retract_feed > 0 ? h.retract_feed : h.feed;
  double reached = h.surface;
  double plunge = h.plunge;
  int breaks = 0;
  for (;;) {
    const double next = std::max(reached - plunge, bottom);
    w.feed(next, h.feed);
    reached = next;
    if (reached <= bottom) break;
    if (h.cycle == 203 && breaks < h.chip_breaks) {
      w.feed(reached + h.chip_retract, retract_feed);
      ++breaks;
    } else {
      w.traverse(clear);
      w.dwell(h.dwell_top);
      w.traverse(h.cycle == 200 ? std::min(clear, reached + h.clearance)
                                : std::min(clear, reached + kAdvancedStop));
      breaks = 0;
    }
    if (h.cycle != 200) plunge = std::max(plunge - h.decrement, std::max(h.min_plunge, 1e-3));
  }
}

// Cycle 208 as the TNC user's manual describes it: from the hole's centre a
// semicircle onto the helix (assumed to go down half a pitch, as the helix
// does over half a turn), the helix at Q334 per turn down to the depth, a
// full circle there for what the plunge left, back to the centre.
void bore_helix(const DrillHole& h, HoleWriter& w, double bottom) {
  const Eigen::Vector2d c = w.at().head<2>();
  const double r = h.helix_radius;
  const int dir = h.helix_rotation;
  double z = std::max(w.z() - h.pitch / 2, bottom);
  w.arc(c + Eigen::Vector2d(r / 2, 0), Eigen::Vector3d(c.x() + r, c.y(), z), dir, h.feed);
  while (z > bottom + 1e-9) {
    if (z - h.pitch >= bottom - 1e-9) {
      z -= h.pitch;
      w.arc(c, Eigen::Vector3d(c.x() + r, c.y(), std::max(z, bottom)), dir, h.feed);
      continue;
    }
    const double angle = dir * 2 * std::numbers::pi * (z - bottom) / h.pitch;
    w.arc(c, Eigen::Vector3d(c.x() + r * std::cos(angle), c.y() + r * std::sin(angle), bottom), dir,
          h.feed);
    z = bottom;
  }
  w.arc(c, w.at(), dir, h.feed);
}

}  // namespace

Eigen::Vector3d expand_hole(const DrillHole& h, std::vector<program::Event>& events) {
  const std::size_t cycle_at = events.size();
  events.emplace_back(program::CannedCycle{});
  const double clear = h.surface + h.clearance;
  const double top = std::max(clear, h.surface + h.second_clearance);
  const double bottom = h.surface + h.depth;
  HoleWriter w(h, events);
  w.traverse(clear);
  switch (h.cycle) {
    case 200:
    case 203:
    case 205:
      pecks(h, w, clear, bottom);
      w.dwell(h.dwell_bottom);
      if (h.cycle == 200) {
        w.traverse(clear);
      } else {
        w.feed(clear, h.retract_feed > 0 ? h.retract_feed : h.feed);
      }
      break;
    case 201:
      w.feed(bottom, h.feed);
      w.dwell(h.dwell_bottom);
      w.feed(clear, h.retract_feed > 0 ? h.retract_feed : h.feed);
      break;
    case 207:
      w.feed(bottom, h.feed);
      w.spindle(!h.spindle_ccw);  // the spindle reverses at the bottom
      w.feed(clear, h.feed);
      w.spindle(h.spindle_ccw);
      break;
    default:  // 208
      if (h.helix_radius > 0 && h.pitch > 0) {
        bore_helix(h, w, bottom);
        w.centre(h.feed);
      } else {
        w.feed(bottom, h.feed);  // along the hole's axis (see the header)
      }
      w.traverse(clear);
      break;
  }
  if (top > w.z()) w.traverse(top);
  w.restore_feed();
  program::CannedCycle c;
  c.code = h.cycle;
  c.x = h.start.x();
  c.y = h.start.y();
  c.top_z = top;
  c.r_z = clear;
  c.bottom_z = bottom;
  c.peck = h.cycle == 200 || h.cycle == 203 || h.cycle == 205 ? h.plunge : 0.0;
  c.dwell_s = h.dwell_bottom;
  c.events = static_cast<std::uint32_t>(events.size() - cycle_at - 1);
  c.moves = w.moves();
  c.source = h.source;
  events[cycle_at] = c;
  return w.at();
}

}  // namespace vcpost::heidenhain
