#include "postproc/heidenhain/interpreter.h"

#include <algorithm>
#include <cmath>

#include "postproc/heidenhain/interpreter_words.h"

namespace vcpost::heidenhain {

using program::Event;

Interpreter::Interpreter(std::string_view text, InterpreterLimits limits)
    : text_(text), limits_(limits), q_(kQ + kQL + kQR, 0.0) {}

std::optional<int> Interpreter::tool_number(std::string_view tool_name) const {
  for (const auto& [n, number] : tool_names_) {
    if (n == tool_name) return number;
  }
  return std::nullopt;
}

void Interpreter::fail(Code code, std::uint32_t at, std::string message) const {
  const auto [line, column] = block_.position(at);
  throw KlartextError(Diagnostic{code, line, column, std::move(message), program_name_});
}

void Interpreter::warn(Code code, std::uint32_t at, std::string message) {
  ++warning_count_;
  if (warnings_.size() >= limits_.max_warnings) return;
  const auto [line, column] = block_.position(at);
  warnings_.push_back(Diagnostic{code, line, column, std::move(message), program_name_});
}

void Interpreter::warn_once(Code code, long key, std::uint32_t at, std::string message) {
  const std::pair<Code, long> k{code, key};
  if (std::find(warned_once_.begin(), warned_once_.end(), k) != warned_once_.end()) return;
  warned_once_.push_back(k);
  warn(code, at, std::move(message) + " (warned once)");
}

program::SourceRef Interpreter::source() const {
  // A called program's events are its CALL PGM block's in the main program:
  // a writer of the main program places and patches only its own blocks.
  if (!programs_.empty()) return programs_.front().call_source;
  return program::SourceRef{block_.line, 1, block_.offset};
}

// ---- Reading blocks

bool Interpreter::read_block() {
  while (pos_ >= text_.size()) {
    if (programs_.empty()) return false;
    return_from_program();  // a called program without END PGM ends with its text
  }
  pos_ = split_block(text_, pos_, line_ + 1, block_);
  line_ += block_.lines;
  lines_read_ += block_.lines;
  parse_block(block_);
  return true;
}

bool Interpreter::next(std::vector<Event>& events) {
  if (ended_) return false;
  try {
    for (;;) {
      if (!read_block()) {
        ended_ = true;
        if (held_) {
          block_.clear();
          fail(Code::E3314, 0, "RND/CHF at the end of the program");
        }
        if (approach_) fail_approach("no contour element follows it before the program ends");
        if (!end_event_) {
          block_.line = line_;
          warn(Code::W3343, 0, "the program ends without END PGM, M2 or M30 (cut short?)");
        }
        return false;
      }
      if (++blocks_run_ > limits_.max_blocks)
        fail(Code::E3317, 0, "the program runs more blocks than the limit");
      const std::size_t before = events.size();
      execute(events);
      if (approach_ && block_.kind != BlockKind::approach) link_approach(events, before);
      if (ended_) return events.size() > before;
      return true;
    }
  } catch (const KlartextError& e) {
    ended_ = true;
    if (program_name_.empty() || !e.diagnostic().file.empty()) throw;
    Diagnostic d = e.diagnostic();  // a called program's: its name goes with it
    d.file = program_name_;
    throw KlartextError(std::move(d));
  } catch (...) {
    ended_ = true;
    throw;
  }
}

void Interpreter::execute(std::vector<Event>& events) {
  const BlockKind kind = block_.kind;
  if (kind == BlockKind::empty || kind == BlockKind::comment) return;
  if (!begun_) {
    if (kind != BlockKind::begin_pgm)
      fail(Code::E3305, block_.keyword_begin,
           "a Klartext program starts with BEGIN PGM <name> MM|INCH");
    return begin_program();
  }
  if (held_ && kind != BlockKind::rounding && kind != BlockKind::chamfer &&
      !(held_->corner_read && (kind == BlockKind::line || kind == BlockKind::line_polar))) {
    fail(Code::E3314, block_.keyword_begin,
         "RND and CHF stand between two straight lines (L or LP)");
  }
  switch (kind) {
    case BlockKind::begin_pgm:
      fail(Code::E3304, block_.keyword_begin, "a second BEGIN PGM");
    case BlockKind::end_pgm:
      if (!programs_.empty()) return return_from_program();
      ended_ = true;
      if (!end_event_) events.emplace_back(program::ProgramEnd{source()});
      end_event_ = true;
      return;
    case BlockKind::blk_form:
      return blk_form();
    case BlockKind::tool_call:
    case BlockKind::tool_def:
      return tool_call(events);
    case BlockKind::line:
    case BlockKind::line_normal:
    case BlockKind::line_polar:
    case BlockKind::centre:
    case BlockKind::circle:
    case BlockKind::circle_radius:
    case BlockKind::circle_tangent:
    case BlockKind::circle_polar:
    case BlockKind::rounding:
    case BlockKind::chamfer:
    case BlockKind::misc:
      return motion(events);
    case BlockKind::approach:
      return approach(events);
    case BlockKind::departure:
      return departure(events);
    case BlockKind::fn:
      return fn(events);
    case BlockKind::formula:
      return formula();
    case BlockKind::label:
      return label_block();
    case BlockKind::call_label:
      return call_label();
    case BlockKind::call_program:
      return call_program(block_.sub_keyword);
    case BlockKind::select_program:
      selected_ = std::string(block_.sub_keyword);
      return;
    case BlockKind::call_selected:
      if (!selected_)
        fail(Code::E3331, block_.keyword_begin, "CALL SELECTED without a SEL PGM before it");
      return call_program(*selected_);
    case BlockKind::cycle_def:
      return cycle_def(events);
    case BlockKind::cycle_call:
      return cycle_call(events);
    case BlockKind::plane:
      return plane_block(events);
    case BlockKind::function:
      return function_block();
    case BlockKind::other:
    case BlockKind::empty:
    case BlockKind::comment:
      break;
  }
  refuse_block();
}

// A block of no kind read: FK, the blocks of functions not read, or none.
void Interpreter::refuse_block() const {
  static constexpr std::string_view refused[] = {"SPL",      "SEL",     "CALL",    "DECLARE",
                                                 "QS",       "SQL",     "STRING",  "TCH",
                                                 "POLARKIN", "SYSREAD", "PATTERN", "CONTOUR"};
  const std::string_view key = block_.keyword;
  static constexpr std::string_view free_contour[] = {"FC",   "FCT",     "FL",  "FLT",
                                                      "FPOL", "FSELECT", "FCP", "FLP"};
  if (std::find(std::begin(free_contour), std::end(free_contour), key) != std::end(free_contour))
    fail(Code::E3330, block_.keyword_begin,
         std::string(key) +
             ": FK free contour programming is not read (the control solves the contour from "
             "its elements' relations); convert it to Klartext on the TNC (FK to Klartext "
             "conversion) or have the CAM system write L, C, CR and CT");
  if (std::find(std::begin(refused), std::end(refused), key) != std::end(refused)) {
    fail(Code::E3319, block_.keyword_begin,
         std::string(key) + " blocks are not read (" +
             (key == "CALL" || key == "SEL" ? "another program's moves are not in this file"
                                            : "write the path with L, C, CC, CR, CT and FN 0-4") +
             ")");
  }
  fail(Code::E3304, block_.keyword_begin, "'" + std::string(key) + "' starts no Klartext block");
}

// ---- Program structure

void Interpreter::begin_program() {
  const std::string_view units = block_.units;
  if (units == "MM") {
    inches_ = false;
  } else if (units == "INCH") {
    inches_ = true;
  } else {
    fail(Code::E3306, block_.keyword_begin,
         "BEGIN PGM needs its units: MM or INCH (found '" + std::string(units) + "')");
  }
  begun_ = true;
}

void Interpreter::blk_form() {
  if (!block_.sub_keyword.empty()) {
    warn_once(Code::W3344, 1, block_.keyword_begin,
              "BLK FORM " + std::string(block_.sub_keyword) + " is not read: no stock box");
    return;
  }
  // BLK FORM 0.1 names the tool axis first, without a value.
  if (!block_.words.empty() && !block_.words.front().has_value) {
    const Name axis = block_.words.front().key;
    if (axis != name("Z"))
      fail(Code::E3321, block_.words.front().begin, "BLK FORM for tool axis Z only");
    block_.words.erase(block_.words.begin());
  }
  const Words w = read_words(a_xyz);
  const double part = block_.cycle_number.value_or(0);
  if (std::abs(part - 0.1) < 1e-9) {
    StockBox box;
    for (std::size_t a = 0; a < 3; ++a)
      box.min[static_cast<Eigen::Index>(a)] = length(w.axis[a].value_or(0));
    box.max = box.min;
    box.source = source();
    stock_ = box;
  } else if (std::abs(part - 0.2) < 1e-9 && stock_) {
    for (std::size_t a = 0; a < 3; ++a) {
      const auto i = static_cast<Eigen::Index>(a);
      if (w.axis[a])
        stock_->max[i] = length(*w.axis[a]);
      else if (w.inc[a])
        stock_->max[i] = stock_->min[i] + length(*w.inc[a]);
    }
    highest_z_ = std::max(highest_z_, stock_->max.z());
  }
}

}  // namespace vcpost::heidenhain
