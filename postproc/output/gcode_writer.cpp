#include "postproc/output/gcode_writer.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <type_traits>

#include "machines/profile.h"
#include "postproc/output/comment_text.h"
#include "postproc/program/working_frame.h"

namespace vcpost::output {

namespace {

using namespace vcpost::program;

// letter + value, built by appending (GCC 12 warns falsely on "X" + string&&).
std::string word(char letter, std::string_view value) {
  std::string s;
  s.reserve(value.size() + 1);
  s += letter;
  s += value;
  return s;
}

}  // namespace

Format format_for(const machines::MachineProfile& profile) {
  const machines::OutputSpec& o = profile.output();
  Format format;
  format.program_number = o.program_number;
  format.high_speed_mode = o.high_speed_mode;
  format.geometry_compensation = o.geometry_compensation;
  format.work_offset = o.work_offset;
  format.decimals = o.decimals;
  format.feed_decimals = o.feed_decimals;
  format.line_numbers = o.line_numbers;
  format.canned_cycles = o.canned_cycles;
  format.cutter_compensation = o.cutter_compensation;
  format.percent_lines = o.percent_lines;
  format.tool_length_offset = o.tool_length_offset;
  format.manual_tool_change = o.tool_change == machines::ToolChange::manual;
  format.home_before_tool_change = o.tool_change_home;
  format.coolant_mist = o.coolant_mist;
  format.coolant_flood = o.coolant_flood;
  format.coolant_off = o.coolant_off;
  format.speed_output = o.speed_output;
  format.tilted_plane = o.tilted_plane;
  switch (profile.output_format()) {
    case machines::OutputFormat::rs274ngc:
      // LinuxCNC reads `O1000` as a subroutine keyword and G4 X as no dwell
      // time: no O line, G4 P in seconds.
      format.program_number.reset();
      format.dwell = DwellWord::p_seconds;
      format.g83_pecks_out_to_r = false;
      break;
    case machines::OutputFormat::fanuc:
    case machines::OutputFormat::mazak:
    case machines::OutputFormat::heidenhain:  // Klartext has a writer of its own
      format.dwell = DwellWord::x_seconds;    // X with a decimal point: seconds
      break;
  }
  return format;
}

GcodeWriter::GcodeWriter(std::ostream& out, Format format)
    : out_(out), format_(std::move(format)), next_n_(format_.line_number_start) {}

// Fixed-point, the point kept: the Fanuc/Mazak way of marking mm.
std::string GcodeWriter::number(double value, int decimals, const SourceRef& source) const {
  return fixed_number(value, decimals, source);
}

void GcodeWriter::block(std::string_view words) {
  if (format_.line_numbers) {
    out_ << 'N' << next_n_ << ' ';
    next_n_ += format_.line_number_step;
    // N has five digits on Mazak and Fanuc controls (and in rs274): wrap.
    if (next_n_ > 99999) next_n_ = format_.line_number_start;
  }
  out_ << words << format_.end_of_line;
  ++blocks_;
}

void GcodeWriter::comment(std::string_view text) {
  if (!format_.comments) return;
  std::string words = take_pending();
  if (!words.empty()) words += ' ';
  words += '(';
  words += clean_comment(text, CommentEnd::parenthesis);
  words += ')';
  block(words);
}

// The feed words due (G94/G95 only where the mode changes), then the S
// words: the words waiting for the next block.
std::string GcodeWriter::take_pending() {
  std::string words;
  if (pending_feed_) {
    if (pending_feed_->per_revolution != per_revolution_) {
      words = pending_feed_->per_revolution ? "G95 " : "G94 ";
      per_revolution_ = pending_feed_->per_revolution;
    }
    words += pending_feed_->f_word;
    pending_feed_.reset();
  }
  if (!pending_.empty()) {
    if (!words.empty()) words += ' ';
    words += pending_;
    pending_.clear();
  }
  return words;
}

void GcodeWriter::header() {
  started_ = true;
  if (format_.percent_lines) out_ << '%' << format_.end_of_line;
  std::string o;
  if (format_.program_number) o = word('O', std::to_string(*format_.program_number));
  if (!format_.title.empty() && format_.comments) {
    o += '(';
    o += clean_comment(format_.title, CommentEnd::parenthesis);
    o += ')';
  }
  if (!o.empty()) out_ << o << format_.end_of_line;
  block("G21 G17 G40 G49 G80 G90 G94");
  block(word('G', std::to_string(format_.work_offset)));
  if (format_.geometry_compensation) block("G61.1");
}

// G41/G42 D or G40 for a motion's block where the side written is not the
// side wanted (see the header): on a straight move; before an arc, only
// the start of compensation, on a block of its own.
void GcodeWriter::compensation_words(std::string& words, bool straight) {
  if (comp_wanted_ == comp_written_) return;
  if (!straight && comp_written_ != CompensationSide::off) return;
  if (comp_wanted_ != CompensationSide::off && comp_written_ != CompensationSide::off)
    end_compensation();  // G41 -> G42: G40 first
  std::string comp;
  if (comp_wanted_ == CompensationSide::off) {
    comp = "G40";
  } else {
    comp = comp_wanted_ == CompensationSide::left ? "G41" : "G42";
    if (const auto d = comp_register_ ? comp_register_ : tool_) comp += " D" + std::to_string(*d);
  }
  comp_written_ = comp_wanted_;
  if (!straight) {
    block(comp);
    return;
  }
  if (!words.empty()) words += ' ';
  words += comp;
}

void GcodeWriter::end_compensation() {
  if (comp_written_ == CompensationSide::off) return;
  block("G40");
  comp_written_ = CompensationSide::off;
}

void GcodeWriter::end_program() {
  end_cycle();
  end_compensation();
  std::string words = take_pending();
  if (high_speed_on_) {
    block("G05 P0");
    high_speed_on_ = false;
  }
  if (format_.geometry_compensation) block("G64");
  if (format_.tilted_plane == machines::TiltedPlane::g68_2 && !frame_.is_identity()) block("G69");
  if (!words.empty()) block(words);
  block("M30");
  if (format_.percent_lines) out_ << '%' << format_.end_of_line;
  ended_ = true;
}

void GcodeWriter::append_axis(std::string& words, char axis, double value, std::string& last,
                              bool force, const SourceRef& source) {
  std::string text = number(value, format_.decimals, source);
  if (!force && text == last) return;
  words += ' ';
  words += axis;
  words += text;
  last = std::move(text);
}

void GcodeWriter::end_cycle() {
  if (!modal_cycle_) return;
  block("G80");
  modal_cycle_.reset();
  motion_mode_ = -1;
}

// Decides whether the hole that follows is written as its cycle: only where
// the cycle makes the hole's very moves (see the header).
void GcodeWriter::start_hole(const CannedCycle& c) {
  hole_.reset();
  if (!format_.canned_cycles || plane_ != 17 || !at_known_ || c.moves == 0) return;
  const SourceRef& src = c.source;
  const std::string top = number(c.top_z, format_.decimals, src);
  // Above the return level the moves go down diagonally to it: no cycle does.
  if (at_.z() > c.top_z && number(at_.z(), format_.decimals, src) != top) return;
  Hole h;
  h.cycle = c;
  h.events_left = c.events;
  h.lead = at_.z() < c.top_z ? 1 : 0;  // the moves' rapid up to the return level
  if (c.code == 83 && c.r_z != c.top_z && !format_.g83_pecks_out_to_r) return;
  const bool straight_out =
      c.code == 73 || c.code == 81 || c.code == 82 || c.code == 83 || c.code == 85 || c.code == 86;
  h.retract_to_r = !straight_out || c.r_z == c.top_z;
  // G99 leaves the tool at R; the moves end at the return level.
  h.tail = !straight_out && c.r_z != c.top_z ? 1 : 0;
  if (h.lead + h.tail >= c.moves) return;
  hole_ = h;
}

// True when `event` is one of the hole's own events and has been dealt
// with (the cycle block stands for it); its lead and tail moves are not.
bool GcodeWriter::take_hole_event(const Event& event) {
  const bool own = is_motion(event) || std::holds_alternative<Dwell>(event) ||
                   std::holds_alternative<SpindleOn>(event) ||
                   std::holds_alternative<SpindleOff>(event);
  if (!own) return false;
  Hole& h = *hole_;
  bool taken = true;
  if (is_motion(event)) {
    const std::uint32_t index = h.moves_seen++;
    const std::uint32_t last = h.cycle.moves - h.tail;  // one past the cycle's moves
    if (index < h.lead || index >= last) {
      taken = false;
    } else {
      at_ = std::holds_alternative<StraightTraverse>(event) ? std::get<StraightTraverse>(event).end
                                                            : std::get<StraightFeed>(event).end;
      if (index + 1 == last) write_cycle();
    }
  }
  if (--h.events_left == 0) hole_.reset();
  return taken;
}

void GcodeWriter::write_cycle() {
  const Hole& h = *hole_;
  const CannedCycle& c = h.cycle;
  const SourceRef& src = c.source;
  const auto same_cycle = [&](const Hole& m) {
    const CannedCycle& o = m.cycle;
    return o.code == c.code && o.r_z == c.r_z && o.bottom_z == c.bottom_z && o.peck == c.peck &&
           o.dwell_s == c.dwell_s && m.retract_to_r == h.retract_to_r &&
           (h.retract_to_r || initial_z_ == c.top_z);
  };
  std::string words;
  end_compensation();  // rs274 runs no cycle under compensation
  // A speed output's Q is not the cycle's (its peck): its own block, set
  // at the start of the cycle's first move.
  if (format_.speed_output && !pending_.empty()) block(take_pending());
  if (pending_g43_) {
    block("G43 H" + std::to_string(*pending_g43_));
    pending_g43_.reset();
  }
  const bool new_cycle = !modal_cycle_ || !same_cycle(*modal_cycle_);
  if (new_cycle) end_cycle();
  // A feed mode change goes on a block of its own before the cycle's: the
  // cycle's F is then read in the mode it is meant in (G94 for a drill
  // after a per-revolution contour, G95 for a tap), on every control.
  if (pending_feed_ && pending_feed_->per_revolution != per_revolution_) {
    per_revolution_ = pending_feed_->per_revolution;
    block(per_revolution_ ? "G95" : "G94");
  }
  if (new_cycle) {
    // The G98 level is where the tool stands when the cycle starts: the
    // return level (start_hole saw to it).
    initial_z_ = c.top_z;
    words = h.retract_to_r ? "G99 G" : "G98 G";
    words += std::to_string(c.code);
    append_axis(words, 'X', c.x, last_x_, true, src);
    append_axis(words, 'Y', c.y, last_y_, true, src);
    std::string ignored;
    append_axis(words, 'Z', c.bottom_z, ignored, true, src);
    append_axis(words, 'R', c.r_z, ignored, true, src);
    if (c.code == 73 || c.code == 83) append_axis(words, 'Q', c.peck, ignored, true, src);
    if (c.code == 82 || c.code == 84 || c.code == 86 || c.code == 89) {
      // Always given: P is modal, and G84 dwells with an earlier cycle's P.
      words += " P";
      words += format_.dwell == DwellWord::p_seconds
                   ? number(c.dwell_s, 3, src)
                   : std::to_string(std::lround(c.dwell_s * 1000));
    }
    modal_cycle_ = h;
  } else {
    append_axis(words, 'X', c.x, last_x_, true, src);
    append_axis(words, 'Y', c.y, last_y_, true, src);
    words.erase(0, 1);
  }
  std::string pending = take_pending();
  if (!pending.empty()) words += ' ' + pending;
  block(words);
  motion_mode_ = -1;
  last_z_ = number(at_.z(), format_.decimals, src);
}

void GcodeWriter::motion(const Event& event) {
  std::string words;
  const SourceRef source = source_of(event);
  end_cycle();
  if (pending_g43_) {
    if (!std::holds_alternative<StraightTraverse>(event)) {
      block("G43 H" + std::to_string(*pending_g43_));
    } else {
      words = "G43 H" + std::to_string(*pending_g43_);
    }
    pending_g43_.reset();
  }
  compensation_words(words, !std::holds_alternative<ArcFeed>(event));
  const auto motion_word = [&](int mode) {
    if (mode != motion_mode_) {
      if (!words.empty()) words += ' ';
      words += mode == 0 ? "G0" : mode == 1 ? "G1" : mode == 2 ? "G2" : "G3";
      motion_mode_ = mode;
    }
  };
  if (const auto* t = std::get_if<StraightTraverse>(&event)) {
    motion_word(0);
    const std::size_t before = words.size();
    append_axis(words, 'X', t->end.x(), last_x_, false, source);
    append_axis(words, 'Y', t->end.y(), last_y_, false, source);
    append_axis(words, 'Z', t->end.z(), last_z_, false, source);
    if (words.size() == before) {  // no change: keep one block per move
      append_axis(words, 'X', t->end.x(), last_x_, true, source);
      append_axis(words, 'Y', t->end.y(), last_y_, true, source);
      append_axis(words, 'Z', t->end.z(), last_z_, true, source);
    }
  } else if (const auto* f = std::get_if<StraightFeed>(&event)) {
    motion_word(1);
    const std::size_t before = words.size();
    append_axis(words, 'X', f->end.x(), last_x_, false, source);
    append_axis(words, 'Y', f->end.y(), last_y_, false, source);
    append_axis(words, 'Z', f->end.z(), last_z_, false, source);
    if (words.size() == before) {
      append_axis(words, 'X', f->end.x(), last_x_, true, source);
      append_axis(words, 'Y', f->end.y(), last_y_, true, source);
      append_axis(words, 'Z', f->end.z(), last_z_, true, source);
    }
  } else if (const auto* a = std::get_if<ArcFeed>(&event)) {
    if (std::abs(a->rotation) != 1) {
      throw OutputError(Code::E3201, "arc of more than one turn (P word) is not written", source);
    }
    const int plane = a->plane == Plane::xy ? 17 : a->plane == Plane::xz ? 18 : 19;
    if (plane != plane_) {
      if (!words.empty()) words += ' ';
      words += word('G', std::to_string(plane));
      plane_ = plane;
    }
    // rotation > 0 is counterclockwise seen from the plane normal's + side:
    // G3 (rs274 and Fanuc agree, also in G18 with its Z-X orientation).
    motion_mode_ = -1;  // always write G2/G3 with an arc
    motion_word(a->rotation > 0 ? 3 : 2);
    const Eigen::Vector3d offset = a->centre - a->start;
    const bool xy = plane == 17, xz = plane == 18, yz = plane == 19;
    append_axis(words, 'X', a->end.x(), last_x_, xy || xz, source);
    append_axis(words, 'Y', a->end.y(), last_y_, xy || yz, source);
    append_axis(words, 'Z', a->end.z(), last_z_, xz || yz, source);
    std::string ignored;
    if (!yz) append_axis(words, 'I', offset.x(), ignored, true, source);
    if (!xz) append_axis(words, 'J', offset.y(), ignored, true, source);
    if (!xy) append_axis(words, 'K', offset.z(), ignored, true, source);
  }
  std::string pending = take_pending();
  if (!pending.empty()) words += ' ' + pending;
  if (!words.empty() && words.front() == ' ') words.erase(0, 1);
  block(words);
  at_known_ = true;
  at_ = std::holds_alternative<StraightTraverse>(event) ? std::get<StraightTraverse>(event).end
        : std::holds_alternative<StraightFeed>(event)   ? std::get<StraightFeed>(event).end
                                                        : std::get<ArcFeed>(event).end;
}

void GcodeWriter::write(const Event& event) {
  if (ended_) return;  // nothing follows M30
  if (!started_) header();
  if (const auto* c = std::get_if<CannedCycle>(&event)) {
    start_hole(*c);
    return;
  }
  if (hole_ && take_hole_event(event)) return;
  std::visit(
      [&](const auto& e) {
        using T = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<T, StraightTraverse> || std::is_same_v<T, StraightFeed> ||
                      std::is_same_v<T, ArcFeed>) {
          motion(event);
        } else {
          write_event(e);
        }
      },
      event);
}

void GcodeWriter::write_event(const SetFeedRate& e) {
  if (e.mode == FeedMode::inverse_time) {
    throw OutputError(Code::E3202, "inverse-time feed (G93) is not written", e.source);
  }
  // A later F replaces an unwritten one, and its mode the unwritten mode:
  // one G94/G95 at most per block.
  const bool per_rev = e.mode == FeedMode::per_revolution;
  pending_feed_ = PendingFeed{
      per_rev, word('F', number(e.rate, per_rev ? 4 : format_.feed_decimals, e.source))};
}

void GcodeWriter::write_event(const SetSpindleSpeed& e) {
  const long s = std::lround(e.rpm);
  if (format_.speed_output && s > 0) {
    // One speed per block: a later one replaces an unwritten one.
    const std::string analog =
        " E" + std::to_string(*format_.speed_output) + " Q" + std::to_string(s);
    pending_ = spindle_on_ ? "M67" + analog : "S" + std::to_string(s) + " M68" + analog;
  } else {
    pending_ += (pending_.empty() ? "S" : " S") + std::to_string(s);
  }
}

void GcodeWriter::write_event(const SpindleOn& e) {
  std::string words = take_pending();
  words += words.empty() ? "" : " ";
  spindle_ccw_ = e.direction != SpindleDirection::clockwise;
  words += spindle_ccw_ ? "M4" : "M3";
  block(words);
  spindle_on_ = true;
}

void GcodeWriter::write_event(const SpindleOff& /*e*/) {
  std::string words = take_pending();
  block(words.empty() ? "M5" : words + " M5");
  spindle_on_ = false;
}

void GcodeWriter::write_event(const SelectTool& e) {
  std::string words = take_pending();
  block((words.empty() ? "" : words + " ") + "T" + std::to_string(e.number));
}

void GcodeWriter::write_event(const ChangeTool& e) { change_tool(e); }

void GcodeWriter::write_event(const ToolLengthOffset& e) {
  if (e.enabled) {
    block("G43 H" + std::to_string(e.register_number.value_or(0)));
  } else {
    block("G49");
  }
  pending_g43_.reset();
}

// Written with the next move (compensation_words).
void GcodeWriter::write_event(const CutterCompensation& e) {
  if (!format_.cutter_compensation) {
    comment(e.side == CompensationSide::off    ? "CUTCOM OFF"
            : e.side == CompensationSide::left ? "CUTCOM LEFT - CL PATH IS THE TOOL CENTRE"
                                               : "CUTCOM RIGHT - CL PATH IS THE TOOL CENTRE");
  } else if (e.side != comp_wanted_ || e.register_number != comp_register_) {
    if (e.side != CompensationSide::off && e.side == comp_written_)
      end_compensation();  // another register: G41 again after G40
    comp_wanted_ = e.side;
    comp_register_ = e.register_number;
  }
}

void GcodeWriter::write_event(const SelectPlane& e) {
  const int plane = e.plane == Plane::xy ? 17 : e.plane == Plane::xz ? 18 : 19;
  if (plane != plane_) {
    block(word('G', std::to_string(plane)));
    plane_ = plane;
  }
}

void GcodeWriter::write_event(const Coolant& e) {
  std::string words = take_pending();
  words += words.empty() ? "" : " ";
  words += e.change == CoolantChange::flood_on  ? format_.coolant_flood
           : e.change == CoolantChange::mist_on ? format_.coolant_mist
                                                : format_.coolant_off;
  block(words);
}

void GcodeWriter::write_event(const Dwell& e) {
  std::string words = take_pending();
  words += words.empty() ? "G4 " : " G4 ";
  switch (format_.dwell) {
    case DwellWord::x_seconds:
      words += word('X', number(e.seconds, 3, e.source));
      break;
    case DwellWord::p_seconds:
      words += word('P', number(e.seconds, 3, e.source));
      break;
    case DwellWord::p_milliseconds:
      words += word('P', std::to_string(std::lround(e.seconds * 1000)));
      break;
  }
  block(words);
}

void GcodeWriter::write_event(const ProgramStop& e) {
  std::string words = take_pending();
  block((words.empty() ? "" : words + " ") + (e.optional ? "M1" : "M0"));
}

void GcodeWriter::write_event(const ProgramEnd& /*e*/) { end_program(); }

void GcodeWriter::write_event(const Message& e) { comment(e.text); }

void GcodeWriter::write_event(const WorkingFrame& e) { working_frame(e); }

// Taken by write() before (start_hole).
void GcodeWriter::write_event(const CannedCycle& /*e*/) {}

void GcodeWriter::change_tool(const program::ChangeTool& change) {
  end_cycle();
  end_compensation();
  comp_wanted_ = CompensationSide::off;  // a tool change ends it
  tool_ = change.number;
  // The tool changes untilted (the change position is the machine's).
  const bool retilt = format_.tilted_plane == machines::TiltedPlane::g68_2 && !frame_.is_identity();
  if (retilt) block("G69");
  if (high_speed_on_) {
    block("G05 P0");
    high_speed_on_ = false;
  }
  switch (format_.home_before_tool_change) {
    case machines::ToolChangeHome::none:
      break;
    case machines::ToolChangeHome::g28:
      // Incremental Z0: straight up from here, then to the reference point.
      block("G91 G28 Z0.");
      block("G90");
      break;
    case machines::ToolChangeHome::g53:
      block("G53 G0 Z0.");
      break;
  }
  if (format_.home_before_tool_change != machines::ToolChangeHome::none) {
    last_z_.clear();  // Z is no longer where the program left it
    at_known_ = false;
  }
  std::string words = take_pending();
  if (!words.empty()) words += ' ';
  const std::string t = "T" + std::to_string(change.number);
  if (format_.manual_tool_change) {
    if (spindle_on_) block("M5");
    comment("TOOL CHANGE: LOAD " + t + ", THEN CYCLE START");
    block(words + t + " M0");
  } else {
    block(words + t + " M6");
  }
  spindle_on_ = false;  // M6 stops the spindle too (LinuxCNC, Fanuc machine macros)
  if (retilt) tilt(frame_);
  if (format_.tool_length_offset) pending_g43_ = change.number;
  if (format_.high_speed_mode) {
    block("G05 P2");
    high_speed_on_ = true;
  }
  motion_mode_ = -1;
}

void GcodeWriter::working_frame(const WorkingFrame& frame) {
  if (frame.rotation == frame_.rotation && frame.origin == frame_.origin) return;
  end_cycle();
  end_compensation();
  if (format_.tilted_plane == machines::TiltedPlane::setup) {
    new_setup(frame);
  } else {
    if (!frame_.is_identity()) block("G69");
    if (!frame.is_identity()) tilt(frame);
  }
  frame_ = frame;
  // Every axis on the next move: the positions are in another frame.
  last_x_.clear();
  last_y_.clear();
  last_z_.clear();
  motion_mode_ = -1;
  at_known_ = false;
}

// G68.2 X Y Z I J K, G53.1: the frame in effect from here.
void GcodeWriter::tilt(const WorkingFrame& frame) {
  const SourceRef& src = frame.source;
  const Eigen::Vector3d angles = program::euler_zxz_of(frame.rotation);
  std::string words = "G68.2";
  std::string ignored;
  append_axis(words, 'X', frame.origin.x(), ignored, true, src);
  append_axis(words, 'Y', frame.origin.y(), ignored, true, src);
  append_axis(words, 'Z', frame.origin.z(), ignored, true, src);
  // Angles to 0.0001 deg (a Fanuc 30i's IS-C increment): 1 um at 570 mm.
  for (int k = 0; k < 3; ++k) {
    words += ' ';
    words += static_cast<char>('I' + k);
    words += fixed_number(angles[k], 4, src);
  }
  block(words);
  block("G53.1");
}

void GcodeWriter::new_setup(const WorkingFrame& frame) {
  const auto same = [&](const WorkingFrame& f) {
    return f.rotation == frame.rotation && f.origin == frame.origin;
  };
  if (setups_.empty()) setups_.emplace_back();  // the untilted set-up, the first
  auto at = std::find_if(setups_.begin(), setups_.end(), same);
  const auto number = static_cast<int>(at - setups_.begin()) + 1;
  const int offset = format_.work_offset + number - 1;
  if (offset > 59) {
    throw OutputError(Code::E3205,
                      "set-up " + std::to_string(number) + " needs work offset G" +
                          std::to_string(offset) +
                          ", beyond G59 (output.tilted_plane \"setup\", "
                          "output.work_offset G" +
                          std::to_string(format_.work_offset) + ")",
                      frame.source);
  }
  if (at == setups_.end()) setups_.push_back(frame);
  const bool turning = spindle_on_;
  if (turning) {
    block("M5");
    spindle_on_ = false;
  }
  const std::string g = word('G', std::to_string(offset));
  comment(setup_instruction(number, frame, g));
  block("M0");
  block(g);
  if (turning) {
    block(spindle_ccw_ ? "M4" : "M3");
    spindle_on_ = true;
  }
}

void GcodeWriter::finish() {
  if (!started_) header();
  if (!ended_) end_program();
  out_.flush();
}

}  // namespace vcpost::output
