// Parameters and the program's flow: FN 0-19 and Q = formulas (the
// formula's functions are formula.h's), LBL, CALL LBL with REP (subprograms
// and repeated sections), FN 9-12 jumps, and called programs (CALL PGM, SEL
// PGM / CALL SELECTED), which run inline with their own QL parameters. Each
// jump and call counts against the interpreter's limits.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/units.h"
#include "postproc/heidenhain/formula.h"
#include "postproc/heidenhain/interpreter.h"
#include "postproc/heidenhain/interpreter_words.h"

namespace vcpost::heidenhain {

using program::Event;

void Interpreter::fn(std::vector<Event>& events) {
  (void)events;
  const FnStatement& f = block_.fn;
  const std::uint32_t at = block_.keyword_begin;
  if (f.number > 13) {
    switch (f.number) {
      case 15:
      case 16:
      case 19:
        warn_once(
            Code::W3344, f.number, at,
            "FN " + std::to_string(f.number) + " passed (print or PLC output: moves nothing)");
        return;
      case 14:
        fail(Code::E3319, at,
             "FN 14 raises an error on the control (" + std::string(block_.sub_keyword) +
                 "): the program stops there");
      default:
        fail(Code::E3319, at,
             "FN " + std::to_string(f.number) + " is not read (it needs the control's own data)");
    }
  }
  const double a = value(*f.a, f.a_begin);
  const double b = f.b ? value(*f.b, f.b_begin) : 0.0;
  if (f.number >= 9 && f.number <= 12) {
    const bool jump = f.number == 9    ? a == b
                      : f.number == 10 ? a != b
                      : f.number == 11 ? a > b
                                       : a < b;
    if (jump) jump_to(*f.jump, f.jump->begin);
    return;
  }
  double result = 0;
  switch (f.number) {
    case 0:
      result = a;
      break;
    case 1:
      result = a + b;
      break;
    case 2:
      result = a - b;
      break;
    case 3:
      result = a * b;
      break;
    case 4:
      if (b == 0) fail(Code::E3318, f.b_begin, "FN 4: division by zero");
      result = a / b;
      break;
    case 5:
      if (a < 0) fail(Code::E3318, f.a_begin, "FN 5: square root of a negative number");
      result = std::sqrt(a);
      break;
    case 6:
      result = std::sin(a * kDeg);
      break;
    case 7:
      result = std::cos(a * kDeg);
      break;
    case 8:
      result = std::hypot(a, b);
      break;
    default:
      result = std::atan2(b, a) / kDeg;
      break;  // 13: ANG
  }
  if (!(std::abs(result) <= 1e12)) fail(Code::E3318, at, "FN result out of range");
  q_[parameter_index(*f.target, at)] = result;
}

void Interpreter::formula() {
  const double result = evaluate_formula(
      block_, block_.formula, [this](const Value& v, std::uint32_t at) { return value(v, at); });
  q_[parameter_index(*block_.fn.target, block_.keyword_begin)] = result;
}

Interpreter::Place Interpreter::find_label(const Label& label, std::uint32_t at) {
  if (!labels_) {
    // One scan of the whole text: every line "[/][n] LBL n|"name"".
    labels_.emplace();
    std::uint64_t k = 0;
    std::uint32_t line = 1;
    while (k < text_.size()) {
      const auto* nl =
          static_cast<const char*>(std::memchr(text_.data() + k, '\n', text_.size() - k));
      const std::uint64_t end = nl ? static_cast<std::uint64_t>(nl - text_.data()) : text_.size();
      std::uint64_t i = k;
      auto blanks = [&] {
        while (i < end && (text_[i] == ' ' || text_[i] == '\t')) ++i;
      };
      blanks();
      if (i < end && text_[i] == '/') ++i;
      while (i < end && text_[i] >= '0' && text_[i] <= '9') ++i;
      blanks();
      if (i < end && text_[i] == '/') ++i;
      if (text_.substr(i, 4) == "LBL " || text_.substr(i, 4) == "LBL\t") {
        i += 4;
        blanks();
        std::string key;
        if (i < end && text_[i] == '"') {
          const std::uint64_t close = text_.find('"', i + 1);
          if (close != std::string_view::npos && close < end)
            key = "\"" + std::string(text_.substr(i + 1, close - i - 1));
        } else {
          std::uint64_t j = i;
          while (j < end && text_[j] >= '0' && text_[j] <= '9') ++j;
          if (j > i) key = std::to_string(std::stol(std::string(text_.substr(i, j - i))));
        }
        if (!key.empty()) labels_->try_emplace(key, Place{k, line});
      }
      k = nl ? end + 1 : text_.size();
      ++line;
    }
  }
  const std::string key =
      label.number >= 0 ? std::to_string(label.number) : "\"" + std::string(label.name);
  const auto it = labels_->find(key);
  if (it != labels_->end() && programs_.empty())
    repeat_from_ = std::min(repeat_from_.value_or(it->second.offset), it->second.offset);
  if (it == labels_->end()) {
    fail(Code::E3315, at,
         "no LBL " +
             (label.number >= 0 ? std::to_string(label.number)
                                : "\"" + std::string(label.name) + "\"") +
             " in this program");
  }
  return it->second;
}

void Interpreter::count_jump(std::uint32_t at) {
  if (++jumps_ > limits_.max_loop_iterations)
    fail(Code::E3317, at,
         "repeats and jumps run past the limit of " + std::to_string(limits_.max_loop_iterations) +
             " (an endless loop?)");
}

void Interpreter::jump_to(const Label& label, std::uint32_t at) {
  if (label.number == 0) fail(Code::E3315, at, "LBL 0 ends a subprogram: it cannot be jumped to");
  const Place p = find_label(label, at);
  count_jump(at);
  pos_ = p.offset;
  line_ = p.line - 1;
}

void Interpreter::label_block() {
  if (block_.label && block_.label->number != 0 && programs_.empty())
    repeat_from_ = std::min(repeat_from_.value_or(block_.offset), block_.offset);
  if (!block_.label || block_.label->number != 0 || frames_.empty()) return;
  Frame& top = frames_.back();
  if (top.section) return;  // LBL 0 inside a repeated section: not its end
  if (top.remaining > 0) {
    --top.remaining;
    count_jump(block_.keyword_begin);
    pos_ = top.label_offset;
    line_ = top.label_line - 1;
    return;
  }
  pos_ = top.return_offset;
  line_ = top.return_line - 1;
  frames_.pop_back();
}

void Interpreter::call_label() {
  const Label& label = *block_.label;
  long repeats = 0;
  if (const Word* rep = block_.find(name("REP"))) {
    const double n = rep->has_value ? value(rep->value, rep->begin) : -1;
    if (n < 0 || n != std::floor(n) || n > 65534)
      fail(Code::E3303, rep->begin, "REP takes a count 0-65534");
    repeats = static_cast<long>(n);
  }
  for (const Word& w : block_.words) {
    if (w.key != name("REP")) fail(Code::E3307, w.begin, "CALL LBL takes REP only");
  }
  // The end of a repeated section: this very block called it.
  if (!frames_.empty() && frames_.back().section && frames_.back().call_offset == block_.offset) {
    Frame& top = frames_.back();
    if (top.remaining > 0) {
      --top.remaining;
      count_jump(label.begin);
      pos_ = top.label_offset;
      line_ = top.label_line - 1;
    } else {
      frames_.pop_back();
    }
    return;
  }
  if (label.number == 0)
    fail(Code::E3315, label.begin, "LBL 0 ends a subprogram: it cannot be called");
  const Place p = find_label(label, label.begin);
  if (frames_.size() >= limits_.max_call_depth)
    fail(Code::E3316, label.begin,
         "calls nested deeper than " + std::to_string(limits_.max_call_depth));
  // With REP n, a section before the call has run once already and runs n
  // more times, back to this block each time; any other call is a
  // subprogram's, run to its LBL 0 (and then REP n more times).
  const bool section = repeats > 0 && p.offset < block_.offset;
  Frame f;
  f.section = section;
  f.call_offset = block_.offset;
  f.return_offset = pos_;
  f.return_line = line_ + 1;
  f.label_offset = p.offset;
  f.label_line = p.line;
  f.remaining = section ? repeats - 1 : repeats;
  frames_.push_back(f);
  count_jump(label.begin);
  pos_ = p.offset;
  line_ = p.line - 1;
}

// ---- Called programs (CALL PGM, SEL PGM / CALL SELECTED)

void Interpreter::call_program(std::string_view path) {
  const std::uint32_t at = block_.keyword_begin;
  if (path.empty()) fail(Code::E3308, at, "CALL PGM needs the program's name or path");
  if (!loader_)
    fail(Code::E3331, at,
         "CALL PGM " + std::string(path) +
             ": the called program is read only where its folder is known (vcpost moves, "
             "report and post read it beside the calling program)");
  if (programs_.size() + frames_.size() >= limits_.max_call_depth)
    fail(Code::E3316, at,
         "calls nested deeper than " + std::to_string(limits_.max_call_depth) +
             " (a program that calls itself?)");
  const std::optional<CalledProgram> called = loader_(path, program_name_);
  if (!called)
    fail(Code::E3331, at,
         "CALL PGM " + std::string(path) +
             ": no such program beside the calling one (a path relative to it, or TNC:\\ "
             "taken from the main program's folder)");
  Caller c;
  c.text = text_;
  c.pos = pos_;
  c.line = line_;
  c.name = program_name_;
  c.labels = std::move(labels_);
  c.frames = std::move(frames_);
  c.inches = inches_;
  c.local.assign(q_.begin() + kQ, q_.begin() + kQ + kQL);
  c.call_source = programs_.empty() ? source() : programs_.front().call_source;
  programs_.push_back(std::move(c));
  count_jump(at);
  // QL parameters are the program's own; Q and QR and the control's state
  // (datum, tilt, tool, feed) go on.
  std::fill(q_.begin() + kQ, q_.begin() + kQ + kQL, 0.0);
  text_ = called->text;
  program_name_ = called->name;
  pos_ = 0;
  line_ = 0;
  labels_.reset();
  frames_.clear();
  begun_ = false;
}

void Interpreter::return_from_program() {
  Caller c = std::move(programs_.back());
  programs_.pop_back();
  text_ = c.text;
  pos_ = c.pos;
  line_ = c.line;
  program_name_ = std::move(c.name);
  labels_ = std::move(c.labels);
  frames_ = std::move(c.frames);
  inches_ = c.inches;
  std::copy(c.local.begin(), c.local.end(), q_.begin() + kQ);
  begun_ = true;
}

}  // namespace vcpost::heidenhain
