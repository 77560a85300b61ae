#include "postproc/gcode/cycles.h"

namespace vcpost::gcode {

namespace {

class CycleWriter {
 public:
  CycleWriter(const CycleCall& c, std::vector<program::Event>& events, const Eigen::Vector3d& at)
      : c_(c), events_(events), at_(at) {}

  void traverse(double x, double y, double z) {
    const Eigen::Vector3d end(x, y, z);
    events_.emplace_back(program::StraightTraverse{at_, end, c_.source});
    at_ = end;
  }
  void feed(double x, double y, double z) {
    const Eigen::Vector3d end(x, y, z);
    events_.emplace_back(program::StraightFeed{at_, end, c_.source});
    at_ = end;
  }
  void dwell(double seconds) { events_.emplace_back(program::Dwell{seconds, c_.source}); }
  void spindle_off() { events_.emplace_back(program::SpindleOff{c_.source}); }
  void spindle_on(bool cw) {
    events_.emplace_back(program::SpindleOn{
        cw ? program::SpindleDirection::clockwise : program::SpindleDirection::counterclockwise,
        c_.source});
  }
  void stop() { events_.emplace_back(program::ProgramStop{false, c_.source}); }

 private:
  const CycleCall& c_;
  std::vector<program::Event>& events_;
  Eigen::Vector3d at_;
};

// One hole at (x, y), the tool at the R plane above it.
void hole(const CycleCall& c, CycleWriter& w, double x, double y, double clear) {
  const double r = c.r, bottom = c.bottom;
  switch (c.code) {
    case G_81_drill:
      w.feed(x, y, bottom);
      w.traverse(x, y, clear);
      break;
    case G_82_drill_dwell:
      w.feed(x, y, bottom);
      w.dwell(c.dwell);
      w.traverse(x, y, clear);
      break;
    case G_73_chip_break_drill:
    case G_83_peck_drill: {
      // Depth stepped down by Q as rs274 steps it (repeated subtraction, so
      // the pecks land where LinuxCNC puts them); the count was bounded by
      // the cycle-move limit before the block ran.
      double depth = r - c.q;
      while (depth > bottom) {
        w.feed(x, y, depth);
        if (c.code == G_83_peck_drill) w.traverse(x, y, r);
        w.traverse(x, y, depth + c.peck_clearance);
        depth -= c.q;
      }
      w.feed(x, y, bottom);
      w.traverse(x, y, clear);
      break;
    }
    case G_74_left_hand_tap:
    case G_84_right_hand_tap:
      w.feed(x, y, bottom);
      w.spindle_off();
      w.spindle_on(c.code == G_74_left_hand_tap);
      w.dwell(c.dwell);
      w.feed(x, y, clear);
      w.spindle_off();
      w.spindle_on(c.code == G_84_right_hand_tap);
      break;
    case G_85_bore_feed_out:
      w.feed(x, y, bottom);
      w.feed(x, y, r);
      w.traverse(x, y, clear);
      break;
    case G_86_bore_spindle_stop:
    case G_76_fine_bore:  // Fanuc fine boring: oriented stop at the bottom, rapid out, as G86
      w.feed(x, y, bottom);
      w.dwell(c.dwell);
      w.spindle_off();
      w.traverse(x, y, clear);
      w.spindle_on(c.spindle_cw);
      break;
    case G_87_back_bore:
      if (c.fanuc) {
        // Back boring: R is the hole's far side; rapid through with the
        // spindle oriented, bore back up to Z, rapid out to the initial level.
        w.spindle_off();
        w.traverse(x, y, r);
        w.spindle_on(c.spindle_cw);
        w.feed(x, y, bottom);
        w.spindle_off();
        w.traverse(x, y, c.initial);
        w.spindle_on(c.spindle_cw);
      } else {
        w.traverse(x + c.i, y + c.j, r);
        w.spindle_off();
        w.traverse(x + c.i, y + c.j, bottom);
        w.traverse(x, y, bottom);
        w.spindle_on(c.spindle_cw);
        w.feed(x, y, c.k);
        w.feed(x, y, bottom);
        w.spindle_off();
        w.traverse(x + c.i, y + c.j, bottom);
        w.traverse(x + c.i, y + c.j, clear);
        w.traverse(x, y, clear);
        w.spindle_on(c.spindle_cw);
      }
      break;
    case G_88_bore_manual_out:
      w.feed(x, y, bottom);
      w.dwell(c.dwell);
      w.spindle_off();
      w.stop();
      w.spindle_on(c.spindle_cw);
      break;
    case G_89_bore_dwell_feed_out:
      w.feed(x, y, bottom);
      w.dwell(c.dwell);
      w.feed(x, y, clear);
      break;
    default:
      break;
  }
}

}  // namespace

Eigen::Vector3d expand_cycle(const CycleCall& c, std::vector<program::Event>& events) {
  CycleWriter w(c, events, c.start);
  double old_z = c.initial;
  double current_z = c.start.z();
  // Below the R plane: straight up to it first.
  if (old_z < c.r) {
    w.traverse(c.start.x(), c.start.y(), c.r);
    old_z = c.r;
    current_z = old_z;
  }
  const double clear = c.retract_to_r ? c.r : old_z;
  double x = c.x, y = c.y;
  for (int n = 0; n < c.repeats; ++n) {
    x += c.dx;
    y += c.dy;
    if (n == 0 && current_z > c.r) {
      w.traverse(x, y, current_z);
      w.traverse(x, y, c.r);
    } else {
      w.traverse(x, y, clear);
      if (clear > c.r) w.traverse(x, y, c.r);
    }
    hole(c, w, x, y, clear);
  }
  // As rs274: the tool is taken to be at the clearance level over the last
  // hole (G88's operator retract included).
  return Eigen::Vector3d(x, y, c.code == G_87_back_bore && c.fanuc ? c.initial : clear);
}

}  // namespace vcpost::gcode
