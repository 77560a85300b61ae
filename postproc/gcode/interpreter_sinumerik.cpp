// Sinumerik's parts of the interpreter: its drilling cycles (CYCLE81 ..
// CYCLE89, called once or MCALL'd for every position that follows), the
// CYCLE800 swivel of the working plane, and the control's keywords passed
// through. Sinumerik's statements (R parameter assignments, MSG, MCALL
// ...) are read into the block by block_siemens.cpp.
#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "postproc/gcode/code_names.h"
#include "postproc/gcode/cycles.h"
#include "postproc/gcode/interpreter.h"
#include "postproc/gcode/interpreter_step.h"
#include "postproc/program/working_frame.h"

namespace vcpost::gcode {

using program::Event;

void Interpreter::run_siemens_cycle(ModalState& s, const SiemensCycle& sc,
                                    std::vector<Event>& events) {
  // CYCLE8x(RTP, RFP, SDIS, DP, DPR, ...): retract plane, reference plane,
  // safety distance, depth (absolute) or depth below RFP; an empty argument
  // counts 0, as on the control.
  auto arg = [&](std::size_t k) { return k < sc.args.size() && sc.args[k] ? *sc.args[k] : 0.0; };
  auto given = [&](std::size_t k) { return k < sc.args.size() && sc.args[k].has_value(); };
  auto mm = [&](double v) { return to_mm(v, s.inches); };
  if (s.feed <= 0.0) fail(Code::E1505, sc.column, "drilling cycle with no feed rate (F) in effect");
  if (s.plane != program::Plane::xy)
    fail(Code::E1404, sc.column, "drilling cycles are followed in the XY plane (G17) only");
  const double rtp = mm(arg(0)), rfp = mm(arg(1)), sdis = mm(std::abs(arg(2)));
  const double bottom = given(3) ? mm(arg(3)) : rfp - mm(std::abs(arg(4)));
  CycleCall call;
  call.fanuc = true;
  call.start = s.position;
  call.x = s.position.x();
  call.y = s.position.y();
  call.r = rfp + sdis;
  call.bottom = bottom;
  call.initial = rtp;
  call.retract_to_r = false;
  call.spindle_cw = !s.spindle_ccw;
  call.source = program::SourceRef{block_.line, sc.column, block_.offset};
  switch (sc.number) {
    case 81:
      call.code = G_81_drill;
      break;
    case 82:
      call.code = G_82_drill_dwell;
      call.dwell = arg(5);
      break;
    case 83: {
      // FDEP (absolute) or FDPR (below RFP): the first peck; later pecks of
      // the same depth (the degression DAM is not followed); VARI 0 breaks
      // the chip with a short back-off, 1 lifts to the R plane.
      const double first = given(5) ? rfp - mm(arg(5)) : mm(std::abs(arg(6)));
      if (first <= 0.0)
        fail(Code::E1513, sc.column, "CYCLE83 needs a first drilling depth (FDEP or FDPR)");
      call.code = arg(11) != 0.0 ? G_83_peck_drill : G_73_chip_break_drill;
      call.q = first;
      call.peck_clearance = 1.0;
      call.dwell = arg(8);
      break;
    }
    case 84:
      call.code = G_84_right_hand_tap;
      call.dwell = arg(5);
      break;
    case 85:
      call.code = G_85_bore_feed_out;
      break;
    case 86:
      call.code = G_76_fine_bore;
      call.dwell = arg(5);
      break;
    case 89:
      call.code = G_89_bore_dwell_feed_out;
      call.dwell = arg(5);
      break;
    default:
      fail(Code::E1404, sc.column, "drilling cycle not followed by vcpost");
  }
  if (call.r < call.bottom)
    fail(Code::E1513, sc.column, "the cycle's depth lies above its reference plane");
  const Eigen::Vector3d end = expand_cycle(call, events);
  // The control ends at the retract plane RTP.
  if (end.z() != rtp) {
    events.emplace_back(
        program::StraightTraverse{end, Eigen::Vector3d(end.x(), end.y(), rtp), call.source});
  }
  s.position = Eigen::Vector3d(end.x(), end.y(), rtp);
  s.moved = true;
}

// Sinumerik CYCLE800(_FR, _TC, _ST, _MODE, _X0, _Y0, _Z0, _A, _B, _C, _X1,
// _Y1, _Z1, _DIR, ...): the swivel of the working plane, axis by axis
// (_MODE bits 7-6 = 00; bits 1-0, 3-2, 5-4 name the axes of the first,
// second and third turn, 1 X, 2 Y, 3 Z: 57 is X Y Z, 27 Z Y X), each turn
// about the axis the turns before have left (_A, _B, _C in that order);
// about the reference point X0 Y0 Z0, the new zero X1 Y1 Z1 in the turned
// frame. _ST units 0 a new plane, 1 added to the one in effect. The
// retraction (_FR) and the direction of the rotary axes (_DIR) say how the
// machine gets there: the tool's tip is taken to stay where it is on the
// part, as after G68.2 (docs/tilted-frames.md). CYCLE800() ends the tilt.
void Interpreter::swivel_working_plane(Step& step, const SiemensCycle& sc) {
  auto arg = [&](std::size_t k) { return k < sc.args.size() && sc.args[k] ? *sc.args[k] : 0.0; };
  program::WorkingFrame frame;
  frame.source = program::SourceRef{block_.line, sc.column, block_.offset};
  if (!sc.args.empty()) {
    const double st = arg(2), mode = arg(3);
    const int units = static_cast<int>(std::fmod(std::abs(st), 10.0));
    if (st != std::floor(st) || units > 1)
      fail(Code::E1513, sc.column,
           "CYCLE800 _ST units digit " + std::to_string(units) +
               ": vcpost reads 0 (a new plane) and 1 (added to the plane in effect)");
    if (mode != std::floor(mode) || mode < 0 || mode > 255)
      fail(Code::E1513, sc.column, "CYCLE800 _MODE must be a whole number 0..255");
    const int bits = static_cast<int>(mode);
    if ((bits >> 6) != 0)
      fail(Code::E1404, sc.column,
           "CYCLE800 by projection angles, solid angle or rotary axes direct (_MODE " +
               std::to_string(bits) +
               ") is not read: write the swivel axis by axis (_MODE 57: X Y Z)");
    Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
    for (int k = 0; k < 3; ++k) {
      const int axis = (bits >> (2 * k)) & 3;
      if (axis == 0)
        fail(Code::E1513, sc.column,
             "CYCLE800 _MODE " + std::to_string(bits) + " names no axis for turn " +
                 std::to_string(k + 1) + " (bits 1 X, 2 Y, 3 Z)");
      r = r * program::turn_about(axis - 1, arg(7 + static_cast<std::size_t>(k)));
    }
    const bool inches = step.state.inches;
    const Eigen::Vector3d reference(to_mm(arg(4), inches), to_mm(arg(5), inches),
                                    to_mm(arg(6), inches));
    const Eigen::Vector3d zero(to_mm(arg(10), inches), to_mm(arg(11), inches),
                               to_mm(arg(12), inches));
    // In the frame in effect (additive) or the work system's (new).
    const program::WorkingFrame base = units == 1 ? tilt_ : program::WorkingFrame{};
    frame.rotation = base.rotation * r;
    frame.origin = base.to_program(reference + r * zero);
  }
  set_tilt(step, frame);
}

// Sinumerik: keywords passed through, and the drilling cycles (CYCLE8x
// called once, or MCALL'd for every position that follows).
void Interpreter::siemens_words(Step& step) {
  const Block& b = step.b;
  for (const auto& [name, column] : b.noted_keywords) {
    int key = 0;
    for (char ch : name) key = key * 31 + ch;
    warn_once('K', key, Code::W1406, column,
              name +
                  " is a mode of the control that does not change the path vcpost reads; "
                  "passed through unchanged");
  }
  const SiemensCycle& sc = b.siemens_cycle;
  if (sc.kind == SiemensCycle::Kind::swivel) {
    swivel_working_plane(step, sc);
  } else if (sc.kind == SiemensCycle::Kind::call) {
    run_siemens_cycle(step.state, sc, step.events);
  } else if (sc.kind == SiemensCycle::Kind::modal_call) {
    mcall_next_ = sc;
  } else if (sc.kind == SiemensCycle::Kind::modal_off) {
    mcall_next_ = SiemensCycle{};
  } else if (mcall_.kind == SiemensCycle::Kind::modal_call && step.has_axis) {
    run_siemens_cycle(step.state, mcall_, step.events);
  }
}

}  // namespace vcpost::gcode
