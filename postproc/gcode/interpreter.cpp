#include "postproc/gcode/interpreter.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>

#include "postproc/gcode/codes.h"
#include "postproc/program/arc.h"

namespace vcpost::gcode {

using program::Event;

namespace {

constexpr double kInch = 25.4;
// A whole number in [0, 1e9]: T, H and arc turns, which become ints (a
// larger value would not fit, and its conversion would be undefined).
bool whole_number(double v) { return v >= 0 && v <= 1e9 && v == std::floor(v); }
// Arc end-radius check, as LinuxCNC: an error only when both the absolute
// (mm) and the relative difference are exceeded.
constexpr double kArcAbsoluteTolerance = 0.002;
constexpr double kArcRelativeTolerance = 0.001;

std::string code_text(char letter, int tenths) {
  std::string s(1, letter);
  s += std::to_string(tenths / 10);
  if (tenths % 10 != 0) {
    s += '.';
    s += std::to_string(tenths % 10);
  }
  return s;
}

// The code of a G or M word found in its table, x10 (61.1 -> 611), as
// find_code() matched it.
int code_of(const Word& w) { return static_cast<int>(std::lround(w.value * 10.0)); }

// The words of one block by letter and by modal group, as positions in
// Block::words plus one (0: none). Built afresh for every block: byte
// entries keep clearing it to a few stores (arrays of pointers, cleared
// with `rep stos`, took a fifth of the reading stage's time).
struct WordIndex {
  std::array<std::uint8_t, 26> by_letter{};
  std::array<std::uint8_t, kGroupCount> g{};
  std::array<std::uint8_t, kGroupCount> m{};
};
// A word is indexed only when none before it was refused: each letter once,
// one G per group, at most four M; so its position is below this bound.
inline constexpr std::size_t kMaxIndexedPosition = 26 + kGroupCount + 4;
static_assert(kMaxIndexedPosition < std::numeric_limits<std::uint8_t>::max());

program::SourceRef source(const Block& b, std::uint32_t column) {
  return program::SourceRef{b.line, column == 0 ? 1u : column, b.offset};
}

}  // namespace

Interpreter::Interpreter(std::string_view text, Dialect dialect, InterpreterLimits limits)
    : text_(text), dialect_(dialect), limits_(limits), parameters_(dialect_) {}

bool Interpreter::line_at(std::uint64_t offset, std::uint32_t number, Line& line) const {
  if (offset >= text_.size()) return false;
  const char* begin = text_.data() + offset;
  const std::size_t rest = text_.size() - offset;
  const void* nl = std::memchr(begin, '\n', rest);
  std::size_t length = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - begin) : rest;
  std::size_t eol_length = nl ? 1 : 0;
  if (length > 0 && begin[length - 1] == '\r') {
    --length;
    ++eol_length;
  }
  line.text = std::string_view(begin, length);
  line.eol = std::string_view(begin + length, eol_length);
  line.offset = offset;
  line.number = number;
  return true;
}

void Interpreter::jump(std::uint64_t offset, std::uint32_t number) {
  pos_ = offset;
  line_ = number - 1;
}

void Interpreter::fail(Code code, std::uint32_t column, std::string message) const {
  throw GcodeError(Diagnostic{code, Severity::error, block_.line, column == 0 ? 1u : column,
                              std::move(message)});
}

void Interpreter::warn(Code code, std::uint32_t column, std::string message) {
  ++warning_count_;
  if (warnings_.size() >= limits_.max_warnings) return;
  warnings_.push_back(
      Diagnostic{code, Severity::warning, block_.line, column == 0 ? 1u : column, std::move(message)});
}

bool Interpreter::next(std::vector<Event>& events) {
  if (ended_) return false;
  try {
    Line l;
    if (!line_at(pos_, line_ + 1, l)) {
      ended_ = true;
      if (!frames_.empty() || !flow_.empty()) {
        block_.line = line_ == 0 ? 1 : line_;
        fail(Code::unmatched_control, 1, "program ends inside a subroutine or control block");
      }
      if (!percent_seen_) {
        block_.line = line_ == 0 ? 1 : line_;
        warn(Code::missing_program_end, 1, "program ends without M2 or M30");
      }
      return false;
    }
    pos_ = l.offset + l.text.size() + l.eol.size();
    line_ = l.number;
    ++lines_read_;
    block_.line = l.number;  // for errors thrown while reading
    read_block(l.text, l.number, l.offset, dialect_, parameters_, block_);
    block_.eol = l.eol;
    if (block_.tape_marker) {
      // A leading '%' opens the program; the next one closes it (the rest
      // of the file is not read, as RS274NGC and Fanuc tape format say).
      if (percent_seen_) {
        ended_ = true;
        return false;
      }
      percent_seen_ = true;
      return true;
    }
    if (block_.deleted) return true;
    if (block_.control.kind != ControlKind::none) {
      handle_control(events);
      return true;
    }
    commit_assignments();
    execute(events);
    return true;
  } catch (...) {
    ended_ = true;
    throw;
  }
}

void Interpreter::commit_assignments() {
  for (const auto& a : block_.assignments) {
    const Access r = a.name.empty() ? parameters_.write(a.number, a.value)
                                    : parameters_.write(a.name, a.value);
    if (!r.ok) fail(r.code, a.column, r.message);
  }
}

void Interpreter::skip_to(const std::string& name, std::initializer_list<ControlKind> stops,
                          bool fanuc_nesting) {
  const std::uint32_t from = block_.line;
  int depth = 0;
  Line l;
  while (line_at(pos_, line_ + 1, l)) {
    const Control c = peek_control(l.text, dialect_);
    bool stop = false;
    if (fanuc_nesting) {
      if (c.kind == ControlKind::if_) {
        ++depth;
      } else if (c.kind == ControlKind::endif && depth > 0) {
        --depth;
      } else if (depth == 0) {
        for (auto k : stops) stop = stop || c.kind == k;
      }
    } else if (c.name == name) {
      for (auto k : stops) stop = stop || c.kind == k;
    }
    if (stop) return;  // positioned at the stopping line: next() reads it
    pos_ = l.offset + l.text.size() + l.eol.size();
    line_ = l.number;
    ++lines_read_;
  }
  throw GcodeError(Diagnostic{Code::unmatched_control, Severity::error, from, 1,
                              "no matching end for the control word of this line"});
}

std::pair<std::uint64_t, std::uint32_t> Interpreter::find_sub(const std::string& name, bool fanuc) {
  const std::string key = (fanuc ? "O" : "o") + name;
  if (auto it = subs_.find(key); it != subs_.end()) return it->second;
  Line l;
  std::uint64_t offset = 0;
  std::uint32_t number = 1;
  while (line_at(offset, number, l)) {
    const Control c = peek_control(l.text, dialect_);
    const std::uint64_t after = l.offset + l.text.size() + l.eol.size();
    if ((fanuc && c.kind == ControlKind::program_number) || (!fanuc && c.kind == ControlKind::sub))
      subs_.try_emplace((fanuc ? "O" : "o") + c.name, after, number + 1);
    offset = after;
    ++number;
  }
  if (auto it = subs_.find(key); it != subs_.end()) return it->second;
  fail(Code::unknown_subroutine, block_.control.column,
       (fanuc ? "program O" : "subroutine o<") + name + (fanuc ? "" : ">") + " not found in this file");
}

void Interpreter::call(const std::string& name, std::vector<double> arguments, bool fanuc,
                       long repeat) {
  if (frames_.size() >= limits_.max_call_depth)
    fail(Code::call_depth, block_.control.column, "subroutine calls nested too deep");
  const auto [body, body_line] = find_sub(name, fanuc);
  frames_.push_back(Frame{pos_, line_ + 1, fanuc, repeat, body, body_line, flow_.size()});
  if (!fanuc) parameters_.push_frame(arguments);
  jump(body, body_line);
}

bool Interpreter::return_from_sub() {
  if (frames_.empty()) return false;
  Frame& f = frames_.back();
  if (f.repeat_left > 1) {
    --f.repeat_left;
    jump(f.body_offset, f.body_line);
    return true;
  }
  flow_.resize(f.flow_depth);
  if (!f.fanuc) parameters_.pop_frame();
  jump(f.return_offset, f.return_line);
  frames_.pop_back();
  return true;
}

bool Interpreter::handle_control(std::vector<Event>& events) {
  const Control& c = block_.control;
  const bool fanuc = c.name.empty();  // Fanuc IF/ELSE/ENDIF have no name
  auto top_is = [&](ControlKind kind) {
    return !flow_.empty() && flow_.back().kind == kind && flow_.back().name == c.name;
  };
  auto advance_past_current = [&] {
    Line l;
    if (line_at(pos_, line_ + 1, l)) {
      pos_ = l.offset + l.text.size() + l.eol.size();
      line_ = l.number;
      ++lines_read_;
    }
  };
  switch (c.kind) {
    case ControlKind::program_number:
      return true;
    case ControlKind::sub: {
      subs_.try_emplace("o" + c.name, pos_, line_ + 1);
      skip_to(c.name, {ControlKind::endsub}, false);
      advance_past_current();
      return true;
    }
    case ControlKind::endsub:
    case ControlKind::return_:
      if (!return_from_sub())
        fail(Code::unmatched_control, c.column, "return from a subroutine that was not called");
      return true;
    case ControlKind::call:
      call(c.name, c.arguments, false, 1);
      return true;
    case ControlKind::if_: {
      const bool taken = c.condition.value_or(0.0) != 0.0;
      flow_.push_back(Flow{ControlKind::if_, c.name, 0, 0, 0, taken});
      if (!taken) skip_to(c.name, {ControlKind::elseif, ControlKind::else_, ControlKind::endif}, fanuc);
      return true;
    }
    case ControlKind::elseif:
    case ControlKind::else_: {
      if (!top_is(ControlKind::if_))
        fail(Code::unmatched_control, c.column, "else without its if");
      Flow& f = flow_.back();
      const bool take = !f.taken && (c.kind == ControlKind::else_ || c.condition.value_or(0.0) != 0.0);
      if (take) {
        f.taken = true;
      } else if (f.taken) {
        skip_to(c.name, {ControlKind::endif}, fanuc);
      } else {
        skip_to(c.name, {ControlKind::elseif, ControlKind::else_, ControlKind::endif}, fanuc);
      }
      return true;
    }
    case ControlKind::endif:
      if (!top_is(ControlKind::if_))
        fail(Code::unmatched_control, c.column, "endif without its if");
      flow_.pop_back();
      return true;
    case ControlKind::while_: {
      if (c.condition.value_or(0.0) != 0.0) {
        flow_.push_back(Flow{ControlKind::while_, c.name, block_.offset, block_.line, 0, true});
      } else {
        skip_to(c.name, {ControlKind::endwhile}, false);
        advance_past_current();
      }
      return true;
    }
    case ControlKind::endwhile: {
      if (!top_is(ControlKind::while_))
        fail(Code::unmatched_control, c.column, "endwhile without its while");
      if (++loop_iterations_ > limits_.max_loop_iterations)
        fail(Code::call_depth, c.column, "loop runs more than the iteration limit");
      const Flow f = flow_.back();
      flow_.pop_back();
      jump(f.start_offset, f.start_line);
      return true;
    }
    case ControlKind::repeat: {
      const long count = std::lround(c.condition.value_or(0.0));
      if (count >= 1) {
        flow_.push_back(Flow{ControlKind::repeat, c.name, pos_, line_ + 1, count, true});
      } else {
        skip_to(c.name, {ControlKind::endrepeat}, false);
        advance_past_current();
      }
      return true;
    }
    case ControlKind::endrepeat: {
      if (!top_is(ControlKind::repeat))
        fail(Code::unmatched_control, c.column, "endrepeat without its repeat");
      if (++loop_iterations_ > limits_.max_loop_iterations)
        fail(Code::call_depth, c.column, "loop runs more than the iteration limit");
      Flow& f = flow_.back();
      if (--f.remaining > 0) {
        jump(f.start_offset, f.start_line);
      } else {
        flow_.pop_back();
      }
      return true;
    }
    case ControlKind::do_:
    case ControlKind::break_:
    case ControlKind::continue_:
      fail(Code::unsupported_flow, c.column,
           "do/break/continue loops are not followed by vcpost; use while/endwhile or repeat");
    case ControlKind::fanuc_goto:
      if (c.condition.value_or(0.0) != 0.0)
        fail(Code::unsupported_flow, c.column,
             c.name + " jumps within the program; vcpost does not follow macro jumps and loops");
      // An IF [..] GOTO not taken: nothing happens, but the block's other
      // words (none are allowed) do not run.
      return true;
    case ControlKind::none:
      break;
  }
  (void)events;
  return true;
}

double Interpreter::length(const Word& w) const {
  double v = w.value;
  if (dialect_.integer_lengths == IntegerLengths::increments && !w.decimal_point && !w.computed)
    v *= state_.inches ? dialect_.increment_inch : dialect_.increment_mm;
  return state_.inches ? v * kInch : v;
}

void Interpreter::execute(std::vector<Event>& events) {
  const Block& b = block_;
  WordIndex index;
  auto word_at = [&](std::uint8_t slot) { return slot == 0 ? nullptr : &b.words[slot - 1u]; };
  int m_words = 0;
  for (std::size_t k = 0; k < b.words.size(); ++k) {
    const Word& w = b.words[k];
    // Stored only for a word that gets indexed: below kMaxIndexedPosition.
    const auto slot_of_w = static_cast<std::uint8_t>(k + 1);
    if (w.letter == 'G') {
      const auto entry = find_code(kGCodes, w.value);
      if (!entry) {
        char text[32];
        std::snprintf(text, sizeof text, "G%g", w.value);
        fail(Code::unknown_g_code, w.column, std::string("unknown G code ") + text);
      }
      if (entry->support == Support::refused)
        fail(Code::unsupported_code, w.column,
             code_text('G', entry->code) +
                 " changes the motion in a way vcpost does not follow; remove it or expand it "
                 "in CAM");
      const auto group = static_cast<std::size_t>(entry->group);
      if (const Word* before = word_at(index.g[group])) {
        // G53 combines with one other non-modal code only in theory; refuse
        // two non-modal codes as LinuxCNC does.
        const bool non_modal = entry->group == Group::non_modal;
        fail(Code::modal_group_conflict, w.column,
             code_text('G', code_of(*before)) + " and " + code_text('G', entry->code) +
                 (non_modal ? " are both non-modal codes" : " are in the same modal group"));
      }
      index.g[group] = slot_of_w;
    } else if (w.letter == 'M') {
      // LinuxCNC's limit; Fanuc-like controls allow fewer.
      if (++m_words > 4) fail(Code::too_many_m_codes, w.column, "more than four M codes in one block");
      const auto entry = find_code(kMCodes, w.value);
      if (!entry) {
        char text[32];
        std::snprintf(text, sizeof text, "M%g", w.value);
        if (dialect_.unknown_m_is_error)
          fail(Code::unknown_m_code, w.column, std::string("unknown M code ") + text);
        warn(Code::unknown_m_code, w.column,
             std::string("M code ") + text + " is not known to vcpost; passed through unchanged");
        continue;
      }
      const auto group = static_cast<std::size_t>(entry->group);
      if (const Word* before = word_at(index.m[group]))
        fail(Code::modal_group_conflict, w.column,
             code_text('M', code_of(*before)) + " and " + code_text('M', entry->code) +
                 " are in the same modal group");
      index.m[group] = slot_of_w;
    } else {
      const char l = w.letter;
      if (l == 'A' || l == 'B' || l == 'C' || l == 'U' || l == 'V' || l == 'W')
        fail(Code::axis_not_supported, w.column,
             std::string(1, w.letter) + " axis: vcpost reads 3-axis (X Y Z) programs only");
      auto& slot = index.by_letter[static_cast<std::size_t>(w.letter - 'A')];
      if (slot != 0)
        fail(Code::word_repeated, w.column, std::string(1, w.letter) + " word given twice");
      slot = slot_of_w;
    }
  }
  auto W = [&](char letter) {
    return word_at(index.by_letter[static_cast<std::size_t>(letter - 'A')]);
  };
  auto G = [&](Group g) { return word_at(index.g[static_cast<std::size_t>(g)]); };
  auto M = [&](Group g) { return word_at(index.m[static_cast<std::size_t>(g)]); };
  // The code of a group's word; only for a group that has one.
  auto Gc = [&](Group g) { return code_of(*G(g)); };
  auto Mc = [&](Group g) { return code_of(*M(g)); };

  // The transaction: all checks against `s`, committed at the end.
  ModalState s = state_;
  const std::size_t first_event = events.size();
  auto emit = [&](auto&& e) { events.emplace_back(std::forward<decltype(e)>(e)); };

  if (b.message) emit(program::Message{*b.message, source(b, b.comments.empty() ? 1 : b.comments.front().column)});

  // Units first: every length of this block is read in the new units.
  if (G(Group::units)) s.inches = Gc(Group::units) == 200;
  const bool inches_before = state_.inches;
  state_.inches = s.inches;  // length() reads state_; restored on error below
  struct Restore {
    ModalState& st;
    bool inches;
    bool armed = true;
    ~Restore() {
      if (armed) st.inches = inches;
    }
  } restore{state_, inches_before};

  if (const Word* g = G(Group::feed_mode)) {
    const int c = Gc(Group::feed_mode);
    const auto mode = c == 930   ? program::FeedMode::inverse_time
                      : c == 950 ? program::FeedMode::per_revolution
                                 : program::FeedMode::per_minute;
    // As LinuxCNC: a G93/G94/G95 word resets the feed to 0 (it must be
    // given again); G94 and G95 say so with a zero feed rate.
    s.feed_mode = mode;
    s.feed = 0.0;
    if (mode != program::FeedMode::inverse_time)
      emit(program::SetFeedRate{0.0, mode, source(b, g->column)});
  }
  // G93: the F event goes right before its move, with the path speed it
  // gives that move (rs274's order and figure).
  const Word* inverse_f = nullptr;
  if (const Word* f = W('F')) {
    if (f->value < 0) fail(Code::bad_word_value, f->column, "negative feed rate");
    if (s.feed_mode == program::FeedMode::inverse_time) {
      s.feed = f->value;
      inverse_f = f;
    } else {
      s.feed = f->value * (s.inches ? kInch : 1.0);
      emit(program::SetFeedRate{s.feed, s.feed_mode, source(b, f->column)});
    }
  }
  // path_rate() costs a square root or an arc length: asked only in G93.
  auto emit_inverse_f = [&](auto path_rate) {
    if (!inverse_f) return;
    emit(program::SetFeedRate{s.feed, program::FeedMode::inverse_time, source(b, inverse_f->column),
                              std::optional<double>(path_rate())});
    inverse_f = nullptr;
  };
  if (const Word* sw = W('S')) {
    if (sw->value < 0) fail(Code::bad_word_value, sw->column, "negative spindle speed");
    s.spindle_rpm = sw->value;
    emit(program::SetSpindleSpeed{sw->value, source(b, sw->column)});
  }
  if (const Word* t = W('T')) {
    if (!whole_number(t->value))
      fail(Code::bad_word_value, t->column, "tool number must be a whole number from 0 to 1e9");
    s.selected_tool = static_cast<int>(t->value);
    emit(program::SelectTool{s.selected_tool, source(b, t->column)});
  }
  if (const Word* m = M(Group::tool_change)) {
    s.tool_in_spindle = s.selected_tool;
    emit(program::ChangeTool{s.tool_in_spindle, source(b, m->column)});
  }
  if (const Word* m = M(Group::spindle)) {
    const int c = Mc(Group::spindle);
    if (c == 50)
      emit(program::SpindleOff{source(b, m->column)});
    else
      emit(program::SpindleOn{c == 30 ? program::SpindleDirection::clockwise
                                      : program::SpindleDirection::counterclockwise,
                              source(b, m->column)});
  }
  if (const Word* m = M(Group::coolant)) {
    const int c = Mc(Group::coolant);
    emit(program::Coolant{c == 70   ? program::CoolantChange::mist_on
                          : c == 80 ? program::CoolantChange::flood_on
                                    : program::CoolantChange::off,
                          source(b, m->column)});
  }
  const Word* nonmodal = G(Group::non_modal);
  const int nonmodal_code = nonmodal ? code_of(*nonmodal) : 0;
  if (nonmodal && nonmodal_code == 40) {
    // Dwell: P seconds (RS274NGC); Fanuc: X seconds or P milliseconds.
    double seconds = 0.0;
    if (dialect_.kind == DialectKind::rs274ngc) {
      const Word* p = W('P');
      if (!p) fail(Code::missing_axis_word, nonmodal->column, "G4 needs P (seconds)");
      seconds = p->value;
    } else if (const Word* x = W('X')) {
      seconds = x->value;
      index.by_letter['X' - 'A'] = 0;  // a time here, not an axis
    } else if (const Word* p = W('P')) {
      seconds = p->decimal_point ? p->value : p->value / 1000.0;
    } else {
      fail(Code::missing_axis_word, nonmodal->column, "G4 needs X (s) or P (ms)");
    }
    if (seconds < 0) fail(Code::bad_word_value, nonmodal->column, "negative dwell");
    emit(program::Dwell{seconds, source(b, nonmodal->column)});
  }
  if (const Word* g = G(Group::plane)) {
    const int c = Gc(Group::plane);
    s.plane = c == 170 ? program::Plane::xy : c == 180 ? program::Plane::xz : program::Plane::yz;
    emit(program::SelectPlane{s.plane, source(b, g->column)});
  }
  if (const Word* g = G(Group::cutter_comp)) {
    const int c = Gc(Group::cutter_comp);
    emit(program::CutterCompensation{c == 400   ? program::CompensationSide::off
                                     : c == 410 ? program::CompensationSide::left
                                                : program::CompensationSide::right,
                                     source(b, g->column)});
  }
  if (const Word* g = G(Group::tool_length)) {
    program::ToolLengthOffset t{Gc(Group::tool_length) == 430, std::nullopt, source(b, g->column)};
    if (const Word* h = W('H')) {
      if (!whole_number(h->value))
        fail(Code::bad_word_value, h->column,
             "H (offset register) must be a whole number from 0 to 1e9");
      t.register_number = static_cast<int>(h->value);
    } else if (t.enabled) {
      t.register_number = s.tool_in_spindle;
    }
    emit(t);
  }
  if (const Word* g = G(Group::coordinate)) {
    const int c = Gc(Group::coordinate);
    if (c != s.work_system && s.moved)
      fail(Code::work_offset_change, g->column,
           "switching from " + code_text('G', s.work_system) + " to " + code_text('G', c) +
               " after motion: vcpost does not know the offsets between them");
    s.work_system = c;
  }
  if (G(Group::distance)) s.absolute = Gc(Group::distance) == 900;
  if (G(Group::arc_distance)) s.arc_absolute = Gc(Group::arc_distance) == 901;

  // Mazak G117: M/S/T words output when the axes reach the given position
  // during the next move; its axis words are that position, not a move.
  // M and S output somewhere inside a move cannot be placed soundly.
  const bool g117 = nonmodal && nonmodal_code == 1170;
  if (g117) {
    if (const Word* sw = W('S'))
      fail(Code::unsupported_code, sw->column,
           "S in a G117 block changes the speed inside the next move; vcpost cannot place it");
    if (const Word* m = M(Group::spindle))
      fail(Code::unsupported_code, m->column,
           "spindle M code in a G117 block acts inside the next move; vcpost cannot place it");
  }
  const bool has_axis = !g117 && (W('X') || W('Y') || W('Z'));
  auto target_of = [&](bool absolute) {
    Eigen::Vector3d t = s.position;
    const char* axes = "XYZ";
    for (int k = 0; k < 3; ++k)
      if (const Word* w = W(axes[k])) t[k] = absolute ? length(*w) : s.position[k] + length(*w);
    return t;
  };
  auto first_axis_column = [&](std::uint32_t fallback) {
    std::uint32_t col = 0;
    for (char a : {'X', 'Y', 'Z'})
      if (const Word* w = W(a)) col = col == 0 ? w->column : std::min(col, w->column);
    return col == 0 ? fallback : col;
  };

  if (const Word* g = G(Group::motion)) {
    const int c = Gc(Group::motion);
    s.motion = c == 0 ? Motion::rapid : c == 10 ? Motion::linear : c == 20 ? Motion::arc_cw
               : c == 30 ? Motion::arc_ccw : Motion::none;
    (void)g;
  }
  const std::uint32_t motion_column =
      G(Group::motion) ? G(Group::motion)->column : first_axis_column(1);

  if (nonmodal && nonmodal_code == 280) {
    // G28: through the given intermediate point to the home position, which
    // rs274 takes as 0 with its default parameters: the offsets are unknown.
    const Eigen::Vector3d via = target_of(s.absolute);
    Eigen::Vector3d home = via;
    const char* axes = "XYZ";
    for (int k = 0; k < 3; ++k)
      if (!has_axis || W(axes[k])) home[k] = 0.0;
    warn(Code::machine_coordinates, nonmodal->column,
         "G28 home position taken as 0 in program coordinates (machine offsets unknown)");
    if (has_axis) emit(program::StraightTraverse{s.position, via, source(b, nonmodal->column)});
    emit(program::StraightTraverse{via, home, source(b, nonmodal->column)});
    s.position = home;
    s.moved = true;
  } else if (has_axis || (!g117 && (s.motion == Motion::arc_cw || s.motion == Motion::arc_ccw) &&
                          (W('I') || W('J') || W('K') || W('R')))) {
    const bool machine = nonmodal && nonmodal_code == 530;
    if (machine) {
      if (s.motion != Motion::rapid && s.motion != Motion::linear)
        fail(Code::unsupported_code, nonmodal->column, "G53 needs G0 or G1");
      warn(Code::machine_coordinates, nonmodal->column,
           "G53 machine coordinates taken as program coordinates (offsets unknown)");
    }
    const Eigen::Vector3d end = target_of(s.absolute || machine);
    const auto src = source(b, motion_column);
    switch (s.motion) {
      case Motion::none:
        fail(Code::words_without_motion, first_axis_column(1),
             "axis words without a motion mode (G0/G1/G2/G3)");
      case Motion::rapid:
        emit(program::StraightTraverse{s.position, end, src});
        break;
      case Motion::linear:
        if (s.feed <= 0.0 || (s.feed_mode == program::FeedMode::inverse_time && !W('F')))
          fail(Code::missing_feed, motion_column, "G1 with no feed rate (F) in effect");
        emit_inverse_f([&] { return s.feed * (end - s.position).norm(); });
        emit(program::StraightFeed{s.position, end, src});
        break;
      case Motion::arc_cw:
      case Motion::arc_ccw: {
        if (s.feed <= 0.0 || (s.feed_mode == program::FeedMode::inverse_time && !W('F')))
          fail(Code::missing_feed, motion_column, "arc with no feed rate (F) in effect");
        const auto ax = program::plane_axes(s.plane);
        const char letters[3] = {'I', 'J', 'K'};
        const Word* off0 = W(letters[ax[0]]);
        const Word* off1 = W(letters[ax[1]]);
        const Word* r = W('R');
        const bool cw = s.motion == Motion::arc_cw;
        Eigen::Vector3d centre = s.position;
        const double a0 = s.position[ax[0]], b0 = s.position[ax[1]];
        const double a1 = end[ax[0]], b1 = end[ax[1]];
        if (r) {
          const double radius = length(*r);
          const double chord = std::hypot(a1 - a0, b1 - b0);
          if (chord < 1e-9)
            fail(Code::missing_arc_data, r->column,
                 "R arc with the same start and end point: a full circle needs I/J/K");
          const double half = chord / 2.0;
          const double abs_r = std::abs(radius);
          if (abs_r < 1e-9) fail(Code::arc_zero_radius, r->column, "arc radius R0");
          if (abs_r < half - kArcAbsoluteTolerance)
            fail(Code::arc_r_too_small, r->column,
                 "R = " + std::to_string(abs_r) + " mm is smaller than half the chord (" +
                     std::to_string(half) + " mm)");
          const double h = abs_r > half ? std::sqrt(abs_r * abs_r - half * half) : 0.0;
          // Short arc (R > 0): centre left of the chord for G3, right for G2.
          double side = cw ? -1.0 : 1.0;
          if (radius < 0) side = -side;
          const double ua = (a1 - a0) / chord, ub = (b1 - b0) / chord;
          centre[ax[0]] = (a0 + a1) / 2.0 - side * ub * h;
          centre[ax[1]] = (b0 + b1) / 2.0 + side * ua * h;
        } else {
          if (!off0 && !off1)
            fail(Code::missing_arc_data, motion_column,
                 std::string("arc needs ") + letters[ax[0]] + " or " + letters[ax[1]] +
                     " (centre) or R (radius)");
          if (s.arc_absolute) {
            if (off0) centre[ax[0]] = length(*off0);
            if (off1) centre[ax[1]] = length(*off1);
          } else {
            if (off0) centre[ax[0]] += length(*off0);
            if (off1) centre[ax[1]] += length(*off1);
          }
          const double r0 = std::hypot(a0 - centre[ax[0]], b0 - centre[ax[1]]);
          const double r1 = std::hypot(a1 - centre[ax[0]], b1 - centre[ax[1]]);
          if (r0 < 1e-9 || r1 < 1e-9)
            fail(Code::arc_zero_radius, motion_column, "arc with zero radius at start or end");
          const double err = std::abs(r1 - r0);
          if (err > kArcAbsoluteTolerance && err / r0 > kArcRelativeTolerance)
            fail(Code::arc_radius_mismatch, motion_column,
                 "radius to end " + std::to_string(r1) + " mm differs from radius to start " +
                     std::to_string(r0) + " mm");
        }
        int turns = 1;
        if (const Word* p = W('P'); p && dialect_.kind == DialectKind::rs274ngc) {
          if (p->value < 1 || !whole_number(p->value))
            fail(Code::bad_word_value, p->column,
                 "P (turns) of an arc must be a whole number from 1 to 1e9");
          turns = static_cast<int>(p->value);
        }
        const program::ArcFeed arc{s.position, end, centre, s.plane, cw ? -turns : turns, src};
        emit_inverse_f([&] { return s.feed * program::arc_length(arc); });
        emit(arc);
        break;
      }
    }
    s.position = end;
    s.moved = true;
  }

  emit_inverse_f([] { return std::optional<double>(); });

  // Stops and subprogram calls come last.
  bool end_program = false;
  if (const Word* m = M(Group::stopping)) {
    const int c = Mc(Group::stopping);
    if (c == 0 || c == 10) {
      emit(program::ProgramStop{c == 10, source(b, m->column)});
    } else if (c == 20 || c == 300) {
      end_program = true;
    } else if (c == 990) {
      if (const Word* p = W('P'))
        fail(Code::unsupported_flow, p->column,
             "M99 P (return to a sequence number) is a jump vcpost does not follow");
      if (frames_.empty()) {
        end_program = true;  // M99 in a main program repeats it on the control: end here
      } else {
        restore.armed = false;
        state_ = s;
        return_from_sub();
        return;
      }
    }
  }
  if (end_program) {
    const auto src = source(b, M(Group::stopping)->column);
    emit(program::SpindleOff{src});
    emit(program::SetFeedRate{0.0, program::FeedMode::per_minute, src});
    emit(program::ProgramEnd{src});
    ended_ = true;
  }
  restore.armed = false;
  state_ = s;
  if (const Word* m = M(Group::subprogram)) {
    const Word* p = W('P');
    if (!p) fail(Code::missing_axis_word, m->column, "M98 needs P (program number)");
    const Word* l = W('L');
    long number = std::lround(p->value);
    long count = l ? std::lround(l->value) : 1;
    // Fanuc's short form M98 Prrrrnnnn: repetitions rrrr, program nnnn.
    if (!l && dialect_.kind == DialectKind::fanuc && number > 9999) {
      count = number / 10000;
      number %= 10000;
    }
    block_.control.column = m->column;
    char name[32];
    std::snprintf(name, sizeof name, "%ld", number);
    call(name, {}, true, count < 1 ? 1 : count);
  }
  (void)first_event;
}

}  // namespace vcpost::gcode
