#include "postproc/cldata/cl_reader.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <utility>

#include "core/text.h"
#include "postproc/cldata/nurbs.h"

namespace vcpost::cldata {

namespace {

using program::SourceRef;
using Vec = Eigen::Vector3d;

constexpr double mm_per_inch = 25.4;

std::string fixed(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4f", v);
  return buffer;
}

// Six significant digits: a value of any size in one short word (1e+300).
std::string general(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

std::string xyz(const Vec& v) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "(%.4f, %.4f, %.4f)", v.x(), v.y(), v.z());
  return buffer;
}

}  // namespace

ClReader::ClReader(std::istream& in, std::string file_name, ClReadOptions options)
    : lexer_(in, std::move(file_name), options.lex), options_(options) {}

void ClReader::fail(Code code, std::uint32_t line, std::uint32_t column,
                    std::string message) const {
  throw ClError(ClDiagnostic{code, line, column, std::move(message)}, lexer_.file_name());
}

void ClReader::fail(Code code, const ClRecord& r, std::string message) const {
  fail(code, r.source.line, r.source.column, std::move(message));
}

void ClReader::fail(Code code, const ClParam& p, std::string message) const {
  fail(code, p.line, p.column, std::move(message));
}

void ClReader::warn(Code code, const SourceRef& src, std::string message) {
  warnings_.push_back(ClDiagnostic{code, src.line, src.column, std::move(message)});
}

bool ClReader::word_is(const ClParam& p, std::string_view upper_word) const {
  if (p.is_number || p.text.size() != upper_word.size()) return false;
  for (std::size_t i = 0; i < upper_word.size(); ++i) {
    char c = p.text[i];
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
    if (c != upper_word[i]) return false;
  }
  return true;
}

double ClReader::number(const ClRecord& r, std::size_t i) const {
  if (i >= r.params.size()) {
    fail(Code::E3104, r,
         std::string(r.major.empty() ? "coordinates" : r.major) + " needs at least " +
             std::to_string(i + 1) + " parameters, has " + std::to_string(r.params.size()));
  }
  const ClParam& p = r.params[i];
  if (p.is_number) return p.value;
  if (p.text.empty()) fail(Code::E3103, p, "empty parameter where a number is expected");
  const char c = p.text.front();
  if ((c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.') {
    std::string_view t = p.text.substr(c == '+' ? 1 : 0);
    double v = 0;
    const auto parsed = std::from_chars(t.data(), t.data() + t.size(), v);
    if (parsed.ec == std::errc::result_out_of_range ||
        (parsed.ec == std::errc() && parsed.ptr == t.data() + t.size() && std::isfinite(v)))
      fail(Code::E3103, p,
           "number '" + std::string(p.text) + "' is out of range (at most 1e12 either way)");
    fail(Code::E3103, p, "malformed number '" + std::string(p.text) + "'");
  }
  fail(Code::E3104, p, "expected a number, found '" + std::string(p.text) + "'");
}

int ClReader::integer(const ClRecord& r, std::size_t i) const {
  const double v = number(r, i);
  if (v < 0 || v > 1e9 || v != std::floor(v)) {
    fail(Code::E3104, r.params[i],
         "expected a whole number, found '" + std::string(r.params[i].text) + "'");
  }
  return static_cast<int>(v);
}

void ClReader::require_numbers(const ClRecord& r) const {
  for (std::size_t i = 0; i < r.params.size(); ++i) number(r, i);
}

void ClReader::check_axis(const Vec& axis, std::uint32_t line, std::uint32_t column) {
  const double n = axis.norm();
  if (!(n > 0) || (axis / n - csys_.axis).norm() > options_.axis_tolerance) {
    if (csys_.frame.is_identity()) {
      fail(Code::E3108, line, column,
           "tool axis " + xyz(axis) +
               " is not +Z: a tilted tool (3+2) needs the CSYS of its frame first, and a tool "
               "axis that changes along the path (5-axis simultaneous) is not evaluated yet");
    }
    fail(Code::E3108, line, column,
         "tool axis " + xyz(axis) + " is not the CSYS frame's z axis " + xyz(csys_.axis) +
             ": a tool axis that changes along the path (5-axis simultaneous) is not evaluated "
             "yet; a fixed tilt (3+2) is, with the CSYS of its frame");
  }
}

std::optional<program::Event> ClReader::next() {
  while (queue_.empty()) {
    if (end_.input_done) return std::nullopt;
    if (!lexer_.next(record_)) {
      finish_input();
      end_.input_done = true;
      continue;
    }
    ++records_;
    process(record_);
  }
  program::Event e = std::move(queue_.front());
  queue_.pop_front();
  return e;
}

void ClReader::finish_input() {
  if (nurbs_.active) finish_nurbs();
  if (next_motion_.arc_pending) {
    fail(Code::E3110, next_motion_.arc_pending->source.line,
         next_motion_.arc_pending->source.column,
         "CIRCLE is not followed by a GOTO before the end of the file");
  }
  if (!end_.fini_seen) {
    if (!end_.end_of_path) {
      warn(Code::W3151, SourceRef{lexer_.line_number(), 1, 0},
           "the file ends without FINI or END-OF-PATH: it may be truncated");
    }
    queue_.push_back(program::ProgramEnd{last_source_});
  }
}

void ClReader::process(const ClRecord& r) {
  if (r.kind == ClRecordKind::comment) {
    if (!end_.fini_seen) {
      creo_cutter_comment(r);
      comment(r);
    }
    return;
  }
  if (end_.fini_seen) {
    if (warnings_.empty() || warnings_.back().code != Code::W3152) {
      warn(Code::W3152, r.source, "records after FINI are ignored");
    }
    return;
  }
  last_source_ = r.source;
  if (r.kind == ClRecordKind::points) {
    if (nurbs_.active) finish_nurbs();
    if (!next_motion_.in_goto) {
      fail(Code::E3107, r,
           "a line of coordinates must follow a GOTO record (or end the previous one with '$')");
    }
    process_motion_points(r, true);
    return;
  }
  const std::string_view m = r.major;
  if (nurbs_.active && m != "KNOT" && m != "CNTRL") finish_nurbs();
  end_.end_of_path = false;

  if (m == "GOTO") {
    next_motion_.in_goto = true;
    next_motion_.rapid_active = std::exchange(next_motion_.rapid_pending, false);
    if (next_motion_.arc_pending)
      next_motion_.arc_active = std::exchange(next_motion_.arc_pending, std::nullopt);
    else
      next_motion_.arc_active.reset();
    process_motion_points(r, false);
    return;
  }
  next_motion_.in_goto = false;
  next_motion_.arc_active.reset();
  next_motion_.rapid_active = false;

  if (r.separator == '=') apt_source(r);
  const RecordRule* rule = find_rule(m);
  if (rule == nullptr) {
    fail(Code::E3118, r,
         "'" + std::string(m) +
             "' is not a record vcpost knows; it is refused rather than "
             "ignored, since it may move the tool or change the frame (record: " +
             std::string(m) + (r.text.empty() ? "" : "/" + std::string(r.text)) + ")");
  }
  (this->*(rule->handler))(r);
}

// --- one handler per record family ------------------------------------------

void ClReader::rapid(const ClRecord& /*record*/) { next_motion_.rapid_pending = true; }

void ClReader::from(const ClRecord& r) {
  require_numbers(r);
  if (r.params.size() != 3 && r.params.size() != 6) {
    fail(Code::E3104, r, "FROM needs x,y,z or x,y,z,i,j,k");
  }
  if (r.params.size() == 6) {
    check_axis(Vec(number(r, 3), number(r, 4), number(r, 5)), r.params[3].line, r.params[3].column);
  }
  position_ = place(unit_ * Vec(number(r, 0), number(r, 1), number(r, 2)));
}

void ClReader::godlta(const ClRecord& r) {
  require_numbers(r);
  if (!position_) {
    fail(Code::E3114, r, "GODLTA before any FROM or GOTO: no position to move from");
  }
  Vec delta;
  if (r.params.size() == 1) {
    delta = unit_ * number(r, 0) * Vec::UnitZ();
  } else if (r.params.size() == 3 || r.params.size() == 6) {
    delta = csys_.rotation * (unit_ * Vec(number(r, 0), number(r, 1), number(r, 2)));
    if (r.params.size() == 6) {
      check_axis(Vec(number(r, 3), number(r, 4), number(r, 5)), r.params[3].line,
                 r.params[3].column);
    }
  } else {
    fail(Code::E3104, r, "GODLTA needs d, or dx,dy,dz[,i,j,k]");
  }
  next_motion_.rapid_active = std::exchange(next_motion_.rapid_pending, false);
  if (next_motion_.arc_pending) {
    fail(Code::E3110, next_motion_.arc_pending->source.line,
         next_motion_.arc_pending->source.column, "CIRCLE must be followed by GOTO, not GODLTA");
  }
  begin_motion(r.source);
  move_to(*position_ + delta, r.source);
  next_motion_.rapid_active = false;
}

void ClReader::loadtl(const ClRecord& r) {
  queue_.push_back(program::ChangeTool{integer(r, 0), r.source});
  tool_changed(integer(r, 0));
}

void ClReader::tool_changed(int number) {
  tool_.in_spindle = number;
  tool_.named.reset();
  tool_.toolno_pending = false;
  tool_.moved = false;
  tool_.new_cutter.reset();
}

// TOOLNO/n[,diameter,...]: the number of the tool change to come.
void ClReader::toolno(const ClRecord& r) {
  tool_.named = integer(r, 0);
  tool_.toolno_pending = true;
}

// After a cutter record: another cutter than the section's, once the
// section has moved, is a tool change (made at the next motion).
void ClReader::note_cutter(const ClRecord& r) {
  if (!tool_.moved || !tool_.section_cutter) return;
  const ClCutter& now = cutters_[*tool_.section_cutter];
  const ClCutter& next = cutters_.back();
  if (now.source_word == next.source_word && now.params == next.params) return;
  tool_.new_cutter =
      NewCutter{std::string(r.major) + "/" + std::string(r.text), r.source.line, r.source.column};
}

// Before the events of a motion record: the tool change TOOLNO or another
// cutter asked for, and the section's cutter at its first motion.
void ClReader::begin_motion(const SourceRef& src) {
  const bool toolno_change = tool_.toolno_pending && tool_.named != tool_.in_spindle;
  tool_.toolno_pending = false;
  if (tool_.new_cutter || toolno_change) {
    if (!tool_.named) {
      fail(Code::E3120, tool_.new_cutter->line, tool_.new_cutter->column,
           tool_.new_cutter->record +
               " is another tool than the one cutting, but no LOAD/TOOL, LOADTL, TOOLNO or "
               "SELECT/TOOL gives its number: the tool change cannot be written (give the tool "
               "numbers in the CAM system)");
    }
    const int number = *tool_.named;
    queue_.push_back(program::ChangeTool{number, src});
    tool_changed(number);
  }
  if (!tool_.moved) {
    tool_.moved = true;
    if (!cutters_.empty()) tool_.section_cutter = cutters_.size() - 1;
  }
}

// LOAD/TOOL,n[,ADJUST,h] and SELECT/TOOL,n.
void ClReader::load_or_select(const ClRecord& r) {
  const std::string_view m = r.major;
  if (r.params.empty() || !word_is(r.params[0], "TOOL")) {
    fail(Code::E3105, r, std::string(m) + " is understood only as " + std::string(m) + "/TOOL,n");
  }
  if (r.params.size() > 2 &&
      !(m == "LOAD" && r.params.size() == 4 && word_is(r.params[2], "ADJUST"))) {
    fail(Code::E3105, r.params[2],
         "'" + std::string(r.params[2].text) + "' after " + std::string(m) +
             "/TOOL,n is not understood (ADJUST,h is, after LOAD)");
  }
  if (r.params.size() == 4) {
    // The length register: G43 H uses the tool number, which it must equal.
    if (integer(r, 3) != integer(r, 1)) {
      fail(Code::E3105, r.params[3],
           "LOAD/TOOL,n,ADJUST,h with h other than n: the output's G43 uses H = the tool number");
    }
  }
  if (m == "LOAD") {
    queue_.push_back(program::ChangeTool{integer(r, 1), r.source});
    tool_changed(integer(r, 1));
  } else {
    queue_.push_back(program::SelectTool{integer(r, 1), r.source});
    tool_.named = integer(r, 1);
  }
}

void ClReader::units(const ClRecord& r) {
  if (r.params.size() != 1) fail(Code::E3116, r, "UNITS needs one word: MM or INCHES");
  const ClParam& p = r.params[0];
  if (word_is(p, "MM")) {
    unit_ = 1.0;
  } else if (word_is(p, "INCHES") || word_is(p, "INCH") || word_is(p, "IN")) {
    unit_ = mm_per_inch;
  } else if (word_is(p, "CM")) {
    unit_ = 10.0;
  } else {
    fail(Code::E3116, p, "unknown units '" + std::string(p.text) + "'");
  }
}

void ClReader::coolnt(const ClRecord& r) {
  using program::CoolantChange;
  if (r.params.empty()) fail(Code::E3104, r, "COOLNT needs ON, FLOOD, MIST or OFF");
  const ClParam& p = r.params[0];
  CoolantChange change = CoolantChange::flood_on;
  if (word_is(p, "ON") || word_is(p, "FLOOD")) {
    change = CoolantChange::flood_on;
  } else if (word_is(p, "MIST")) {
    change = CoolantChange::mist_on;
  } else if (word_is(p, "OFF")) {
    change = CoolantChange::off;
  } else if (word_is(p, "THRU") || word_is(p, "AIR") || word_is(p, "TAPKUL")) {
    warn(Code::W3154, r.source, "COOLNT/" + std::string(p.text) + " is written as flood coolant");
  } else {
    fail(Code::E3105, p, "unknown COOLNT word '" + std::string(p.text) + "'");
  }
  queue_.push_back(program::Coolant{change, r.source});
}

// CUTCOM/LEFT|RIGHT|OFF[,XYPLAN][,register]; CAMWorks' CUTCOM/ON before the side.
void ClReader::cutcom(const ClRecord& r) {
  using program::CompensationSide;
  if (r.params.empty()) fail(Code::E3104, r, "CUTCOM needs LEFT, RIGHT or OFF");
  const ClParam& p = r.params[0];
  CompensationSide side = CompensationSide::off;
  if (word_is(p, "ON")) return;  // CAMWorks: the side follows in its own record
  if (word_is(p, "LEFT")) {
    side = CompensationSide::left;
  } else if (word_is(p, "RIGHT")) {
    side = CompensationSide::right;
  } else if (!word_is(p, "OFF")) {
    fail(Code::E3105, p, "unknown CUTCOM word '" + std::string(p.text) + "'");
  }
  std::optional<int> register_number;
  for (std::size_t i = 1; i < r.params.size(); ++i) {
    const ClParam& q = r.params[i];
    if (word_is(q, "XYPLAN")) continue;
    if (q.is_number && !register_number) {
      register_number = integer(r, i);
      continue;
    }
    fail(Code::E3105, q,
         "CUTCOM/" + std::string(p.text) + "," + std::string(q.text) +
             ": only the XYPLAN plane and one register number are understood");
  }
  queue_.push_back(program::CutterCompensation{side, r.source, register_number});
}

void ClReader::delay(const ClRecord& r) {
  double seconds = 0;
  if (!r.params.empty() && word_is(r.params[0], "REV")) {
    if (!(spindle_.rpm > 0)) fail(Code::E3104, r, "DELAY/REV with the spindle stopped");
    seconds = number(r, 1) * 60.0 / spindle_.rpm;
  } else {
    seconds = number(r, 0);
  }
  if (seconds < 0) fail(Code::E3104, r, "DELAY must not be negative");
  queue_.push_back(program::Dwell{seconds, r.source});
}

void ClReader::stop(const ClRecord& r) {
  queue_.push_back(program::ProgramStop{r.major == "OPSTOP", r.source});
}

void ClReader::fini(const ClRecord& r) {
  if (cycle_.active) cycle_.active.reset();
  queue_.push_back(program::ProgramEnd{r.source});
  end_.fini_seen = true;
}

void ClReader::end_of_path(const ClRecord& /*record*/) { end_.end_of_path = true; }

// A `$$` comment record: a comment of the output, where it stands (the
// CAM system's operation names, notes for the operator), blanks trimmed.
void ClReader::comment(const ClRecord& r) {
  std::string_view t = r.text;
  while (!t.empty() && (t.front() == ' ' || t.front() == '\t')) t.remove_prefix(1);
  while (!t.empty() && (t.back() == ' ' || t.back() == '\t' || t.back() == '\r'))
    t.remove_suffix(1);
  if (!t.empty()) queue_.push_back(program::Message{std::string(t), r.source});
}

// Text the output carries as a comment.
void ClReader::message(const ClRecord& r) {
  const std::string_view m = r.major;
  if (m == "PPRINT") {
    queue_.push_back(program::Message{std::string(r.text), r.source});
  } else if (m == "PARTNO" || m == "INSERT") {
    queue_.push_back(program::Message{std::string(m) + " " + std::string(r.text), r.source});
  } else {
    queue_.push_back(program::Message{std::string(m) + "/" + std::string(r.text), r.source});
  }
}

void ClReader::tlaxis(const ClRecord& r) {
  require_numbers(r);
  if (r.params.size() < 3) fail(Code::E3104, r, "TLAXIS needs i,j,k");
  check_axis(Vec(number(r, 0), number(r, 1), number(r, 2)), r.params[0].line, r.params[0].column);
}

// MULTAX[/ON|OFF]: GOTOs carry i,j,k, each checked to be +Z.
void ClReader::multax(const ClRecord& r) {
  multax_ = r.params.empty() || !word_is(r.params[0], "OFF");
}

void ClReader::nurbs(const ClRecord& r) {
  if (!r.params.empty()) {
    fail(Code::E3111, r, "NURBS/ with parameters is not understood");
  }
  if (!position_) fail(Code::E3114, r, "NURBS before any position");
  begin_motion(r.source);
  nurbs_.active = true;
  nurbs_.rapid = std::exchange(next_motion_.rapid_pending, false);
  nurbs_.source = r.source;
  nurbs_.knots.clear();
  nurbs_.cntrl.clear();
}

void ClReader::nurbs_data(const ClRecord& r) {
  const std::string_view m = r.major;
  if (!nurbs_.active) fail(Code::E3111, r, std::string(m) + " outside a NURBS/ block");
  require_numbers(r);
  if (m == "KNOT") {
    for (std::size_t i = 0; i < r.params.size(); ++i) nurbs_.knots.push_back(number(r, i));
  } else {
    if (r.params.size() != 3 && r.params.size() != 4) {
      fail(Code::E3111, r, "CNTRL needs x,y,z or x,y,z,w");
    }
    const double w = r.params.size() == 4 ? number(r, 3) : 1.0;
    const Vec p = place(unit_ * Vec(number(r, 0), number(r, 1), number(r, 2)));
    nurbs_.cntrl.emplace_back(w * p.x(), w * p.y(), w * p.z(), w);
  }
}

// Frames. The points are posted as written: a frame record is accepted when
// it leaves them where they are (the identity), refused otherwise.
// NX's MSYS only says where the output frame lies in the part's: the GOTOs
// are already in it, so any MSYS is accepted.
void ClReader::msys(const ClRecord& r) { require_numbers(r); }

// SolidWorks CAM: CSYS/r11,r12,r13,tx,r21,...,tz; CATIA/APT: the 12 values
// of a 3x4 matrix, a frame at R p + t. A rotation about Z (with any
// translation): the points that follow are in that frame, placed at R p + t
// (a 3-axis machine makes a translation and a turn about its Z axis). A
// tilted frame (R z not +Z, 3+2): the points and tool axes that follow
// stay in the base frame, as SolidWorks CAM writes them (boss.apt: after
// CSYS/0,0,1,0,1,0,0,0,0,1,0,0 every GOTO carries the axis 1,0,0 = R z, and
// the clearance X 120, retract X 97.5 stand 25 and 2.5 mm off the stock's
// X 95 face as Z 25 and 2.5 do above its top in the untilted operations);
// the events are in the frame's coordinates, R^T (p - t), after a
// WorkingFrame event that says where it lies (docs/cldata.md).
void ClReader::csys(const ClRecord& r) {
  require_numbers(r);
  if (r.params.size() != 12) {
    fail(Code::E3104, r, "CSYS needs the 12 values of a 3x4 matrix");
  }
  Eigen::Matrix3d rotation;
  Vec offset;
  for (Eigen::Index row = 0; row < 3; ++row) {
    for (Eigen::Index col = 0; col < 3; ++col)
      rotation(row, col) = number(r, static_cast<std::size_t>(4 * row + col));
    offset[row] = unit_ * number(r, static_cast<std::size_t>(4 * row + 3));
  }
  constexpr double tolerance = 1e-6;
  const bool rigid =
      ((rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <=
       tolerance) &&
      rotation.determinant() > 0;
  if (!rigid) {
    fail(Code::E3119, r,
         "CSYS mirrors or scales (its 3x3 part is not a rotation within 1e-6): the points it "
         "places are not a rigid set-up's");
  }
  const bool about_z = std::abs(rotation(2, 2) - 1) <= tolerance;
  program::WorkingFrame frame;
  if (about_z) {
    csys_.rotation = rotation;
    csys_.offset = offset;
    csys_.axis = Vec::UnitZ();
  } else {
    // Exactly orthonormal (a turn by multiples of 90 degrees stays exact),
    // so that turning in and out leaves the points where they are.
    Eigen::Matrix3d exact;
    exact.col(0) = rotation.col(0).normalized();
    exact.col(2) =
        (rotation.col(2) - rotation.col(2).dot(exact.col(0)) * exact.col(0)).normalized();
    exact.col(1) = exact.col(2).cross(exact.col(0));
    frame.rotation = exact;
    frame.origin = offset;
    csys_.rotation = exact.transpose();
    csys_.offset = -(exact.transpose() * offset);
    csys_.axis = exact.col(2);
  }
  frame.source = r.source;
  if (frame.rotation != csys_.frame.rotation || frame.origin != csys_.frame.origin) {
    csys_.frame = frame;
    queue_.push_back(frame);
  }
}

void ClReader::trntyp(const ClRecord& r) {
  if (r.params.empty() || !word_is(r.params[0], "WORLD")) {
    fail(Code::E3119, r, "TRNTYP is understood only as TRNTYP/WORLD,0,0,0");
  }
  for (std::size_t i = 1; i < r.params.size(); ++i) {
    if (number(r, i) != 0) {
      fail(Code::E3119, r.params[i], "TRNTYP/WORLD with an offset is not applied");
    }
  }
}

void ClReader::origin(const ClRecord& r) {
  require_numbers(r);
  for (std::size_t i = 0; i < r.params.size(); ++i) {
    if (number(r, i) != 0) {
      fail(Code::E3119, r.params[i],
           "ORIGIN other than 0,0,0 is not applied: give the CL file in the work frame");
    }
  }
}

// ROTABL/angle,AXIS,...: an indexed table turns the part under a tool axis
// that is +Z only in the turned frame; a 3-axis machine has no such table.
void ClReader::rotabl(const ClRecord& r) {
  for (std::size_t i = 0; i < r.params.size(); ++i) {
    if (r.params[i].is_number && r.params[i].value != 0) {
      fail(Code::E3108, r.params[i],
           "ROTABL turns the table by " + std::string(r.params[i].text) +
               ": an indexed rotary set-up is not 3-axis motion");
    }
  }
}

void ClReader::tracut(const ClRecord& r) {
  fail(Code::E3117, r, "TRACUT transformations are not applied; write the CL file without TRACUT");
}

void ClReader::gohome(const ClRecord& r) {
  fail(Code::E3117, r,
       "GOHOME needs the machine's home position, which vcpost does not know; give the CAM "
       "system's GOTO to the home point instead");
}

void ClReader::apt_source(const ClRecord& r) {
  fail(Code::E3113, r,
       "'" + std::string(r.major) +
           "' is an APT part-programming statement (geometry, not cutter locations); "
           "give the CAM system's CL output instead");
}

// Records with no motion and no state the output needs.
void ClReader::ignore(const ClRecord& /*record*/) {}

// The dispatch table, sorted by word (checked at compile time).
const ClReader::RecordRule* ClReader::find_rule(std::string_view word) {
  static constexpr RecordRule rules[] = {
      {"AUTOPS", &ClReader::apt_source},
      {"BOX", &ClReader::ignore},
      {"CIRCLE", &ClReader::circle},
      {"CLRSRF", &ClReader::ignore},
      {"CNTRL", &ClReader::nurbs_data},
      {"COOLNT", &ClReader::coolnt},
      {"CSI_SET_EXTENSION_LENGTH", &ClReader::ignore},
      {"CSI_SET_FLUTE_LENGTH", &ClReader::ignore},
      {"CSYS", &ClReader::csys},
      {"CUTCOM", &ClReader::cutcom},
      {"CUTTER", &ClReader::cutter},
      {"CYCLE", &ClReader::cycle},
      {"DELAY", &ClReader::delay},
      {"END", &ClReader::ignore},
      {"END-OF-PATH", &ClReader::end_of_path},
      {"FEDRAT", &ClReader::fedrat},
      {"FINI", &ClReader::fini},
      {"FROM", &ClReader::from},
      {"GO", &ClReader::apt_source},
      {"GOBACK", &ClReader::apt_source},
      {"GODLTA", &ClReader::godlta},
      {"GODOWN", &ClReader::apt_source},
      {"GOFWD", &ClReader::apt_source},
      {"GOHOME", &ClReader::gohome},
      {"GOLFT", &ClReader::apt_source},
      {"GORGT", &ClReader::apt_source},
      {"GOUP", &ClReader::apt_source},
      {"INDIRP", &ClReader::apt_source},
      {"INDIRV", &ClReader::apt_source},
      {"INSERT", &ClReader::message},
      {"KNOT", &ClReader::nurbs_data},
      {"LOAD", &ClReader::load_or_select},
      {"LOADTL", &ClReader::loadtl},
      {"MACHIN", &ClReader::ignore},
      {"MFGNO", &ClReader::message},
      {"MODE", &ClReader::ignore},
      {"MOVARC", &ClReader::circle},
      {"MSYS", &ClReader::msys},
      {"MULTAX", &ClReader::multax},
      {"NURBS", &ClReader::nurbs},
      {"OPFEATEND", &ClReader::message},
      {"OPFEATSTART", &ClReader::message},
      {"OPSKIP", &ClReader::message},
      {"OPSTOP", &ClReader::stop},
      {"ORIGIN", &ClReader::origin},
      {"PAINT", &ClReader::ignore},
      {"PARTNO", &ClReader::message},
      {"PPRINT", &ClReader::message},
      {"PSIS", &ClReader::apt_source},
      {"RAPID", &ClReader::rapid},
      {"ROTABL", &ClReader::rotabl},
      {"SELECT", &ClReader::load_or_select},
      {"SEQNO", &ClReader::ignore},
      {"SPINDL", &ClReader::spindl},
      {"STOP", &ClReader::stop},
      {"TLAXIS", &ClReader::tlaxis},
      {"TLDATA", &ClReader::tldata},
      {"TLLFT", &ClReader::apt_source},
      {"TLON", &ClReader::apt_source},
      {"TLRGT", &ClReader::apt_source},
      {"TOOL PATH", &ClReader::message},
      {"TOOLNO", &ClReader::toolno},
      {"TPRINT", &ClReader::ignore},
      {"TRACUT", &ClReader::tracut},
      {"TRNTYP", &ClReader::trntyp},
      {"UNIT", &ClReader::units},
      {"UNITS", &ClReader::units},
  };
  static_assert(std::ranges::is_sorted(rules, {}, &RecordRule::word));
  const auto* it = std::ranges::lower_bound(rules, word, {}, &RecordRule::word);
  return it != std::end(rules) && it->word == word ? it : nullptr;
}

void ClReader::process_motion_points(const ClRecord& r, bool continuation) {
  require_numbers(r);
  const std::size_t count = r.params.size();
  // Six values per point (x,y,z,i,j,k) in MULTAX mode, and on a 3-axis line
  // of exactly six: a tool axis written without MULTAX.
  const std::size_t group = multax_ || count == 6 ? 6 : 3;
  if (count == 0 || count % group != 0) {
    fail(Code::E3104, r,
         std::string(continuation ? "coordinate line" : "GOTO") + " has " + std::to_string(count) +
             " values; expected groups of " + std::to_string(group) +
             (group == 3 ? " (x,y,z)" : " (x,y,z,i,j,k)"));
  }
  begin_motion(r.source);
  for (std::size_t i = 0; i < count; i += group) {
    if (group == 6) {
      check_axis(Vec(r.params[i + 3].value, r.params[i + 4].value, r.params[i + 5].value),
                 r.params[i + 3].line, r.params[i + 3].column);
    }
    const Vec p =
        place(unit_ * Vec(r.params[i].value, r.params[i + 1].value, r.params[i + 2].value));
    if (cycle_.active) {
      drill(p, r.source);
    } else {
      move_to(p, r.source);
    }
  }
}

void ClReader::move_to(const Vec& p, const SourceRef& src) {
  if (!p.allFinite()) {
    fail(Code::E3103, src.line, src.column, "coordinate out of range after units");
  }
  const Vec start = position_.value_or(p);
  if (next_motion_.arc_active) {
    if (!position_) {
      fail(Code::E3114, src.line, src.column,
           "circular move before any position: the arc has no start");
    }
    emit_arc(start, p, *next_motion_.arc_active, src);
  } else if (next_motion_.rapid_active) {
    queue_.push_back(program::StraightTraverse{start, p, src});
  } else {
    queue_.push_back(program::StraightFeed{start, p, src});
  }
  position_ = p;
}

void ClReader::emit_arc(const Vec& start, const Vec& end, const Arc& arc, const SourceRef& src) {
  const Vec a = arc.axis;
  const Vec s = (start - arc.centre) - (start - arc.centre).dot(a) * a;
  const Vec e = (end - arc.centre) - (end - arc.centre).dot(a) * a;
  const double rs = s.norm();
  const double re = e.norm();
  if (std::abs(rs - re) > options_.arc_tolerance) {
    fail(Code::E3109, src.line, src.column,
         "arc end point is " + fixed(re) + " mm from the centre, its start " + fixed(rs) +
             " mm (tolerance " + fixed(options_.arc_tolerance) + " mm)");
  }
  if (arc.radius && std::abs(*arc.radius - rs) > options_.arc_tolerance) {
    fail(Code::E3109, arc.source.line, arc.source.column,
         "circle radius " + fixed(*arc.radius) + " mm, but the arc starts " + fixed(rs) +
             " mm from its centre");
  }
  if (!(rs > 0)) {
    fail(Code::E3109, src.line, src.column, "arc of zero radius");
  }
  // Principal axes become ARC_FEED in a plane; rotation sign = direction
  // about the plane's positive normal (rs274: XY about +Z, XZ about +Y,
  // YZ about +X).
  // NX's TIMES,n: n full turns before the arc itself, each written as a
  // full circle (every control takes those; not every one takes a P word)
  // with the axis coordinate rising linearly in the angle over the whole.
  double partial = std::atan2(s.cross(e).dot(a), s.dot(e));
  if (partial <= 1e-12) partial += 2 * std::numbers::pi;
  const double total = partial + 2 * std::numbers::pi * arc.turns;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(std::abs(a[k]) - 1.0) <= options_.axis_tolerance) {
      program::ArcFeed f;
      f.plane = k == 2 ? program::Plane::xy : k == 1 ? program::Plane::xz : program::Plane::yz;
      f.rotation = a[k] > 0 ? 1 : -1;
      f.source = src;
      f.start = start;
      for (int turn = 1; turn <= arc.turns + 1; ++turn) {
        f.end = start;
        f.end[k] = start[k] + (end[k] - start[k]) * (2 * std::numbers::pi * turn / total);
        if (turn == arc.turns + 1) f.end = end;
        f.centre = arc.centre;
        f.centre[k] = f.start[k];
        queue_.push_back(f);
        f.start = f.end;
      }
      return;
    }
  }
  // Tilted circle: lines within the chord tolerance (helical part linear
  // in the angle).
  const double sweep = total;
  const double r = std::max(rs, re);
  const double step =
      r > options_.chord_tolerance ? 2 * std::acos(1 - options_.chord_tolerance / r) : sweep;
  const double lines = std::max(1.0, std::ceil(sweep / step));
  if (!(lines <= 1e6)) {
    fail(Code::E3109, src.line, src.column,
         "tilted arc needs more than a million lines within the chord tolerance");
  }
  const auto n = static_cast<int>(lines);
  const double h0 = (start - arc.centre).dot(a);
  const double h1 = (end - arc.centre).dot(a);
  const Vec u = s / rs;
  const Vec v = a.cross(u);
  Vec previous = start;
  for (int i = 1; i <= n; ++i) {
    const double t = static_cast<double>(i) / n;
    const double phi = sweep * t;
    const double radius = rs + (re - rs) * t;
    Vec p =
        arc.centre + radius * (std::cos(phi) * u + std::sin(phi) * v) + (h0 + (h1 - h0) * t) * a;
    if (i == n) p = end;
    queue_.push_back(program::StraightFeed{previous, p, src});
    previous = p;
  }
}

void ClReader::set_feed(const Feed& f, const SourceRef& src) {
  if (feed_.emitted && *feed_.emitted == f) return;
  feed_.emitted = f;
  queue_.push_back(program::SetFeedRate{f.rate, f.mode, src});
}

void ClReader::fedrat(const ClRecord& r) {
  std::optional<double> value;
  double factor = unit_;
  program::FeedMode mode = program::FeedMode::per_minute;
  for (const ClParam& p : r.params) {
    if (p.is_number) {
      if (value) fail(Code::E3104, p, "FEDRAT has two numbers");
      value = p.value;
    } else if (word_is(p, "MMPM")) {
      factor = 1.0;
    } else if (word_is(p, "IPM")) {
      factor = mm_per_inch;
    } else if (word_is(p, "MMPR")) {
      factor = 1.0;
      mode = program::FeedMode::per_revolution;
    } else if (word_is(p, "IPR")) {
      factor = mm_per_inch;
      mode = program::FeedMode::per_revolution;
    } else if (word_is(p, "PERMIN")) {
      factor = unit_;
    } else if (word_is(p, "PERREV")) {
      factor = unit_;
      mode = program::FeedMode::per_revolution;
    } else {
      number(r, static_cast<std::size_t>(&p - r.params.data()));  // bad number or word
      fail(Code::E3105, p, "unknown FEDRAT word '" + std::string(p.text) + "'");
    }
  }
  if (!value) fail(Code::E3104, r, "FEDRAT needs a feed value");
  if (!(*value > 0)) fail(Code::E3104, r, "FEDRAT must be positive");
  feed_.programmed = Feed{*value * factor, mode};
  if (!cycle_.active) set_feed(*feed_.programmed, r.source);
}

void ClReader::spindl(const ClRecord& r) {
  std::optional<double> value;
  enum class Kind { rpm, smm, sfm } kind = Kind::rpm;
  bool off = false;
  for (std::size_t i = 0; i < r.params.size(); ++i) {
    const ClParam& p = r.params[i];
    if (p.is_number) {
      if (value) fail(Code::E3104, p, "SPINDL has two speeds");
      value = p.value;
    } else if (word_is(p, "RPM")) {
      kind = Kind::rpm;
    } else if (word_is(p, "SMM")) {
      kind = Kind::smm;
    } else if (word_is(p, "SFM")) {
      kind = Kind::sfm;
    } else if (word_is(p, "CLW")) {
      spindle_.direction = program::SpindleDirection::clockwise;
    } else if (word_is(p, "CCLW")) {
      spindle_.direction = program::SpindleDirection::counterclockwise;
    } else if (word_is(p, "OFF")) {
      off = true;
    } else if (word_is(p, "ON")) {
      // the default
    } else if (word_is(p, "RANGE") || word_is(p, "MAXRPM")) {
      warn(Code::W3154, r.source,
           "SPINDL/" + std::string(p.text) + " ignored (gear range, speed limit)");
      ++i;  // its value
      number(r, i);
    } else {
      number(r, i);
      fail(Code::E3105, p, "unknown SPINDL word '" + std::string(p.text) + "'");
    }
  }
  if (off) {
    queue_.push_back(program::SpindleOff{r.source});
    return;
  }
  if (value) {
    double rpm = *value;
    if (rpm < 0) fail(Code::E3104, r, "negative spindle speed");
    if (kind != Kind::rpm) {
      const double d = cutters_.empty() ? 0.0 : cutters_.back().diameter();
      if (!(d > 0)) {
        fail(Code::E3115, r, "SPINDL in surface speed needs a CUTTER/TLDATA diameter before it");
      }
      const double vc = kind == Kind::smm ? *value : *value * 0.3048;  // m/min
      rpm = 1000.0 * vc / (std::numbers::pi * d);
    }
    spindle_.rpm = rpm;
    queue_.push_back(program::SetSpindleSpeed{rpm, r.source});
    if (rpm == 0) {
      queue_.push_back(program::SpindleOff{r.source});
      return;
    }
  }
  queue_.push_back(program::SpindleOn{spindle_.direction, r.source});
}

void ClReader::cutter(const ClRecord& r) {
  // CAMWorks ends the record with a comma: no eighth value.
  const std::size_t n =
      r.params.size() - (r.params.size() > 1 && r.params.back().text.empty() ? 1 : 0);
  for (std::size_t i = 0; i < n; ++i) number(r, i);
  if (n == 0 || n > 7) {
    fail(Code::E3104, r, "CUTTER needs 1 to 7 values, has " + std::to_string(n));
  }
  add_cutter(cutter_from_apt(cutter_values(r, 0, n)), r, "CUTTER: ");
}

void ClReader::tldata(const ClRecord& r) {
  if (r.params.empty() || r.params[0].is_number) {
    fail(Code::E3104, r, "TLDATA needs a tool kind word first (MILL, DRILL, ...)");
  }
  if (!word_is(r.params[0], "MILL")) {
    ClCutter c;
    c.source_word = "TLDATA/" + std::string(r.params[0].text);
    c.why_not = "TLDATA/" + std::string(r.params[0].text) + " is not a milling cutter";
    add_cutter(std::move(c), r, "");
    return;
  }
  if (r.params.size() < 3) fail(Code::E3104, r, "TLDATA/MILL needs d and r");
  add_cutter(cutter_from_tldata_mill(cutter_values(r, 1, r.params.size())), r, "TLDATA/MILL: ");
}

// Parameters [first, last) of a CUTTER or TLDATA record as the cutter's
// values: lengths in mm, the angles (parameters 4 and 5 of both records)
// in degrees as written.
std::vector<double> ClReader::cutter_values(const ClRecord& r, std::size_t first,
                                            std::size_t last) const {
  std::vector<double> v;
  v.reserve(last - first);
  for (std::size_t i = first; i < last; ++i) {
    const double x = number(r, i);
    const bool angle = i == 4 || i == 5;
    v.push_back(angle ? x : x * unit_);
  }
  return v;
}

// A cutter record's cutter: kept (in record order), a warning when the
// engine cannot model it (`what` names the record), and a tool change
// when it is another cutter (note_cutter).
void ClReader::add_cutter(ClCutter c, const ClRecord& r, std::string_view what) {
  if (!c.params.empty() && !(c.diameter() > 0 && c.diameter() <= kLargestCutterDiameterMm)) {
    fail(Code::E3122, r,
         std::string(what) + "diameter " + general(c.diameter()) +
             " mm is no milling tool's size (give a diameter above 0 and up to 5000 mm)");
  }
  c.source = r.source;
  if (!c.tool) warn(Code::W3153, r.source, std::string(what) + c.why_not);
  cutters_.push_back(std::move(c));
  note_cutter(r);
}

// Creo writes the cutter only as a comment: `$$-> CUTTER / 0.375000`.
void ClReader::creo_cutter_comment(const ClRecord& r) {
  std::string_view t = r.text;
  if (t.substr(0, 2) != "->") return;
  t.remove_prefix(2);
  while (!t.empty() && (t.front() == ' ' || t.front() == '\t')) t.remove_prefix(1);
  if (t.size() < 6) return;
  const std::string head = to_upper(t.substr(0, 6));
  if (head != "CUTTER") return;
  const auto slash = t.find('/');
  if (slash == std::string_view::npos) return;
  std::vector<double> v;
  std::string_view rest = t.substr(slash + 1);
  while (!rest.empty()) {
    const auto comma = rest.find(',');
    std::string item(rest.substr(0, comma));
    char* endp = nullptr;
    const double x = std::strtod(item.c_str(), &endp);
    if (endp == item.c_str()) return;  // not numbers: leave the comment alone
    v.push_back(x * unit_);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  if (v.empty() || v.size() > 7) return;
  ClCutter c = cutter_from_apt(v);
  c.source_word = "$$-> CUTTER";
  c.source = r.source;
  cutters_.push_back(std::move(c));
}

void ClReader::circle(const ClRecord& r) {
  std::size_t n = r.params.size();
  Arc arc;
  arc.source = r.source;
  if (n >= 2 && word_is(r.params[n - 2], "TIMES")) {
    arc.turns = integer(r, n - 1);
    if (arc.turns > 1000) fail(Code::E3104, r.params[n - 1], "more than 1000 turns");
    n -= 2;
  }
  // CAMWorks names the direction: CLOCKWISE turns the other way about i,j,k.
  bool clockwise_word = false;
  if (n >= 1 &&
      (word_is(r.params[n - 1], "CLOCKWISE") || word_is(r.params[n - 1], "CLW") ||
       word_is(r.params[n - 1], "COUNTERCLOCKWISE") || word_is(r.params[n - 1], "CCLW"))) {
    clockwise_word = word_is(r.params[n - 1], "CLOCKWISE") || word_is(r.params[n - 1], "CLW");
    --n;
  }
  for (std::size_t i = 0; i < n; ++i) number(r, i);
  if (n == 4) {
    arc.axis = Vec::UnitZ();
    arc.radius = number(r, 3) * unit_;
  } else if (n >= 6) {
    arc.axis = Vec(number(r, 3), number(r, 4), number(r, 5));
    if (n >= 7) arc.radius = number(r, 6) * unit_;
    // NX's form (x,y,z,i,j,k,r,tol,thick,dia,crad) turns clockwise about
    // i,j,k: all 19 arcs of the NX contour sample are 3..90 deg so, and
    // 270..357 deg the other way. APT, Creo (7 values) and SolidWorks (6)
    // turn counterclockwise (369 + 1026 SolidWorks arcs, Creo full circles).
    if (n >= 8) arc.axis = -arc.axis;
    if (clockwise_word) arc.axis = -arc.axis;
  } else {
    fail(Code::E3104, r,
         std::string(r.major) + " needs xc,yc,zc,i,j,k[,r,...] (or xc,yc,zc,r), has " +
             std::to_string(n) + " values");
  }
  const double norm = arc.axis.norm();
  if (!(norm > 0)) fail(Code::E3104, r, "circle axis is a zero vector");
  arc.axis = csys_.rotation * (arc.axis / norm);
  arc.centre = place(unit_ * Vec(number(r, 0), number(r, 1), number(r, 2)));
  if (arc.radius && !(*arc.radius > 0)) fail(Code::E3104, r, "circle radius must be positive");
  next_motion_.arc_pending = arc;
}

void ClReader::cycle(const ClRecord& r) {
  if (r.params.empty()) fail(Code::E3104, r, "CYCLE needs a cycle word");
  const ClParam& kind = r.params[0];
  if (word_is(kind, "OFF")) {
    cycle_.active.reset();
    if (feed_.programmed) set_feed(*feed_.programmed, r.source);
    return;
  }
  // SolidWorks' markers before a cycle (CLEAR: its parameters start afresh,
  // which the next CYCLE/<kind> record does anyway): nothing moves.
  if (word_is(kind, "INIT") || word_is(kind, "CLEAR")) return;
  if (word_is(kind, "ON")) {
    // CAMWorks writes CYCLE/ON before the cycle itself: nothing to resume yet.
    if (cycle_.last) cycle_.active = cycle_.last;
    return;
  }
  cycle_.active = parse_cycle(r, unit_, lexer_.file_name());
  cycle_.last = cycle_.active;
}

namespace {

// What a control's canned cycle `code` is told for cycle c at the hole
// whose top is p (the event counts are filled in after the expansion).
program::CannedCycle canned_cycle(const ClCycle& c, int code, const Vec& p, const SourceRef& src) {
  program::CannedCycle m;
  m.code = code;
  m.x = p.x();
  m.y = p.y();
  m.top_z = p.z() + c.retract.value_or(c.clearance);
  m.r_z = p.z() + c.clearance;
  m.bottom_z = p.z() - c.depth;
  m.peck = code == 73 || code == 83 ? c.first_peck : 0.0;
  m.dwell_s = code == 82 || code == 84 || code == 86 || code == 89 ? c.dwell_s : 0.0;
  m.source = src;
  return m;
}

}  // namespace

// The canned cycle's moves at the hole whose top is p; the cycle's feed
// comes before its first feed move, not before the rapids to the hole.
void ClReader::drill(const Vec& p, const SourceRef& src) {
  const ClCycle& c = *cycle_.active;
  const Vec start = position_.value_or(p + c.retract.value_or(c.clearance) * Vec::UnitZ());
  const std::size_t marker = queue_.size();
  const std::optional<int> code = canned_code(c, spindle_.direction);
  if (code) queue_.push_back(canned_cycle(c, *code, p, src));
  const std::size_t first = queue_.size();
  expand_cycle(c, p, start, spindle_.direction, src, queue_);
  if (code) {
    auto& m = std::get<program::CannedCycle>(queue_[marker]);
    for (std::size_t i = first; i < queue_.size(); ++i) {
      ++m.events;
      if (program::is_motion(queue_[i])) ++m.moves;
    }
  }
  const Feed feed{c.feed, c.mode};
  if (!feed_.emitted || !(*feed_.emitted == feed)) {
    auto at = queue_.begin() + static_cast<std::ptrdiff_t>(first);
    while (at != queue_.end() && !std::holds_alternative<program::StraightFeed>(*at)) ++at;
    queue_.insert(at, program::SetFeedRate{feed.rate, feed.mode, src});
    feed_.emitted = feed;
  }
  for (auto it = queue_.rbegin(); it != queue_.rend(); ++it) {
    if (program::is_motion(*it)) {
      position_ = std::holds_alternative<program::StraightTraverse>(*it)
                      ? std::get<program::StraightTraverse>(*it).end
                      : std::get<program::StraightFeed>(*it).end;
      break;
    }
  }
}

void ClReader::finish_nurbs() {
  nurbs_.active = false;
  std::string error;
  const auto curve = nx_nurbs(*position_, nurbs_.knots, nurbs_.cntrl, error);
  if (!curve) fail(Code::E3111, nurbs_.source.line, nurbs_.source.column, error);
  nurbs_.scratch.clear();
  if (!flatten(*curve, options_.chord_tolerance, nurbs_.scratch)) {
    fail(Code::E3111, nurbs_.source.line, nurbs_.source.column,
         "NURBS needs more than a million lines within the chord tolerance");
  }
  Vec previous = *position_;
  for (const Vec& p : nurbs_.scratch) {
    if (nurbs_.rapid) {
      queue_.push_back(program::StraightTraverse{previous, p, nurbs_.source});
    } else {
      queue_.push_back(program::StraightFeed{previous, p, nurbs_.source});
    }
    previous = p;
  }
  position_ = previous;
}

}  // namespace vcpost::cldata
