// The machine's functions in a Klartext program: TOOL CALL and TOOL DEF
// (tool, spindle speed, FAUTO's feed, TOOL DEF's radius), a block's M
// functions before and after its move (spindle, coolant, stops, M128,
// M99's cycle call, M2/M30's end), and FUNCTION blocks (TCPM, MODE MILL).
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "postproc/heidenhain/interpreter.h"
#include "postproc/heidenhain/interpreter_words.h"

namespace vcpost::heidenhain {

using program::Event;

void Interpreter::tool_call(std::vector<Event>& events) {
  const bool call = block_.kind == BlockKind::tool_call;
  if (call && called_tool_calls_refused_ && !programs_.empty())
    fail(Code::E3332, block_.keyword_begin,
         "TOOL CALL in the called program " + program_name_ +
             ": vcpost post writes the calling program's blocks only and cannot change a speed "
             "in another file; post the called program on its own");
  std::optional<int> number;
  if (const Word* t = block_.find(name("T"))) {
    const double n = value(t->value, t->begin);
    if (n < 0 || n != std::floor(n) || n > 32767)
      fail(Code::E3303, t->begin, "a tool number is a whole number 0-32767");
    number = static_cast<int>(n);
  } else if (!block_.tool_name.empty()) {
    number = tool_number(block_.tool_name);
    if (!number) {
      number = static_cast<int>(tool_names_.size()) + 1;
      tool_names_.emplace_back(std::string(block_.tool_name), *number);
    }
  }
  std::optional<double> speed;
  for (const Word& w : block_.words) {
    switch (w.key) {
      case name("T"):
        break;
      case name("X"):
      case name("Y"):
        if (w.has_value) fail(Code::E3307, w.begin, "a TOOL CALL takes its axis without a value");
        fail(Code::E3321, w.begin,
             "tool axis " + std::string(1, static_cast<char>(w.key)) +
                 ": only tool axis Z is read (a horizontal spindle turns the frame)");
      case name("Z"):
        if (w.has_value) fail(Code::E3307, w.begin, "a TOOL CALL takes its axis without a value");
        break;
      case name("S"):
        if (!w.has_value)
          fail(Code::E3303, w.begin, "S needs the spindle speed (S(VC=..) is not read)");
        speed = value(w.value, w.begin);
        if (*speed < 0) fail(Code::E3303, w.begin, "a spindle speed is not negative");
        break;
      case name("F"):
        if (!w.has_value) fail(Code::E3303, w.begin, "F needs a value");
        tool_feed_ = feed_rate(value(w.value, w.begin));
        break;
      case name("DL"):
      case name("DR"):
      case name("DR2"):
      case name("DL2"):
        break;  // oversizes: the path is the programmed one (see the header)
      case name("R"):
        if (call) fail(Code::E3307, w.begin, "TOOL CALL takes DL and DR, not L and R");
        if (number && w.has_value)
          defined_radii_.emplace_back(*number, length(value(w.value, w.begin)));
        break;
      case name("L"):
      case name("R2"):
        if (call) fail(Code::E3307, w.begin, "TOOL CALL takes DL and DR, not L and R");
        break;  // TOOL DEF's length and second radius
      default:
        fail(Code::E3307, w.begin,
             "'" + std::string(block_.text.substr(w.begin, w.end - w.begin)) + "' is no word of " +
                 std::string(block_.keyword));
    }
  }
  const program::SourceRef src = source();
  if (number && call) {
    tool_radius_.reset();
    for (const auto& [tool, radius] : defined_radii_)
      if (tool == *number) tool_radius_ = radius;
  }
  if (number) {
    events.emplace_back(program::SelectTool{*number, src});
    if (call) events.emplace_back(program::ChangeTool{*number, src});
  }
  if (speed && call) {
    spindle_rpm_ = *speed;
    events.emplace_back(program::SetSpindleSpeed{*speed, src});
  }
}

void Interpreter::start_functions(const Words& w, std::vector<Event>& events) {
  const program::SourceRef src = source();
  for (const Words::M& m : w.m) {
    switch (m.action) {
      case MAction::spindle_cw:
      case MAction::cw_coolant:
        spindle_ccw_ = false;
        events.emplace_back(program::SpindleOn{program::SpindleDirection::clockwise, src});
        break;
      case MAction::spindle_ccw:
      case MAction::ccw_coolant:
        spindle_ccw_ = true;
        events.emplace_back(program::SpindleOn{program::SpindleDirection::counterclockwise, src});
        break;
      case MAction::mist:
        events.emplace_back(program::Coolant{program::CoolantChange::mist_on, src});
        break;
      case MAction::flood:
        events.emplace_back(program::Coolant{program::CoolantChange::flood_on, src});
        break;
      case MAction::tcpm_on:
        tcpm_ = true;
        break;
      case MAction::refused:
        fail(Code::E3319, m.at,
             "M" + std::to_string(m.number) +
                 (m.number == 89    ? " (modal cycle call) is not read: call each hole with M99"
                  : m.number == 103 ? " (plunging feed factor) is not read"
                                    : " (feed per revolution) is not read"));
      case MAction::passed:
        warn_once(
            Code::W3341, m.number, m.at,
            "M" + std::to_string(m.number) + " passed: a machine function taken as moving nothing");
        break;
      default:
        break;
    }
    if (m.action == MAction::cw_coolant || m.action == MAction::ccw_coolant)
      events.emplace_back(program::Coolant{program::CoolantChange::flood_on, src});
  }
}

void Interpreter::end_functions(const Words& w, std::vector<Event>& events) {
  const program::SourceRef src = source();
  for (const Words::M& m : w.m) {
    switch (m.action) {
      case MAction::spindle_off:
        events.emplace_back(program::SpindleOff{src});
        break;
      case MAction::coolant_off:
        events.emplace_back(program::Coolant{program::CoolantChange::off, src});
        break;
      case MAction::tcpm_off:
        tcpm_ = false;
        break;
      case MAction::cycle_call:
        run_cycle(m.at, events);
        break;
      case MAction::stop:
      case MAction::optional_stop:
        events.emplace_back(program::ProgramStop{m.action == MAction::optional_stop, src});
        break;
      default:
        break;
    }
  }
  for (const Words::M& m : w.m) {
    if (m.action == MAction::end) {
      if (!programs_.empty())
        fail(Code::E3319, m.at,
             "M" + std::to_string(m.number) +
                 " in a called program (the TNC manual: a called program must not contain M2 or "
                 "M30; end it with END PGM)");
      events.emplace_back(program::SpindleOff{src});
      events.emplace_back(program::ProgramEnd{src});
      end_event_ = true;
      ended_ = true;
    }
  }
}

void Interpreter::function_block() {
  const std::string_view what = block_.sub_keyword;
  if (what.starts_with("RESET TCPM")) {
    tcpm_ = false;
  } else if (what.starts_with("TCPM")) {
    tcpm_ = true;
  } else if (!what.starts_with("MODE MILL")) {
    warn_once(Code::W3344, 1000 + static_cast<long>(what.size()), block_.keyword_begin,
              "FUNCTION " + std::string(what.substr(0, what.find(' '))) +
                  " passed: taken as moving nothing");
  }
}

}  // namespace vcpost::heidenhain
