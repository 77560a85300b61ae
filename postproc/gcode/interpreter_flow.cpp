// The interpreter's flow control, kept apart from the block transaction
// as LinuxCNC keeps interp_o_word.cc: o-word subroutines, calls and
// returns, if/elseif/else/endif, while and repeat loops, Fanuc's program
// numbers, IF/GOTO and nesting, M98/M99 subprogram calls and G65 macro
// calls. They move the reading position and keep the call and flow stacks;
// each pass counts against the interpreter's limits.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "postproc/gcode/interpreter.h"
#include "postproc/gcode/interpreter_step.h"
#include "postproc/gcode/lexer.h"

namespace vcpost::gcode {

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
  throw GcodeError(
      Diagnostic{Code::E1303, from, 1, "no matching end for the control word of this line"});
}

// The subroutine (o-word sub, or program O<number>) in this file; the first
// look-up of a name not yet met indexes the whole file.
Interpreter::Sub* Interpreter::lookup_sub(const std::string& name, bool fanuc) {
  const std::string key = (fanuc ? "O" : "o") + name;
  auto found = subs_.find(key);
  if (found == subs_.end()) {
    Line l;
    std::uint64_t offset = 0;
    std::uint32_t number = 1;
    while (line_at(offset, number, l)) {
      const Control c = peek_control(l.text, dialect_);
      const std::uint64_t after = l.offset + l.text.size() + l.eol.size();
      if ((fanuc && c.kind == ControlKind::program_number) ||
          (!fanuc && c.kind == ControlKind::sub))
        subs_.try_emplace((fanuc ? "O" : "o") + c.name, Sub{after, number + 1});
      offset = after;
      ++number;
    }
    found = subs_.find(key);
  }
  return found == subs_.end() ? nullptr : &found->second;
}

Interpreter::Sub& Interpreter::find_sub(const std::string& name, bool fanuc) {
  Sub* sub = lookup_sub(name, fanuc);
  if (!sub)
    fail(Code::E1302, block_.control.column,
         (fanuc ? "program O" : "subroutine o<") + name + (fanuc ? "" : ">") +
             " not found in this file");
  if (!fanuc && !sub->met) sub->called_ahead = true;
  return *sub;
}

// A definition met in the flow of the program. rs274 refuses a second
// definition of a name, and one met after a call has run it (the call
// searched ahead for it): it says "found in illegal location".
void Interpreter::define_sub(const Control& c) {
  auto [it, fresh] = subs_.try_emplace("o" + c.name, Sub{pos_, line_ + 1});
  Sub& sub = it->second;
  if (!fresh && dialect_.kind == machines::Dialect::rs274ngc) {
    if (sub.body_line != line_ + 1)
      fail(Code::E1310, c.column,
           "subroutine o<" + c.name + "> is defined twice (first at line " +
               std::to_string(sub.body_line - 1) + "); rs274 refuses the second definition");
    if (sub.met || sub.called_ahead)
      fail(Code::E1310, c.column,
           "subroutine o<" + c.name +
               "> is defined after a call that ran it; rs274 refuses the definition here "
               "(\"found in illegal location\"): define it before its calls, or after the "
               "program's end (M2)");
  }
  sub.met = true;
}

// LinuxCNC nests at most 9 calls (INTERP_SUB_ROUTINE_LEVELS, 10 with the
// main program).
std::size_t Interpreter::call_depth_limit() const {
  constexpr std::size_t kRs274Levels = 9;
  return dialect_.kind == machines::Dialect::rs274ngc
             ? std::min(limits_.max_call_depth, kRs274Levels)
             : limits_.max_call_depth;
}

void Interpreter::call(const std::string& name, const std::vector<double>& arguments, bool fanuc,
                       long repeat, bool own_locals) {
  if (frames_.size() >= call_depth_limit())
    fail(Code::E1304, block_.control.column,
         "subroutine calls nested more than " + std::to_string(call_depth_limit()) + " deep" +
             (dialect_.kind == machines::Dialect::rs274ngc ? " (rs274's limit)" : ""));
  const Sub& sub = find_sub(name, fanuc);
  frames_.push_back(Frame{pos_, line_ + 1, fanuc, own_locals, repeat, lines_read_, sub.body_offset,
                          sub.body_line, flow_.size()});
  if (own_locals) parameters_.push_frame(arguments);
  jump(sub.body_offset, sub.body_line);
}

void Interpreter::count_pass(std::uint64_t pass_start, long left, std::uint32_t column) {
  if (++loop_iterations_ > limits_.max_loop_iterations)
    fail(Code::E1307, column,
         "loop or subprogram repeat runs more than " + std::to_string(limits_.max_loop_iterations) +
             " passes, the iteration limit");
  const std::uint64_t pass = lines_read_ - pass_start;
  const auto more = static_cast<std::uint64_t>(std::max(left, 0L));
  if (pass > 0 && lines_read_ <= limits_.max_blocks &&
      more > (limits_.max_blocks - lines_read_) / pass)
    fail(Code::E1309, column,
         std::to_string(more) + " more passes of " + std::to_string(pass) +
             " lines would run the program past " + std::to_string(limits_.max_blocks) +
             " blocks (loops and calls counted), the limit");
}

bool Interpreter::return_from_sub() {
  if (frames_.empty()) return false;
  Frame& f = frames_.back();
  if (f.repeat_left > 1) {
    --f.repeat_left;
    count_pass(f.pass_start, f.repeat_left, block_.control.column);
    f.pass_start = lines_read_;
    jump(f.body_offset, f.body_line);
    return true;
  }
  flow_.resize(f.flow_depth);
  if (f.own_locals) parameters_.pop_frame();
  jump(f.return_offset, f.return_line);
  frames_.pop_back();
  return true;
}

// A control line (o-words, Fanuc IF/WHILE/GOTO, program numbers): it moves
// the reading position and keeps the call and flow stacks.
void Interpreter::handle_control() {
  const Control& c = block_.control;
  switch (c.kind) {
    case ControlKind::none:
    case ControlKind::program_number:
      return;
    case ControlKind::sub:
      // A definition met in the flow of the program is skipped to its end.
      define_sub(c);
      skip_to(c.name, {ControlKind::endsub}, false);
      skip_current_line();
      return;
    case ControlKind::endsub:
    case ControlKind::return_:
      if (!return_from_sub())
        fail(Code::E1303, c.column, "return from a subroutine that was not called");
      return;
    case ControlKind::call:
      call(c.name, c.arguments, false, 1, true);
      return;
    case ControlKind::if_:
    case ControlKind::elseif:
    case ControlKind::else_:
    case ControlKind::endif:
      branch(c);
      return;
    case ControlKind::while_:
    case ControlKind::endwhile:
    case ControlKind::repeat:
    case ControlKind::endrepeat:
      loop(c);
      return;
    case ControlKind::do_:
    case ControlKind::break_:
    case ControlKind::continue_:
      fail(Code::E1301, c.column,
           "do/break/continue loops are not followed by vcpost; use while/endwhile or repeat");
    case ControlKind::fanuc_goto:
      if (c.condition.value_or(0.0) != 0.0)
        fail(Code::E1301, c.column,
             c.name + " jumps within the program; vcpost does not follow macro jumps and loops");
      // An IF [..] GOTO not taken: nothing happens, but the block's other
      // words (none are allowed) do not run.
      return;
  }
}

// The innermost open if/while/repeat is of `kind` and has this line's name.
bool Interpreter::flow_top_is(ControlKind kind) const {
  return !flow_.empty() && flow_.back().kind == kind && flow_.back().name == block_.control.name;
}

// Steps over the line skip_to() stopped at (its end line).
void Interpreter::skip_current_line() {
  Line l;
  if (line_at(pos_, line_ + 1, l)) {
    pos_ = l.offset + l.text.size() + l.eol.size();
    line_ = l.number;
    ++lines_read_;
  }
}

// if / elseif / else / endif: the first branch whose condition holds runs,
// the others are skipped (Fanuc's IF/ELSE/ENDIF, without names, nest).
void Interpreter::branch(const Control& c) {
  const bool fanuc = c.name.empty();
  if (c.kind == ControlKind::if_) {
    const bool taken = c.condition.value_or(0.0) != 0.0;
    flow_.push_back(Flow{ControlKind::if_, c.name, 0, 0, 0, taken});
    if (!taken)
      skip_to(c.name, {ControlKind::elseif, ControlKind::else_, ControlKind::endif}, fanuc);
    return;
  }
  if (c.kind == ControlKind::endif) {
    if (!flow_top_is(ControlKind::if_)) fail(Code::E1303, c.column, "endif without its if");
    flow_.pop_back();
    return;
  }
  if (!flow_top_is(ControlKind::if_)) fail(Code::E1303, c.column, "else without its if");
  Flow& f = flow_.back();
  const bool take = !f.taken && (c.kind == ControlKind::else_ || c.condition.value_or(0.0) != 0.0);
  if (take) {
    f.taken = true;
  } else if (f.taken) {
    skip_to(c.name, {ControlKind::endif}, fanuc);
  } else {
    skip_to(c.name, {ControlKind::elseif, ControlKind::else_, ControlKind::endif}, fanuc);
  }
}

// while / endwhile and repeat / endrepeat, each pass counted against the
// iteration limit.
void Interpreter::loop(const Control& c) {
  switch (c.kind) {
    case ControlKind::while_:
      if (c.condition.value_or(0.0) != 0.0) {
        flow_.push_back(Flow{ControlKind::while_, c.name, block_.offset, block_.line, 0, true});
      } else {
        skip_to(c.name, {ControlKind::endwhile}, false);
        skip_current_line();
      }
      return;
    case ControlKind::repeat: {
      const long count = std::lround(c.condition.value_or(0.0));
      if (count >= 1) {
        flow_.push_back(
            Flow{ControlKind::repeat, c.name, pos_, line_ + 1, count, true, lines_read_});
      } else {
        skip_to(c.name, {ControlKind::endrepeat}, false);
        skip_current_line();
      }
      return;
    }
    case ControlKind::endwhile: {
      if (!flow_top_is(ControlKind::while_))
        fail(Code::E1303, c.column, "endwhile without its while");
      count_pass(lines_read_, 0, c.column);
      const Flow f = flow_.back();
      flow_.pop_back();
      jump(f.start_offset, f.start_line);
      return;
    }
    default: {  // endrepeat
      if (!flow_top_is(ControlKind::repeat))
        fail(Code::E1303, c.column, "endrepeat without its repeat");
      Flow& f = flow_.back();
      count_pass(f.pass_start, f.remaining - 1, c.column);
      if (--f.remaining > 0) {
        f.pass_start = lines_read_;
        jump(f.start_offset, f.start_line);
      } else {
        flow_.pop_back();
      }
      return;
    }
  }
}

// G65 P<program> L<count> <arguments>: a macro call. A program of this file
// runs with the block's words as its local variables (argument
// specification I: A #1, B #2, C #3, I #4, J #5, K #6, D #7, E #8, F #9,
// H #11, M #13, Q #17, R #18, S #19, T #20, U #21, V #22, W #23, X #24,
// Y #25, Z #26); a program elsewhere (a machine maker's macro) is taken as
// moving nothing, with a warning.
void Interpreter::macro_call(const Step& step) {
  const Word* p = step.word('P');
  const Word* g65 = step.nonmodal;
  if (!p) fail(Code::E1514, g65->column, "G65 needs P (program number)");
  if (p->value < 0 || p->value > 1e9 || p->value != std::floor(p->value))
    fail(Code::E1511, p->column, "G65 P must be a program number, a whole number");
  const Word* l = step.word('L');
  if (l && (l->value < 0 || l->value > 1e9 || l->value != std::floor(l->value)))
    fail(Code::E1511, l->column,
         "G65 L (the number of passes) must be a whole number from 0 to 1e9");
  const std::string name = std::to_string(static_cast<long>(p->value));
  if (!lookup_sub(name, true)) {
    warn_once('G', G_65_macro_call, Code::W1306, g65->column,
              "G65 P" + name +
                  " calls a macro program that is not in this file (a machine maker's macro): "
                  "taken as not moving the tool");
    return;
  }
  const long count = l ? static_cast<long>(l->value) : 1;
  if (count == 0) return;
  block_.control.column = g65->column;
  call(name, {}, true, count, true);
  static constexpr std::string_view kLetters = "ABCIJKDEFHMQRSTUVWXYZ";
  static constexpr int kLocals[] = {1,  2,  3,  4,  5,  6,  7,  8,  9,  11, 13,
                                    17, 18, 19, 20, 21, 22, 23, 24, 25, 26};
  static_assert(std::size(kLocals) == kLetters.size());
  for (const Word& w : step.b.words) {
    const auto k = kLetters.find(w.letter);
    if (k == std::string_view::npos || w.letter == 'M') continue;
    const Access a = parameters_.write(kLocals[k], w.value);
    if (!a.ok) fail(a.code, w.column, a.message);
  }
}

// M98 P (L count; Fanuc's short form M98 Prrrrnnnn: rrrr repetitions of
// program nnnn), after the block is committed.
void Interpreter::call_subprogram(const Step& step) {
  const Word* m = step.m(Group::subprogram);
  const Word* p = step.word('P');
  if (!p) fail(Code::E1514, m->column, "M98 needs P (program number)");
  const Word* l = step.word('L');
  if (p->value < 0 || p->value > 1e9 || p->value != std::floor(p->value))
    fail(Code::E1511, p->column, "M98 P must be a program number, a whole number");
  // L counts the passes, as rs274 and Fanuc do: L0 runs none; a negative or
  // fractional count is refused (rs274: "Negative l word used").
  if (l && (l->value < 0 || l->value > 1e9 || l->value != std::floor(l->value)))
    fail(Code::E1511, l->column,
         "M98 L (the number of passes) must be a whole number from 0 to 1e9");
  auto number = static_cast<long>(p->value);
  long count = l ? static_cast<long>(l->value) : 1;
  if (!l && dialect_.kind == machines::Dialect::fanuc && number > 9999) {
    count = number / 10000;
    number %= 10000;
  }
  if (count == 0) return;
  block_.control.column = m->column;
  char name[32];
  std::snprintf(name, sizeof name, "%ld", number);
  call(name, {}, true, count, false);
}

}  // namespace vcpost::gcode
