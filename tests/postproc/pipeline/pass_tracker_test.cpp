// The pass tracker on paths whose neighbouring pass is known by hand
// (rasters, spirals, offset contours, Z-levels, mixed point spacing), and
// against a plain reference that checks every kept point on the sample
// generator's programs.
#include "postproc/pipeline/pass_tracker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "postproc/samplegen/parts.h"
#include "postproc/samplegen/tool_placement.h"
#include "postproc/samplegen/toolpath.h"

namespace vcpost::pipeline {
namespace {

using Eigen::Vector3d;
using geometry::Side;
constexpr double pi = std::numbers::pi;

// One contact point of a path: where, surface normal, feed (unit, tangent),
// and whether a new pass starts there (after a rapid).
struct Point {
  Vector3d cc;
  Vector3d normal;
  Vector3d feed;
  bool starts_pass = false;
  int pass = 0;
};

std::vector<std::optional<NeighbourPass>> track(PassTracker& tracker,
                                                const std::vector<Point>& path) {
  std::vector<std::optional<NeighbourPass>> out;
  out.reserve(path.size());
  for (const Point& p : path) {
    if (p.starts_pass) tracker.break_pass();
    out.push_back(tracker.step(p.cc, p.normal, p.feed));
  }
  return out;
}

// Straight passes along u, `stepover` apart along v = n x u, points
// `spacing` apart, each pass `length` long, starting at `origin`.
std::vector<Point> raster(const Vector3d& origin, const Vector3d& u, const Vector3d& n,
                          double stepover, double spacing, double length, int passes, bool zigzag) {
  const Vector3d v = n.cross(u);
  const auto count = static_cast<int>(std::lround(length / spacing));
  std::vector<Point> path;
  for (int k = 0; k < passes; ++k) {
    const bool back = zigzag && k % 2 == 1;
    for (int i = 0; i <= count; ++i) {
      const double s = back ? length - spacing * i : spacing * i;
      path.push_back({origin + s * u + k * stepover * v, n, back ? Vector3d(-u) : u, i == 0, k});
    }
  }
  return path;
}

TEST(PassTrackerGeometry, ZigZagRasterGivesTheStepoverWithAlternatingSides) {
  PassTracker tracker(10, 40, 1 << 16);
  const Vector3d up(0, 0, 1);
  const auto path = raster({0, 0, 0}, {1, 0, 0}, up, 0.7, 0.1, 30, 6, true);
  const auto found = track(tracker, path);
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Point& p = path[i];
    if (p.pass == 0) {
      EXPECT_FALSE(found[i]) << i;
      continue;
    }
    ASSERT_TRUE(found[i]) << i;
    EXPECT_NEAR(found[i]->ae, 0.7, 1e-9) << i;
    // The previous pass lies at -y. Along +x, left is +y (N x F): right;
    // along -x it is on the left.
    EXPECT_EQ(found[i]->side, p.pass % 2 == 0 ? Side::right : Side::left) << i;
    EXPECT_NEAR(found[i]->point.y(), 0.7 * (p.pass - 1), 1e-9) << i;
  }
}

TEST(PassTrackerGeometry, PassesAtThirtyDegreesToTheGridOnARaisedPlane) {
  // The same raster turned 30 deg about z and lifted to z = 3.1: the grid's
  // cells no longer line up with the passes.
  PassTracker tracker(10, 40, 1 << 16);
  const Vector3d up(0, 0, 1);
  const Vector3d u(std::cos(pi / 6), std::sin(pi / 6), 0);
  const auto path = raster({-4, 2, 3.1}, u, up, 0.7, 0.1, 25, 5, true);
  const auto found = track(tracker, path);
  int measured = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i].pass == 0) {
      EXPECT_FALSE(found[i]) << i;
      continue;
    }
    ASSERT_TRUE(found[i]) << i;
    EXPECT_NEAR(found[i]->ae, 0.7, 1e-9) << i;
    EXPECT_EQ(found[i]->side, path[i].pass % 2 == 0 ? Side::right : Side::left) << i;
    ++measured;
  }
  EXPECT_EQ(measured, 4 * 251);
}

TEST(PassTrackerGeometry, OneWayRasterOnATiltedPlaneKeepsThePreviousPassOnTheRight) {
  const Vector3d n = Vector3d(-0.3, 0.2, 1).normalized();
  const Vector3d u = Vector3d(1, 0, 0.3).normalized();  // in the plane: u . n = 0
  ASSERT_NEAR(u.dot(n), 0, 1e-15);
  PassTracker tracker(10, 40, 1 << 16);
  const auto path = raster({1, 1, 1}, u, n, 0.7, 0.05, 12, 4, false);
  const auto found = track(tracker, path);
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i].pass == 0) continue;
    ASSERT_TRUE(found[i]) << i;
    EXPECT_NEAR(found[i]->ae, 0.7, 1e-9) << i;
    EXPECT_EQ(found[i]->side, Side::right) << i;
  }
}

TEST(PassTrackerGeometry, DensePassBesideASparseOneAndTheOtherWayRound) {
  const Vector3d up(0, 0, 1), along(1, 0, 0);
  for (const bool dense_first : {false, true}) {
    PassTracker tracker(10, 40, 1 << 16);
    std::vector<Point> path;
    const auto add_pass = [&](double y, double spacing, int pass) {
      const auto count = static_cast<int>(std::lround(20 / spacing));
      for (int i = 0; i <= count; ++i)
        path.push_back({{spacing * i, y, 0}, up, along, i == 0, pass});
    };
    add_pass(0, dense_first ? 0.01 : 2.0, 0);
    add_pass(0.7, dense_first ? 2.0 : 0.01, 1);
    const auto found = track(tracker, path);
    int measured = 0;
    for (std::size_t i = 0; i < path.size(); ++i) {
      if (path[i].pass == 0) {
        EXPECT_FALSE(found[i]);
        continue;
      }
      ASSERT_TRUE(found[i]) << dense_first << " " << i;
      EXPECT_NEAR(found[i]->ae, 0.7, 1e-9) << dense_first << " " << i;
      EXPECT_EQ(found[i]->side, Side::right);
      ++measured;
    }
    EXPECT_EQ(measured, dense_first ? 11 : 2001);
  }
}

// Archimedean spiral r = b * theta (pitch 2 pi b), outwards and
// anticlockwise, points `spacing` apart along it.
struct Spiral {
  double b;
  Vector3d at(double t) const { return {b * t * std::cos(t), b * t * std::sin(t), 0}; }
  Vector3d tangent(double t) const {
    return Vector3d(b * std::cos(t) - b * t * std::sin(t), b * std::sin(t) + b * t * std::cos(t), 0)
        .normalized();
  }
};

TEST(PassTrackerGeometry, SpiralMeasuresTheTurnInsideAcrossTheFeed) {
  const double pitch = 0.7;
  const Spiral spiral{pitch / (2 * pi)};
  PassTracker tracker(10, 40, 1 << 18);
  const Vector3d up(0, 0, 1);
  std::vector<Point> path;
  std::vector<double> thetas;
  for (double t = 2 * pi; spiral.b * t < 16;) {
    path.push_back({spiral.at(t), up, spiral.tangent(t), path.empty(), 0});
    thetas.push_back(t);
    t += 0.05 / (spiral.b * std::hypot(t, 1));  // 0.05 mm of arc
  }
  const auto found = track(tracker, path);
  int measured = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const double t = thetas[i];
    if (spiral.b * t < 9) continue;  // inner turns are shorter than the path gap (40 mm)
    // Independent figure: where the turn inside crosses the plane across
    // the feed, by bisection on the exact curve near t - 2 pi.
    const Vector3d& cc = path[i].cc;
    const Vector3d& f = path[i].feed;
    double lo = t - 2 * pi - 0.3, hi = t - 2 * pi + 0.3;
    for (int k = 0; k < 100; ++k) {
      const double mid = (lo + hi) / 2;
      ((spiral.at(mid) - cc).dot(f) < 0 ? lo : hi) = mid;
    }
    const double expected = (spiral.at(lo) - cc).norm();
    ASSERT_TRUE(found[i]) << i;
    // The tracker interpolates between points 0.05 mm apart on a turn of
    // radius >= 9 mm: the chord lies inside the arc by at most
    // 0.05^2 / (8 * 9) = 3.5e-5 mm.
    EXPECT_NEAR(found[i]->ae, expected, 4e-5) << i;
    EXPECT_GT(found[i]->ae, expected - 1e-12) << i;  // the chord bows inwards: away from CC
    EXPECT_NEAR(found[i]->ae, pitch, 0.01) << i;
    EXPECT_EQ(found[i]->side, Side::left) << i;  // the turn inside: left of an anticlockwise feed
    ++measured;
  }
  EXPECT_GT(measured, 5000);
}

// Concentric arcs of 300 deg about the z axis, all anticlockwise, each
// sampled at the same angles 1 deg apart (so every arc has a point on every
// radius). Not whole circles: a closed circle longer than the path gap
// meets its own start, an earlier pass a few micrometres away.
std::vector<Point> circles(const std::vector<double>& radii, double z_step, Vector3d normal_of_xy) {
  std::vector<Point> path;
  for (std::size_t k = 0; k < radii.size(); ++k) {
    for (int i = 0; i <= 300; ++i) {
      const double a = i * pi / 180;
      const Vector3d radial(std::cos(a), std::sin(a), 0);
      const Vector3d normal = normal_of_xy.z() != 0 ? normal_of_xy : radial;
      path.push_back({radii[k] * radial + Vector3d(0, 0, -z_step * static_cast<double>(k)), normal,
                      Vector3d(-std::sin(a), std::cos(a), 0), i == 0, static_cast<int>(k)});
    }
  }
  return path;
}

TEST(PassTrackerGeometry, OffsetContoursOutwardsMeasureTheOffset) {
  // Each circle 0.7 outside the previous one: the previous circle curves
  // away from the feed line, so its crossing (a point on the same radius)
  // is the nearest candidate.
  PassTracker tracker(10, 40, 1 << 16);
  const auto path = circles({10, 10.7, 11.4, 12.1}, 0, {0, 0, 1});
  const auto found = track(tracker, path);
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i].pass == 0) {
      EXPECT_FALSE(found[i]) << i;
      continue;
    }
    ASSERT_TRUE(found[i]) << i;
    EXPECT_NEAR(found[i]->ae, 0.7, 1e-9) << i;
    EXPECT_EQ(found[i]->side, Side::left) << i;  // inside an anticlockwise feed
  }
}

TEST(PassTrackerGeometry, OffsetContoursInwardsMeasureTheOffsetNotTheNearerPointsAhead) {
  // Each circle 0.7 inside the previous one (radius R = r + 0.7): the
  // previous circle bends towards the feed line, and its points 2 deg
  // along (R sin 2 deg < 1 mm = 0.1 D, within the abeam allowance) lie
  // 0.7 - R (1 - cos 2 deg) = 0.687 across, its first point 1 deg behind
  // the second point of an arc 0.697. The circle itself lies 0.7 away
  // across the feed: its crossing, not a point of it ahead or behind, is ae.
  PassTracker tracker(10, 40, 1 << 16);
  const auto path = circles({20.7, 20, 19.3}, 0, {0, 0, 1});
  const auto found = track(tracker, path);
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i].pass == 0) continue;
    ASSERT_TRUE(found[i]) << i;
    EXPECT_NEAR(found[i]->ae, 0.7, 1e-9) << i;
    EXPECT_EQ(found[i]->side, Side::right) << i;  // outside an anticlockwise feed
  }
}

TEST(PassTrackerGeometry, ZLevelPassesOnACylinderWallMeasureTheStepDown) {
  // Circles of radius 20 on the outside of a vertical cylinder, 0.7 mm
  // apart in z, going down: N is radial, N x F = +z, so the level above
  // lies on the left, 0.7 away (points of that level off the radius are
  // farther: they add a radial offset).
  PassTracker tracker(10, 40, 1 << 16);
  const auto path = circles({20, 20, 20, 20}, 0.7, {0, 0, 0});
  const auto found = track(tracker, path);
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i].pass == 0) {
      EXPECT_FALSE(found[i]) << i;
      continue;
    }
    ASSERT_TRUE(found[i]) << i;
    EXPECT_NEAR(found[i]->ae, 0.7, 1e-9) << i;
    EXPECT_EQ(found[i]->side, Side::left) << i;
    EXPECT_NEAR(found[i]->point.z(), path[i].cc.z() + 0.7, 1e-9) << i;
  }
}

// A ball raster of the sample generator against the exact width of cut:
// for every contact point P of a pass (feed F: the written motion on the
// tangent plane, as the post takes it), where the previous pass's contact
// track crosses the plane through P across F, and the distance to that
// crossing. The track is the exact contact of the ball dropped at every
// point of that pass's straight xy line (the generator's drop-cutter),
// found by bisection on the line: no sampled point of the path, no rule
// of the tracker. The tracker's ae must be that distance, within
// `tolerance` (it follows straight chords between points at most 0.5 mm
// apart). On these surfaces the contact track of a pass leans off the
// written line (the ball's contact moves across it as the normal turns),
// so other points of the previous pass near the plane lie nearer across
// F than the crossing.
void expect_exact_raster_ae(const std::string& part_name, const samplegen::PathSpec& spec,
                            double tolerance) {
  const auto part = samplegen::make_part(part_name);
  ASSERT_TRUE(part) << part_name;
  const samplegen::SampleSurface& surface = *part->surface;
  std::vector<samplegen::PathPoint> points;
  samplegen::generate(surface, spec, 6,
                      [&](const samplegen::PathPoint& p) { points.push_back(p); });
  const double radius = spec.tool_radius;
  PassTracker tracker(2 * radius, 8 * radius, 1 << 16);
  // Each pass's written line in xy (its first and last point off the link).
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> lines;
  for (const auto& p : points) {
    if (p.link) continue;
    if (static_cast<std::size_t>(p.pass) >= lines.size())
      lines.emplace_back(p.tip.head<2>(), Eigen::Vector2d::Zero());
    lines.back().second = p.tip.head<2>();
  }
  double worst = 0, sum_below = 0;
  int checked = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    const bool starts = p.pass_start || i == 0;
    Vector3d motion =
        starts ? Vector3d(points[i + 1].tip - p.tip) : Vector3d(p.tip - points[i - 1].tip);
    motion -= motion.dot(p.normal) * p.normal;
    if (starts) tracker.break_pass();
    const Vector3d feed = motion.normalized();
    const auto found = tracker.step(p.cc, p.normal, feed);
    if (p.link || p.pass == 0) continue;
    // The previous pass's exact contact track where it crosses the plane.
    const Eigen::Vector2d a = lines[static_cast<std::size_t>(p.pass - 1)].first;
    const Eigen::Vector2d b = lines[static_cast<std::size_t>(p.pass - 1)].second;
    const Eigen::Vector2d u = (b - a).normalized();
    const double length = (b - a).norm();
    const auto contact = [&](double s) {
      const auto placed = samplegen::drop_tool(surface, 0, radius, a + s * u, p.uv);
      return Vector3d(surface.point(placed.uv));
    };
    const auto height = [&](double s) { return feed.dot(contact(s) - p.cc); };
    const double s0 = (p.tip.head<2>() - a).dot(u);
    double lo = std::max(0.0, s0 - 3), hi = std::min(length, s0 + 3);
    const double h_lo = height(lo), h_hi = height(hi);
    if ((h_lo < 0) == (h_hi < 0)) continue;  // the previous pass ends beside P
    for (int k = 0; k < 60; ++k) {
      const double mid = (lo + hi) / 2;
      ((height(mid) < 0) == (h_lo < 0) ? lo : hi) = mid;
    }
    const Vector3d d = contact(lo) - p.cc;
    const double exact = (d - d.dot(feed) * feed).norm();
    ASSERT_TRUE(found) << part_name << " point " << i;
    worst = std::max(worst, std::abs(found->ae - exact));
    sum_below += exact - found->ae;
    EXPECT_NEAR(found->ae, exact, tolerance)
        << part_name << " point " << i << " pass " << p.pass << " at " << p.cc.transpose();
    ++checked;
  }
  std::cout << part_name << ": " << checked << " points, ae off the exact by at most " << worst
            << " mm, " << sum_below / checked << " mm below it on average\n";
  EXPECT_GT(checked, 500) << part_name;
}

// A raster of the part's own ball at ae `stepover` (mm), points at most
// 0.5 mm apart and as near the ball-centre path as the samples'.
samplegen::PathSpec ball_raster(const samplegen::Part& part, double stepover) {
  samplegen::PathSpec spec;
  spec.tool_radius = part.tool_diameter / 2;
  spec.stepover = stepover;
  spec.step = 0.5;
  spec.chord_tolerance = samplegen::kSampleChordTolerance;
  return spec;
}

TEST(PassTrackerGeometry, WavyRasterMeasuresTheExactSpacingOfTheContactTracks) {
  // The wavy sample's raster along x at ae 0.5 mm over y 10..13 (D 10).
  const auto part = samplegen::make_part("wavy");
  samplegen::PathSpec spec = ball_raster(*part, 0.5);
  spec.window = Eigen::AlignedBox2d(Eigen::Vector2d(10, 10), Eigen::Vector2d(110, 13));
  expect_exact_raster_ae("wavy", spec, 5e-4);
}

TEST(PassTrackerGeometry, CylinderRasterAt45DegreesMeasuresTheExactSpacingOfTheContactTracks) {
  // The R100 semi-cylinder's raster at 45 deg to its axis, ae 0.2 (D 12):
  // the contact tracks lie at 43.3 deg to the axis in xy (their y is the
  // centre's times 100/106), 1.7 deg off the feed.
  const auto part = samplegen::make_part("cylinder");
  samplegen::PathSpec spec = ball_raster(*part, 0.2);
  spec.angle_deg = 45;
  spec.window = part->raster_window;
  expect_exact_raster_ae("cylinder", spec, 5e-4);
}

// The tracker's rule written plainly: every kept point, no index.
class Reference {
 public:
  Reference(double radius, double gap, std::size_t memory)
      : radius_(radius), gap_(gap), memory_(memory) {}
  void break_pass() { open_ = false; }

  std::optional<NeighbourPass> step(const Vector3d& cc, const Vector3d& n, const Vector3d& f,
                                    bool search) {
    const double cos45 = std::sqrt(0.5);
    const Stored* last = stored_.empty() ? nullptr : &stored_.back();
    if (!open_ || (last && last->feed.dot(f) < cos45)) {
      ++pass_;
      open_ = true;
    }
    const Stored current{cc, f, last ? last->path + (cc - last->point).norm() : 0.0, pass_,
                         last && last->pass == pass_};
    std::optional<NeighbourPass> best;
    std::vector<NeighbourPass> all;
    const std::size_t first = stored_.size() > memory_ ? stored_.size() - memory_ : 0;
    const Vector3d left = n.cross(f);
    for (std::size_t i = first; search && i < stored_.size(); ++i) {
      const Stored& e = stored_[i];
      if (std::abs(e.feed.dot(f)) < cos45) continue;                   // not parallel
      if (e.pass == pass_ && current.path - e.path <= gap_) continue;  // this pass, just behind
      const auto h = [&](std::size_t j) { return f.dot(stored_[j].point - cc); };
      const auto crosses = [](double from, double to) {
        return (from <= 0) != (to <= 0) || to == 0;
      };
      // The segment into entry j belongs to an earlier pass's stretch
      // parallel to the feed (and is looked at for a crossing).
      const auto segment_into = [&](std::size_t j) {
        const Stored& s = stored_[j];
        return j > first && j < stored_.size() && s.joined && std::abs(s.feed.dot(f)) >= cos45 &&
               !(s.pass == pass_ && current.path - s.path <= gap_);
      };
      const double h1 = h(i);
      std::optional<Vector3d> candidate;
      if (segment_into(i) && crosses(h(i - 1), h1)) {  // crosses the plane across the feed
        const Vector3d& p0 = stored_[i - 1].point;
        const double h0 = h(i - 1);
        const double t = h0 == h1 ? 1.0 : h0 / (h0 - h1);
        candidate = p0 + t * (e.point - p0);
      } else if (std::abs(h1) <= 0.1 * radius_) {
        // Almost abeam: a lone point, or an end of a stretch that does not
        // cross the plane before it leaves the abeam allowance.
        const bool before = segment_into(i), after = segment_into(i + 1);
        bool reaches = before && after;
        for (std::size_t j = i + 1; after && !before && segment_into(j); ++j) {
          if (crosses(h(j - 1), h(j))) reaches = true;
          if (reaches || std::abs(h(j)) > 0.1 * radius_) break;
        }
        for (std::size_t j = i; before && !after && segment_into(j); --j) {
          if (crosses(h(j - 1), h(j))) reaches = true;
          if (reaches || std::abs(h(j - 1)) > 0.1 * radius_) break;
        }
        if (!reaches) candidate = e.point;
      }
      if (!candidate) continue;
      const Vector3d d = *candidate - cc;
      const double across = std::hypot(left.dot(d), n.dot(d));
      if (across > radius_ || across <= 1e-9) continue;
      const NeighbourPass here{across, left.dot(d) >= 0 ? Side::left : Side::right, *candidate};
      all.push_back(here);
      if (best && across >= best->ae) continue;
      best = here;
    }
    // Every candidate within the tie of the best: any one of them may be
    // the tracker's answer.
    ties_.clear();
    for (const NeighbourPass& c : all) {
      if (best && c.ae <= best->ae + 1e-10) ties_.push_back(c);
    }
    stored_.push_back(current);
    return best;
  }
  // The candidates of the last search that tie with its best.
  const std::vector<NeighbourPass>& ties() const { return ties_; }

 private:
  struct Stored {
    Vector3d point, feed;
    double path;
    int pass;
    bool joined;
  };
  double radius_, gap_;
  std::size_t memory_;
  std::vector<Stored> stored_;
  std::vector<NeighbourPass> ties_;
  int pass_ = 0;
  bool open_ = false;
};

// The contact points of a sample-generator path, with the feed of the
// move into each point (out of it at a pass start) on the tangent plane.
std::vector<Point> sample_path(const samplegen::SampleSurface& surface,
                               const samplegen::PathSpec& spec) {
  std::vector<samplegen::PathPoint> points;
  samplegen::generate(surface, spec, 6,
                      [&](const samplegen::PathPoint& p) { points.push_back(p); });
  std::vector<Point> path;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    const bool starts = p.pass_start || i == 0;
    Vector3d motion = Vector3d::UnitX();
    if (!starts) {
      motion = p.tip - points[i - 1].tip;
    } else if (i + 1 < points.size()) {
      motion = points[i + 1].tip - p.tip;
    }
    motion -= motion.dot(p.normal) * p.normal;
    if (motion.norm() < 1e-12) continue;
    path.push_back({p.cc, p.normal, motion.normalized(), starts, p.pass});
  }
  return path;
}

void expect_same_as_reference(const std::vector<Point>& path, double radius, std::size_t memory,
                              std::size_t check_every, const std::string& name) {
  PassTracker tracker(radius, 4 * radius, memory);
  Reference reference(radius, 4 * radius, memory);
  std::uint64_t lcg = 12345;  // checks at pseudo-random points, about one in check_every
  int checked = 0, found = 0, ties = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Point& p = path[i];
    if (p.starts_pass) {
      tracker.break_pass();
      reference.break_pass();
    }
    lcg = lcg * 6364136223846793005ULL + 1442695040888963407ULL;
    const bool check = (lcg >> 33) % check_every == 0;
    const auto got = tracker.step(p.cc, p.normal, p.feed);
    const auto want = reference.step(p.cc, p.normal, p.feed, check);
    if (!check) continue;
    ++checked;
    ASSERT_EQ(got.has_value(), want.has_value()) << name << " point " << i;
    if (!want) continue;
    ++found;
    // The same neighbour: the reference's best, or a candidate within the
    // tie (1e-10 mm) of it, with its side and point.
    EXPECT_NEAR(got->ae, want->ae, 1e-10) << name << " point " << i;
    bool same = false;
    for (const NeighbourPass& c : reference.ties()) {
      same = same || (std::abs(c.ae - got->ae) <= 1e-12 && c.side == got->side &&
                      (c.point - got->point).norm() <= 1e-12);
    }
    EXPECT_TRUE(same) << name << " point " << i << ": ae " << got->ae << " at "
                      << got->point.transpose() << ", reference " << want->ae << " at "
                      << want->point.transpose() << " (" << reference.ties().size() << " tied)";
    ties += reference.ties().size() > 1;
  }
  if (ties > 0) std::cout << name << ": " << ties << " of " << found << " ties\n";
  EXPECT_GT(found, checked / 2) << name;  // the paths are mostly passes beside passes
}

TEST(PassTrackerReference, SameNeighbourAsEveryKeptPointOnTheSamplePrograms) {
  for (const auto& program : samplegen::sample_programs()) {
    const auto part = samplegen::make_part(program.part);
    ASSERT_TRUE(part) << program.part;
    const auto path = sample_path(*part->surface, program.path);
    ASSERT_GT(path.size(), 100u) << program.stem;
    expect_same_as_reference(path, program.program.tool_diameter, 1 << 16, 1, program.stem);
  }
}

// The path of the wavy sample program's raster (tests change its density).
samplegen::PathSpec wavy_raster_spec() {
  samplegen::PathSpec spec;
  for (const auto& program : samplegen::sample_programs()) {
    if (program.part == "wavy" && program.path.pattern == samplegen::Pattern::raster) {
      spec = program.path;
    }
  }
  return spec;
}

TEST(PassTrackerReference, SameNeighbourOnADenseWavyRasterWithAShortMemory) {
  // The wavy raster at 0.1 mm along and 0.35 mm across, about 30 k points:
  // 2000 points checked, once remembering everything and once only the
  // last 700 points (about 2.5 passes: older ones are forgotten).
  const auto part = samplegen::make_part("wavy");
  ASSERT_TRUE(part);
  samplegen::PathSpec spec = wavy_raster_spec();
  spec.stepover = 0.35;
  spec.step = 0.1;
  spec.window = Eigen::AlignedBox2d(spec.window.min(), spec.window.min() + Eigen::Vector2d(25, 30));
  const auto path = sample_path(*part->surface, spec);
  ASSERT_GT(path.size(), 20000u);
  const double d = 2 * spec.tool_radius;
  const auto every = path.size() / 2000;
  expect_same_as_reference(path, d, 1 << 20, every, "wavy dense");
  expect_same_as_reference(path, d, 700, every, "wavy dense, memory 700");
}

TEST(PassTrackerReference, SameNeighbourOnTheFineWavyRaster) {
  // The sample generator's wavy raster as the post job meets it: 0.0775 mm
  // along and across (about eight passes to a grid cell), curved passes
  // (no run is flat), a 10 x 7 mm window: about 12 k points, all checked.
  const auto part = samplegen::make_part("wavy");
  ASSERT_TRUE(part);
  samplegen::PathSpec spec = wavy_raster_spec();
  spec.stepover = 0.0775;
  spec.step = 0.0775;
  spec.window = Eigen::AlignedBox2d(spec.window.min() + Eigen::Vector2d(12, 9),
                                    spec.window.min() + Eigen::Vector2d(22, 16));
  const auto path = sample_path(*part->surface, spec);
  ASSERT_GT(path.size(), 10000u);
  const double d = 2 * spec.tool_radius;
  expect_same_as_reference(path, d, 1 << 20, 1, "wavy fine");
  expect_same_as_reference(path, d, 1000, 1, "wavy fine, memory 1000");
}

TEST(PassTrackerReference, SameNeighbourOnASpiralOverAWavySurface) {
  // An Archimedean spiral (0.3 mm pitch, 0.05 mm along) seen from above,
  // laid on z = 4 sin(2 pi x / 40) cos(2 pi y / 55) + 2 sin(2 pi (x + y) / 17)
  // with the true normal and the feed along the curve: no pass breaks, the
  // path gap (24 mm for D 6) decides what counts as the turn inside.
  constexpr double kx = 2 * pi / 40, ky = 2 * pi / 55, kd = 2 * pi / 17;
  const auto lift = [&](double x, double y) {
    const double z = 4 * std::sin(kx * x) * std::cos(ky * y) + 2 * std::sin(kd * (x + y));
    const double zx =
        4 * kx * std::cos(kx * x) * std::cos(ky * y) + 2 * kd * std::cos(kd * (x + y));
    const double zy =
        -4 * ky * std::sin(kx * x) * std::sin(ky * y) + 2 * kd * std::cos(kd * (x + y));
    return std::pair{Vector3d(x, y, z), Vector3d(-zx, -zy, 1).normalized()};
  };
  const Spiral spiral{0.3 / (2 * pi)};
  std::vector<Point> path;
  for (double t = 2 * pi * 6; spiral.b * t < 6.5;) {
    const Vector3d flat = spiral.at(t) + Vector3d(3, -2, 0);
    const auto [cc, normal] = lift(flat.x(), flat.y());
    // The feed: the curve's tangent lifted onto the tangent plane.
    const Vector3d ahead = spiral.at(t + 1e-6) + Vector3d(3, -2, 0);
    const Vector3d along = lift(ahead.x(), ahead.y()).first - cc;
    path.push_back(
        {cc, normal, (along - along.dot(normal) * normal).normalized(), path.empty(), 0});
    t += 0.05 / (spiral.b * std::hypot(t, 1));
  }
  ASSERT_GT(path.size(), 5000u);
  expect_same_as_reference(path, 6, 1 << 20, 1, "wavy spiral");
  expect_same_as_reference(path, 6, 3000, 1, "wavy spiral, memory 3000");
}

TEST(PassTrackerReference, SameNeighbourOnTightArcsWhileTheFeedTurns) {
  // Arcs of 300 deg about z, from 3 mm radius inwards 0.1 mm apart, points
  // 0.02 mm apart: the feed turns 0.4 deg a step, and the nearest points of
  // the arc outside lie near the abeam allowance (1 mm along the feed),
  // where a turn of the feed moves them across it most. A list of nearby
  // runs that forgot the turn would miss them within a few steps.
  std::vector<Point> path;
  for (int k = 0; k < 10; ++k) {
    const double r = 3 - 0.1 * k;
    const auto n = static_cast<int>(std::lround(300 * pi / 180 * r / 0.02));
    for (int i = 0; i <= n; ++i) {
      const double a = 300 * pi / 180 * i / n;
      path.push_back({{r * std::cos(a), r * std::sin(a), 0},
                      {0, 0, 1},
                      {-std::sin(a), std::cos(a), 0},
                      i == 0,
                      k});
    }
  }
  ASSERT_GT(path.size(), 6000u);
  expect_same_as_reference(path, 10, 1 << 20, 1, "tight arcs");
}

TEST(PassTrackerReference, SameNeighbourWhileTheGridIsCompactedManyTimes) {
  // A sparse wavy raster (1 mm along, 0.6 mm across: most steps list their
  // run in two or three cells) through a memory of 4000 points: the grid
  // drops forgotten runs every few passes, the first time with almost all
  // of its nodes alive.
  const auto part = samplegen::make_part("wavy");
  ASSERT_TRUE(part);
  samplegen::PathSpec spec = wavy_raster_spec();
  spec.stepover = 0.6;
  spec.step = 1.0;
  const auto path = sample_path(*part->surface, spec);
  ASSERT_GT(path.size(), 9000u);
  expect_same_as_reference(path, 2 * spec.tool_radius, 4000, path.size() / 2000, "wavy sparse");
}

}  // namespace
}  // namespace vcpost::pipeline
