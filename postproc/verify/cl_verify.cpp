// CL in, G-code or Klartext out: the same motions, spindle on/off and tool
// changes, one to one and in order; S and F values are free (see verify.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "postproc/cldata/cl_reader.h"
#include "postproc/gcode/diagnostics.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/heidenhain/interpreter.h"
#include "postproc/verify/verify.h"
#include "postproc/verify/verify_detail.h"

namespace vcpost::verify {

namespace {

using program::Event;

// An S or F value of one side: the CL's number, or the output's word.
struct SfValue {
  double value = 0;
  std::string text;  // the output's word as written; empty for CL values
  std::uint32_t line = 0, column = 0;
};

// A motion, spindle on/off or tool change, with the S/F values set since
// the previous item on the same side.
struct Item {
  Event event;
  std::uint32_t line = 0, column = 0;
  std::optional<SfValue> s, f;
  program::WorkingFrame frame;  // in effect at the item (motions are in its coordinates)
};

std::string number(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4f", v);
  std::string text = buffer;
  while (!text.empty() && text.back() == '0') text.pop_back();
  if (!text.empty() && text.back() == '.') text.pop_back();
  return text;
}

bool is_item(const Event& e) {
  return program::is_motion(e) || std::holds_alternative<program::SpindleOn>(e) ||
         std::holds_alternative<program::SpindleOff>(e) ||
         std::holds_alternative<program::ChangeTool>(e);
}

bool is_feed(const Event& e) {
  return std::holds_alternative<program::StraightFeed>(e) ||
         std::holds_alternative<program::ArcFeed>(e);
}

// A change of the cutter compensation's side: an item (without S/F) when
// `side` differs from `current`, which it then becomes.
std::optional<Item> side_change(const program::CutterCompensation& c, const program::SourceRef& src,
                                program::CompensationSide& current) {
  if (c.side == current) return std::nullopt;
  current = c.side;
  return Item{c, src.line, src.column, std::nullopt, std::nullopt, {}};
}

class ClItems {
 public:
  ClItems(std::string_view text, const std::string& name, bool compensation, bool manual_change,
          bool setups)
      : in_(std::string(text)),
        reader_(in_, name),
        compensation_(compensation),
        manual_change_(manual_change),
        setups_(setups) {}

  std::optional<Item> next() {
    std::optional<Item> item = next_item();
    if (item) item->frame = frame_;
    return item;
  }

 private:
  std::optional<Item> next_item() {
    if (spindle_stop_) {
      spindle_stop_ = false;
      return Item{
          program::SpindleOff{last_}, last_.line, last_.column, std::nullopt, std::nullopt, {}};
    }
    if (restart_) {
      // A set-up's M0 between M5 and M3/M4: the spindle turns again.
      const program::SpindleOn on{*restart_, last_};
      restart_.reset();
      return Item{on, last_.line, last_.column, std::nullopt, std::nullopt, {}};
    }
    if (queued_) return std::exchange(queued_, std::nullopt);
    using program::CompensationSide;
    // A CL record that does not read leaves as the reader's ClError: its
    // code, file:line:col and hint.
    while (auto event = reader_.next()) {
      const auto src = program::source_of(*event);
      last_ = src;
      if (const auto* s = std::get_if<program::SetSpindleSpeed>(&*event)) {
        s_ = SfValue{s->rpm, "", src.line, src.column};
      } else if (const auto* f = std::get_if<program::SetFeedRate>(&*event)) {
        f_ = SfValue{f->rate, "", src.line, src.column};
      } else if (const auto* c = std::get_if<program::CutterCompensation>(&*event)) {
        if (!compensation_) continue;
        if (auto item = side_change(*c, src, side_)) return item;
      } else if (const auto* w = std::get_if<program::WorkingFrame>(&*event)) {
        if (w->rotation == frame_.rotation && w->origin == frame_.origin) continue;
        frame_ = *w;
        // The output ends the compensation before a new frame (G40) ...
        if (side_ != CompensationSide::off) {
          if (setups_ && spindle_on_) {
            spindle_stop_ = true;
            restart_ = direction_;
          }
          return side_change({CompensationSide::off, src}, src, side_);
        }
        // ... and a set-up stops the spindle for the operator (M5, M0, M3).
        if (setups_ && spindle_on_) {
          restart_ = direction_;
          return Item{
              program::SpindleOff{src}, src.line, src.column, std::nullopt, std::nullopt, {}};
        }
      } else if (is_item(*event)) {
        Item item{*event, src.line, src.column, std::move(s_), std::move(f_), {}};
        s_.reset();
        f_.reset();
        const bool change = std::holds_alternative<program::ChangeTool>(*event);
        const bool spindle_was_on = spindle_on_;
        if (const auto* on = std::get_if<program::SpindleOn>(&*event)) {
          spindle_on_ = true;
          direction_ = on->direction;
        }
        if (change || std::holds_alternative<program::SpindleOff>(*event)) spindle_on_ = false;
        // The output ends the compensation before a tool change (G40)...
        if (change && side_ != CompensationSide::off) {
          queued_ = std::move(item);
          if (manual_change_ && spindle_was_on) spindle_stop_ = true;
          return side_change({CompensationSide::off, src}, src, side_);
        }
        // ... and stops the spindle before a change by hand (M5 before M0).
        if (change && manual_change_ && spindle_was_on) {
          queued_ = std::move(item);
          return Item{
              program::SpindleOff{src}, src.line, src.column, std::nullopt, std::nullopt, {}};
        }
        return item;
      }
    }
    // ... and before the program's end.
    return side_change({CompensationSide::off, last_}, last_, side_);
  }

  std::istringstream in_;
  cldata::ClReader reader_;
  bool compensation_;
  bool manual_change_;
  bool setups_;
  program::WorkingFrame frame_;
  program::SpindleDirection direction_ = program::SpindleDirection::clockwise;
  std::optional<program::SpindleDirection> restart_;  // due after a set-up's spindle stop
  bool spindle_on_ = false;
  bool spindle_stop_ = false;  // a spindle stop is due between the G40 and the change
  std::optional<SfValue> s_, f_;
  program::CompensationSide side_ = program::CompensationSide::off;
  std::optional<Item> queued_;
  program::SourceRef last_;
};

// The output's items. Throws gcode::GcodeError.
class GcodeItems {
 public:
  GcodeItems(std::string_view text, const gcode::Dialect& dialect, bool compensation,
             bool manual_change)
      : interpreter_(text, dialect), compensation_(compensation), manual_change_(manual_change) {}

  std::optional<Item> next() {
    if (!held_.empty() && !holding_) {
      Item item = std::move(held_.front());
      held_.pop_front();
      return item;
    }
    while (true) {
      while (at_ < events_.size()) {
        const Event& e = events_[at_++];
        const auto src = program::source_of(e);
        // The move up to the tool change position (G28 / G53 Z only) is
        // the output's own: not compared when a tool change follows it.
        if (home_block_ && program::is_motion(e)) {
          held_.push_back(Item{e, src.line, src.column, std::nullopt, std::nullopt, frame_});
          holding_ = true;
          continue;
        }
        if (manual_change_ && tool_word_ && std::holds_alternative<program::ProgramStop>(e)) {
          held_.clear();
          holding_ = false;
          return Item{program::ChangeTool{*tool_word_, src},
                      src.line,
                      src.column,
                      std::move(s_),
                      std::nullopt,
                      frame_};
        }
        // Only S/F words: a modal change (G94 after G95) also sets a feed.
        if (std::holds_alternative<program::SetSpindleSpeed>(e)) {
          if (s_word_) s_ = word('S', std::get<program::SetSpindleSpeed>(e).rpm, src);
        } else if (std::holds_alternative<program::SetFeedRate>(e)) {
          if (f_word_) f_ = word('F', std::get<program::SetFeedRate>(e).rate, src);
        } else if (const auto* c = std::get_if<program::CutterCompensation>(&e)) {
          if (!compensation_) continue;
          if (auto item = side_change(*c, src, side_)) return item;
        } else if (const auto* w = std::get_if<program::WorkingFrame>(&e)) {
          frame_ = *w;
        } else if (is_item(e)) {
          // A canned cycle's F belongs to its first feed move, where the CL
          // reader sets the cycle's feed, not to the rapids before it.
          const bool f_later = f_ && !is_feed(e) &&
                               std::any_of(events_.begin() + static_cast<std::ptrdiff_t>(at_),
                                           events_.end(), is_feed);
          std::optional<SfValue> f;
          if (!f_later) f = std::move(f_);
          Item item{e, src.line, src.column, std::move(s_), std::move(f), frame_};
          s_.reset();
          if (!f_later) f_.reset();
          if (std::holds_alternative<program::ChangeTool>(e)) held_.clear();
          holding_ = false;
          if (!held_.empty()) {  // no tool change after the move up: compare it
            held_.push_back(std::move(item));
            return next();
          }
          return item;
        }
      }
      events_.clear();
      at_ = 0;
      if (done_ || !interpreter_.next(events_)) {
        done_ = true;
        if (!held_.empty()) {  // a move up at the end: compared
          holding_ = false;
          return next();
        }
        return std::nullopt;
      }
      bool m5 = false, home = false, xy = false;
      s_word_.reset();
      f_word_.reset();
      tool_word_.reset();
      for (const auto& w : interpreter_.block().words) {
        if (w.letter == 'S' || w.letter == 'F')
          (w.letter == 'S' ? s_word_ : f_word_) = Span{w.begin, w.end, w.column};
        m5 = m5 || (w.letter == 'M' && w.value == 5);
        home = home || (w.letter == 'G' && (w.value == 28 || w.value == 53));
        xy = xy || w.letter == 'X' || w.letter == 'Y';
        if (w.letter == 'T') tool_word_ = static_cast<int>(w.value);
      }
      home_block_ = home && !xy;
      // M2/M30 stop the spindle themselves (as rs274 reports it); CL FINI
      // says nothing of it, so that implied stop is not compared.
      const bool ends = std::any_of(events_.begin(), events_.end(), [](const Event& e) {
        return std::holds_alternative<program::ProgramEnd>(e);
      });
      if (ends && !m5)
        std::erase_if(
            events_, [](const Event& e) { return std::holds_alternative<program::SpindleOff>(e); });
    }
  }

 private:
  struct Span {
    std::uint32_t begin = 0, end = 0, column = 0;
  };
  // The word as written in the current block.
  SfValue word(char letter, double value, const program::SourceRef& src) const {
    const gcode::Block& block = interpreter_.block();
    const Span& span = letter == 'S' ? *s_word_ : *f_word_;
    return SfValue{value, std::string(block.text.substr(span.begin, span.end - span.begin)),
                   src.line, span.column};
  }

  gcode::Interpreter interpreter_;
  bool compensation_;
  bool manual_change_;
  bool home_block_ = false;       // the current block moves Z home (G28 / G53)
  std::optional<int> tool_word_;  // the current block's T
  std::deque<Item> held_;         // home moves, until the next item shows a tool change
  bool holding_ = false;          // held_ may still be dropped
  program::CompensationSide side_ = program::CompensationSide::off;
  program::WorkingFrame frame_;  // G68.2 in effect
  std::vector<Event> events_;
  std::size_t at_ = 0;
  bool done_ = false;
  std::optional<Span> s_word_, f_word_;
  std::optional<SfValue> s_, f_;
};

// The Klartext output's items, read back by the Klartext reader. Throws
// heidenhain::KlartextError.
class KlartextItems {
 public:
  explicit KlartextItems(std::string_view text) : interpreter_(text) {}

  std::optional<Item> next() {
    while (true) {
      while (at_ < events_.size()) {
        const Event& e = events_[at_++];
        const auto src = program::source_of(e);
        if (const auto* s = std::get_if<program::SetSpindleSpeed>(&e)) {
          s_ = word(interpreter_.block().s_span, s->rpm, src);
        } else if (const auto* f = std::get_if<program::SetFeedRate>(&e)) {
          const heidenhain::Block& block = interpreter_.block();
          const heidenhain::Word* w = block.find(heidenhain::name("F"));
          f_ = word(w ? std::optional<heidenhain::ByteSpan>(
                            {block.offset + w->begin, block.offset + w->end})
                      : std::nullopt,
                    f->rate, src);
        } else if (const auto* w = std::get_if<program::WorkingFrame>(&e)) {
          frame_ = *w;
        } else if (is_item(e)) {
          Item item{e, src.line, src.column, std::move(s_), std::move(f_), frame_};
          s_.reset();
          f_.reset();
          return item;
        }
      }
      events_.clear();
      at_ = 0;
      if (done_ || !interpreter_.next(events_)) {
        done_ = true;
        return std::nullopt;
      }
      // M30 stops the spindle itself (the reader says so, as rs274 does);
      // CL FINI says nothing of it: that implied stop is not compared.
      const bool ends = std::any_of(events_.begin(), events_.end(), [](const Event& e) {
        return std::holds_alternative<program::ProgramEnd>(e);
      });
      const heidenhain::Block& block = interpreter_.block();
      const bool m5 = std::any_of(block.words.begin(), block.words.end(), [](const auto& w) {
        return w.key == heidenhain::name("M") && w.has_value && w.value.number == 5;
      });
      if (ends && !m5)
        std::erase_if(
            events_, [](const Event& e) { return std::holds_alternative<program::SpindleOff>(e); });
    }
  }

 private:
  // The word as written in the current block (its span in the text).
  SfValue word(const std::optional<heidenhain::ByteSpan>& span, double value,
               const program::SourceRef& src) const {
    const heidenhain::Block& block = interpreter_.block();
    if (!span) return SfValue{value, "", src.line, 1};
    return SfValue{
        value, std::string(block.text.substr(span->begin - block.offset, span->end - span->begin)),
        src.line, static_cast<std::uint32_t>(span->begin - block.offset + 1)};
  }

  heidenhain::Interpreter interpreter_;
  program::WorkingFrame frame_;  // PLANE in effect
  std::vector<Event> events_;
  std::size_t at_ = 0;
  bool done_ = false;
  std::optional<SfValue> s_, f_;
};

std::string point(const Eigen::Vector3d& p) {
  return "(" + number(p.x()) + ", " + number(p.y()) + ", " + number(p.z()) + ")";
}

const char* kind_name(const Event& e) {
  if (std::holds_alternative<program::StraightTraverse>(e)) return "rapid";
  if (std::holds_alternative<program::StraightFeed>(e)) return "feed move";
  if (std::holds_alternative<program::ArcFeed>(e)) return "arc";
  if (std::holds_alternative<program::SpindleOn>(e)) return "spindle start";
  if (std::holds_alternative<program::SpindleOff>(e)) return "spindle stop";
  if (std::holds_alternative<program::CutterCompensation>(e)) return "cutter compensation";
  return "tool change";
}

Eigen::Vector3d end_of(const Event& e) {
  if (const auto* t = std::get_if<program::StraightTraverse>(&e)) return t->end;
  if (const auto* f = std::get_if<program::StraightFeed>(&e)) return f->end;
  return std::get<program::ArcFeed>(e).end;
}

class Comparer {
 public:
  // The output writes an arc centre as its start plus I/J/K, each rounded
  // to the grid: the centre may be off by the end-point tolerance and half
  // a step more.
  Comparer(double tolerance, double half_step, int feed_decimals, bool setups, Result& result,
           ChangeSink& changes, ViolationSink& sink)
      : setups_(setups),
        tolerance_(tolerance),
        centre_tolerance_(tolerance + half_step),
        feed_step_(std::pow(10.0, -std::clamp(feed_decimals, 0, 9))),
        result_(result),
        changes_(changes),
        sink_(sink) {}

  // Compares a pair of items; false when the sequences no longer line up.
  bool compare(const Item& cl, const Item& out) {
    changes(cl, out);
    const bool cl_motion = program::is_motion(cl.event), out_motion = program::is_motion(out.event);
    if (cl_motion != out_motion) {
      add(cl_motion ? Code::E7131 : Code::E7135, cl, out,
          std::string("the output has a ") + kind_name(out.event) + " where the CL data have a " +
              kind_name(cl.event) + ": " + event_text(out.event) + " vs " + event_text(cl.event));
      return false;
    }
    if (!cl_motion) return compare_control(cl, out);
    ++result_.motions;
    if (cl.event.index() != out.event.index()) {
      add(Code::E7133, cl, out,
          std::string("the output has a ") + kind_name(out.event) + " where the CL data have a " +
              kind_name(cl.event));
    }
    Eigen::Vector3d a = end_of(cl.event), b = end_of(out.event);
    if (!setups_) {
      compare_frames(cl, out);
      a = cl.frame.to_program(a);
      b = out.frame.to_program(b);
    }
    const double off = (b - a).cwiseAbs().maxCoeff();
    if (!(off <= tolerance_ + 1e-9)) {
      add(Code::E7132, cl, out,
          "end point " + point(b) + " is " + number_um(off) + " from the CL point " + point(a) +
              " (tolerance " + number_um(tolerance_) + " per axis)");
    }
    const auto* ca = std::get_if<program::ArcFeed>(&cl.event);
    const auto* oa = std::get_if<program::ArcFeed>(&out.event);
    if (ca && oa) compare_arc(*ca, *oa, cl, out);
    return true;
  }

  void add(Code code, const Item& cl, const Item& out, std::string message) {
    sink_.add(code, out.line, out.column, cl.line, std::move(message));
  }

 private:
  static std::string number_um(double mm) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.4f mm", mm);
    return buffer;
  }

  bool compare_control(const Item& cl, const Item& out) {
    if (cl.event.index() != out.event.index()) {
      add(Code::E7135, cl, out,
          std::string("the output has a ") + kind_name(out.event) + " where the CL data have a " +
              kind_name(cl.event));
      return false;
    }
    if (!same_event(cl.event, out.event, false))
      add(Code::E7135, cl, out,
          "the output means " + event_text(out.event) + " where the CL data mean " +
              event_text(cl.event));
    return true;
  }

  void compare_arc(const program::ArcFeed& a, const program::ArcFeed& b, const Item& cl,
                   const Item& out) {
    if (a.plane != b.plane || a.rotation != b.rotation) {
      add(Code::E7134, cl, out,
          "arc " + event_text(out.event) + " differs in plane or direction from the CL's " +
              event_text(cl.event));
      return;
    }
    // The centre's axis component is not meaningful (events.h). Where the
    // frames are compared, the centres on the part, along the CL frame's axes.
    Eigen::Vector3d d = (b.centre - a.centre).cwiseAbs();
    if (!setups_)
      d = (cl.frame.rotation.transpose() *
           (out.frame.to_program(b.centre) - cl.frame.to_program(a.centre)))
              .cwiseAbs();
    d[a.plane == program::Plane::xy ? 2 : a.plane == program::Plane::xz ? 1 : 0] = 0;
    if (!(d.maxCoeff() <= centre_tolerance_ + 1e-9))
      add(Code::E7134, cl, out,
          "arc centre " + point(b.centre) + " is " + number_um(d.maxCoeff()) + " from the CL's " +
              point(a.centre) + " (tolerance " + number_um(centre_tolerance_) + " per axis)");
  }

  // The output's frame turns the tool as the CL's does (the origins are
  // checked through the points): named once per CL frame.
  void compare_frames(const Item& cl, const Item& out) {
    const bool same_cl_frame =
        cl.frame.rotation == checked_.rotation && cl.frame.origin == checked_.origin;
    if (same_cl_frame && reported_) return;
    if (!same_cl_frame) reported_ = false;
    checked_ = cl.frame;
    // Angles written to 0.0001 deg turn an axis by up to 2e-6 rad.
    constexpr double kTurnTolerance = 5e-6;
    const double off = (out.frame.rotation - cl.frame.rotation).cwiseAbs().maxCoeff();
    if (off <= kTurnTolerance) return;
    reported_ = true;
    const Eigen::Vector3d za = cl.frame.rotation.col(2), zb = out.frame.rotation.col(2);
    const Eigen::Vector3d xa = cl.frame.rotation.col(0), xb = out.frame.rotation.col(0);
    add(Code::E7143, cl, out,
        "the output's working plane has the tool axis " + point(zb) + " and x " + point(xb) +
            " where the CL's has " + point(za) + " and " + point(xa));
  }

  void changes(const Item& cl, const Item& out) {
    for (const char letter : {'S', 'F'}) {
      const auto& o = letter == 'S' ? out.s : out.f;
      const auto& c = letter == 'S' ? cl.s : cl.f;
      if (!o) continue;
      // The CL value on the output's grid (integer S, F to its decimals) is no change.
      const double step = letter == 'S' ? 1.0 : feed_step_;
      if (c && std::abs(std::round(c->value / step) * step - o->value) <= 1e-6 * step) continue;
      changes_.add(Change{o->line, o->column, c ? c->line : cl.line, letter,
                          c ? letter + number(c->value) : "", o->text, !c});
    }
  }

  bool setups_;
  program::WorkingFrame checked_;  // the CL frame last compared
  bool reported_ = false;          // its difference named
  double tolerance_;
  double centre_tolerance_;
  double feed_step_;  // mm/min
  Result& result_;
  ChangeSink& changes_;
  ViolationSink& sink_;
};

}  // namespace

namespace {

// Where the output stops reading: the reader's position and message.
struct Unreadable {
  std::uint32_t line = 0, column = 0;
  std::string message;
};

using OutputRead = std::variant<std::optional<Item>, Unreadable>;

// The CL data's items against the output's, one to one. `next_output`
// gives the output's next item, or the Unreadable where it stops reading.
template <class NextOutput>
Result compare_with_cl(std::string_view cl_text, std::string_view output, const Options& options,
                       const std::string& input_name, NextOutput next_output) {
  Result result;
  result.kind = InputKind::cldata;
  const double half_step = 0.5 * std::pow(10.0, -std::clamp(options.output_decimals, 0, 9));
  result.tolerance_mm = std::max(options.tolerance_mm, half_step);
  ViolationSink sink(options.max_violations);
  ChangeSink changes(result, options.on_change);
  Comparer comparer(result.tolerance_mm, half_step, options.output_feed_decimals, options.setups,
                    result, changes, sink);
  ClItems cl(cl_text, input_name, options.cutter_compensation, options.manual_tool_change,
             options.setups);
  while (true) {
    const std::optional<Item> a = cl.next();
    OutputRead read = next_output();
    if (const auto* u = std::get_if<Unreadable>(&read)) {
      sink.add(Code::E7123, u->line, u->column, a ? a->line : 0,
               "the output does not interpret: " + u->message +
                   " (is --machine the profile the output was posted for?)");
      break;
    }
    const std::optional<Item> b = std::move(std::get<std::optional<Item>>(read));
    if (!a && !b) break;
    if (!a || !b) {
      if (b)
        sink.add(Code::E7131, b->line, b->column, 0,
                 std::string("the output has a ") + kind_name(b->event) +
                     " after the CL data's last (" + event_text(b->event) + ")");
      else
        sink.add(Code::E7131,
                 static_cast<std::uint32_t>(std::count(output.begin(), output.end(), '\n') + 1), 1,
                 a->line,
                 std::string("the output ends before the CL data's ") + kind_name(a->event) + " (" +
                     event_text(a->event) + ")");
      break;
    }
    if (!comparer.compare(*a, *b)) break;
  }
  sink.move_into(result);
  return result;
}

}  // namespace

Result verify_cl(std::string_view cl_text, std::string_view output, const Options& options,
                 const std::string& input_name) {
  GcodeItems out(output, options.dialect, options.cutter_compensation, options.manual_tool_change);
  return compare_with_cl(cl_text, output, options, input_name, [&out]() -> OutputRead {
    try {
      return out.next();
    } catch (const gcode::GcodeError& e) {
      const auto& d = e.diagnostic();
      return Unreadable{d.line, d.column, std::string(to_string(d.code)) + " " + d.message};
    }
  });
}

Result verify_cl_klartext(std::string_view cl_text, std::string_view output, const Options& options,
                          const std::string& input_name) {
  KlartextItems out(output);
  return compare_with_cl(cl_text, output, options, input_name, [&out]() -> OutputRead {
    try {
      return out.next();
    } catch (const heidenhain::KlartextError& e) {
      const auto& d = e.diagnostic();
      return Unreadable{d.line, d.column, std::string(e.id()) + " " + d.message};
    }
  });
}

}  // namespace vcpost::verify
