// The move blocks of a Klartext program: L and LN (straight, rotary axes
// that stay, M91/M92/M140 retracts), LP (polar), CC (the pole), C, CR, CT
// and CP (arcs), and RND and CHF, whose corner is cut into the held line
// before it once the line after it is read.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "core/units.h"
#include "postproc/heidenhain/interpreter.h"
#include "postproc/heidenhain/interpreter_words.h"

namespace vcpost::heidenhain {

using program::Event;

namespace {

// An arc's end may miss its circle by this much (mm) plus a relative part:
// CAM systems round coordinates to 3 or 4 decimals.
constexpr double kArcTolerance = 0.005;
constexpr double kArcRelativeTolerance = 1e-4;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

void Interpreter::motion(std::vector<Event>& events) {
  static constexpr std::uint32_t kMove = a_comp | a_feed | a_m;
  std::uint32_t allowed = a_m;
  switch (block_.kind) {
    case BlockKind::line:
      allowed = kMove | a_xyz | a_abc;
      break;
    case BlockKind::line_normal:
      allowed = kMove | a_xyz | a_normal;
      break;
    case BlockKind::line_polar:
      allowed = kMove | a_polar | a_xyz;
      break;
    case BlockKind::centre:
      allowed = a_xyz;
      break;
    case BlockKind::circle:
      allowed = kMove | a_xyz | a_dr;
      break;
    case BlockKind::circle_radius:
      allowed = kMove | a_xyz | a_dr | a_r;
      break;
    case BlockKind::circle_tangent:
      allowed = kMove | a_xyz;
      break;
    case BlockKind::circle_polar:
      allowed = kMove | a_polar | a_xyz | a_dr;
      break;
    case BlockKind::rounding:
      allowed = a_r | a_feed;
      break;
    case BlockKind::chamfer:
      allowed = a_chf | a_feed;
      break;
    default:
      break;  // misc: M words only
  }
  const Words w = read_words(allowed);
  start_functions(w, events);
  switch (block_.kind) {
    case BlockKind::line:
    case BlockKind::line_normal: {
      rotary(w);
      if (block_.kind == BlockKind::line_normal &&
          (std::abs(w.normal[3].value_or(0)) > 1e-9 || std::abs(w.normal[4].value_or(0)) > 1e-9)) {
        fail(Code::E3321, w.first_word, "LN with a tool orientation TX/TY off Z");
      }
      if (w.has(MAction::machine_frame)) {
        machine_retract(w, events);
      } else if (w.any_xyz()) {
        straight(w, cartesian_target(w), events);
      } else {
        set_feed_and_compensation(w, events);
      }
      break;
    }
    case BlockKind::line_polar:
      straight(w, polar_target(w, true), events);
      break;
    case BlockKind::centre:
      centre(w);
      break;
    case BlockKind::circle:
      circle(w, events);
      break;
    case BlockKind::circle_radius:
      circle_radius(w, events);
      break;
    case BlockKind::circle_tangent:
      circle_tangent(w, events);
      break;
    case BlockKind::circle_polar:
      circle_polar(w, events);
      break;
    case BlockKind::rounding:
    case BlockKind::chamfer:
      corner(w);
      break;
    default:
      break;
  }
  if (w.has(MAction::retract)) machine_retract(w, events);
  if (block_.kind == BlockKind::misc && block_.keyword == "STOP")
    events.emplace_back(program::ProgramStop{false, source()});
  end_functions(w, events);
}

void Interpreter::set_feed_and_compensation(const Words& w, std::vector<Event>& events) {
  const program::SourceRef src = source();
  if (w.comp && *w.comp != compensation_) {
    compensation_ = *w.comp;
    events.emplace_back(program::CutterCompensation{compensation_, src});
  }
  std::optional<double> rate;
  if (w.feed) rate = feed_rate(*w.feed);
  if (w.fauto) rate = tool_feed_;
  if (rate) {
    if (*rate < 0) fail(Code::E3303, w.first_word, "a feed rate is not negative");
    if (*rate != feed_) {
      feed_ = *rate;
      events.emplace_back(program::SetFeedRate{feed_, program::FeedMode::per_minute, src});
    }
  }
}

void Interpreter::rotary(const Words& w) {
  static constexpr char letters[] = {'A', 'B', 'C'};
  for (std::size_t a = 0; a < 3; ++a) {
    if (!w.rot[a] && !w.rot_inc[a]) continue;
    const double to = w.rot[a] ? *w.rot[a] : rotary_[a] + *w.rot_inc[a];
    if (std::abs(std::remainder(to, 360.0)) > 1e-9) {
      char text[64];
      std::snprintf(text, sizeof text, "%c%+g", letters[a], to);
      fail(Code::E3321, w.first_word,
           std::string(text) +
               (tcpm_ ? ": M128 with rotary axes moving changes the tool axis along the path; "
                        "only 3-axis motion is read"
                      : ": a rotary axis turns the part or the tool; tilted work (3+2) is not "
                        "read yet"));
    }
    rotary_[a] = to;
  }
}

Eigen::Vector3d Interpreter::cartesian_target(const Words& w) const {
  Eigen::Vector3d end = position_;
  for (std::size_t a = 0; a < 3; ++a) {
    const auto i = static_cast<Eigen::Index>(a);
    if (w.axis[a]) end[i] = length(*w.axis[a]) + shift_[i];
    if (w.inc[a]) end[i] += length(*w.inc[a]);
  }
  return end;
}

Eigen::Vector3d Interpreter::polar_target(const Words& w, bool line) const {
  if (!pole_) fail(Code::E3312, block_.keyword_begin, "polar coordinates need a pole: CC first");
  const Eigen::Vector2d rel = xy(position_) - *pole_;
  double radius = rel.norm();
  double angle = std::atan2(rel.y(), rel.x()) / kDeg;
  if (w.pa) angle = *w.pa;
  if (w.ipa) angle += *w.ipa;
  if (line) {
    if (w.pr) radius = length(*w.pr);
    if (w.ipr) radius += length(*w.ipr);
    if (radius < 0) fail(Code::E3303, w.first_word, "a polar radius is not negative");
  }
  Eigen::Vector3d end = position_;
  end.x() = pole_->x() + radius * std::cos(angle * kDeg);
  end.y() = pole_->y() + radius * std::sin(angle * kDeg);
  if (w.axis[2]) end.z() = length(*w.axis[2]) + shift_.z();
  if (w.inc[2]) end.z() += length(*w.inc[2]);
  if (w.axis[0] || w.axis[1] || w.inc[0] || w.inc[1])
    fail(Code::E3307, w.first_word, "polar blocks take PA/PR, not X/Y");
  return end;
}

void Interpreter::emit_move(Event move, std::vector<Event>& events) {
  const auto* t = std::get_if<program::StraightTraverse>(&move);
  const Eigen::Vector3d end = t ? t->end : std::get<program::StraightFeed>(move).end;
  const Eigen::Vector3d start = t ? t->start : std::get<program::StraightFeed>(move).start;
  if (corner_follows()) {
    held_ = Held{std::move(move), std::nullopt, 0, true, {}, false};
  } else {
    events.push_back(std::move(move));
  }
  const Eigen::Vector2d d = xy(end - start);
  if (d.norm() > 1e-9) tangent_ = d.normalized();
  last_rapid_ = t != nullptr;
  position_ = end;
  highest_z_ = std::max(highest_z_, end.z());
}

void Interpreter::straight(const Words& w, const Eigen::Vector3d& end, std::vector<Event>& events) {
  if (held_) finish_corner(end, events);  // the line before and the corner; on from there
  set_feed_and_compensation(w, events);
  const program::SourceRef src = source();
  if (w.fmax) {
    emit_move(program::StraightTraverse{position_, end, src}, events);
    return;
  }
  if (feed_ <= 0) fail(Code::E3325, block_.keyword_begin, "a feed move before any feed rate F");
  emit_move(program::StraightFeed{position_, end, src}, events);
}

void Interpreter::machine_retract(const Words& w, std::vector<Event>& events) {
  set_feed_and_compensation(w, events);
  const bool m140 = w.has(MAction::retract);
  if (m140 && !w.mb_max) {
    // M140 MB <distance>: back along the tool axis by that much.
    if (!w.mb) fail(Code::E3308, w.first_word, "M140 needs MB <distance> or MB MAX");
    const Eigen::Vector3d end = position_ + Eigen::Vector3d(0, 0, length(*w.mb));
    emit_move(program::StraightTraverse{position_, end, source()}, events);
    return;
  }
  // The machine datum is unknown: the move stands for a retract (see the header).
  const bool z_given = w.axis[2].has_value() || w.inc[2].has_value() || m140;
  warn_once(Code::W3342, 0, w.m.empty() ? 0 : w.m.front().at,
            "M91/M92/M140 moves in machine coordinates are taken as retracts to a safe height "
            "(the stock's top or the highest point so far); their X and Y are not followed");
  if (!z_given) return;
  const double safe =
      std::max({position_.z(), highest_z_, stock_ ? stock_->max.z() : position_.z()});
  const Eigen::Vector3d end(position_.x(), position_.y(), safe);
  program::StraightTraverse move{position_, end, source()};
  move.machine_frame = true;
  events.emplace_back(move);
  position_ = end;
}

// A corner's RND/CHF block: its size and feed wait for the next line.
void Interpreter::corner(const Words& w) {
  if (!held_ || held_->corner_read)
    fail(Code::E3314, block_.keyword_begin,
         "RND and CHF stand between two straight lines (L or LP)");
  const bool rounding = block_.kind == BlockKind::rounding;
  const std::optional<double> size = rounding ? w.r : w.chf;
  if (!size)
    fail(Code::E3308, block_.keyword_begin,
         rounding ? "RND needs R<radius>" : "CHF needs its length");
  if (*size <= 0) fail(Code::E3303, w.first_word, "a corner's size is positive");
  held_->corner = length(*size);
  held_->rounding = rounding;
  held_->corner_source = source();
  held_->corner_read = true;
  if (w.feed) {
    held_->corner_feed =
        program::SetFeedRate{feed_rate(*w.feed), program::FeedMode::per_minute, source()};
  }
}

bool Interpreter::corner_follows() const {
  // The next line that is not blank: does it start (after its number) with RND or CHF?
  std::uint64_t k = pos_;
  for (;;) {
    while (k < text_.size() &&
           (text_[k] == ' ' || text_[k] == '\t' || text_[k] == '\r' || text_[k] == '\n'))
      ++k;
    if (k < text_.size() && text_[k] == '/') ++k;
    while (k < text_.size() && text_[k] >= '0' && text_[k] <= '9') ++k;
    while (k < text_.size() && (text_[k] == ' ' || text_[k] == '\t')) ++k;
    if (k >= text_.size()) return false;
    if (text_[k] == '\n' || text_[k] == '\r') continue;  // a bare block number
    const std::string_view rest = text_.substr(k, 4);
    return rest.starts_with("RND") || rest.starts_with("CHF");
  }
}

// The held line, shortened, and the corner before the move to `end` (this
// block's, which goes on from the corner's end).
void Interpreter::finish_corner(const Eigen::Vector3d& end, std::vector<Event>& events) {
  Held held = std::move(*held_);
  held_.reset();
  auto* traverse = std::get_if<program::StraightTraverse>(&held.move);
  auto* feed = std::get_if<program::StraightFeed>(&held.move);
  const Eigen::Vector3d p0 = traverse ? traverse->start : feed->start;
  const Eigen::Vector3d p1 = traverse ? traverse->end : feed->end;
  const Eigen::Vector3d& p2 = end;
  const std::uint32_t at = block_.keyword_begin;
  if (std::abs(p0.z() - p1.z()) > 1e-9 || std::abs(p1.z() - p2.z()) > 1e-9)
    fail(Code::E3314, at, "RND/CHF between lines in the working plane (Z constant) only");
  const Eigen::Vector2d a = xy(p1 - p0), b = xy(p2 - p1);
  if (a.norm() < 1e-9 || b.norm() < 1e-9)
    fail(Code::E3314, at, "RND/CHF next to a line of no length");
  const Eigen::Vector2d u1 = a.normalized(), u2 = b.normalized();
  const double turn = std::atan2(cross(u1, u2), u1.dot(u2));  // signed turn angle
  const double cut = held.rounding ? held.corner * std::tan(std::abs(turn) / 2) : held.corner;
  if (cut > a.norm() + 1e-9 || cut > b.norm() + 1e-9)
    fail(Code::E3314, at, "the RND/CHF corner is larger than its lines");
  const Eigen::Vector3d t1(p1.x() - u1.x() * cut, p1.y() - u1.y() * cut, p1.z());
  const Eigen::Vector3d t2(p1.x() + u2.x() * cut, p1.y() + u2.y() * cut, p1.z());
  if (traverse) traverse->end = t1;
  if (feed) feed->end = t1;
  events.push_back(held.move);
  if (std::abs(turn) > 1e-9) {
    const double restore = feed_;
    if (held.corner_feed) events.push_back(*held.corner_feed);
    if (held.rounding) {
      const int rotation = turn > 0 ? 1 : -1;
      const Eigen::Vector2d c = xy(t1) + rotation * held.corner * left_normal(u1);
      events.emplace_back(program::ArcFeed{t1, t2, Eigen::Vector3d(c.x(), c.y(), t1.z()),
                                           program::Plane::xy, rotation, held.corner_source});
    } else {
      events.emplace_back(program::StraightFeed{t1, t2, held.corner_source});
    }
    if (held.corner_feed)
      events.emplace_back(
          program::SetFeedRate{restore, program::FeedMode::per_minute, held.corner_source});
  }
  position_ = t2;
  tangent_ = u2;
}

void Interpreter::centre(const Words& w) {
  Eigen::Vector2d c = xy(position_);
  if (w.axis[2] || w.inc[2]) fail(Code::E3307, w.first_word, "CC takes X and Y (tool axis Z)");
  for (std::size_t a = 0; a < 2; ++a) {
    const auto i = static_cast<Eigen::Index>(a);
    if (w.axis[a]) c[i] = length(*w.axis[a]) + shift_[i];
    if (w.inc[a]) c[i] = position_[i] + length(*w.inc[a]);
  }
  pole_ = c;
}

void Interpreter::arc(const Words& w, const Eigen::Vector3d& end, const Eigen::Vector2d& centre,
                      int rotation, std::vector<Event>& events) {
  set_feed_and_compensation(w, events);
  if (feed_ <= 0) fail(Code::E3325, block_.keyword_begin, "an arc before any feed rate F");
  const double r0 = (xy(position_) - centre).norm();
  const double r1 = (xy(end) - centre).norm();
  if (std::abs(r0 - r1) > kArcTolerance + kArcRelativeTolerance * std::max(r0, r1)) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "the arc's end is %.4f mm from its centre, its start %.4f mm (the end is not on "
                  "the circle)",
                  r1, r0);
    fail(Code::E3310, block_.keyword_begin, text);
  }
  if (r0 < 1e-9) fail(Code::E3310, block_.keyword_begin, "an arc of radius 0");
  events.emplace_back(program::ArcFeed{position_, end,
                                       Eigen::Vector3d(centre.x(), centre.y(), position_.z()),
                                       program::Plane::xy, rotation, source()});
  tangent_ = arc_tangent(centre, xy(end), rotation);
  position_ = end;
  highest_z_ = std::max(highest_z_, end.z());
}

void Interpreter::circle(const Words& w, std::vector<Event>& events) {
  if (!pole_) fail(Code::E3312, block_.keyword_begin, "C needs a circle centre: CC first");
  if (w.dr != 0) arc_direction_ = w.dr;
  if (arc_direction_ == 0)
    fail(Code::E3308, block_.keyword_begin, "C needs its direction DR+ or DR-");
  arc(w, cartesian_target(w), *pole_, arc_direction_, events);
}

void Interpreter::circle_radius(const Words& w, std::vector<Event>& events) {
  if (!w.r) fail(Code::E3308, block_.keyword_begin, "CR needs its radius R");
  if (w.dr != 0) arc_direction_ = w.dr;
  if (arc_direction_ == 0)
    fail(Code::E3308, block_.keyword_begin, "CR needs its direction DR+ or DR-");
  const Eigen::Vector3d end = cartesian_target(w);
  const double r = length(*w.r);
  const Eigen::Vector2d chord = xy(end - position_);
  const double c = chord.norm();
  if (c < 1e-9)
    fail(Code::E3311, block_.keyword_begin, "CR to its own start: a full circle needs C");
  const double half = c / 2;
  if (std::abs(r) < half - kArcTolerance) {
    char text[128];
    std::snprintf(text, sizeof text, "radius %.4f mm is below half the chord (%.4f mm)",
                  std::abs(r), half);
    fail(Code::E3311, block_.keyword_begin, text);
  }
  const double h = std::sqrt(std::max(0.0, r * r - half * half));
  // DR+ with R+ (at most half a circle): the centre is left of the chord.
  const double side = static_cast<double>(arc_direction_) * (r > 0 ? 1.0 : -1.0);
  const Eigen::Vector2d centre = xy(position_) + chord / 2 + side * h * left_normal(chord / c);
  arc(w, end, centre, arc_direction_, events);
}

void Interpreter::circle_tangent(const Words& w, std::vector<Event>& events) {
  if (!tangent_)
    fail(Code::E3313, block_.keyword_begin, "CT continues a contour: a move must come first");
  const Eigen::Vector3d end = cartesian_target(w);
  const Eigen::Vector2d d = xy(end - position_);
  const Eigen::Vector2d n = left_normal(*tangent_);
  const double dn = d.dot(n);
  if (std::abs(dn) < 1e-9)
    fail(Code::E3313, block_.keyword_begin, "CT's end lies on the tangent: no arc (write L)");
  const double k = d.squaredNorm() / (2 * dn);
  const Eigen::Vector2d centre = xy(position_) + k * n;
  arc(w, end, centre, k > 0 ? 1 : -1, events);
}

void Interpreter::circle_polar(const Words& w, std::vector<Event>& events) {
  if (!pole_) fail(Code::E3312, block_.keyword_begin, "CP needs a pole: CC first");
  if (w.dr != 0) arc_direction_ = w.dr;
  if (arc_direction_ == 0)
    fail(Code::E3308, block_.keyword_begin, "CP needs its direction DR+ or DR-");
  if (!w.pa && !w.ipa) fail(Code::E3308, block_.keyword_begin, "CP needs PA or IPA");
  const Eigen::Vector3d end = polar_target(w, false);
  int rotation = arc_direction_;
  if (w.ipa) {
    // An incremental angle may run past a turn (a helix): the turns started.
    const double turns = std::abs(*w.ipa) / 360.0;
    rotation *= std::max(1, static_cast<int>(std::ceil(turns - 1e-9)));
    if ((*w.ipa > 0) != (arc_direction_ > 0))
      fail(Code::E3307, w.first_word, "IPA's sign and DR disagree");
  }
  set_feed_and_compensation(w, events);
  if (feed_ <= 0) fail(Code::E3325, block_.keyword_begin, "an arc before any feed rate F");
  events.emplace_back(program::ArcFeed{position_, end,
                                       Eigen::Vector3d(pole_->x(), pole_->y(), position_.z()),
                                       program::Plane::xy, rotation, source()});
  tangent_ = arc_tangent(*pole_, xy(end), rotation);
  position_ = end;
  highest_z_ = std::max(highest_z_, end.z());
}

}  // namespace vcpost::heidenhain
