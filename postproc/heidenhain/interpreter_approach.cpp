// Contour approach and departure (APPR, DEP): an APPR waits for the
// contour element after it, whose direction shapes its path (approach.h
// computes the paths); a DEP leaves the contour element before it.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "postproc/heidenhain/approach.h"
#include "postproc/heidenhain/interpreter.h"
#include "postproc/heidenhain/interpreter_words.h"

namespace vcpost::heidenhain {

using program::Event;

// An APPR or DEP block's words and the path's form.
struct Interpreter::LinkWords {
  Words words;
  LinkInput in;
  bool polar = false;
};

namespace {

// LT, LN, CT, LCT, with P before them for a polar end point (APPR PLT ...).
std::optional<ContourLink> link_of(std::string_view form, bool& polar) {
  polar = form.starts_with('P');
  if (polar) form.remove_prefix(1);
  if (form == "LT") return ContourLink::line_tangent;
  if (form == "LN") return ContourLink::line_normal;
  if (form == "CT") return ContourLink::circle_tangent;
  if (form == "LCT") return ContourLink::line_circle;
  return std::nullopt;
}

int side_of(program::CompensationSide c) {
  return c == program::CompensationSide::left ? 1 : c == program::CompensationSide::right ? -1 : 0;
}

// The direction a motion starts in, in the working plane (zero when it
// starts along the tool axis).
Eigen::Vector2d start_direction(const Event& e) {
  if (const auto* a = std::get_if<program::ArcFeed>(&e))
    return arc_tangent(xy(a->centre), xy(a->start), a->rotation > 0 ? 1 : -1);
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  if (const auto* t = std::get_if<program::StraightTraverse>(&e)) d = t->end - t->start;
  if (const auto* f = std::get_if<program::StraightFeed>(&e)) d = f->end - f->start;
  const Eigen::Vector2d p = xy(d);
  return p.norm() > 1e-9 ? Eigen::Vector2d(p.normalized()) : Eigen::Vector2d::Zero();
}

}  // namespace

Interpreter::LinkWords Interpreter::link_words(bool departure) const {
  LinkWords out;
  bool polar = false;
  const auto link = link_of(block_.sub_keyword, polar);
  if (!link || (departure && polar && *link != ContourLink::line_circle))
    fail(Code::E3307, block_.keyword_begin,
         std::string(block_.keyword) + " " + std::string(block_.sub_keyword) +
             " is no approach or departure (LT, LN, CT, LCT; polar PLT, PLN, PCT, PLCT)");
  out.words = read_words(a_xyz | a_polar | a_r | a_comp | a_feed | a_m | a_link);
  const Words& w = out.words;
  out.in.link = *link;
  out.polar = polar;
  out.in.len = length(w.len.value_or(0));
  out.in.cca = w.cca.value_or(0);
  const bool arc = *link == ContourLink::circle_tangent || *link == ContourLink::line_circle;
  if (arc) out.in.radius = length(w.r.value_or(0));
  if (!arc && w.r) {
    if (*w.r != 0) fail(Code::E3307, w.first_word, "R is no word of an LT or LN path");
    out.words.comp = program::CompensationSide::off;  // R0
  }
  return out;
}

void Interpreter::approach(std::vector<Event>& events) {
  if (approach_) fail_approach("a second APPR before the first's contour element");
  LinkWords lw = link_words(false);
  const Words& w = lw.words;
  start_functions(w, events);
  const program::CompensationSide side = w.comp.value_or(compensation_);
  lw.in.side = side_of(side);
  if (side != compensation_) {
    compensation_ = side;
    events.emplace_back(program::CutterCompensation{side, source()});
  }
  PendingApproach a;
  a.in = lw.in;
  a.start = position_;
  a.first = lw.polar ? polar_target(w, true) : cartesian_target(w);
  a.rapid_to_auxiliary = last_rapid_ && lw.in.link != ContourLink::line_circle;
  a.feed_before = feed_;
  a.rapid = w.fmax;
  if (w.feed) feed_ = feed_rate(*w.feed);
  if (w.fauto) feed_ = tool_feed_;
  a.feed = feed_;
  if (feed_ <= 0 && !a.rapid)
    fail(Code::E3325, block_.keyword_begin, "APPR before any feed rate F");
  a.source = source();
  const auto [line, column] = block_.position(block_.keyword_begin);
  a.line = line;
  a.column = column;
  approach_ = a;
  position_ = a.first;
  highest_z_ = std::max(highest_z_, position_.z());
  tangent_.reset();
  end_functions(w, events);
}

void Interpreter::fail_approach(const std::string& why) const {
  const PendingApproach& a = *approach_;
  throw KlartextError(Diagnostic{Code::E3329, a.line, a.column, "APPR " + why, {}});
}

// The approach, once the contour element after it is known (its direction
// at PA shapes the path): its moves go in before that element's.
void Interpreter::link_approach(std::vector<Event>& events, std::size_t before) {
  const Event* first = nullptr;
  for (std::size_t k = before; k < events.size() && !first; ++k)
    if (program::is_motion(events[k])) first = &events[k];
  if (!first && held_) first = &held_->move;
  if (!first) {
    switch (block_.kind) {
      case BlockKind::centre:
      case BlockKind::fn:
      case BlockKind::formula:
      case BlockKind::misc:
      case BlockKind::label:
      case BlockKind::comment:
      case BlockKind::empty:
        return;  // the contour element is still to come
      default:
        fail_approach("needs its first contour element (L, C, CR, CT, CP, LP) right after it");
    }
  }
  const Eigen::Vector2d tangent = start_direction(*first);
  if (tangent.norm() == 0)
    fail_approach("is followed by a move along the tool axis: no contour to join");
  const PendingApproach a = *approach_;
  std::string why;
  const auto path = approach_path(a.in, xy(a.start), xy(a.first), tangent, why);
  if (!path) fail_approach(why);
  approach_.reset();
  std::vector<Event> link;
  const Eigen::Vector3d auxiliary(path->auxiliary.x(), path->auxiliary.y(), a.start.z());
  auto set_feed = [&](double rate) {
    link.emplace_back(program::SetFeedRate{rate, program::FeedMode::per_minute, a.source});
  };
  // PS -> PH: at the feed before APPR (at rapid after an FMAX block); LCT at APPR's.
  const bool lct = a.in.link == ContourLink::line_circle;
  if ((auxiliary - a.start).norm() > 1e-9) {
    if (lct && a.feed != a.feed_before) set_feed(a.feed);
    if (a.rapid_to_auxiliary) {
      link.emplace_back(program::StraightTraverse{a.start, auxiliary, a.source});
    } else {
      if (a.feed_before <= 0 && !lct)
        throw KlartextError(
            Diagnostic{Code::E3325,
                       a.line,
                       a.column,
                       "APPR moves to its auxiliary point at the feed before it: none was given",
                       {}});
      link.emplace_back(program::StraightFeed{a.start, auxiliary, a.source});
    }
    if (!lct && a.feed != a.feed_before) set_feed(a.feed);
  } else if (a.feed != a.feed_before) {
    set_feed(a.feed);
  }
  // PH -> PA, the tool axis reaching PA's height on the way (TNC 620/640 manuals).
  if (path->centre) {
    link.emplace_back(program::ArcFeed{
        auxiliary, a.first, Eigen::Vector3d(path->centre->x(), path->centre->y(), auxiliary.z()),
        program::Plane::xy, path->rotation, a.source});
  } else if (a.rapid) {
    link.emplace_back(program::StraightTraverse{auxiliary, a.first, a.source});
  } else {
    link.emplace_back(program::StraightFeed{auxiliary, a.first, a.source});
  }
  events.insert(events.begin() + static_cast<std::ptrdiff_t>(before), link.begin(), link.end());
}

void Interpreter::departure(std::vector<Event>& events) {
  LinkWords lw = link_words(true);
  Words& w = lw.words;
  start_functions(w, events);
  if (!tangent_)
    fail(Code::E3329, block_.keyword_begin,
         "DEP leaves a contour: a contour element must come right before it");
  lw.in.side = side_of(compensation_);
  w.comp.reset();
  set_feed_and_compensation(w, events);
  if (feed_ <= 0 && !w.fmax) fail(Code::E3325, block_.keyword_begin, "DEP before any feed rate F");
  const Eigen::Vector3d target = lw.polar ? polar_target(w, true) : cartesian_target(w);
  const bool given_xy = w.axis[0] || w.axis[1] || w.inc[0] || w.inc[1] || w.pa || w.ipa;
  const bool lct = lw.in.link == ContourLink::line_circle;
  if (!lct && given_xy)
    fail(Code::E3307, w.first_word, "DEP LT, LN and CT take no end point but Z");
  if (lct && !given_xy) fail(Code::E3308, block_.keyword_begin, "DEP LCT needs its end point X Y");
  std::string why;
  const auto path = departure_path(lw.in, xy(position_), *tangent_, xy(target), why);
  if (!path) fail(Code::E3329, block_.keyword_begin, "DEP " + why);
  const program::SourceRef src = source();
  // The tool axis reaches the DEP's height on the way to PN (TNC 620/640 manuals).
  const Eigen::Vector3d end(path->end.x(), path->end.y(), target.z());
  Eigen::Vector3d from = position_;
  if (path->centre) {
    const Eigen::Vector3d to(path->auxiliary.x(), path->auxiliary.y(), lct ? from.z() : end.z());
    events.emplace_back(
        program::ArcFeed{from, to, Eigen::Vector3d(path->centre->x(), path->centre->y(), from.z()),
                         program::Plane::xy, path->rotation, src});
    tangent_ = arc_tangent(*path->centre, path->auxiliary, path->rotation);
    from = to;
  }
  if ((end - from).norm() > 1e-9) {
    if (w.fmax) {
      events.emplace_back(program::StraightTraverse{from, end, src});
    } else {
      events.emplace_back(program::StraightFeed{from, end, src});
    }
    if (xy(end - from).norm() > 1e-9) tangent_ = xy(end - from).normalized();
  }
  position_ = end;
  highest_z_ = std::max(highest_z_, end.z());
  last_rapid_ = w.fmax;
  if (compensation_ != program::CompensationSide::off) {
    compensation_ = program::CompensationSide::off;
    events.emplace_back(program::CutterCompensation{compensation_, src});
  }
  end_functions(w, events);
}

}  // namespace vcpost::heidenhain
