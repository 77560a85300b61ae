// Cycles: CYCL DEF (datum shift 7, dwell 9, working plane 19, the
// drilling cycles' Q parameters, machine cycles passed), CYCL CALL [POS] and
// M99, and the drilling cycles 200-208 run as a DrillHole that cycles.h
// expands into moves.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "postproc/heidenhain/cycles.h"
#include "postproc/heidenhain/interpreter.h"
#include "postproc/heidenhain/interpreter_words.h"
#include "postproc/program/working_frame.h"

namespace vcpost::heidenhain {

using program::Event;

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
      if (b == e) fail(Code::E3308, at, "CYCL DEF 9.1 needs the dwell time in seconds");
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
      fail(Code::E3322, at,
           "CYCL DEF " + std::to_string(major) +
               " (mirror, rotation or scaling) changes the frame: it is not read");
    default:
      break;
  }
  if (major >= 300) {
    warn_once(Code::W3340, major, at,
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
    fail(Code::E3307, w.first_word, "CYCL CALL takes a position only as CYCL CALL POS");
  }
  run_cycle(block_.keyword_begin, events);
  end_functions(w, events);
}

void Interpreter::run_cycle(std::uint32_t at, std::vector<Event>& events) {
  if (cycle_ == 0) fail(Code::E3324, at, "a cycle call without a CYCL DEF before it");
  if (cycle_ != 200 && cycle_ != 201 && cycle_ != 203 && cycle_ != 205 && cycle_ != 207 &&
      cycle_ != 208)
    fail(Code::E3322, at,
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
  if (h.depth > 0) fail(Code::E3323, at, "Q201, the depth, is negative (below the surface Q203)");
  if (h.depth == 0) return;  // the control runs no hole of depth 0
  if (cycle_ == 207) {
    const double pitch = length(q(239));
    if (pitch == 0 || spindle_rpm_ <= 0)
      fail(Code::E3323, at, "cycle 207 needs the pitch Q239 and a spindle speed");
    h.feed = std::abs(pitch) * spindle_rpm_;
    h.spindle_ccw = pitch < 0 ? !spindle_ccw_ : spindle_ccw_;
  } else {
    h.feed = feed_rate(q(206));
    if (h.feed <= 0) fail(Code::E3323, at, "Q206, the plunging feed, must be positive");
  }
  if (cycle_ == 200 || cycle_ == 203 || cycle_ == 205) {
    h.plunge = length(q(202));
    if (h.plunge <= 0) fail(Code::E3323, at, "Q202, the plunging depth, must be positive");
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
      fail(Code::E3323, at, "the hole's pecks (Q201 / Q202) make more moves than the limit");
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
  if (pitch <= 0) fail(Code::E3323, at, "Q334, the depth per helix turn, must be positive");
  if (!tool_radius_) {
    warn_once(Code::W3345, 208, at,
              "cycle 208 taken along the hole's axis: its helix needs the tool's radius, which is "
              "in the control's tool table (give the tool with --tool or a CAM comment)");
    return;
  }
  const double radius = nominal / 2 - *tool_radius_;
  if (radius < -1e-9)
    fail(Code::E3323, at, "cycle 208: the tool is wider than the nominal diameter Q335");
  if (radius <= 1e-9) return;  // as wide as the hole: straight down, as the control bores it
  if (std::abs(h.depth) / pitch + 4 > static_cast<double>(limits_.max_cycle_moves))
    fail(Code::E3323, at, "the helix's turns (Q201 / Q334) make more moves than the limit");
  h.helix_radius = radius;
  h.pitch = pitch;
  h.helix_rotation = (q_[351] < 0 ? -1 : 1) * (spindle_ccw_ ? -1 : 1);
}

}  // namespace vcpost::heidenhain
