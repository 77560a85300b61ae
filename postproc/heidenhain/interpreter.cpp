#include "postproc/heidenhain/interpreter.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "core/units.h"
#include "postproc/heidenhain/approach.h"
#include "postproc/heidenhain/cycles.h"
#include "postproc/heidenhain/formula.h"
#include "postproc/heidenhain/plane_forms.h"
#include "postproc/program/working_frame.h"

namespace vcpost::heidenhain {

namespace {

using program::Event;

// An arc's end may miss its circle by this much (mm) plus a relative part:
// CAM systems round coordinates to 3 or 4 decimals.
constexpr double kArcTolerance = 0.005;
constexpr double kArcRelativeTolerance = 1e-4;

constexpr std::size_t kQ = 2000, kQL = 500, kQR = 500;

// Words a block kind takes (bits of Words::allowed).
enum Allow : std::uint32_t {
  a_xyz = 1u << 0,     // X Y Z IX IY IZ
  a_abc = 1u << 1,     // A B C IA IB IC
  a_polar = 1u << 2,   // PA IPA PR IPR
  a_dr = 1u << 3,      // DR+ DR-
  a_r = 1u << 4,       // R (radius, CR RND)
  a_comp = 1u << 5,    // R0 RL RR R+ R-
  a_feed = 1u << 6,    // F FMAX FAUTO FQ
  a_m = 1u << 7,       // M (and MB after M140)
  a_normal = 1u << 8,  // NX NY NZ TX TY TZ (LN)
  a_chf = 1u << 9,     // CHF's length
  a_link = 1u << 10,   // LEN CCA (APPR, DEP)
};

// The M functions the reader follows; every other one passes with a warning.
enum class MAction {
  stop,
  optional_stop,
  end,
  spindle_cw,
  spindle_ccw,
  spindle_off,
  mist,
  flood,
  coolant_off,
  cw_coolant,
  ccw_coolant,
  machine_frame,
  cycle_call,
  tcpm_on,
  tcpm_off,
  retract,
  quiet,
  refused,
  passed
};

MAction m_action(long m) {
  switch (m) {
    case 0:
      return MAction::stop;
    case 1:
      return MAction::optional_stop;
    case 2:
    case 30:
      return MAction::end;
    case 3:
      return MAction::spindle_cw;
    case 4:
      return MAction::spindle_ccw;
    case 5:
      return MAction::spindle_off;
    case 7:
      return MAction::mist;
    case 8:
      return MAction::flood;
    case 9:
      return MAction::coolant_off;
    case 13:
      return MAction::cw_coolant;
    case 14:
      return MAction::ccw_coolant;
    case 91:
    case 92:
      return MAction::machine_frame;
    case 99:
      return MAction::cycle_call;
    case 128:
      return MAction::tcpm_on;
    case 129:
      return MAction::tcpm_off;
    case 140:
      return MAction::retract;
    case 94:
    case 126:
    case 127:
      return MAction::quiet;  // rotary display and path: no move here
    case 89:                  // modal cycle call
    case 103:                 // plunging feed factor
    case 136:                 // feed per revolution
      return MAction::refused;
    default:
      return MAction::passed;
  }
}

Eigen::Vector2d xy(const Eigen::Vector3d& p) { return {p.x(), p.y()}; }
Eigen::Vector2d left_normal(const Eigen::Vector2d& d) { return {-d.y(), d.x()}; }
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Direction of an arc's tangent at `p` (unit, XY), rotation +1 ccw.
Eigen::Vector2d arc_tangent(const Eigen::Vector2d& centre, const Eigen::Vector2d& p, int rotation) {
  const Eigen::Vector2d radial = (p - centre).normalized();
  const Eigen::Vector2d t = left_normal(radial);
  return rotation > 0 ? t : Eigen::Vector2d(-t);
}

}  // namespace

// The words of a motion block, evaluated (program units; feeds as written).
struct Interpreter::Words {
  std::array<std::optional<double>, 3> axis, inc;     // X Y Z, IX IY IZ
  std::array<std::optional<double>, 3> rot, rot_inc;  // A B C, IA IB IC
  std::optional<double> pa, ipa, pr, ipr, r, chf, len, cca;
  std::array<std::optional<double>, 6> normal;  // NX NY NZ TX TY TZ
  int dr = 0;
  std::optional<program::CompensationSide> comp;
  bool fmax = false;
  std::optional<double> feed;  // program units
  bool fauto = false;
  bool mb_max = false;
  std::optional<double> mb;
  struct M {
    long number;
    MAction action;
    std::uint32_t at;
  };
  std::vector<M> m;
  std::uint32_t first_word = 0;
  bool has(MAction a) const {
    return std::any_of(m.begin(), m.end(), [a](const M& x) { return x.action == a; });
  }
  bool any_xyz() const {
    return std::any_of(axis.begin(), axis.end(), [](auto& v) { return v.has_value(); }) ||
           std::any_of(inc.begin(), inc.end(), [](auto& v) { return v.has_value(); });
  }
};

// An APPR or DEP block's words and the path's form.
struct Interpreter::LinkWords {
  Words words;
  LinkInput in;
  bool polar = false;
};

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
          fail(Code::corner_not_between_lines, 0, "RND/CHF at the end of the program");
        }
        if (approach_) fail_approach("no contour element follows it before the program ends");
        if (!end_event_) {
          block_.line = line_;
          warn(Code::missing_end, 0, "the program ends without END PGM, M2 or M30 (cut short?)");
        }
        return false;
      }
      if (++blocks_run_ > limits_.max_blocks)
        fail(Code::loop_limit, 0, "the program runs more blocks than the limit");
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
      fail(Code::missing_begin, block_.keyword_begin,
           "a Klartext program starts with BEGIN PGM <name> MM|INCH");
    return begin_program();
  }
  if (held_ && kind != BlockKind::rounding && kind != BlockKind::chamfer &&
      !(held_->corner_read && (kind == BlockKind::line || kind == BlockKind::line_polar))) {
    fail(Code::corner_not_between_lines, block_.keyword_begin,
         "RND and CHF stand between two straight lines (L or LP)");
  }
  switch (kind) {
    case BlockKind::begin_pgm:
      fail(Code::unknown_block, block_.keyword_begin, "a second BEGIN PGM");
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
        fail(Code::program_not_found, block_.keyword_begin,
             "CALL SELECTED without a SEL PGM before it");
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
  static constexpr std::string_view refused[] = {"SPL",      "SEL",     "CALL",    "DECLARE",
                                                 "QS",       "SQL",     "STRING",  "TCH",
                                                 "POLARKIN", "SYSREAD", "PATTERN", "CONTOUR"};
  const std::string_view key = block_.keyword;
  static constexpr std::string_view free_contour[] = {"FC",   "FCT",     "FL",  "FLT",
                                                      "FPOL", "FSELECT", "FCP", "FLP"};
  if (std::find(std::begin(free_contour), std::end(free_contour), key) != std::end(free_contour))
    fail(Code::fk_contour, block_.keyword_begin,
         std::string(key) +
             ": FK free contour programming is not read (the control solves the contour from "
             "its elements' relations); convert it to Klartext on the TNC (FK to Klartext "
             "conversion) or have the CAM system write L, C, CR and CT");
  if (std::find(std::begin(refused), std::end(refused), key) != std::end(refused)) {
    fail(Code::unsupported_function, block_.keyword_begin,
         std::string(key) + " blocks are not read (" +
             (key == "CALL" || key == "SEL" ? "another program's moves are not in this file"
                                            : "write the path with L, C, CC, CR, CT and FN 0-4") +
             ")");
  }
  fail(Code::unknown_block, block_.keyword_begin,
       "'" + std::string(key) + "' starts no Klartext block");
}

// ---- Values and words

std::size_t Interpreter::parameter_index(const Value& v, std::uint32_t at) const {
  const auto n = static_cast<std::size_t>(v.number);
  std::size_t index = n;
  switch (v.bank) {
    case Value::Bank::q:
      if (n >= kQ) fail(Code::bad_parameter, at, "Q parameters run from Q0 to Q1999");
      break;
    case Value::Bank::ql:
      if (n >= kQL) fail(Code::bad_parameter, at, "QL parameters run from QL0 to QL499");
      index = kQ + n;
      break;
    case Value::Bank::qr:
      if (n >= kQR) fail(Code::bad_parameter, at, "QR parameters run from QR0 to QR499");
      index = kQ + kQL + n;
      break;
    case Value::Bank::literal:
      fail(Code::bad_parameter, at, "a Q parameter is expected here");
  }
  return index;
}

double Interpreter::value(const Value& v, std::uint32_t at) const {
  if (!v.is_parameter()) return v.number;
  const double q = q_[parameter_index(v, at)];
  return v.negate ? -q : q;
}

Interpreter::Words Interpreter::read_words(std::uint32_t allowed) const {
  Words w;
  bool radius_taken = false;
  for (const Word& word : block_.words) {
    if (w.first_word == 0) w.first_word = word.begin;
    const auto need_value = [&] {
      if (!word.has_value)
        fail(Code::bad_number, word.begin,
             "'" + std::string(block_.text.substr(word.begin, word.end - word.begin)) +
                 "' needs a value");
      return value(word.value, word.begin);
    };
    auto bad = [&]() {
      fail(Code::unexpected_word, word.begin,
           "'" + std::string(block_.text.substr(word.begin, word.end - word.begin)) +
               "' is no word of " + std::string(block_.keyword) + " blocks");
    };
    switch (word.key) {
      case name("X"):
      case name("Y"):
      case name("Z"):
      case name("IX"):
      case name("IY"):
      case name("IZ"): {
        if (!(allowed & a_xyz)) bad();
        const bool inc = (word.key >> 8) == 'I';
        const int axis = static_cast<int>(word.key & 0xff) - 'X';
        (inc ? w.inc : w.axis)[static_cast<std::size_t>(axis)] = need_value();
        break;
      }
      case name("A"):
      case name("B"):
      case name("C"):
      case name("IA"):
      case name("IB"):
      case name("IC"): {
        if (!(allowed & a_abc)) bad();
        const bool inc = (word.key >> 8) == 'I';
        const int axis = static_cast<int>(word.key & 0xff) - 'A';
        (inc ? w.rot_inc : w.rot)[static_cast<std::size_t>(axis)] = need_value();
        break;
      }
      case name("PA"):
        if (!(allowed & a_polar)) bad();
        w.pa = need_value();
        break;
      case name("IPA"):
        if (!(allowed & a_polar)) bad();
        w.ipa = need_value();
        break;
      case name("PR"):
        if (!(allowed & a_polar)) bad();
        w.pr = need_value();
        break;
      case name("IPR"):
        if (!(allowed & a_polar)) bad();
        w.ipr = need_value();
        break;
      case name("LEN"):
        if (!(allowed & a_link)) bad();
        w.len = need_value();
        break;
      case name("CCA"):
        if (!(allowed & a_link)) bad();
        w.cca = need_value();
        break;
      case name("CHF"):
        if (!(allowed & a_chf)) bad();
        w.chf = need_value();
        break;
      case name("DR"):
        if (!(allowed & a_dr) || word.has_value || word.sign == 0) bad();
        w.dr = word.sign == '+' ? 1 : -1;
        break;
      case name("R"):
        if ((allowed & a_r) && !radius_taken && word.has_value) {
          w.r = need_value();
          radius_taken = true;
        } else if ((allowed & a_comp) && word.has_value && !word.value.is_parameter() &&
                   word.value.number == 0) {
          w.comp = program::CompensationSide::off;
        } else if ((allowed & a_comp) && !word.has_value && word.sign != 0) {
          // R+ / R-: paraxial lengthening; no side of the contour.
        } else {
          bad();
        }
        break;
      case name("RL"):
        if (!(allowed & a_comp)) bad();
        w.comp = program::CompensationSide::left;
        break;
      case name("RR"):
        if (!(allowed & a_comp)) bad();
        w.comp = program::CompensationSide::right;
        break;
      case name("F"):
        if (!(allowed & a_feed)) bad();
        w.feed = need_value();
        break;
      case name("FMAX"):
        if (!(allowed & a_feed)) bad();
        w.fmax = true;
        break;
      case name("FAUTO"):
        if (!(allowed & a_feed)) bad();
        w.fauto = true;
        break;
      case name("FU"):
      case name("FZ"):
        fail(Code::unsupported_function, word.begin,
             "feed per revolution or per tooth (FU, FZ) is not read: write F in mm/min");
      case name("M"): {
        if (!(allowed & a_m)) bad();
        const double m = need_value();
        if (m < 0 || m != std::floor(m) || m > 999)
          fail(Code::bad_number, word.begin, "M takes a whole number 0-999");
        const auto number = static_cast<long>(m);
        w.m.push_back({number, m_action(number), word.begin});
        break;
      }
      case name("MB"):
        if (!(allowed & a_m)) bad();
        if (word.sign == '*')
          w.mb_max = true;
        else
          w.mb = need_value();
        break;
      case name("NX"):
      case name("NY"):
      case name("NZ"):
      case name("TX"):
      case name("TY"):
      case name("TZ"): {
        if (!(allowed & a_normal)) bad();
        const bool tool = (word.key >> 8) == 'T';
        const auto axis = static_cast<std::size_t>((word.key & 0xff) - 'X');
        w.normal[(tool ? 3 : 0) + axis] = need_value();
        break;
      }
      default:
        bad();
    }
  }
  return w;
}

// ---- Program structure

void Interpreter::begin_program() {
  const std::string_view units = block_.units;
  if (units == "MM") {
    inches_ = false;
  } else if (units == "INCH") {
    inches_ = true;
  } else {
    fail(Code::bad_units, block_.keyword_begin,
         "BEGIN PGM needs its units: MM or INCH (found '" + std::string(units) + "')");
  }
  begun_ = true;
}

void Interpreter::blk_form() {
  if (!block_.sub_keyword.empty()) {
    warn_once(Code::function_passed, 1, block_.keyword_begin,
              "BLK FORM " + std::string(block_.sub_keyword) + " is not read: no stock box");
    return;
  }
  // BLK FORM 0.1 names the tool axis first, without a value.
  if (!block_.words.empty() && !block_.words.front().has_value) {
    const Name axis = block_.words.front().key;
    if (axis != name("Z"))
      fail(Code::tool_axis_change, block_.words.front().begin, "BLK FORM for tool axis Z only");
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

void Interpreter::tool_call(std::vector<Event>& events) {
  const bool call = block_.kind == BlockKind::tool_call;
  if (call && called_tool_calls_refused_ && !programs_.empty())
    fail(Code::called_tool_call, block_.keyword_begin,
         "TOOL CALL in the called program " + program_name_ +
             ": vcpost post writes the calling program's blocks only and cannot change a speed "
             "in another file; post the called program on its own");
  std::optional<int> number;
  if (const Word* t = block_.find(name("T"))) {
    const double n = value(t->value, t->begin);
    if (n < 0 || n != std::floor(n) || n > 32767)
      fail(Code::bad_number, t->begin, "a tool number is a whole number 0-32767");
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
        if (w.has_value)
          fail(Code::unexpected_word, w.begin, "a TOOL CALL takes its axis without a value");
        fail(Code::tool_axis_change, w.begin,
             "tool axis " + std::string(1, static_cast<char>(w.key)) +
                 ": only tool axis Z is read (a horizontal spindle turns the frame)");
      case name("Z"):
        if (w.has_value)
          fail(Code::unexpected_word, w.begin, "a TOOL CALL takes its axis without a value");
        break;
      case name("S"):
        if (!w.has_value)
          fail(Code::bad_number, w.begin, "S needs the spindle speed (S(VC=..) is not read)");
        speed = value(w.value, w.begin);
        if (*speed < 0) fail(Code::bad_number, w.begin, "a spindle speed is not negative");
        break;
      case name("F"):
        if (!w.has_value) fail(Code::bad_number, w.begin, "F needs a value");
        tool_feed_ = feed_rate(value(w.value, w.begin));
        break;
      case name("DL"):
      case name("DR"):
      case name("DR2"):
      case name("DL2"):
        break;
      case name("R"):
        if (call) fail(Code::unexpected_word, w.begin, "TOOL CALL takes DL and DR, not L and R");
        if (number && w.has_value)
          defined_radii_.emplace_back(*number, length(value(w.value, w.begin)));
        break;
      case name("L"):
      case name("R2"):
        if (call) fail(Code::unexpected_word, w.begin, "TOOL CALL takes DL and DR, not L and R");
        break;  // TOOL DEF's length and radius  // oversizes: the path is the programmed one (see
                // the header)
      default:
        fail(Code::unexpected_word, w.begin,
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

// ---- Motion blocks

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
        fail(Code::tool_axis_change, w.first_word, "LN with a tool orientation TX/TY off Z");
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
        fail(Code::unsupported_function, m.at,
             "M" + std::to_string(m.number) +
                 (m.number == 89    ? " (modal cycle call) is not read: call each hole with M99"
                  : m.number == 103 ? " (plunging feed factor) is not read"
                                    : " (feed per revolution) is not read"));
      case MAction::passed:
        warn_once(
            Code::m_code_passed, m.number, m.at,
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
        fail(Code::unsupported_function, m.at,
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
    if (*rate < 0) fail(Code::bad_number, w.first_word, "a feed rate is not negative");
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
      fail(Code::tool_axis_change, w.first_word,
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
  if (!pole_) fail(Code::no_pole, block_.keyword_begin, "polar coordinates need a pole: CC first");
  const Eigen::Vector2d rel = xy(position_) - *pole_;
  double radius = rel.norm();
  double angle = std::atan2(rel.y(), rel.x()) / kDeg;
  if (w.pa) angle = *w.pa;
  if (w.ipa) angle += *w.ipa;
  if (line) {
    if (w.pr) radius = length(*w.pr);
    if (w.ipr) radius += length(*w.ipr);
    if (radius < 0) fail(Code::bad_number, w.first_word, "a polar radius is not negative");
  }
  Eigen::Vector3d end = position_;
  end.x() = pole_->x() + radius * std::cos(angle * kDeg);
  end.y() = pole_->y() + radius * std::sin(angle * kDeg);
  if (w.axis[2]) end.z() = length(*w.axis[2]) + shift_.z();
  if (w.inc[2]) end.z() += length(*w.inc[2]);
  if (w.axis[0] || w.axis[1] || w.inc[0] || w.inc[1])
    fail(Code::unexpected_word, w.first_word, "polar blocks take PA/PR, not X/Y");
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
  if (feed_ <= 0)
    fail(Code::missing_feed, block_.keyword_begin, "a feed move before any feed rate F");
  emit_move(program::StraightFeed{position_, end, src}, events);
}

void Interpreter::machine_retract(const Words& w, std::vector<Event>& events) {
  set_feed_and_compensation(w, events);
  const bool m140 = w.has(MAction::retract);
  if (m140 && !w.mb_max) {
    // M140 MB <distance>: back along the tool axis by that much.
    if (!w.mb) fail(Code::missing_word, w.first_word, "M140 needs MB <distance> or MB MAX");
    const Eigen::Vector3d end = position_ + Eigen::Vector3d(0, 0, length(*w.mb));
    emit_move(program::StraightTraverse{position_, end, source()}, events);
    return;
  }
  // The machine datum is unknown: the move stands for a retract (see the header).
  const bool z_given = w.axis[2].has_value() || w.inc[2].has_value() || m140;
  warn_once(Code::machine_coordinates, 0, w.m.empty() ? 0 : w.m.front().at,
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
    fail(Code::corner_not_between_lines, block_.keyword_begin,
         "RND and CHF stand between two straight lines (L or LP)");
  const bool rounding = block_.kind == BlockKind::rounding;
  const std::optional<double> size = rounding ? w.r : w.chf;
  if (!size)
    fail(Code::missing_word, block_.keyword_begin,
         rounding ? "RND needs R<radius>" : "CHF needs its length");
  if (*size <= 0) fail(Code::bad_number, w.first_word, "a corner's size is positive");
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
    fail(Code::corner_not_between_lines, at,
         "RND/CHF between lines in the working plane (Z constant) only");
  const Eigen::Vector2d a = xy(p1 - p0), b = xy(p2 - p1);
  if (a.norm() < 1e-9 || b.norm() < 1e-9)
    fail(Code::corner_not_between_lines, at, "RND/CHF next to a line of no length");
  const Eigen::Vector2d u1 = a.normalized(), u2 = b.normalized();
  const double turn = std::atan2(cross(u1, u2), u1.dot(u2));  // signed turn angle
  const double cut = held.rounding ? held.corner * std::tan(std::abs(turn) / 2) : held.corner;
  if (cut > a.norm() + 1e-9 || cut > b.norm() + 1e-9)
    fail(Code::corner_not_between_lines, at, "the RND/CHF corner is larger than its lines");
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
  if (w.axis[2] || w.inc[2])
    fail(Code::unexpected_word, w.first_word, "CC takes X and Y (tool axis Z)");
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
  if (feed_ <= 0) fail(Code::missing_feed, block_.keyword_begin, "an arc before any feed rate F");
  const double r0 = (xy(position_) - centre).norm();
  const double r1 = (xy(end) - centre).norm();
  if (std::abs(r0 - r1) > kArcTolerance + kArcRelativeTolerance * std::max(r0, r1)) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "the arc's end is %.4f mm from its centre, its start %.4f mm (the end is not on "
                  "the circle)",
                  r1, r0);
    fail(Code::arc_radius_mismatch, block_.keyword_begin, text);
  }
  if (r0 < 1e-9) fail(Code::arc_radius_mismatch, block_.keyword_begin, "an arc of radius 0");
  events.emplace_back(program::ArcFeed{position_, end,
                                       Eigen::Vector3d(centre.x(), centre.y(), position_.z()),
                                       program::Plane::xy, rotation, source()});
  tangent_ = arc_tangent(centre, xy(end), rotation);
  position_ = end;
  highest_z_ = std::max(highest_z_, end.z());
}

void Interpreter::circle(const Words& w, std::vector<Event>& events) {
  if (!pole_) fail(Code::no_pole, block_.keyword_begin, "C needs a circle centre: CC first");
  if (w.dr != 0) arc_direction_ = w.dr;
  if (arc_direction_ == 0)
    fail(Code::missing_word, block_.keyword_begin, "C needs its direction DR+ or DR-");
  arc(w, cartesian_target(w), *pole_, arc_direction_, events);
}

void Interpreter::circle_radius(const Words& w, std::vector<Event>& events) {
  if (!w.r) fail(Code::missing_word, block_.keyword_begin, "CR needs its radius R");
  if (w.dr != 0) arc_direction_ = w.dr;
  if (arc_direction_ == 0)
    fail(Code::missing_word, block_.keyword_begin, "CR needs its direction DR+ or DR-");
  const Eigen::Vector3d end = cartesian_target(w);
  const double r = length(*w.r);
  const Eigen::Vector2d chord = xy(end - position_);
  const double c = chord.norm();
  if (c < 1e-9)
    fail(Code::arc_radius_too_small, block_.keyword_begin,
         "CR to its own start: a full circle needs C");
  const double half = c / 2;
  if (std::abs(r) < half - kArcTolerance) {
    char text[128];
    std::snprintf(text, sizeof text, "radius %.4f mm is below half the chord (%.4f mm)",
                  std::abs(r), half);
    fail(Code::arc_radius_too_small, block_.keyword_begin, text);
  }
  const double h = std::sqrt(std::max(0.0, r * r - half * half));
  // DR+ with R+ (at most half a circle): the centre is left of the chord.
  const double side = static_cast<double>(arc_direction_) * (r > 0 ? 1.0 : -1.0);
  const Eigen::Vector2d centre = xy(position_) + chord / 2 + side * h * left_normal(chord / c);
  arc(w, end, centre, arc_direction_, events);
}

void Interpreter::circle_tangent(const Words& w, std::vector<Event>& events) {
  if (!tangent_)
    fail(Code::tangent_undefined, block_.keyword_begin,
         "CT continues a contour: a move must come first");
  const Eigen::Vector3d end = cartesian_target(w);
  const Eigen::Vector2d d = xy(end - position_);
  const Eigen::Vector2d n = left_normal(*tangent_);
  const double dn = d.dot(n);
  if (std::abs(dn) < 1e-9)
    fail(Code::tangent_undefined, block_.keyword_begin,
         "CT's end lies on the tangent: no arc (write L)");
  const double k = d.squaredNorm() / (2 * dn);
  const Eigen::Vector2d centre = xy(position_) + k * n;
  arc(w, end, centre, k > 0 ? 1 : -1, events);
}

void Interpreter::circle_polar(const Words& w, std::vector<Event>& events) {
  if (!pole_) fail(Code::no_pole, block_.keyword_begin, "CP needs a pole: CC first");
  if (w.dr != 0) arc_direction_ = w.dr;
  if (arc_direction_ == 0)
    fail(Code::missing_word, block_.keyword_begin, "CP needs its direction DR+ or DR-");
  if (!w.pa && !w.ipa) fail(Code::missing_word, block_.keyword_begin, "CP needs PA or IPA");
  const Eigen::Vector3d end = polar_target(w, false);
  int rotation = arc_direction_;
  if (w.ipa) {
    // An incremental angle may run past a turn (a helix): the turns started.
    const double turns = std::abs(*w.ipa) / 360.0;
    rotation *= std::max(1, static_cast<int>(std::ceil(turns - 1e-9)));
    if ((*w.ipa > 0) != (arc_direction_ > 0))
      fail(Code::unexpected_word, w.first_word, "IPA's sign and DR disagree");
  }
  set_feed_and_compensation(w, events);
  if (feed_ <= 0) fail(Code::missing_feed, block_.keyword_begin, "an arc before any feed rate F");
  events.emplace_back(program::ArcFeed{position_, end,
                                       Eigen::Vector3d(pole_->x(), pole_->y(), position_.z()),
                                       program::Plane::xy, rotation, source()});
  tangent_ = arc_tangent(*pole_, xy(end), rotation);
  position_ = end;
  highest_z_ = std::max(highest_z_, end.z());
}

// ---- Contour approach and departure (APPR, DEP)

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
    fail(Code::unexpected_word, block_.keyword_begin,
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
    if (*w.r != 0) fail(Code::unexpected_word, w.first_word, "R is no word of an LT or LN path");
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
    fail(Code::missing_feed, block_.keyword_begin, "APPR before any feed rate F");
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
  throw KlartextError(Diagnostic{Code::approach_undefined, a.line, a.column, "APPR " + why, {}});
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
            Diagnostic{Code::missing_feed,
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
    fail(Code::approach_undefined, block_.keyword_begin,
         "DEP leaves a contour: a contour element must come right before it");
  lw.in.side = side_of(compensation_);
  w.comp.reset();
  set_feed_and_compensation(w, events);
  if (feed_ <= 0 && !w.fmax)
    fail(Code::missing_feed, block_.keyword_begin, "DEP before any feed rate F");
  const Eigen::Vector3d target = lw.polar ? polar_target(w, true) : cartesian_target(w);
  const bool given_xy = w.axis[0] || w.axis[1] || w.inc[0] || w.inc[1] || w.pa || w.ipa;
  const bool lct = lw.in.link == ContourLink::line_circle;
  if (!lct && given_xy)
    fail(Code::unexpected_word, w.first_word, "DEP LT, LN and CT take no end point but Z");
  if (lct && !given_xy)
    fail(Code::missing_word, block_.keyword_begin, "DEP LCT needs its end point X Y");
  std::string why;
  const auto path = departure_path(lw.in, xy(position_), *tangent_, xy(target), why);
  if (!path) fail(Code::approach_undefined, block_.keyword_begin, "DEP " + why);
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

// ---- Parameters and flow

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
            Code::function_passed, f.number, at,
            "FN " + std::to_string(f.number) + " passed (print or PLC output: moves nothing)");
        return;
      case 14:
        fail(Code::unsupported_function, at,
             "FN 14 raises an error on the control (" + std::string(block_.sub_keyword) +
                 "): the program stops there");
      default:
        fail(Code::unsupported_function, at,
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
      if (b == 0) fail(Code::math_domain, f.b_begin, "FN 4: division by zero");
      result = a / b;
      break;
    case 5:
      if (a < 0) fail(Code::math_domain, f.a_begin, "FN 5: square root of a negative number");
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
  if (!(std::abs(result) <= 1e12)) fail(Code::math_domain, at, "FN result out of range");
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
    fail(Code::unknown_label, at,
         "no LBL " +
             (label.number >= 0 ? std::to_string(label.number)
                                : "\"" + std::string(label.name) + "\"") +
             " in this program");
  }
  return it->second;
}

void Interpreter::count_jump(std::uint32_t at) {
  if (++jumps_ > limits_.max_loop_iterations)
    fail(Code::loop_limit, at,
         "repeats and jumps run past the limit of " + std::to_string(limits_.max_loop_iterations) +
             " (an endless loop?)");
}

void Interpreter::jump_to(const Label& label, std::uint32_t at) {
  if (label.number == 0)
    fail(Code::unknown_label, at, "LBL 0 ends a subprogram: it cannot be jumped to");
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
      fail(Code::bad_number, rep->begin, "REP takes a count 0-65534");
    repeats = static_cast<long>(n);
  }
  for (const Word& w : block_.words) {
    if (w.key != name("REP")) fail(Code::unexpected_word, w.begin, "CALL LBL takes REP only");
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
    fail(Code::unknown_label, label.begin, "LBL 0 ends a subprogram: it cannot be called");
  const Place p = find_label(label, label.begin);
  if (frames_.size() >= limits_.max_call_depth)
    fail(Code::call_depth, label.begin,
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
  if (path.empty()) fail(Code::missing_word, at, "CALL PGM needs the program's name or path");
  if (!loader_)
    fail(Code::program_not_found, at,
         "CALL PGM " + std::string(path) +
             ": the called program is read only where its folder is known (vcpost moves, "
             "report and post read it beside the calling program)");
  if (programs_.size() + frames_.size() >= limits_.max_call_depth)
    fail(Code::call_depth, at,
         "calls nested deeper than " + std::to_string(limits_.max_call_depth) +
             " (a program that calls itself?)");
  const std::optional<CalledProgram> called = loader_(path, program_name_);
  if (!called)
    fail(Code::program_not_found, at,
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

// ---- Cycles

void Interpreter::cycle_def(std::vector<Event>& events) {
  const double number = *block_.cycle_number;
  const int major = static_cast<int>(number);
  const int minor = static_cast<int>(std::lround((number - major) * 10));
  const std::uint32_t at = block_.keyword_begin;
  switch (major) {
    case 7: {  // datum shift
      if (minor == 0) return;
      const Words w = read_words(a_xyz);
      for (std::size_t a = 0; a < 3; ++a) {
        const auto i = static_cast<Eigen::Index>(a);
        if (w.axis[a]) shift_[i] = length(*w.axis[a]);
        if (w.inc[a]) shift_[i] += length(*w.inc[a]);
      }
      return;
    }
    case 9: {  // dwell: the block's last number ("9.1 V.ZEIT1.5", hyperMILL's "V.IDO5")
      if (minor != 1) return;
      const std::string_view t = block_.sub_keyword;
      std::size_t e = t.size();
      while (e > 0 && !(t[e - 1] >= '0' && t[e - 1] <= '9')) --e;
      std::size_t b = e;
      while (b > 0 && ((t[b - 1] >= '0' && t[b - 1] <= '9') || t[b - 1] == '.')) --b;
      if (b == e) fail(Code::missing_word, at, "CYCL DEF 9.1 needs the dwell time in seconds");
      events.emplace_back(program::Dwell{std::stod(std::string(t.substr(b, e - b))), source()});
      return;
    }
    case 19: {  // working plane (the older form of PLANE)
      if (minor == 0) return;
      const Words w = read_words(a_abc);
      WorkingPlane p;
      p.kind = "CYCL DEF 19";
      p.source = source();
      static constexpr const char* letters[] = {"A", "B", "C"};
      for (std::size_t a = 0; a < 3; ++a) {
        if (!w.rot[a]) continue;
        p.values.emplace_back(letters[a], *w.rot[a]);
        if (std::abs(std::remainder(*w.rot[a], 360.0)) > 1e-9) p.identity = false;
      }
      plane_ = p;
      // Taken as spatial angles (the TNC's default for cycle 19; a machine
      // set up for axis angles reads them as its rotary axes' positions).
      tilt(p.identity ? Eigen::Matrix3d::Identity()
                      : program::spatial_angles(w.rot[0].value_or(0), w.rot[1].value_or(0),
                                                w.rot[2].value_or(0)),
           events);
      q_[120] = q_[121] = q_[122] = 0;
      return;
    }
    case 32:  // tolerance, HSC mode: how the control smooths, not where it goes
      return;
    case 8:
    case 10:
    case 11:
    case 26:
      if (minor == 0) return;
      fail(Code::unsupported_cycle, at,
           "CYCL DEF " + std::to_string(major) +
               " (mirror, rotation or scaling) changes the frame: it is not read");
    default:
      break;
  }
  if (major >= 300) {
    warn_once(Code::machine_cycle, major, at,
              "CYCL DEF " + std::to_string(major) +
                  " passed: a machine or probing cycle, taken as moving nothing");
    return;
  }
  for (const CycleParameter& p : block_.cycle_parameters)
    q_[parameter_index(Value{static_cast<double>(p.number), Value::Bank::q, false}, p.begin)] =
        value(p.value, p.begin);
  cycle_ = major;
}

void Interpreter::cycle_call(std::vector<Event>& events) {
  const Words w = read_words(a_xyz | a_feed | a_m);
  start_functions(w, events);
  if (block_.sub_keyword == "POS") {
    // Position over the hole first, then call the cycle there.
    const Eigen::Vector3d end = cartesian_target(w);
    const Eigen::Vector3d over(end.x(), end.y(), position_.z());
    events.emplace_back(program::StraightTraverse{position_, over, source()});
    events.emplace_back(program::StraightTraverse{over, end, source()});
    position_ = end;
    highest_z_ = std::max(highest_z_, end.z());
  } else if (w.any_xyz()) {
    fail(Code::unexpected_word, w.first_word, "CYCL CALL takes a position only as CYCL CALL POS");
  }
  run_cycle(block_.keyword_begin, events);
  end_functions(w, events);
}

void Interpreter::run_cycle(std::uint32_t at, std::vector<Event>& events) {
  if (cycle_ == 0) fail(Code::cycle_not_defined, at, "a cycle call without a CYCL DEF before it");
  if (cycle_ != 200 && cycle_ != 201 && cycle_ != 203 && cycle_ != 205 && cycle_ != 207 &&
      cycle_ != 208)
    fail(Code::unsupported_cycle, at,
         "cycle " + std::to_string(cycle_) +
             " makes moves vcpost does not model (drilling cycles "
             "200, 201, 203, 205, 207 and 208 are read)");
  auto q = [&](int n) { return q_[static_cast<std::size_t>(n)]; };
  DrillHole h;
  h.cycle = cycle_;
  h.start = position_;
  h.surface = length(q(203)) + shift_.z();
  h.clearance = length(q(200));
  h.second_clearance = length(q(204));
  h.depth = length(q(201));
  h.dwell_top = q(210);
  h.dwell_bottom = q(211);
  h.retract_feed = feed_rate(q(208));
  h.spindle_ccw = spindle_ccw_;
  h.restore_feed = feed_;
  h.source = source();
  if (h.depth > 0)
    fail(Code::cycle_value, at, "Q201, the depth, is negative (below the surface Q203)");
  if (h.depth == 0) return;  // the control runs no hole of depth 0
  if (cycle_ == 207) {
    const double pitch = length(q(239));
    if (pitch == 0 || spindle_rpm_ <= 0)
      fail(Code::cycle_value, at, "cycle 207 needs the pitch Q239 and a spindle speed");
    h.feed = std::abs(pitch) * spindle_rpm_;
    h.spindle_ccw = pitch < 0 ? !spindle_ccw_ : spindle_ccw_;
  } else {
    h.feed = feed_rate(q(206));
    if (h.feed <= 0) fail(Code::cycle_value, at, "Q206, the plunging feed, must be positive");
  }
  if (cycle_ == 200 || cycle_ == 203 || cycle_ == 205) {
    h.plunge = length(q(202));
    if (h.plunge <= 0) fail(Code::cycle_value, at, "Q202, the plunging depth, must be positive");
    if (cycle_ != 200) {
      h.decrement = length(q(212));
      h.min_plunge = length(q(205));
    }
    if (cycle_ == 203) {
      h.chip_breaks = static_cast<int>(std::max(0.0, q(213)));
      h.chip_retract = length(q(256));
    }
    const double pecks = std::abs(h.depth) / std::max(h.min_plunge, std::max(h.plunge - 0.0, 1e-3));
    if (pecks * 3 > static_cast<double>(limits_.max_cycle_moves))
      fail(Code::cycle_value, at, "the hole's pecks (Q201 / Q202) make more moves than the limit");
  }
  if (cycle_ == 208) bore_milling(h, at);
  position_ = expand_hole(h, events);
  highest_z_ = std::max(highest_z_, position_.z());
  tangent_.reset();
}

// Cycle 208's helix: its radius from Q335 and the tool's radius (the
// control's tool table; the caller gives it), its direction from Q351
// (+1 climb, -1 up-cut) and the spindle's (climb inside a hole with M3 runs
// counterclockwise).
void Interpreter::bore_milling(DrillHole& h, std::uint32_t at) {
  const double nominal = length(q_[335]);
  const double pitch = length(q_[334]);
  if (pitch <= 0) fail(Code::cycle_value, at, "Q334, the depth per helix turn, must be positive");
  if (!tool_radius_) {
    warn_once(Code::helix_unknown, 208, at,
              "cycle 208 taken along the hole's axis: its helix needs the tool's radius, which is "
              "in the control's tool table (give the tool with --tool or a CAM comment)");
    return;
  }
  const double radius = nominal / 2 - *tool_radius_;
  if (radius < -1e-9)
    fail(Code::cycle_value, at, "cycle 208: the tool is wider than the nominal diameter Q335");
  if (radius <= 1e-9) return;  // as wide as the hole: straight down, as the control bores it
  if (std::abs(h.depth) / pitch + 4 > static_cast<double>(limits_.max_cycle_moves))
    fail(Code::cycle_value, at, "the helix's turns (Q201 / Q334) make more moves than the limit");
  h.helix_radius = radius;
  h.pitch = pitch;
  h.helix_rotation = (q_[351] < 0 ? -1 : 1) * (spindle_ccw_ ? -1 : 1);
}

// ---- Working plane and functions

void Interpreter::plane_block(std::vector<program::Event>& events) {
  WorkingPlane p;
  p.kind = std::string(block_.sub_keyword);
  p.source = source();
  for (const Word& w : block_.words) {
    if (!w.has_value) continue;  // STAY, TURN, MOVE, SEQ+, TABLE ROT
    const std::string key(block_.text.substr(w.begin, w.end - w.begin));
    std::size_t letters = 0;
    while (letters < key.size() && key[letters] >= 'A' && key[letters] <= 'Z') ++letters;
    p.values.emplace_back(key.substr(0, letters), value(w.value, w.begin));
  }
  auto get = [&](std::string_view k, double fallback) {
    for (const auto& [n, v] : p.values)
      if (n == k) return v;
    return fallback;
  };
  // STAY, MOVE and TURN say how the rotary axes get there; the frame is the
  // same (MOVE and TURN: the tool's tip is taken to stay where it is on the
  // part, which MOVE keeps and TURN's first positioning block sets anyway).
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  const bool axial_zero =
      p.kind == "AXIAL" && std::all_of(p.values.begin(), p.values.end(), [](const auto& v) {
        return std::abs(std::remainder(v.second, 360.0)) < 1e-9;
      });
  if (p.kind == "RESET" || axial_zero) {
    p.identity = true;
  } else if (p.kind == "SPATIAL") {
    rotation = program::spatial_angles(get("SPA", 0), get("SPB", 0), get("SPC", 0));
  } else if (p.kind == "EULER") {
    rotation = program::euler_zxz(get("EULPR", 0), get("EULNU", 0), get("EULROT", 0));
  } else if (p.kind == "VECTOR") {
    const auto r =
        program::frame_from_vectors(Eigen::Vector3d(get("BX", 1), get("BY", 0), get("BZ", 0)),
                                    Eigen::Vector3d(get("NX", 0), get("NY", 0), get("NZ", 1)));
    if (!r)
      fail(Code::bad_number, block_.keyword_begin,
           "PLANE VECTOR needs a normal vector and a base vector not parallel to it");
    rotation = *r;
  } else if (p.kind == "RELATIV") {
    // One incremental spatial angle about the tilted frame's own axis.
    rotation =
        tilt_.rotation * program::spatial_angles(get("SPA", 0), get("SPB", 0), get("SPC", 0));
  } else if (p.kind == "PROJECTED") {
    const auto r = projected_angles(get("PROPR", 0), get("PROMIN", 0), get("ROT", 0));
    if (!r)
      fail(Code::tilted_plane, block_.keyword_begin,
           "PLANE PROJECTED: PROPR and PROMIN of +-90 both give no plane");
    rotation = *r;
  } else if (p.kind == "POINTS") {
    rotation = points_plane(p);
  } else if (p.kind == "AXIAL") {
    // One rotary axis turned: the tool leans relative to the part as
    // SPATIAL's angle about that axis (ISO 841 signs table axes so that
    // head and table agree); two or more need the machine's kinematics.
    int turned = 0;
    for (const auto& [letter, angle] : p.values) {
      if (std::abs(std::remainder(angle, 360.0)) < 1e-9) continue;
      if (letter != "A" && letter != "B" && letter != "C") continue;
      if (++turned > 1)
        fail(Code::tilted_plane, block_.keyword_begin,
             "PLANE AXIAL with more than one rotary axis turned: the plane depends on the "
             "machine's kinematics (the order of its axes); write the tilt as PLANE SPATIAL");
      rotation = program::turn_about(letter[0] - 'A', angle);
    }
  } else {
    fail(Code::tilted_plane, block_.keyword_begin,
         "PLANE " + p.kind +
             " is not read: write the tilt as PLANE SPATIAL, PROJECTED, EULER, VECTOR, POINTS "
             "or AXIAL");
  }
  if (p.kind != "RESET") p.identity = rotation.isApprox(Eigen::Matrix3d::Identity(), 1e-12);
  plane_ = p;
  tilt(p.identity ? Eigen::Matrix3d::Identity() : rotation, events);
  q_[120] = q_[121] = q_[122] = 0;  // the rotary positions the plane asks for
}

// PLANE POINTS P1X P1Y P1Z P2X ... P3Z: the words P1, X+.. in turn.
Eigen::Matrix3d Interpreter::points_plane(const WorkingPlane& p) const {
  std::array<Eigen::Vector3d, 3> points{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                        Eigen::Vector3d::Zero()};
  int point = -1;
  for (const auto& [letter, v] : p.values) {
    if (letter == "P" && v >= 1 && v <= 3 && v == std::floor(v)) {
      point = static_cast<int>(v) - 1;
    } else if (point >= 0 && letter.size() == 1 && letter[0] >= 'X' && letter[0] <= 'Z') {
      points[static_cast<std::size_t>(point)][letter[0] - 'X'] = length(v);
      point = -1;
    }
  }
  const auto r = plane_through(points[0], points[1], points[2]);
  if (!r)
    fail(Code::tilted_plane, block_.keyword_begin,
         "PLANE POINTS: the three points lie on one line (or P1 to P3 are missing)");
  return *r;
}

// The working plane turned to `rotation` about the active datum (CYCL DEF
// 7): a point programmed at p in it is at rotation p + shift in the
// untilted frame. The events keep the datum shift added (e = p + shift),
// so the frame's origin is shift - rotation shift.
void Interpreter::tilt(const Eigen::Matrix3d& rotation, std::vector<program::Event>& events) {
  program::WorkingFrame frame;
  frame.rotation = rotation;
  frame.origin = shift_ - rotation * shift_;
  frame.source = source();
  if (frame.rotation == tilt_.rotation && frame.origin == tilt_.origin) return;
  const Eigen::Vector3d tip = tilt_.to_program(position_);
  position_ = rotation.transpose() * (tip - frame.origin);
  tilt_ = frame;
  tangent_.reset();
  events.emplace_back(frame);
}

void Interpreter::function_block() {
  const std::string_view what = block_.sub_keyword;
  if (what.starts_with("RESET TCPM")) {
    tcpm_ = false;
  } else if (what.starts_with("TCPM")) {
    tcpm_ = true;
  } else if (!what.starts_with("MODE MILL")) {
    warn_once(Code::function_passed, 1000 + static_cast<long>(what.size()), block_.keyword_begin,
              "FUNCTION " + std::string(what.substr(0, what.find(' '))) +
                  " passed: taken as moving nothing");
  }
}

}  // namespace vcpost::heidenhain
