// The working plane: PLANE in its forms (RESET, SPATIAL, EULER, VECTOR,
// RELATIV, PROJECTED, POINTS, AXIAL) turned into the WorkingFrame the events
// carry, about the datum CYCL DEF 7 set (CYCL DEF 19 comes here through
// tilt()).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "postproc/heidenhain/interpreter.h"
#include "postproc/heidenhain/interpreter_words.h"
#include "postproc/heidenhain/plane_forms.h"
#include "postproc/program/working_frame.h"

namespace vcpost::heidenhain {

using program::Event;

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
      fail(Code::E3303, block_.keyword_begin,
           "PLANE VECTOR needs a normal vector and a base vector not parallel to it");
    rotation = *r;
  } else if (p.kind == "RELATIV") {
    // One incremental spatial angle about the tilted frame's own axis.
    rotation =
        tilt_.rotation * program::spatial_angles(get("SPA", 0), get("SPB", 0), get("SPC", 0));
  } else if (p.kind == "PROJECTED") {
    const auto r = projected_angles(get("PROPR", 0), get("PROMIN", 0), get("ROT", 0));
    if (!r)
      fail(Code::E3320, block_.keyword_begin,
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
        fail(Code::E3320, block_.keyword_begin,
             "PLANE AXIAL with more than one rotary axis turned: the plane depends on the "
             "machine's kinematics (the order of its axes); write the tilt as PLANE SPATIAL");
      rotation = program::turn_about(letter[0] - 'A', angle);
    }
  } else {
    fail(Code::E3320, block_.keyword_begin,
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
    fail(Code::E3320, block_.keyword_begin,
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

}  // namespace vcpost::heidenhain
