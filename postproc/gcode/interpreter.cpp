#include "postproc/gcode/interpreter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>

#include "postproc/gcode/code_names.h"
#include "postproc/gcode/codes.h"
#include "postproc/gcode/cycles.h"
#include "postproc/gcode/interpreter_step.h"
#include "postproc/gcode/lexer.h"
#include "postproc/gcode/splines.h"
#include "postproc/program/arc.h"
#include "postproc/program/working_frame.h"

namespace vcpost::gcode {

using program::Event;

namespace {

// rs274's arc tolerances (interp_internal.hh), inch figures in mm: the
// radius tolerance (a zero radius, an R too short for the chord) is 0.00005
// inch in both units; the radius to the end may differ from the radius to
// the start by the centre-arc tolerance, 2 * 0.01 * sqrt(2) mm (0.0283) in
// mm programs and 2 * 0.001 * sqrt(2) inch (0.0718 mm) in inch programs,
// or by up to 100 times that when within 0.1 % of the radius.
constexpr double kArcRadiusTolerance = 0.00005 * kMmPerInch;
constexpr double kCentreArcToleranceMm = 2 * 0.01 * std::numbers::sqrt2;
constexpr double kCentreArcToleranceInch = 2 * 0.001 * std::numbers::sqrt2 * kMmPerInch;
constexpr double kArcRelativeTolerance = 0.001;

}  // namespace

Interpreter::Interpreter(std::string_view text, Dialect dialect, InterpreterLimits limits)
    : text_(text),
      dialect_(dialect),
      limits_(limits),
      parameters_(dialect_),
      nurbs_(limits.max_cycle_moves) {
  // Canned cycles retract to the R plane (G99) in rs274 at start, to the
  // initial level (G98) on Fanuc-like controls.
  state_.retract_to_r = dialect_.kind == machines::Dialect::rs274ngc;
}

bool Interpreter::line_at(std::uint64_t offset, std::uint32_t number, Line& line) const {
  if (offset >= text_.size()) return false;
  const char* begin = text_.data() + offset;
  const std::size_t rest = text_.size() - offset;
  // Looks no further than just past the longest line the reader accepts: a
  // line without end (a huge file of one line) costs no more than that.
  const std::size_t scan = std::min(rest, kMaxLineLength + 2);
  const void* nl = std::memchr(begin, '\n', scan);
  std::size_t length = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - begin) : scan;
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
  throw GcodeError(Diagnostic{code, block_.line, column == 0 ? 1u : column, std::move(message)});
}

void Interpreter::warn(Code code, std::uint32_t column, std::string message) {
  ++warning_count_;
  if (warnings_.size() >= limits_.max_warnings) return;
  warnings_.push_back(Diagnostic{code, block_.line, column == 0 ? 1u : column, std::move(message)});
}

bool Interpreter::next(std::vector<Event>& events) {
  if (ended_) return false;
  try {
    Line l;
    if (!line_at(pos_, line_ + 1, l)) {
      ended_ = true;
      if (!frames_.empty() || !flow_.empty()) {
        block_.line = line_ == 0 ? 1 : line_;
        fail(Code::E1303, 1, "program ends inside a subroutine or control block");
      }
      if (!percent_seen_) {
        block_.line = line_ == 0 ? 1 : line_;
        warn(Code::W1305, 1, "program ends without M2 or M30");
      }
      return false;
    }
    pos_ = l.offset + l.text.size() + l.eol.size();
    line_ = l.number;
    block_.line = l.number;  // for errors thrown while reading
    if (++lines_read_ > limits_.max_blocks)
      fail(Code::E1309, 1,
           "program runs more than " + std::to_string(limits_.max_blocks) +
               " blocks (loops and calls counted), the limit");
    read_block(l.text, l.number, l.offset, dialect_, parameters_, block_);
    block_.eol = l.eol;
    if (block_.tape_marker) {
      // A leading '%' opens the program; the next one closes it (the rest
      // of the file is not read, as RS274NGC and Fanuc tape format say).
      if (percent_seen_) {
        ended_ = true;
        warn_unread_rest();
        return false;
      }
      // rs274 takes '%' as the opening only on the program's first line.
      if (content_seen_ && dialect_.kind == machines::Dialect::rs274ngc)
        fail(Code::E1001, 1,
             "'%' in the middle of a program that did not open with '%': rs274 refuses it "
             "(\"Bad character '%' used\")");
      percent_seen_ = true;
      return true;
    }
    if (!block_.words.empty() || block_.control.kind != ControlKind::none ||
        !block_.assignments.empty())
      content_seen_ = true;
    if (block_.deleted) return true;
    if (block_.control.kind != ControlKind::none) {
      handle_control();
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

// After the closing '%': lines that hold more than blanks and comments are
// not read (nor posted): say so, with their number.
void Interpreter::warn_unread_rest() {
  std::uint64_t unread = 0;
  std::uint32_t first = 0;
  Line l;
  for (std::uint32_t number = line_ + 1; line_at(pos_, number, l); ++number) {
    pos_ = l.offset + l.text.size() + l.eol.size();
    if (syntax::only_comments(l.text) || l.text.find_first_not_of(" \t%") == std::string_view::npos)
      continue;
    if (first == 0) first = number;
    ++unread;
  }
  if (unread > 0)
    warn(Code::W1311, 1,
         std::to_string(unread) + " line" + (unread == 1 ? "" : "s") +
             " after the closing '%' (from line " + std::to_string(first) +
             ") are not read, neither checked nor posted: the control stops at the '%'");
}

void Interpreter::commit_assignments() {
  for (const auto& a : block_.assignments) {
    const Access r =
        a.name.empty() ? parameters_.write(a.number, a.value) : parameters_.write(a.name, a.value);
    if (!r.ok) fail(r.code, a.column, r.message);
  }
}

double Interpreter::length(const Word& w, bool inches) const {
  double v = w.value;
  if (dialect_.integer_lengths == IntegerLengths::increments && !w.decimal_point && !w.computed)
    v *= inches ? dialect_.increment_inch : dialect_.increment_mm;
  return to_mm(v, inches);
}

void Interpreter::warn_once(char letter, int key, Code code, std::uint32_t column,
                            std::string message) {
  for (const auto& k : warned_once_)
    if (k.first == letter && k.second == key) return;
  warned_once_.emplace_back(letter, key);
  warn(code, column, std::move(message) + " (reported once)");
}

namespace {

bool is_cycle_code(int c) {
  return c == G_73_chip_break_drill || c == G_74_left_hand_tap || c == G_76_fine_bore ||
         (c >= G_81_drill && c <= G_89_bore_dwell_feed_out);
}

// Codes whose axis words are values, not a point to move to: G10, G52, G92.
bool axis_words_are_values(int nonmodal) {
  return nonmodal == G_10_set_offsets || nonmodal == G_52_local_origin ||
         nonmodal == G_92_set_position;
}

// Codes that take the block's axis words for themselves (no move of their own
// kind from them): those above, and G28, G30 (the point passed on the way home).
bool uses_axis_words(int nonmodal) {
  return axis_words_are_values(nonmodal) || nonmodal == G_28_home || nonmodal == G_30_home_2;
}

constexpr char kAxes[] = "XYZ";

std::size_t work_index(int code) {
  switch (code) {
    case G_54_work_1:
      return 0;
    case G_55_work_2:
      return 1;
    case G_56_work_3:
      return 2;
    case G_57_work_4:
      return 3;
    case G_58_work_5:
      return 4;
    case G_59_work_6:
      return 5;
    case G_59_1_work_7:
      return 6;
    case G_59_2_work_8:
      return 7;
    case G_59_3_work_9:
      return 8;
    default:
      return 9;  // G54.1
  }
}

Eigen::Vector3d total_offset(const Origins& f, int system) {
  return Eigen::Vector3d(f.work[work_index(system)] + f.g92 + f.local);
}

}  // namespace

// The block's code families in the order the interpreter applies them
// (RS274NGC's order of execution): each handler is called only when its
// family is in the block, so a plain move costs a few tests.
void Interpreter::execute(std::vector<Event>& events) {
  Step step(block_, events, state_);
  index_words(step);
  classify_words(step);
  if (dialect_.kind == machines::Dialect::rs274ngc) check_unused_words(step);
  if (step.b.message) emit_message(step);
  if (step.g(Group::units)) set_units(step);
  if (step.g(Group::feed_mode)) set_feed_mode(step);
  if (step.word('F') && !step.siemens_dwell && !step.macro_call) set_feed(step);
  if (step.word('S') && !step.macro_call && !step.siemens_dwell && !step.speed_limit)
    set_spindle_speed(step);
  if (dialect_.speed_output && step.m(Group::overrides)) analog_output(step);
  if (step.word('T') && !step.macro_call) select_tool(step);
  if (step.m(Group::tool_change)) change_tool(step);
  if (step.m(Group::spindle)) spindle(step);
  if (step.m(Group::coolant)) coolant(step);
  if (step.nonmodal_code == G_4_dwell) dwell(step);
  if (step.g(Group::plane)) set_plane(step);
  if (step.g(Group::cutter_comp)) cutter_compensation(step);
  if (step.g(Group::tool_length)) tool_length(step);
  if (changes_origins(step)) set_origins(step);
  set_distance_modes(step);
  if (step.g(Group::rotation)) tilt_working_plane(step);
  take_axis_words(step);
  set_motion_mode(step);
  if (step.nonmodal_code == G_5_3_nurbs_end) end_nurbs(step);
  move(step);
  step.emit_inverse_f([] { return std::optional<double>(); });
  if (dialect_.kind == machines::Dialect::sinumerik) siemens_words(step);
  const bool returns = stop(step);
  state_ = step.state;
  if (step.origins) origins_ = *step.origins;
  if (returns) {
    return_from_sub();  // M99 in a subprogram
    return;
  }
  if (dialect_.kind == machines::Dialect::sinumerik &&
      step.b.siemens_cycle.kind != SiemensCycle::Kind::none &&
      step.b.siemens_cycle.kind != SiemensCycle::Kind::call)
    mcall_ = mcall_next_;
  if (step.m(Group::subprogram)) call_subprogram(step);
  if (step.macro_call) macro_call(step);
}

// Indexes the words by letter and modal group: unknown and refused codes,
// two codes of one group and a letter given twice are errors here.
void Interpreter::index_words(Step& step) {
  const Block& b = step.b;
  const bool fanuc_like = dialect_.kind != machines::Dialect::rs274ngc;
  WordIndex& index = step.index;
  int m_words = 0;
  const Word* axis_word = nullptr;
  for (std::size_t k = 0; k < b.words.size(); ++k) {
    const Word& w = b.words[k];
    // Stored only for a word that gets indexed: below kMaxIndexedPosition.
    const auto slot_of_w = static_cast<std::uint8_t>(k + 1);
    if (w.letter == 'G') {
      const auto entry = find_g_code(dialect_.kind, w.value);
      if (!entry) {
        char text[32];
        std::snprintf(text, sizeof text, "G%g", w.value);
        const bool fanuc_code = dialect_.kind == machines::Dialect::rs274ngc &&
                                find_g_code(machines::Dialect::fanuc, w.value).has_value();
        fail(Code::E1401, w.column,
             std::string("unknown G code ") + text +
                 (fanuc_code ? "; it is a Fanuc-like control's code: read a Fanuc, Haas or Makino "
                               "program with --dialect fanuc (or its --machine)"
                             : ""));
      }
      if (entry->support == Support::refused)
        fail(Code::E1404, w.column,
             code_text('G', entry->code) +
                 " changes the motion in a way vcpost does not follow (it " +
                 (entry->what ? entry->what : "is not followed") +
                 "); remove it or expand it in CAM");
      if (entry->support == Support::noted)
        warn_once('G', entry->code, Code::W1406, w.column,
                  code_text('G', entry->code) +
                      " is a mode of the control that does not change the path vcpost reads; "
                      "passed through unchanged");
      Group grp = entry->group;
      // Fanuc: the canned cycles and G80 are a group of their own (09), so
      // "G00 G80" and "G81 ... " beside a G01 mode are no conflict.
      if (fanuc_like && grp == Group::motion &&
          (entry->code == G_80_cycle_off || is_cycle_code(entry->code)))
        grp = Group::canned_cycle;
      const auto group = static_cast<std::size_t>(grp);
      if (const Word* before = step.at(index.g[group])) {
        // RS274NGC: G80 beside another motion code gives way to it (rs274
        // reads "G0 G80" so).
        if (grp == Group::motion && entry->code == G_80_cycle_off) continue;
        if (grp == Group::motion && code_of(*before) == G_80_cycle_off) {
          index.g[group] = slot_of_w;
          continue;
        }
        // G53 combines with one other non-modal code only in theory; refuse
        // two non-modal codes as LinuxCNC does.
        const bool non_modal = grp == Group::non_modal;
        fail(Code::E1403, w.column,
             code_text('G', code_of(*before)) + " and " + code_text('G', entry->code) +
                 (non_modal ? " are both non-modal codes" : " are in the same modal group"));
      }
      index.g[group] = slot_of_w;
    } else if (w.letter == 'M') {
      // LinuxCNC's limit; Fanuc-like controls allow fewer.
      if (++m_words > 4) fail(Code::E1405, w.column, "more than four M codes in one block");
      if (index_m_word(step, w, slot_of_w)) continue;
    } else {
      const char l = w.letter;
      if ((l == 'A' || l == 'B' || l == 'C' || l == 'U' || l == 'V' || l == 'W') && !axis_word)
        axis_word = &w;
      auto& slot = index.by_letter[static_cast<std::size_t>(w.letter - 'A')];
      if (slot != 0) fail(Code::E1008, w.column, std::string(1, w.letter) + " word given twice");
      slot = slot_of_w;
    }
  }
  // A, B, C, U, V, W: rotary or parallel axes, but a G65 macro call's
  // arguments (#1, #2, #3, #21, #22, #23).
  const Word* g65 = step.at(index.g[static_cast<std::size_t>(Group::non_modal)]);
  if (axis_word && !(fanuc_like && g65 && code_of(*g65) == G_65_macro_call))
    fail(Code::E1506, axis_word->column,
         std::string(1, axis_word->letter) + " axis: vcpost reads 3-axis (X Y Z) programs only");
}

// Indexes one M word; true when it is passed over (a machine's own M code,
// or the second of Fanuc's M7 M8).
bool Interpreter::index_m_word(Step& step, const Word& w, std::uint8_t slot) {
  const bool fanuc_like = dialect_.kind != machines::Dialect::rs274ngc;
  auto entry = find_code(kMCodes, w.value);
  // Fanuc-like controls: beyond the standard M codes, every M is the
  // machine's own (M50 is no feed override there).
  if (entry && fanuc_like && entry->group == Group::overrides) entry.reset();
  if (entry && fanuc_like && (entry->code == M_60_pallet_change || entry->code == M_61_set_tool))
    entry.reset();
  if (!entry) {
    char text[32];
    std::snprintf(text, sizeof text, "M%g", w.value);
    if (dialect_.unknown_m_is_error)
      fail(Code::E1402, w.column,
           std::string("unknown M code ") + text +
               "; if it is a machine's own M code of a Fanuc-like program, read it with "
               "--dialect fanuc (or its --machine)");
    warn_once('M', static_cast<int>(std::lround(w.value * 10.0)), Code::W1402, w.column,
              std::string("M code ") + text +
                  " is not known to vcpost (a machine's own function); passed through unchanged");
    return true;
  }
  if (entry->support == Support::refused)
    fail(Code::E1404, w.column,
         code_text('M', entry->code) +
             " changes the program's state in a way vcpost does not follow (it " + entry->what +
             ")");
  const auto group = static_cast<std::size_t>(entry->group);
  if (const Word* before = step.at(step.index.m[group])) {
    // Fanuc-like controls take mist and flood together (M7 M8).
    const int pair = code_of(*before) + entry->code;
    if (fanuc_like && entry->group == Group::coolant && pair == M_7_mist + M_8_flood &&
        entry->code != code_of(*before)) {
      step.mist_and_flood = true;
      return true;
    }
    fail(Code::E1403, w.column,
         code_text('M', code_of(*before)) + " and " + code_text('M', entry->code) +
             " are in the same modal group");
  }
  step.index.m[group] = slot;
  return false;
}

// The non-modal and motion codes, and the checks of axis words they share.
void Interpreter::classify_words(Step& step) {
  const bool fanuc_like = dialect_.kind != machines::Dialect::rs274ngc;
  step.nonmodal = step.g(Group::non_modal);
  step.nonmodal_code = step.nonmodal ? code_of(*step.nonmodal) : 0;
  const int nonmodal_code = step.nonmodal_code;
  if (fanuc_like && nonmodal_code == G_4_dwell && step.word('X')) {
    step.dwell_x = step.word('X');
    step.index.by_letter['X' - 'A'] = 0;
  }
  step.has_xyz = step.word('X') || step.word('Y') || step.word('Z');
  step.motion_word = step.g(Group::motion);
  step.cycle_word = step.g(Group::canned_cycle);
  step.motion_code = step.motion_word ? code_of(*step.motion_word) : -1;
  const int motion_code = step.motion_code;
  if (step.motion_word && motion_code == G_80_cycle_off && step.has_xyz &&
      !uses_axis_words(nonmodal_code))
    fail(Code::E1508, step.first_axis_column(0),
         "axis words with G80: without a motion mode (G0/G1/G2/G3)");
  if (step.nonmodal && uses_axis_words(nonmodal_code) && step.motion_word &&
      motion_code != G_80_cycle_off && step.has_xyz)
    fail(Code::E1403, step.nonmodal->column,
         code_text('G', nonmodal_code) + " and " + code_text('G', motion_code) +
             " both use the axis words");
  step.macro_call = nonmodal_code == G_65_macro_call;
  const bool siemens = dialect_.kind == machines::Dialect::sinumerik;
  step.siemens_dwell = siemens && nonmodal_code == G_4_dwell;
  step.speed_limit =
      siemens && (nonmodal_code == G_25_spindle_min || nonmodal_code == G_26_spindle_max);
}

// rs274's check of words that no code of the block uses (D H I J K L P Q R).
void Interpreter::check_unused_words(const Step& step) {
  const ModalState& s = step.state;
  auto has_letter = [&](char l) {
    return step.index.by_letter[static_cast<std::size_t>(l - 'A')] != 0;
  };
  const bool checked_words =
      has_letter('D') || has_letter('E') || has_letter('H') || has_letter('I') || has_letter('J') ||
      has_letter('K') || has_letter('L') || has_letter('P') || has_letter('Q') || has_letter('R');
  if (!checked_words) return;
  const int nonmodal_code = step.nonmodal_code;
  int to_be = step.motion_code;
  if (to_be < 0 && step.has_xyz && !uses_axis_words(nonmodal_code)) {
    to_be = s.cycle != 0                  ? s.cycle
            : s.motion == Motion::rapid   ? G_0_rapid
            : s.motion == Motion::linear  ? G_1_linear
            : s.motion == Motion::arc_cw  ? G_2_arc_cw
            : s.motion == Motion::arc_ccw ? G_3_arc_ccw
            : s.motion == Motion::nurbs   ? G_5_2_nurbs
                                          : -1;
  }
  const Word* comp = step.g(Group::cutter_comp);
  const int comp_code = comp ? code_of(*comp) : 0;
  const bool comp_on =
      comp_code == G_41_compensation_left || comp_code == G_41_1_compensation_left_dynamic ||
      comp_code == G_42_compensation_right || comp_code == G_42_1_compensation_right_dynamic;
  const Word* tlo = step.g(Group::tool_length);
  const int tlo_code = tlo ? code_of(*tlo) : 0;
  const bool g10 = nonmodal_code == G_10_set_offsets;
  const bool g64 =
      step.g(Group::path_control) && step.g_code(Group::path_control) == G_64_path_blending;
  const bool arc = to_be == G_2_arc_cw || to_be == G_3_arc_ccw;
  // rs274 takes I, J (and P, Q for G5) only with a G5 or G5.1 word in the block.
  const bool spline =
      step.motion_code == G_5_cubic_spline || step.motion_code == G_5_1_quadratic_spline;
  const bool cubic = step.motion_code == G_5_cubic_spline;
  const bool cycle = is_cycle_code(to_be);
  const bool m98 = step.m(Group::subprogram) != nullptr;
  // M codes that take words: M50-M53 and M62-M66 (P), M66-M68 (Q, L, E),
  // M61 (Q), M19 (R, Q, P).
  const Word* mo = step.m(Group::overrides);
  const int moc = mo ? code_of(*mo) : 0;
  const bool m_p = (moc >= M_50_feed_override && moc <= M_53_feed_stop) ||
                   (moc >= M_62_digital_output_sync && moc <= M_66_wait_input);
  const bool m_q = (moc >= M_66_wait_input && moc <= M_68_analog_output) ||
                   (step.m(Group::tool_change) && step.m_code(Group::tool_change) == M_61_set_tool);
  const bool m19 = step.m(Group::spindle) && step.m_code(Group::spindle) == M_19_spindle_orient;
  auto unused = [&](char letter, bool used, const char* users) {
    if (const Word* w = step.word(letter); w && !used)
      fail(Code::E1009, w->column,
           std::string(1, letter) + " word with no " + users + " to use it");
  };
  unused('D', comp_on || to_be == G_73_chip_break_drill || to_be == G_83_peck_drill,
         "G41, G42, G73 or G83");
  unused('E', moc >= M_66_wait_input && moc <= M_68_analog_output, "M66, M67 or M68");
  unused('H', tlo_code == G_43_tool_length || tlo_code == G_43_2_tool_length_added, "G43 or G43.2");
  unused('I', arc || spline || to_be == G_87_back_bore || g10, "G2, G3, G5, G5.1, G10 or G87");
  unused('J', arc || spline || to_be == G_87_back_bore || g10, "G2, G3, G5, G5.1, G10 or G87");
  unused('K', arc || to_be == G_87_back_bore, "G2, G3 or G87");
  unused('L', cycle || g10 || comp_on || m98 || moc == M_66_wait_input || to_be == G_5_2_nurbs,
         "G10, cutter compensation, canned cycle, M98 or G5.2 (NURBS)");
  unused('P',
         g10 || nonmodal_code == G_4_dwell || g64 || arc || cubic || to_be == G_5_2_nurbs ||
             to_be == G_74_left_hand_tap || to_be == G_82_drill_dwell ||
             to_be == G_84_right_hand_tap || to_be == G_86_bore_spindle_stop ||
             to_be == G_88_bore_manual_out || to_be == G_89_bore_dwell_feed_out || m98 || m_p ||
             m19,
         "G2, G3, G4, G5, G5.2, G10, G64, G74, G82, G84, G86, G88, G89 or M98");
  unused('Q',
         to_be == G_73_chip_break_drill || to_be == G_83_peck_drill || cubic || g10 || g64 || m_q ||
             m19,
         "G5, G10, G64, G73 or G83");
  unused('R', arc || cycle || g10 || g64 || m19, "G2, G3, G10, G64 or canned cycle");
  if (arc && !step.g(Group::plane)) {
    // (With a plane word in the block, that plane decides; checked with the arc.)
    const char plane_axis = s.plane == program::Plane::xy   ? 'K'
                            : s.plane == program::Plane::xz ? 'J'
                                                            : 'I';
    if (const Word* w = step.word(plane_axis))
      fail(Code::E1009, w->column,
           std::string(1, plane_axis) + " word given for an arc in the " +
               (s.plane == program::Plane::xy   ? "XY"
                : s.plane == program::Plane::xz ? "XZ"
                                                : "YZ") +
               " plane");
  }
}

void Interpreter::emit_message(Step& step) {
  const Block& b = step.b;
  step.emit(
      program::Message{*b.message, source(b, b.comments.empty() ? 1 : b.comments.front().column)});
}

// Units first: every length of this block is read in the new units.
void Interpreter::set_units(Step& step) {
  const int c = step.g_code(Group::units);
  step.state.inches = c == G_20_inch || c == G_70_inch || c == G_700_inch;
}

void Interpreter::set_feed_mode(Step& step) {
  const Word* g = step.g(Group::feed_mode);
  const int c = code_of(*g);
  const auto mode = c == G_93_inverse_time     ? program::FeedMode::inverse_time
                    : c == G_95_per_revolution ? program::FeedMode::per_revolution
                                               : program::FeedMode::per_minute;
  // As LinuxCNC: a G93/G94/G95 word resets the feed to 0 (it must be
  // given again); G94 and G95 say so with a zero feed rate.
  step.state.feed_mode = mode;
  step.state.feed = 0.0;
  if (mode != program::FeedMode::inverse_time)
    step.emit(program::SetFeedRate{0.0, mode, source(step.b, g->column)});
}

void Interpreter::set_feed(Step& step) {
  const Word* f = step.word('F');
  ModalState& s = step.state;
  if (f->value < 0) fail(Code::E1511, f->column, "negative feed rate");
  if (s.feed_mode == program::FeedMode::inverse_time) {
    s.feed = f->value;
    step.inverse_f = f;
  } else {
    s.feed = to_mm(f->value, s.inches);
    step.emit(program::SetFeedRate{s.feed, s.feed_mode, source(step.b, f->column)});
  }
}

void Interpreter::set_spindle_speed(Step& step) {
  const Word* sw = step.word('S');
  if (sw->value < 0) fail(Code::E1511, sw->column, "negative spindle speed");
  step.state.spindle_rpm = sw->value;
  step.emit(program::SetSpindleSpeed{sw->value, source(step.b, sw->column)});
}

// M67/M68 E<n> Q<value>: on the profile's speed output (the spindle's speed
// command wired to motion.analog-out-<n>), the spindle speed, as an S word;
// on another output, nothing vcpost follows. As LinuxCNC, E and Q are due.
void Interpreter::analog_output(Step& step) {
  const Word* m = step.m(Group::overrides);
  const int c = code_of(*m);
  if (c != M_67_analog_output_sync && c != M_68_analog_output) return;
  const Word* e = step.word('E');
  const Word* q = step.word('Q');
  if (!e || !q)
    fail(Code::E1621, m->column,
         std::string(c == M_67_analog_output_sync ? "M67" : "M68") +
             " needs E (the output) and Q (its value)");
  if (e->value != *dialect_.speed_output) return;
  if (q->value < 0)
    fail(Code::E1620, q->column,
         "negative spindle speed on the speed output E" + std::to_string(*dialect_.speed_output));
  step.state.spindle_rpm = q->value;
  step.emit(program::SetSpindleSpeed{q->value, source(step.b, m->column)});
}

void Interpreter::select_tool(Step& step) {
  const Word* t = step.word('T');
  if (!whole_number(t->value))
    fail(Code::E1511, t->column, "tool number must be a whole number from 0 to 1e9");
  step.state.selected_tool = static_cast<int>(t->value);
  step.emit(program::SelectTool{step.state.selected_tool, source(step.b, t->column)});
}

void Interpreter::change_tool(Step& step) {
  if (step.m_code(Group::tool_change) != M_6_tool_change) return;  // only M6 changes the tool
  step.state.tool_in_spindle = step.state.selected_tool;
  step.emit(program::ChangeTool{step.state.tool_in_spindle,
                                source(step.b, step.m(Group::tool_change)->column)});
}

void Interpreter::spindle(Step& step) {
  const Word* m = step.m(Group::spindle);
  const int c = code_of(*m);
  if (c == M_5_spindle_stop || c == M_19_spindle_orient) {
    step.emit(program::SpindleOff{source(step.b, m->column)});
  } else {
    step.state.spindle_ccw = c == M_4_spindle_ccw;
    step.emit(program::SpindleOn{c == M_3_spindle_cw ? program::SpindleDirection::clockwise
                                                     : program::SpindleDirection::counterclockwise,
                                 source(step.b, m->column)});
  }
}

void Interpreter::coolant(Step& step) {
  const Word* m = step.m(Group::coolant);
  const int c = code_of(*m);
  step.emit(program::Coolant{c == M_7_mist    ? program::CoolantChange::mist_on
                             : c == M_8_flood ? program::CoolantChange::flood_on
                                              : program::CoolantChange::off,
                             source(step.b, m->column)});
  if (step.mist_and_flood)
    step.emit(program::Coolant{
        c == M_7_mist ? program::CoolantChange::flood_on : program::CoolantChange::mist_on,
        source(step.b, m->column)});
}

// G4: P seconds (RS274NGC); Fanuc: X seconds or P milliseconds; Sinumerik:
// F seconds or S spindle turns.
void Interpreter::dwell(Step& step) {
  const Word* g4 = step.nonmodal;
  double seconds = 0.0;
  if (dialect_.kind == machines::Dialect::rs274ngc) {
    const Word* p = step.word('P');
    if (!p) fail(Code::E1514, g4->column, "G4 needs P (seconds)");
    seconds = p->value;
  } else if (step.siemens_dwell) {
    if (const Word* f = step.word('F')) {
      seconds = f->value;
    } else if (const Word* sw = step.word('S'); sw && step.state.spindle_rpm > 0) {
      seconds = sw->value / step.state.spindle_rpm * 60.0;
    } else {
      fail(Code::E1514, g4->column, "G4 needs F (seconds) or S (spindle turns)");
    }
  } else if (step.dwell_x) {
    seconds = step.dwell_x->value;
  } else if (const Word* p = step.word('P')) {
    seconds = p->decimal_point ? p->value : p->value / 1000.0;
  } else {
    fail(Code::E1514, g4->column, "G4 needs X (s) or P (ms)");
  }
  if (seconds < 0) fail(Code::E1511, g4->column, "negative dwell");
  step.emit(program::Dwell{seconds, source(step.b, g4->column)});
}

void Interpreter::set_plane(Step& step) {
  const Word* g = step.g(Group::plane);
  const int c = code_of(*g);
  step.state.plane = c == G_17_plane_xy   ? program::Plane::xy
                     : c == G_18_plane_xz ? program::Plane::xz
                                          : program::Plane::yz;
  step.emit(program::SelectPlane{step.state.plane, source(step.b, g->column)});
}

void Interpreter::cutter_compensation(Step& step) {
  const Word* g = step.g(Group::cutter_comp);
  const int c = code_of(*g);
  program::CutterCompensation comp{
      c == G_40_compensation_off ? program::CompensationSide::off
      : (c == G_41_compensation_left || c == G_41_1_compensation_left_dynamic)
          ? program::CompensationSide::left
          : program::CompensationSide::right,
      source(step.b, g->column)};
  const Word* d = step.word('D');
  if (d != nullptr && c != G_40_compensation_off && whole_number(d->value))
    comp.register_number = static_cast<int>(d->value);
  step.emit(comp);
}

void Interpreter::tool_length(Step& step) {
  const Word* g = step.g(Group::tool_length);
  program::ToolLengthOffset t{code_of(*g) != G_49_tool_length_off, std::nullopt,
                              source(step.b, g->column)};
  if (const Word* h = step.word('H')) {
    if (!whole_number(h->value))
      fail(Code::E1511, h->column, "H (offset register) must be a whole number from 0 to 1e9");
    t.register_number = static_cast<int>(h->value);
  } else if (t.enabled) {
    t.register_number = step.state.tool_in_spindle;
  }
  step.emit(t);
}

// Most blocks touch no offset: the sums are made only where one may change.
bool Interpreter::changes_origins(const Step& step) {
  const int c = step.nonmodal_code;
  return step.g(Group::coordinate) || c == G_10_set_offsets || c == G_28_home ||
         c == G_28_1_set_home || c == G_30_home_2 || c == G_30_1_set_home_2 ||
         c == G_52_local_origin || (c >= G_92_set_position && c <= G_92_3_restore_position);
}

// Origins: what the block does to the origin offsets, applied to a copy.
// The tool stays where it is on the machine: its program position moves
// by the change of the active offset (rs274 does so).
void Interpreter::set_origins(Step& step) {
  ModalState& s = step.state;
  const int nonmodal_code = step.nonmodal_code;
  step.offset_before = total_offset(origins_, s.work_system);
  if (const Word* g = step.g(Group::coordinate)) {
    const int c = code_of(*g);
    if (c == G_54_1_work_extended) {
      // G54.1 P1..: extended offsets, never set by the program: as G54.1 P1.
      step.index.by_letter['P' - 'A'] = 0;
    }
    s.work_system = c;
  }
  if (nonmodal_code == G_10_set_offsets) {
    set_origin_g10(step);
  } else if (nonmodal_code == G_92_set_position || nonmodal_code == G_52_local_origin) {
    set_origin_g92_g52(step);
  } else if (nonmodal_code == G_92_1_clear_position || nonmodal_code == G_92_2_suspend_position) {
    step.origins = origins_;
    step.origins->g92.setZero();
    if (nonmodal_code == G_92_1_clear_position) step.origins->g92_saved.setZero();
  } else if (nonmodal_code == G_92_3_restore_position) {
    step.origins = origins_;
    step.origins->g92 = step.origins->g92_saved;
  } else if (nonmodal_code == G_28_1_set_home || nonmodal_code == G_30_1_set_home_2) {
    step.origins = origins_;
    (nonmodal_code == G_28_1_set_home ? step.origins->home28 : step.origins->home30) =
        s.position + step.offset_before;
  }
  step.offset_after = total_offset(step.origins ? *step.origins : origins_, s.work_system);
  if (step.offset_after != step.offset_before) {
    s.position += step.offset_before - step.offset_after;
    if (s.moved)
      warn_once('F', 0, Code::W1512, step.nonmodal ? step.nonmodal->column : 1,
                "the program's coordinate frame moves here (G10, G52, G92 or another work system); "
                "positions after it are read in the new frame, as rs274 does");
  } else if (step.g(Group::coordinate) && state_.work_system != s.work_system && s.moved) {
    warn_once('F', 1, Code::W1512, step.g(Group::coordinate)->column,
              "switching from " + code_text('G', state_.work_system) + " to " +
                  code_text('G', s.work_system) +
                  " after motion: its offsets are unknown and taken as equal (as rs274 does)");
  }
}

// G10 L2 (offsets given) and L20 (the position given) of a work system;
// L1, L10, L11, L12, L13 set tool data, whose lengths are not applied.
void Interpreter::set_origin_g10(Step& step) {
  const bool fanuc_like = dialect_.kind != machines::Dialect::rs274ngc;
  const ModalState& s = step.state;
  const Word* l = step.word('L');
  const Word* p = step.word('P');
  if (!l) fail(Code::E1514, step.nonmodal->column, "G10 needs L (what it sets)");
  const long lv = std::lround(l->value);
  const bool sets_origin = lv == 2 || (lv == 20 && !fanuc_like);
  if (sets_origin) {
    if (!p) fail(Code::E1514, step.nonmodal->column, "G10 L2/L20 needs P (coordinate system)");
    const long pv = std::lround(p->value);
    if (pv < 0 || pv > 9) fail(Code::E1511, p->column, "G10 P must be 0 (the active system) to 9");
    if (const Word* r = step.word('R'))
      fail(Code::E1404, r->column,
           "G10 R rotates the coordinate system; vcpost does not follow rotation");
    static constexpr int kSystems[] = {G_54_work_1,   G_55_work_2,   G_56_work_3,
                                       G_57_work_4,   G_58_work_5,   G_59_work_6,
                                       G_59_1_work_7, G_59_2_work_8, G_59_3_work_9};
    const int system = pv == 0 ? s.work_system : kSystems[pv - 1];
    step.origins = origins_;
    Origins& origins = *step.origins;
    Eigen::Vector3d& o = origins.work[work_index(system)];
    for (int k = 0; k < 3; ++k) {
      const Word* w = step.word(kAxes[k]);
      if (!w) continue;
      if (lv == 2) {
        o[k] = length(*w, s.inches);
      } else {  // L20: the current position becomes the given value
        const double machine = s.position[k] + step.offset_before[k];
        o[k] = machine - origins.g92[k] - origins.local[k] - length(*w, s.inches);
      }
    }
  } else if (lv == 20 && fanuc_like) {
    warn_once('L', 20, Code::W1406, l->column,
              "G10 L20 sets an extended work offset (G54.1 P..); taken as not changing the "
              "active frame");
  }
}

// G92: the current position becomes the given one; G52: a local origin
// (LinuxCNC keeps it in the G92 register, Fanuc has a local system).
void Interpreter::set_origin_g92_g52(Step& step) {
  const bool fanuc_like = dialect_.kind != machines::Dialect::rs274ngc;
  const ModalState& s = step.state;
  const bool g92 = step.nonmodal_code == G_92_set_position;
  step.origins = origins_;
  Origins& origins = *step.origins;
  if (g92 && !step.has_xyz) fail(Code::E1507, step.nonmodal->column, "G92 needs an axis word");
  for (int k = 0; k < 3; ++k) {
    const Word* w = step.word(kAxes[k]);
    if (!w) continue;
    if (!g92) {
      (fanuc_like ? origins.local : origins.g92)[k] = length(*w, s.inches);
    } else {
      const double machine = s.position[k] + step.offset_before[k];
      origins.g92[k] = machine - origins.work[work_index(s.work_system)][k] - origins.local[k] -
                       length(*w, s.inches);
    }
  }
  if (g92) origins.g92_saved = origins.g92;
}

void Interpreter::set_distance_modes(Step& step) {
  if (step.g(Group::distance)) step.state.absolute = step.g_code(Group::distance) == G_90_absolute;
  if (step.g(Group::arc_distance))
    step.state.arc_absolute = step.g_code(Group::arc_distance) == G_90_1_arc_absolute;
  if (step.g(Group::return_mode))
    step.state.retract_to_r = step.g_code(Group::return_mode) == G_99_retract_to_r;
}

// Fanuc G68.2 X Y Z I J K: the working plane tilted by the Euler angles
// I (about Z), J (about the turned X), K (about the twice-turned Z), its
// origin at X Y Z of the current frame (the work system's; absolute). G69
// ends it. The coordinates that follow are the tilted frame's, the tool's
// tip staying where it is on the part; G53.1 turns the tool to the frame's
// z and moves nothing there (docs/tilted-frames.md).
void Interpreter::tilt_working_plane(Step& step) {
  const Word* g = step.g(Group::rotation);
  const int c = code_of(*g);
  program::WorkingFrame frame;
  frame.source = source(step.b, g->column);
  if (c == G_68_2_tilted_plane) {
    if (const Word* p = step.word('P'); p && p->value != 0)
      fail(Code::E1404, p->column,
           "G68.2 with P (three points, two vectors or projection angles) is not read: write the "
           "tilt "
           "as G68.2 X Y Z I J K (Euler angles)");
    if (!tilt_.is_identity())
      fail(Code::E1404, g->column,
           "G68.2 while a tilted plane is active (a multiple tilt) is not read: G69 first");
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k)
      if (const Word* w = step.word(kAxes[k])) origin[k] = length(*w, step.state.inches);
    auto angle = [&](char letter) {
      const Word* w = step.word(letter);
      return w ? w->value : 0.0;
    };
    frame.rotation = program::euler_zxz(angle('I'), angle('J'), angle('K'));
    frame.origin = origin;
    step.frame_words = true;
  } else if (c != G_69_rotation_off) {
    return;
  }
  set_tilt(step, frame);
}

// The tilt in effect from this block on; the tool's tip stays where it is
// on the part (its position given in the new frame).
void Interpreter::set_tilt(Step& step, const program::WorkingFrame& frame) {
  if (frame.rotation == tilt_.rotation && frame.origin == tilt_.origin) return;
  ModalState& s = step.state;
  s.position = frame.rotation.transpose() * (tilt_.to_program(s.position) - frame.origin);
  tilt_ = frame;
  step.emit(frame);
}

// Which codes take the axis words for themselves, so that they are no move.
void Interpreter::take_axis_words(Step& step) {
  const int nonmodal_code = step.nonmodal_code;
  // Mazak G117: M/S/T words output when the axes reach the given position
  // during the next move; its axis words are that position, not a move.
  // M and S output somewhere inside a move cannot be placed soundly.
  const bool g117 = nonmodal_code == G_117_position_output;
  if (g117) {
    if (const Word* sw = step.word('S'))
      fail(Code::E1404, sw->column,
           "S in a G117 block changes the speed inside the next move; vcpost cannot place it");
    if (const Word* m = step.m(Group::spindle))
      fail(Code::E1404, m->column,
           "spindle M code in a G117 block acts inside the next move; vcpost cannot place it");
  }
  // G43.1: the axis words are the tool length offset.
  const bool dynamic_offset =
      step.g(Group::tool_length) && step.g_code(Group::tool_length) == G_43_1_tool_length_dynamic;
  step.axes_taken = g117 || step.macro_call || dynamic_offset || step.frame_words ||
                    axis_words_are_values(nonmodal_code);
  step.has_axis = !step.axes_taken && step.has_xyz;
}

// Motion modes. RS274NGC: one group (a cycle replaces G1, G80 leaves no
// mode). Fanuc: G0-G3 stay under a cycle; G80 or a G0-G3 word ends it.
void Interpreter::set_motion_mode(Step& step) {
  ModalState& s = step.state;
  if (step.motion_word) {
    const int c = step.motion_code;
    if (is_cycle_code(c)) {
      if (s.cycle != c) s.cycle_initial_set = s.cycle_initial_set && s.cycle != 0;
      s.cycle = c;
      s.motion = Motion::none;
    } else {
      if (c == G_80_cycle_off || s.cycle != 0) s.cycle_initial_set = false;
      s.cycle = 0;
      s.motion = c == G_0_rapid                ? Motion::rapid
                 : c == G_1_linear             ? Motion::linear
                 : c == G_2_arc_cw             ? Motion::arc_cw
                 : c == G_3_arc_ccw            ? Motion::arc_ccw
                 : c == G_5_cubic_spline       ? Motion::spline_cubic
                 : c == G_5_1_quadratic_spline ? Motion::spline_quadratic
                 : c == G_5_2_nurbs            ? Motion::nurbs
                                               : Motion::none;
    }
  }
  if (step.cycle_word) {
    const int c = code_of(*step.cycle_word);
    if (c == G_80_cycle_off) {
      s.cycle = 0;
      s.cycle_initial_set = false;
    } else {
      s.cycle = c;
    }
  }
  step.motion_column = step.motion_word  ? step.motion_word->column
                       : step.cycle_word ? step.cycle_word->column
                                         : step.first_axis_column(1);
}

// The block's position: the program's coordinates of its axis words.
Eigen::Vector3d Interpreter::target_of(const Step& step, bool absolute) const {
  const ModalState& s = step.state;
  Eigen::Vector3d t = s.position;
  for (int k = 0; k < 3; ++k)
    if (const Word* w = step.word(kAxes[k]))
      t[k] = absolute ? length(*w, s.inches) : s.position[k] + length(*w, s.inches);
  return t;
}

// What moves the tool: a reference return, a macro call, a canned cycle or
// a move of the motion mode.
void Interpreter::move(Step& step) {
  const int c = step.nonmodal_code;
  const ModalState& s = step.state;
  if (c == G_28_home || c == G_30_home_2) {
    reference_return(step);
  } else if (step.macro_call) {
    // G65 moves nothing itself: its program runs after the block (macro_call).
  } else if (step.has_axis && s.cycle != 0) {
    canned_cycle(step);
  } else if (step.has_axis ||
             (!step.axes_taken && (s.motion == Motion::arc_cw || s.motion == Motion::arc_ccw) &&
              (step.word('I') || step.word('J') || step.word('K') || step.word('R'))) ||
             (s.motion == Motion::nurbs && step.motion_code == G_5_2_nurbs)) {
    // (G5.2 without axis words: the curve opens, or a weight for its start.)
    motion(step);
  }
}

// G28/G30: through the given intermediate point to the reference point,
// which rs274 takes from parameters 5161-5163 / 5181-5183 (0 in its
// default file, and the machine's are unknown to vcpost).
void Interpreter::reference_return(Step& step) {
  ModalState& s = step.state;
  const int code = step.nonmodal_code;
  const Word* g = step.nonmodal;
  const Eigen::Vector3d via = target_of(step, s.absolute);
  const Eigen::Vector3d reference =
      (code == G_28_home ? origins_.home28 : origins_.home30) - step.offset_after;
  Eigen::Vector3d home = via;
  for (int k = 0; k < 3; ++k)
    if (!step.has_axis || step.word(kAxes[k])) home[k] = reference[k];
  warn_once('G', code, Code::W1509, g->column,
            code_text('G', code) +
                " reference point taken as machine 0 with the program's offsets "
                "(rs274's default parameters; the machine's are unknown)");
  if (step.has_axis)
    step.emit(program::StraightTraverse{s.position, via, source(step.b, g->column)});
  step.emit(program::StraightTraverse{via, home, source(step.b, g->column)});
  s.position = home;
  s.moved = true;
}

// A canned cycle at the block's position (Fanuc: K or L repeats); R, Z, Q
// and P not given are those of the cycle's earlier blocks.
void Interpreter::canned_cycle(Step& step) {
  const bool fanuc_like = dialect_.kind != machines::Dialect::rs274ngc;
  ModalState& s = step.state;
  const int c = s.cycle;
  const std::uint32_t column = step.motion_column;
  if (s.feed <= 0.0) fail(Code::E1505, column, "canned cycle with no feed rate (F) in effect");
  if (s.feed_mode == program::FeedMode::inverse_time)
    fail(Code::E1513, column, "canned cycles cannot run in inverse-time feed (G93)");
  if (s.plane != program::Plane::xy)
    fail(Code::E1404, column, "canned cycles are followed in the XY plane (G17) only");
  const bool same = state_.cycle == c;
  CycleCall call;
  call.code = c;
  call.fanuc = fanuc_like;
  call.start = s.position;
  call.source = source(step.b, column);
  call.spindle_cw = !s.spindle_ccw;
  call.peck_clearance = 0.254;
  if (!s.cycle_initial_set) {
    s.cycle_initial = s.position.z();
    s.cycle_initial_set = true;
  }
  const Word* r = step.word('R');
  if (!r && !same) fail(Code::E1513, column, code_text('G', c) + " needs R (the R plane)");
  const Word* z = step.word('Z');
  if (!z && !same) fail(Code::E1513, column, code_text('G', c) + " needs Z (the hole bottom)");
  const double r_word = r ? length(*r, s.inches) : s.cycle_r;
  const double z_word = z ? length(*z, s.inches) : s.cycle_z;
  s.cycle_r = r_word;
  s.cycle_z = z_word;
  const Word* q = step.word('Q');
  if (c == G_73_chip_break_drill || c == G_83_peck_drill) {
    if (!q && !same) fail(Code::E1513, column, code_text('G', c) + " needs Q (the peck depth)");
    const double qv = q ? length(*q, s.inches) : s.cycle_q;
    if (qv <= 0.0)
      fail(Code::E1513, q ? q->column : column,
           code_text('G', c) + " with a peck depth Q <= 0 (the control alarms too)");
    s.cycle_q = qv;
    call.q = qv;
  }
  const Word* p = step.word('P');
  const bool dwell_needed = c == G_82_drill_dwell || c == G_86_bore_spindle_stop ||
                            c == G_88_bore_manual_out || c == G_89_bore_dwell_feed_out;
  if (dwell_needed && !p && !same && !fanuc_like)
    fail(Code::E1513, column, code_text('G', c) + " needs P (the dwell)");
  if (p) s.cycle_p = fanuc_like && !p->decimal_point ? p->value / 1000.0 : p->value;
  call.dwell =
      (dwell_needed || c == G_74_left_hand_tap || c == G_84_right_hand_tap || c == G_76_fine_bore)
          ? s.cycle_p
          : 0.0;
  if (c == G_87_back_bore && !fanuc_like) {
    if (!same && (!step.word('I') || !step.word('J') || !step.word('K')))
      fail(Code::E1513, column, "G87 needs I, J and K");
    if (const Word* w = step.word('I')) s.cycle_i = length(*w, s.inches);
    if (const Word* w = step.word('J')) s.cycle_j = length(*w, s.inches);
    if (const Word* w = step.word('K')) s.cycle_k = length(*w, s.inches);
    call.i = s.cycle_i;
    call.j = s.cycle_j;
  }
  if ((c == G_76_fine_bore || c == G_87_back_bore) && fanuc_like)
    warn_once('G', c, Code::W1406, column,
              code_text('G', c) +
                  ": the tool's shift at the hole bottom (Q, direction a machine "
                  "parameter) is not followed; the path is read without it");
  call.repeats = cycle_repeats(step);
  place_cycle(step, call, r_word, z_word);
  if (call.r < call.bottom && !(c == G_87_back_bore && fanuc_like))
    fail(Code::E1513, r ? r->column : column, "R plane below the hole bottom Z in a canned cycle");
  call.retract_to_r = s.retract_to_r && !(c == G_87_back_bore && fanuc_like);
  if (call.repeats > 0) {
    // Each hole: its pecks (three moves each at most) and three more.
    const bool pecks = (c == G_73_chip_break_drill || c == G_83_peck_drill) && call.q > 0;
    const double per_hole = 3.0 * ((pecks ? (call.r - call.bottom) / call.q : 0.0) + 1.0) + 3.0;
    if (per_hole * call.repeats > static_cast<double>(limits_.max_cycle_moves))
      fail(Code::E1308, column,
           "canned cycle makes more than " + std::to_string(limits_.max_cycle_moves) +
               " moves in one block (L repeats times pecks), the limit");
    s.position = expand_cycle(call, step.events);
    s.moved = true;
  }
  if (s.cycle_initial < call.r) s.cycle_initial = call.r;
}

// L (Fanuc: K) repeats of a canned cycle; 1 without.
int Interpreter::cycle_repeats(const Step& step) const {
  const bool fanuc_like = dialect_.kind != machines::Dialect::rs274ngc;
  const Word* l = step.word('L');
  const Word* kw = fanuc_like ? step.word('K') : nullptr;
  const Word* rep = kw ? kw : l;
  if (rep && (rep->value < 0 || rep->value > 1e6 || rep->value != std::floor(rep->value)))
    fail(Code::E1511, rep->column, "cycle repeat count must be a whole number");
  const int repeats = rep ? static_cast<int>(rep->value) : 1;
  if (rep && repeats == 0 && !fanuc_like)
    fail(Code::E1513, rep->column, "cannot do zero repeats of a canned cycle");
  return repeats;
}

// The cycle's hole position, R plane and bottom: G91 reads R from the
// initial level and Z from the R plane, X and Y as steps between repeats.
void Interpreter::place_cycle(const Step& step, CycleCall& call, double r_word,
                              double z_word) const {
  const ModalState& s = step.state;
  const double old_z = s.cycle_initial;
  const Word* x = step.word('X');
  const Word* y = step.word('Y');
  if (s.absolute) {
    call.r = r_word;
    call.bottom = z_word;
    call.x = x ? length(*x, s.inches) : s.position.x();
    call.y = y ? length(*y, s.inches) : s.position.y();
  } else {
    call.r = r_word + old_z;
    call.bottom = call.r + z_word;
    call.x = s.position.x();
    call.y = s.position.y();
    call.dx = x ? length(*x, s.inches) : 0.0;
    call.dy = y ? length(*y, s.inches) : 0.0;
  }
  if (call.code == G_87_back_bore && !call.fanuc)
    call.k = s.absolute ? s.cycle_k : call.bottom + s.cycle_k;
  call.initial = old_z;
}

// A move of the motion mode (G0, G1, G2, G3; G53: machine coordinates).
void Interpreter::motion(Step& step) {
  ModalState& s = step.state;
  const Word* nonmodal = step.nonmodal;
  const bool machine = step.nonmodal_code == G_53_machine_coordinates;
  if (machine) {
    if (s.motion != Motion::rapid && s.motion != Motion::linear)
      fail(Code::E1404, nonmodal->column, "G53 needs G0 or G1");
    warn_once('G', G_53_machine_coordinates, Code::W1509, nonmodal->column,
              "G53 machine coordinates: the offsets the program sets (G10, G92, G52) are taken "
              "off, the machine's own are unknown and taken as 0 (as rs274 does)");
  }
  Eigen::Vector3d end = target_of(step, s.absolute || machine);
  if (machine) {
    // The words are machine coordinates: in the program's frame they lie
    // the active offsets off (rs274 prints them so).
    const Eigen::Vector3d offset =
        total_offset(step.origins ? *step.origins : origins_, s.work_system);
    for (int k = 0; k < 3; ++k)
      if (step.word(kAxes[k])) end[k] -= offset[k];
  }
  const auto src = source(step.b, step.motion_column);
  switch (s.motion) {
    case Motion::none:
      fail(Code::E1508, step.first_axis_column(1),
           "axis words without a motion mode (G0/G1/G2/G3)");
    case Motion::rapid:
      step.emit(program::StraightTraverse{s.position, end, src});
      break;
    case Motion::linear:
      if (s.feed <= 0.0 || (s.feed_mode == program::FeedMode::inverse_time && !step.word('F')))
        fail(Code::E1505, step.motion_column, "G1 with no feed rate (F) in effect");
      step.emit_inverse_f([&] { return s.feed * (end - s.position).norm(); });
      step.emit(program::StraightFeed{s.position, end, src});
      break;
    case Motion::arc_cw:
    case Motion::arc_ccw:
      arc(step, end);
      break;
    case Motion::spline_cubic:
    case Motion::spline_quadratic:
      spline(step, end);
      break;
    case Motion::nurbs:
      nurbs_point(step, end);
      return;  // the tool stays until G5.3
  }
  s.position = end;
  s.moved = true;
}

// G2/G3 to `end`: the centre from R or from I, J, K; P full turns.
void Interpreter::arc(Step& step, const Eigen::Vector3d& end) {
  const ModalState& s = step.state;
  const std::uint32_t column = step.motion_column;
  if (s.feed <= 0.0 || (s.feed_mode == program::FeedMode::inverse_time && !step.word('F')))
    fail(Code::E1505, column, "arc with no feed rate (F) in effect");
  const bool cw = s.motion == Motion::arc_cw;
  const Eigen::Vector3d centre =
      step.word('R') ? centre_from_radius(step, end, cw) : centre_from_offsets(step, end);
  int turns = 1;
  if (const Word* p = step.word('P'); p && (dialect_.kind == machines::Dialect::rs274ngc ||
                                            dialect_.kind == machines::Dialect::sinumerik)) {
    if (p->value < 1 || !whole_number(p->value))
      fail(Code::E1511, p->column,
           dialect_.kind == machines::Dialect::sinumerik
               ? "TURN= (full turns beyond the end point) must be a whole number from 0 to "
                 "999999999"
               : "P (turns) of an arc must be a whole number from 1 to 1e9");
    turns = static_cast<int>(p->value);
  }
  const program::ArcFeed arc{
      s.position, end, centre, s.plane, cw ? -turns : turns, source(step.b, column)};
  step.emit_inverse_f([&] { return s.feed * program::arc_length(arc); });
  step.emit(arc);
}

// G5 (cubic) and G5.1 (quadratic) splines, as rs274 reads them: in the XY
// plane, without Z; the control points are the start, start + (I, J), for
// G5 end + (P, Q), and the end. A G5 without I and J continues the last
// one smoothly: (I, J) is minus that one's (P, Q).
void Interpreter::spline(Step& step, const Eigen::Vector3d& end) {
  ModalState& s = step.state;
  const std::uint32_t column = step.motion_column;
  const bool cubic = s.motion == Motion::spline_cubic;
  const char* code = cubic ? "G5" : "G5.1";
  if (s.feed <= 0.0 || (s.feed_mode == program::FeedMode::inverse_time && !step.word('F')))
    fail(Code::E1505, column, std::string(code) + " with no feed rate (F) in effect");
  if (s.plane != program::Plane::xy)
    fail(Code::E1404, column,
         std::string(code) + ": splines are in the XY plane (G17) only, as rs274 reads them");
  if (const Word* z = step.word('Z'))
    fail(Code::E1404, z->column,
         std::string(code) + ": a spline may not move Z (rs274 refuses it too)");
  const Word* i = step.word('I');
  const Word* j = step.word('J');
  if ((i == nullptr) != (j == nullptr) || (!cubic && i == nullptr))
    fail(Code::E1514, column,
         std::string(code) + (cubic ? " needs both I and J, or neither" : " needs both I and J"));
  const Word* p = step.word('P');
  const Word* q = step.word('Q');
  if (cubic && (p == nullptr || q == nullptr)) fail(Code::E1514, column, "G5 needs both P and Q");
  const Eigen::Vector2d start = s.position.head<2>();
  const Eigen::Vector2d to = end.head<2>();
  const Eigen::Vector2d first =
      start + (i ? Eigen::Vector2d(length(*i, s.inches), length(*j, s.inches))
                 : Eigen::Vector2d(s.cycle_i, s.cycle_j));
  std::vector<Eigen::Vector2d> control{start, first};
  if (cubic) {
    const Eigen::Vector2d pq(length(*p, s.inches), length(*q, s.inches));
    control.emplace_back(to + pq);
    s.cycle_i = -pq.x();
    s.cycle_j = -pq.y();
  }
  control.push_back(to);
  const std::vector<Eigen::Vector2d> points = spline_polyline(control);
  step.emit_inverse_f([&] {
    double path = 0.0;
    Eigen::Vector2d at = start;
    for (const auto& point : points) {
      path += (point - at).norm();
      at = point;
    }
    return s.feed * path;
  });
  const auto src = source(step.b, column);
  Eigen::Vector3d from = s.position;
  for (const auto& point : points) {
    const Eigen::Vector3d next(point.x(), point.y(), s.position.z());
    step.emit(program::StraightFeed{from, next, src});
    from = next;
  }
}

// The frame a NURBS curve's control points are in (nurbs.h).
NurbsFrame Interpreter::nurbs_frame(const Step& step) const {
  const ModalState& s = step.state;
  return NurbsFrame{s.plane, s.inches,
                    total_offset(step.origins ? *step.origins : origins_, s.work_system)};
}

// G5.2 (or axis words under its mode): a control point of the curve, at
// the block's end point in the plane; the tool stays where it is, so that
// G91 points are measured from the curve's start, as in rs274.
void Interpreter::nurbs_point(Step& step, const Eigen::Vector3d& end) {
  const ModalState& s = step.state;
  const auto ax = program::plane_axes(s.plane);
  const NurbsWords words{step.word(kAxes[ax[0]]), step.word(kAxes[ax[1]]), step.word('P'),
                         step.word('L'), step.motion_column};
  const bool continues = state_.motion == Motion::nurbs && step.nonmodal_code != G_5_3_nurbs_end;
  const bool zero_feed = s.feed_mode == program::FeedMode::per_minute && s.feed <= 0.0;
  nurbs_.add(words, continues, zero_feed, Eigen::Vector2d(s.position[ax[0]], s.position[ax[1]]),
             Eigen::Vector2d(end[ax[0]], end[ax[1]]), nurbs_frame(step), step.b.line);
  if (const Word* other = step.word(kAxes[ax[2]]))
    warn_once('G', 52, Code::W1516, other->column,
              std::string(1, kAxes[ax[2]]) +
                  " in a G5.2 block: the curve lies in the working plane, LinuxCNC (and vcpost) "
                  "leave " +
                  std::string(1, kAxes[ax[2]]) + " where it is");
}

// G5.3: the tool follows the curve, as straight feeds within
// kSplineTolerance, to its last control point. Axis words in the block (or
// a G5.2 word) open the next curve there, as in rs274.
void Interpreter::end_nurbs(Step& step) {
  ModalState& s = step.state;
  const std::uint32_t column = step.nonmodal->column;
  if (step.motion_word && step.motion_code != G_5_2_nurbs)
    fail(Code::E1403, step.motion_word->column,
         "G5.3 with " + code_text('G', step.motion_code) +
             ": only G5.2 may share a block with G5.3 (rs274: \"Between G5.2 and G5.3 codes, "
             "only additional G5.2 codes are allowed.\")");
  std::vector<Eigen::Vector2d> points;
  const Eigen::Vector2d last =
      nurbs_.end(state_.motion == Motion::nurbs, nurbs_frame(step), column, step.b.line, points);
  if (s.feed_mode == program::FeedMode::inverse_time && !step.word('F'))
    fail(Code::E1505, column,
         "G5.3 in inverse time (G93) needs its F word: the curve takes 1/F minutes");
  if (s.feed <= 0.0) fail(Code::E1505, column, "G5.3 with no feed rate (F) in effect");
  const auto ax = program::plane_axes(s.plane);
  auto in_space = [&](const Eigen::Vector2d& p) {
    Eigen::Vector3d q = s.position;
    q[ax[0]] = p.x();
    q[ax[1]] = p.y();
    return q;
  };
  step.emit_inverse_f([&] {
    double path = 0.0;
    Eigen::Vector3d at = s.position;
    for (const auto& p : points) {
      path += (in_space(p) - at).norm();
      at = in_space(p);
    }
    return s.feed * path;
  });
  const auto src = source(step.b, column);
  Eigen::Vector3d from = s.position;
  for (const auto& p : points) {
    const Eigen::Vector3d next = in_space(p);
    step.emit(program::StraightFeed{from, next, src});
    from = next;
  }
  s.position = in_space(last);
  s.moved = true;
  const bool next_curve = step.motion_code == G_5_2_nurbs || (!step.motion_word && step.has_axis);
  if (!next_curve) s.motion = Motion::none;
}

// R arc: the centre on the chord's bisector; R > 0 the short arc (centre
// left of the chord for G3, right for G2), R < 0 the long one.
Eigen::Vector3d Interpreter::centre_from_radius(const Step& step, const Eigen::Vector3d& end,
                                                bool cw) const {
  const ModalState& s = step.state;
  const Word* r = step.word('R');
  const auto ax = program::plane_axes(s.plane);
  Eigen::Vector3d centre = s.position;
  const double a0 = s.position[ax[0]], b0 = s.position[ax[1]];
  const double a1 = end[ax[0]], b1 = end[ax[1]];
  const double radius = length(*r, s.inches);
  const double chord = std::hypot(a1 - a0, b1 - b0);
  if (chord < 1e-9)
    fail(Code::E1501, r->column,
         "R arc with the same start and end point: a full circle needs I/J/K");
  const double half = chord / 2.0;
  const double abs_r = std::abs(radius);
  if (abs_r < 1e-9) fail(Code::E1504, r->column, "arc radius R0");
  if (abs_r < half - kArcRadiusTolerance)
    fail(Code::E1503, r->column,
         "R = " + std::to_string(abs_r) + " mm is smaller than half the chord (" +
             std::to_string(half) + " mm)");
  const double h = abs_r > half ? std::sqrt(abs_r * abs_r - half * half) : 0.0;
  double side = cw ? -1.0 : 1.0;
  if (radius < 0) side = -side;
  const double ua = (a1 - a0) / chord, ub = (b1 - b0) / chord;
  centre[ax[0]] = (a0 + a1) / 2.0 - side * ub * h;
  centre[ax[1]] = (b0 + b1) / 2.0 + side * ua * h;
  return centre;
}

// I, J, K arc: the centre's offsets from the start (G91.1) or its
// coordinates (G90.1); the radii to start and end must agree.
Eigen::Vector3d Interpreter::centre_from_offsets(const Step& step,
                                                 const Eigen::Vector3d& end) const {
  const ModalState& s = step.state;
  const std::uint32_t column = step.motion_column;
  const auto ax = program::plane_axes(s.plane);
  const char letters[3] = {'I', 'J', 'K'};
  const Word* off0 = step.word(letters[ax[0]]);
  const Word* off1 = step.word(letters[ax[1]]);
  Eigen::Vector3d centre = s.position;
  const double a0 = s.position[ax[0]], b0 = s.position[ax[1]];
  const double a1 = end[ax[0]], b1 = end[ax[1]];
  if (!off0 && !off1)
    fail(Code::E1501, column,
         std::string("arc needs ") + letters[ax[0]] + " or " + letters[ax[1]] +
             " (centre) or R (radius)");
  if (off0)
    centre[ax[0]] =
        (s.arc_absolute || off0->absolute ? 0.0 : centre[ax[0]]) + length(*off0, s.inches);
  if (off1)
    centre[ax[1]] =
        (s.arc_absolute || off1->absolute ? 0.0 : centre[ax[1]]) + length(*off1, s.inches);
  const double r0 = std::hypot(a0 - centre[ax[0]], b0 - centre[ax[1]]);
  const double r1 = std::hypot(a1 - centre[ax[0]], b1 - centre[ax[1]]);
  if (r0 < kArcRadiusTolerance || r1 < kArcRadiusTolerance)
    fail(Code::E1504, column, "arc with zero radius at start or end");
  const double err = std::abs(r1 - r0);
  const double tolerance = s.inches ? kCentreArcToleranceInch : kCentreArcToleranceMm;
  if (err > 100.0 * tolerance ||
      (err > tolerance && err / std::max(r0, r1) > kArcRelativeTolerance))
    fail(Code::E1502, column,
         "radius to end " + std::to_string(r1) + " mm differs from radius to start " +
             std::to_string(r0) + " mm");
  return centre;
}

// Stops (M0, M1), program ends (M2, M30; M99 in a main program) come last.
// True for M99 in a subprogram: the caller returns once the block is committed.
bool Interpreter::stop(Step& step) {
  const Word* m = step.m(Group::stopping);
  if (!m) return false;
  const int c = code_of(*m);
  const auto src = source(step.b, m->column);
  bool end_program = false;
  if (c == M_0_stop || c == M_1_optional_stop) {
    step.emit(program::ProgramStop{c == M_1_optional_stop, src});
  } else if (c == M_2_end || c == M_30_end_rewind) {
    end_program = true;
  } else if (c == M_99_return) {
    if (const Word* p = step.word('P'))
      fail(Code::E1301, p->column,
           "M99 P (return to a sequence number) is a jump vcpost does not follow");
    if (!frames_.empty()) return true;
    end_program = true;  // M99 in a main program repeats it on the control: end here
  }
  if (end_program) {
    step.emit(program::SpindleOff{src});
    step.emit(program::SetFeedRate{0.0, program::FeedMode::per_minute, src});
    step.emit(program::ProgramEnd{src});
    ended_ = true;
  }
  return false;
}

}  // namespace vcpost::gcode
