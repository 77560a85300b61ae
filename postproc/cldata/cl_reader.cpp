#include "postproc/cldata/cl_reader.h"

#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <numbers>
#include <utility>

#include <Eigen/Geometry>

#include "postproc/cldata/nurbs.h"

namespace vcpost::cldata {

namespace {

using program::SourceRef;
using Vec = Eigen::Vector3d;

constexpr double mm_per_inch = 25.4;

// Records that carry no motion and no state vcpost uses.
bool is_ignored(std::string_view m) {
  static constexpr std::array<std::string_view, 12> words{
      "PAINT", "MACHIN", "MSYS",  "CSYS", "TRNTYP", "TPRINT",
      "TOOLNO", "CLRSRF", "END", "MODE", "SEQNO",  "ORIGIN"};
  for (const auto w : words) {
    if (m == w) return true;
  }
  return false;
}

// APT part-programming statements: they describe motion by geometry and
// need an APT processor, they are not cutter locations.
bool is_apt_source(std::string_view m) {
  static constexpr std::array<std::string_view, 14> words{
      "TLON",  "TLLFT", "TLRGT",  "GOFWD",  "GOLFT", "GORGT", "GOBACK",
      "GOUP",  "GODOWN", "GO",    "INDIRV", "INDIRP", "PSIS",  "AUTOPS"};
  for (const auto w : words) {
    if (m == w) return true;
  }
  return false;
}

std::string fixed(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4f", v);
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

void ClReader::fail(ClCode code, std::uint32_t line, std::uint32_t column,
                    std::string message) const {
  throw ClError(ClDiagnostic{code, line, column, std::move(message)}, lexer_.file_name());
}

void ClReader::fail(ClCode code, const ClRecord& r, std::string message) const {
  fail(code, r.source.line, r.source.column, std::move(message));
}

void ClReader::fail(ClCode code, const ClParam& p, std::string message) const {
  fail(code, p.line, p.column, std::move(message));
}

void ClReader::warn(ClCode code, const SourceRef& src, std::string message) {
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
    fail(ClCode::wrong_parameters, r,
         std::string(r.major.empty() ? "coordinates" : r.major) + " needs at least " +
             std::to_string(i + 1) + " parameters, has " + std::to_string(r.params.size()));
  }
  const ClParam& p = r.params[i];
  if (p.is_number) return p.value;
  if (p.text.empty()) fail(ClCode::bad_number, p, "empty parameter where a number is expected");
  const char c = p.text.front();
  if ((c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.') {
    fail(ClCode::bad_number, p, "malformed number '" + std::string(p.text) + "'");
  }
  fail(ClCode::wrong_parameters, p, "expected a number, found '" + std::string(p.text) + "'");
}

int ClReader::integer(const ClRecord& r, std::size_t i) const {
  const double v = number(r, i);
  if (v < 0 || v > 1e9 || v != std::floor(v)) {
    fail(ClCode::wrong_parameters, r.params[i],
         "expected a whole number, found '" + std::string(r.params[i].text) + "'");
  }
  return static_cast<int>(v);
}

void ClReader::require_numbers(const ClRecord& r) const {
  for (std::size_t i = 0; i < r.params.size(); ++i) number(r, i);
}

void ClReader::check_axis(const Vec& axis, std::uint32_t line, std::uint32_t column) {
  const double n = axis.norm();
  if (!(n > 0) || (axis / n - Vec::UnitZ()).norm() > options_.axis_tolerance) {
    fail(ClCode::tool_axis_not_z, line, column,
         "tool axis " + xyz(axis) +
             " is not +Z: multi-axis (or tilted 3+2) paths cannot be converted to 3-axis "
             "motion");
  }
}

std::optional<program::Event> ClReader::next() {
  while (queue_.empty()) {
    if (input_done_) return std::nullopt;
    if (!lexer_.next(record_)) {
      finish_input();
      input_done_ = true;
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
  if (nurbs_active_) finish_nurbs();
  if (arc_pending_) {
    fail(ClCode::arc_without_goto, arc_pending_->source.line, arc_pending_->source.column,
         "CIRCLE is not followed by a GOTO before the end of the file");
  }
  if (!ended_) {
    if (!end_of_path_) {
      warn(ClCode::missing_fini, SourceRef{lexer_.line_number(), 1, 0},
           "the file ends without FINI or END-OF-PATH: it may be truncated");
    }
    queue_.push_back(program::ProgramEnd{last_source_});
  }
}

void ClReader::process(const ClRecord& r) {
  if (r.kind == ClRecordKind::comment) {
    if (!ended_) creo_cutter_comment(r);
    return;
  }
  if (ended_) {
    if (warnings_.empty() || warnings_.back().code != ClCode::after_fini) {
      warn(ClCode::after_fini, r.source, "records after FINI are ignored");
    }
    return;
  }
  last_source_ = r.source;
  if (r.kind == ClRecordKind::points) {
    if (nurbs_active_) finish_nurbs();
    if (!in_goto_) {
      fail(ClCode::orphan_points, r,
           "a line of coordinates must follow a GOTO record (or end the previous one with '$')");
    }
    process_motion_points(r, true);
    return;
  }
  const std::string_view m = r.major;
  if (nurbs_active_ && m != "KNOT" && m != "CNTRL") finish_nurbs();
  end_of_path_ = false;

  if (m == "GOTO") {
    in_goto_ = true;
    rapid_active_ = std::exchange(rapid_pending_, false);
    if (arc_pending_) arc_active_ = std::exchange(arc_pending_, std::nullopt);
    else arc_active_.reset();
    process_motion_points(r, false);
    return;
  }
  in_goto_ = false;
  arc_active_.reset();
  rapid_active_ = false;

  if (m == "RAPID") {
    rapid_pending_ = true;
  } else if (m == "FEDRAT") {
    fedrat(r);
  } else if (m == "CIRCLE" || m == "MOVARC") {
    circle(r);
  } else if (m == "FROM") {
    require_numbers(r);
    if (r.params.size() != 3 && r.params.size() != 6) {
      fail(ClCode::wrong_parameters, r, "FROM needs x,y,z or x,y,z,i,j,k");
    }
    if (r.params.size() == 6) {
      check_axis(Vec(number(r, 3), number(r, 4), number(r, 5)), r.params[3].line,
                 r.params[3].column);
    }
    position_ = unit_ * Vec(number(r, 0), number(r, 1), number(r, 2));
  } else if (m == "GODLTA") {
    require_numbers(r);
    if (!position_) {
      fail(ClCode::no_start_position, r, "GODLTA before any FROM or GOTO: no position to move from");
    }
    Vec delta;
    if (r.params.size() == 1) {
      delta = unit_ * number(r, 0) * Vec::UnitZ();
    } else if (r.params.size() == 3 || r.params.size() == 6) {
      delta = unit_ * Vec(number(r, 0), number(r, 1), number(r, 2));
      if (r.params.size() == 6) {
        check_axis(Vec(number(r, 3), number(r, 4), number(r, 5)), r.params[3].line,
                   r.params[3].column);
      }
    } else {
      fail(ClCode::wrong_parameters, r, "GODLTA needs d, or dx,dy,dz[,i,j,k]");
    }
    rapid_active_ = std::exchange(rapid_pending_, false);
    if (arc_pending_) {
      fail(ClCode::arc_without_goto, arc_pending_->source.line, arc_pending_->source.column,
           "CIRCLE must be followed by GOTO, not GODLTA");
    }
    move_to(*position_ + delta, r.source);
    rapid_active_ = false;
  } else if (m == "SPINDL") {
    spindl(r);
  } else if (m == "CUTTER") {
    cutter(r);
  } else if (m == "TLDATA") {
    tldata(r);
  } else if (m == "LOADTL") {
    queue_.push_back(program::ChangeTool{integer(r, 0), r.source});
  } else if (m == "LOAD" || m == "SELECT") {
    if (r.params.empty() || !word_is(r.params[0], "TOOL")) {
      fail(ClCode::unexpected_word, r, std::string(m) + " is understood only as " +
                                           std::string(m) + "/TOOL,n");
    }
    if (m == "LOAD") {
      queue_.push_back(program::ChangeTool{integer(r, 1), r.source});
    } else {
      queue_.push_back(program::SelectTool{integer(r, 1), r.source});
    }
  } else if (m == "UNITS" || m == "UNIT") {
    if (r.params.size() != 1) fail(ClCode::bad_units, r, "UNITS needs one word: MM or INCHES");
    const ClParam& p = r.params[0];
    if (word_is(p, "MM")) {
      unit_ = 1.0;
    } else if (word_is(p, "INCHES") || word_is(p, "INCH") || word_is(p, "IN")) {
      unit_ = mm_per_inch;
    } else if (word_is(p, "CM")) {
      unit_ = 10.0;
    } else {
      fail(ClCode::bad_units, p, "unknown units '" + std::string(p.text) + "'");
    }
  } else if (m == "COOLNT") {
    using program::CoolantChange;
    if (r.params.empty()) fail(ClCode::wrong_parameters, r, "COOLNT needs ON, FLOOD, MIST or OFF");
    const ClParam& p = r.params[0];
    CoolantChange change = CoolantChange::flood_on;
    if (word_is(p, "ON") || word_is(p, "FLOOD")) {
      change = CoolantChange::flood_on;
    } else if (word_is(p, "MIST")) {
      change = CoolantChange::mist_on;
    } else if (word_is(p, "OFF")) {
      change = CoolantChange::off;
    } else if (word_is(p, "THRU") || word_is(p, "AIR") || word_is(p, "TAPKUL")) {
      warn(ClCode::ignored_option, r.source,
           "COOLNT/" + std::string(p.text) + " is written as flood coolant");
    } else {
      fail(ClCode::unexpected_word, p, "unknown COOLNT word '" + std::string(p.text) + "'");
    }
    queue_.push_back(program::Coolant{change, r.source});
  } else if (m == "CUTCOM") {
    using program::CompensationSide;
    if (r.params.empty()) fail(ClCode::wrong_parameters, r, "CUTCOM needs LEFT, RIGHT or OFF");
    const ClParam& p = r.params[0];
    CompensationSide side = CompensationSide::off;
    if (word_is(p, "LEFT")) {
      side = CompensationSide::left;
    } else if (word_is(p, "RIGHT")) {
      side = CompensationSide::right;
    } else if (!word_is(p, "OFF")) {
      fail(ClCode::unexpected_word, p, "unknown CUTCOM word '" + std::string(p.text) + "'");
    }
    queue_.push_back(program::CutterCompensation{side, r.source});
  } else if (m == "DELAY") {
    double seconds = 0;
    if (!r.params.empty() && word_is(r.params[0], "REV")) {
      if (!(rpm_ > 0)) fail(ClCode::wrong_parameters, r, "DELAY/REV with the spindle stopped");
      seconds = number(r, 1) * 60.0 / rpm_;
    } else {
      seconds = number(r, 0);
    }
    if (seconds < 0) fail(ClCode::wrong_parameters, r, "DELAY must not be negative");
    queue_.push_back(program::Dwell{seconds, r.source});
  } else if (m == "STOP") {
    queue_.push_back(program::ProgramStop{false, r.source});
  } else if (m == "OPSTOP") {
    queue_.push_back(program::ProgramStop{true, r.source});
  } else if (m == "FINI") {
    if (cycle_) cycle_.reset();
    queue_.push_back(program::ProgramEnd{r.source});
    ended_ = true;
  } else if (m == "END-OF-PATH") {
    end_of_path_ = true;
  } else if (m == "PPRINT") {
    queue_.push_back(program::Message{std::string(r.text), r.source});
  } else if (m == "PARTNO" || m == "INSERT") {
    queue_.push_back(program::Message{std::string(m) + " " + std::string(r.text), r.source});
  } else if (m == "TOOL PATH") {
    queue_.push_back(program::Message{"TOOL PATH/" + std::string(r.text), r.source});
  } else if (m == "TLAXIS") {
    require_numbers(r);
    if (r.params.size() < 3) fail(ClCode::wrong_parameters, r, "TLAXIS needs i,j,k");
    check_axis(Vec(number(r, 0), number(r, 1), number(r, 2)), r.params[0].line,
               r.params[0].column);
  } else if (m == "MULTAX") {
    multax_ = r.params.empty() || !word_is(r.params[0], "OFF");
  } else if (m == "NURBS") {
    if (!r.params.empty()) {
      fail(ClCode::bad_nurbs, r, "NURBS/ with parameters is not understood");
    }
    if (!position_) fail(ClCode::no_start_position, r, "NURBS before any position");
    nurbs_active_ = true;
    nurbs_rapid_ = std::exchange(rapid_pending_, false);
    nurbs_source_ = r.source;
    knots_.clear();
    cntrl_.clear();
  } else if (m == "KNOT" || m == "CNTRL") {
    if (!nurbs_active_) fail(ClCode::bad_nurbs, r, std::string(m) + " outside a NURBS/ block");
    require_numbers(r);
    if (m == "KNOT") {
      for (std::size_t i = 0; i < r.params.size(); ++i) knots_.push_back(number(r, i));
    } else {
      if (r.params.size() != 3 && r.params.size() != 4) {
        fail(ClCode::bad_nurbs, r, "CNTRL needs x,y,z or x,y,z,w");
      }
      const double w = r.params.size() == 4 ? number(r, 3) : 1.0;
      const Vec p = unit_ * Vec(number(r, 0), number(r, 1), number(r, 2));
      cntrl_.emplace_back(w * p.x(), w * p.y(), w * p.z(), w);
    }
  } else if (m == "CYCLE") {
    cycle(r);
  } else if (m == "TRACUT") {
    fail(ClCode::unsupported_record, r,
         "TRACUT transformations are not applied; write the CL file without TRACUT");
  } else if (r.separator == '=' || is_apt_source(m)) {
    fail(ClCode::apt_source_statement, r,
         "'" + std::string(m) +
             "' is an APT part-programming statement (geometry, not cutter locations); "
             "give the CAM system's CL output instead");
  } else if (is_ignored(m)) {
    // documented as ignored: no motion, no state vcpost needs
  } else {
    if (unknown_words_.find(m) == unknown_words_.end()) {
      unknown_words_.emplace(m);
      warn(ClCode::unknown_record, r.source,
           "unknown record '" + std::string(m) + "' ignored (reported once)");
    }
  }
}

void ClReader::process_motion_points(const ClRecord& r, bool continuation) {
  require_numbers(r);
  const std::size_t count = r.params.size();
  std::size_t group = 3;
  if (multax_) {
    group = 6;
  } else if (count == 6) {
    group = 6;
  }
  if (count == 0 || count % group != 0) {
    fail(ClCode::wrong_parameters, r,
         std::string(continuation ? "coordinate line" : "GOTO") + " has " +
             std::to_string(count) + " values; expected groups of " + std::to_string(group) +
             (group == 3 ? " (x,y,z)" : " (x,y,z,i,j,k)"));
  }
  for (std::size_t i = 0; i < count; i += group) {
    if (group == 6) {
      check_axis(Vec(r.params[i + 3].value, r.params[i + 4].value, r.params[i + 5].value),
                 r.params[i + 3].line, r.params[i + 3].column);
    }
    const Vec p = unit_ * Vec(r.params[i].value, r.params[i + 1].value, r.params[i + 2].value);
    if (cycle_) {
      drill(p, r.source);
    } else {
      move_to(p, r.source);
    }
  }
}

void ClReader::move_to(const Vec& p, const SourceRef& src) {
  if (!p.allFinite()) {
    fail(ClCode::bad_number, src.line, src.column, "coordinate out of range after units");
  }
  const Vec start = position_.value_or(p);
  if (arc_active_) {
    if (!position_) {
      fail(ClCode::no_start_position, src.line, src.column,
           "circular move before any position: the arc has no start");
    }
    emit_arc(start, p, *arc_active_, src);
  } else if (rapid_active_) {
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
    fail(ClCode::arc_inconsistent, src.line, src.column,
         "arc end point is " + fixed(re) + " mm from the centre, its start " + fixed(rs) +
             " mm (tolerance " + fixed(options_.arc_tolerance) + " mm)");
  }
  if (arc.radius && std::abs(*arc.radius - rs) > options_.arc_tolerance) {
    fail(ClCode::arc_inconsistent, arc.source.line, arc.source.column,
         "circle radius " + fixed(*arc.radius) + " mm, but the arc starts " + fixed(rs) +
             " mm from its centre");
  }
  if (!(rs > 0)) {
    fail(ClCode::arc_inconsistent, src.line, src.column, "arc of zero radius");
  }
  // Principal axes become ARC_FEED in a plane; rotation sign = direction
  // about the plane's positive normal (rs274: XY about +Z, XZ about +Y,
  // YZ about +X).
  for (int k = 0; k < 3; ++k) {
    if (std::abs(std::abs(a[k]) - 1.0) <= options_.axis_tolerance) {
      program::ArcFeed f;
      f.start = start;
      f.end = end;
      f.centre = arc.centre;
      f.centre[k] = start[k];
      f.plane = k == 2 ? program::Plane::xy : k == 1 ? program::Plane::xz : program::Plane::yz;
      f.rotation = a[k] > 0 ? 1 : -1;
      f.source = src;
      queue_.push_back(f);
      return;
    }
  }
  // Tilted circle: lines within the chord tolerance (helical part linear
  // in the angle).
  double sweep = std::atan2(s.cross(e).dot(a), s.dot(e));
  if (sweep <= 1e-12) sweep += 2 * std::numbers::pi;
  const double r = std::max(rs, re);
  const double step =
      r > options_.chord_tolerance ? 2 * std::acos(1 - options_.chord_tolerance / r) : sweep;
  const double lines = std::max(1.0, std::ceil(sweep / step));
  if (!(lines <= 1e6)) {
    fail(ClCode::arc_inconsistent, src.line, src.column,
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
    Vec p = arc.centre + radius * (std::cos(phi) * u + std::sin(phi) * v) + (h0 + (h1 - h0) * t) * a;
    if (i == n) p = end;
    queue_.push_back(program::StraightFeed{previous, p, src});
    previous = p;
  }
}

void ClReader::set_feed(const Feed& f, const SourceRef& src) {
  if (machine_feed_ && *machine_feed_ == f) return;
  machine_feed_ = f;
  queue_.push_back(program::SetFeedRate{f.rate, f.mode, src});
}

void ClReader::fedrat(const ClRecord& r) {
  std::optional<double> value;
  double factor = unit_;
  program::FeedMode mode = program::FeedMode::per_minute;
  for (const ClParam& p : r.params) {
    if (p.is_number) {
      if (value) fail(ClCode::wrong_parameters, p, "FEDRAT has two numbers");
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
      fail(ClCode::unexpected_word, p, "unknown FEDRAT word '" + std::string(p.text) + "'");
    }
  }
  if (!value) fail(ClCode::wrong_parameters, r, "FEDRAT needs a feed value");
  if (!(*value > 0)) fail(ClCode::wrong_parameters, r, "FEDRAT must be positive");
  program_feed_ = Feed{*value * factor, mode};
  if (!cycle_) set_feed(*program_feed_, r.source);
}

void ClReader::spindl(const ClRecord& r) {
  std::optional<double> value;
  enum class Kind { rpm, smm, sfm } kind = Kind::rpm;
  bool off = false;
  for (std::size_t i = 0; i < r.params.size(); ++i) {
    const ClParam& p = r.params[i];
    if (p.is_number) {
      if (value) fail(ClCode::wrong_parameters, p, "SPINDL has two speeds");
      value = p.value;
    } else if (word_is(p, "RPM")) {
      kind = Kind::rpm;
    } else if (word_is(p, "SMM")) {
      kind = Kind::smm;
    } else if (word_is(p, "SFM")) {
      kind = Kind::sfm;
    } else if (word_is(p, "CLW")) {
      direction_ = program::SpindleDirection::clockwise;
    } else if (word_is(p, "CCLW")) {
      direction_ = program::SpindleDirection::counterclockwise;
    } else if (word_is(p, "OFF")) {
      off = true;
    } else if (word_is(p, "ON")) {
      // the default
    } else if (word_is(p, "RANGE") || word_is(p, "MAXRPM")) {
      warn(ClCode::ignored_option, r.source,
           "SPINDL/" + std::string(p.text) + " ignored (gear range, speed limit)");
      ++i;  // its value
      number(r, i);
    } else {
      number(r, i);
      fail(ClCode::unexpected_word, p, "unknown SPINDL word '" + std::string(p.text) + "'");
    }
  }
  if (off) {
    queue_.push_back(program::SpindleOff{r.source});
    return;
  }
  if (value) {
    double rpm = *value;
    if (rpm < 0) fail(ClCode::wrong_parameters, r, "negative spindle speed");
    if (kind != Kind::rpm) {
      const double d = cutters_.empty() ? 0.0 : cutters_.back().diameter();
      if (!(d > 0)) {
        fail(ClCode::surface_speed_no_tool, r,
             "SPINDL in surface speed needs a CUTTER/TLDATA diameter before it");
      }
      const double vc = kind == Kind::smm ? *value : *value * 0.3048;  // m/min
      rpm = 1000.0 * vc / (std::numbers::pi * d);
    }
    rpm_ = rpm;
    queue_.push_back(program::SetSpindleSpeed{rpm, r.source});
    if (rpm == 0) {
      queue_.push_back(program::SpindleOff{r.source});
      return;
    }
  }
  queue_.push_back(program::SpindleOn{direction_, r.source});
}

void ClReader::cutter(const ClRecord& r) {
  require_numbers(r);
  if (r.params.empty() || r.params.size() > 7) {
    fail(ClCode::wrong_parameters, r,
         "CUTTER needs 1 to 7 values, has " + std::to_string(r.params.size()));
  }
  std::vector<double> v(r.params.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    const bool angle = i == 4 || i == 5;
    v[i] = r.params[i].value * (angle ? 1.0 : unit_);
  }
  ClCutter c = cutter_from_apt(v);
  c.source = r.source;
  if (!c.tool) warn(ClCode::tool_not_modelled, r.source, "CUTTER: " + c.why_not);
  cutters_.push_back(std::move(c));
}

void ClReader::tldata(const ClRecord& r) {
  if (r.params.empty() || r.params[0].is_number) {
    fail(ClCode::wrong_parameters, r, "TLDATA needs a tool kind word first (MILL, DRILL, ...)");
  }
  if (!word_is(r.params[0], "MILL")) {
    ClCutter c;
    c.source_word = "TLDATA/" + std::string(r.params[0].text);
    c.why_not = "TLDATA/" + std::string(r.params[0].text) + " is not a milling cutter";
    c.source = r.source;
    warn(ClCode::tool_not_modelled, r.source, c.why_not);
    cutters_.push_back(std::move(c));
    return;
  }
  if (r.params.size() < 3) fail(ClCode::wrong_parameters, r, "TLDATA/MILL needs d and r");
  std::vector<double> v;
  for (std::size_t i = 1; i < r.params.size(); ++i) {
    const double x = number(r, i);
    const bool angle = i == 4 || i == 5;
    v.push_back(angle ? x : x * unit_);
  }
  ClCutter c = cutter_from_tldata_mill(v);
  c.source = r.source;
  if (!c.tool) warn(ClCode::tool_not_modelled, r.source, "TLDATA/MILL: " + c.why_not);
  cutters_.push_back(std::move(c));
}

// Creo writes the cutter only as a comment: `$$-> CUTTER / 0.375000`.
void ClReader::creo_cutter_comment(const ClRecord& r) {
  std::string_view t = r.text;
  if (t.substr(0, 2) != "->") return;
  t.remove_prefix(2);
  while (!t.empty() && (t.front() == ' ' || t.front() == '\t')) t.remove_prefix(1);
  if (t.size() < 6) return;
  std::string head(t.substr(0, 6));
  for (char& c : head) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
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
  require_numbers(r);
  const std::size_t n = r.params.size();
  Arc arc;
  arc.source = r.source;
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
  } else {
    fail(ClCode::wrong_parameters, r,
         std::string(r.major) + " needs xc,yc,zc,i,j,k[,r,...] (or xc,yc,zc,r), has " +
             std::to_string(n) + " values");
  }
  const double norm = arc.axis.norm();
  if (!(norm > 0)) fail(ClCode::wrong_parameters, r, "circle axis is a zero vector");
  arc.axis /= norm;
  arc.centre = unit_ * Vec(number(r, 0), number(r, 1), number(r, 2));
  if (arc.radius && !(*arc.radius > 0)) fail(ClCode::wrong_parameters, r, "circle radius must be positive");
  arc_pending_ = arc;
}

void ClReader::cycle(const ClRecord& r) {
  if (r.params.empty()) fail(ClCode::wrong_parameters, r, "CYCLE needs a cycle word");
  const ClParam& kind = r.params[0];
  if (word_is(kind, "OFF")) {
    cycle_.reset();
    if (program_feed_) set_feed(*program_feed_, r.source);
    return;
  }
  if (word_is(kind, "INIT")) return;  // SolidWorks' marker before the cycle
  if (word_is(kind, "ON")) {
    if (!last_cycle_) fail(ClCode::unsupported_cycle, r, "CYCLE/ON without a previous cycle");
    cycle_ = last_cycle_;
    return;
  }
  if (!word_is(kind, "DRILL")) {
    fail(ClCode::unsupported_cycle, kind,
         "CYCLE/" + std::string(kind.text) +
             " is not expanded (only CYCLE/DRILL with FEDTO, RAPTO, RTRCTO, feed and DWELL "
             "is); post this operation with another post-processor");
  }
  Cycle c;
  bool has_depth = false, has_rapto = false, has_feed = false;
  std::size_t i = 1;
  const auto feed_word = [&](const ClParam& p, double& factor) {
    if (word_is(p, "MMPM")) { factor = 1.0; c.mode = program::FeedMode::per_minute; return true; }
    if (word_is(p, "IPM")) { factor = mm_per_inch; c.mode = program::FeedMode::per_minute; return true; }
    if (word_is(p, "MMPR")) { factor = 1.0; c.mode = program::FeedMode::per_revolution; return true; }
    if (word_is(p, "IPR")) { factor = mm_per_inch; c.mode = program::FeedMode::per_revolution; return true; }
    return false;
  };
  if (i < r.params.size() && r.params[i].is_number) {
    // Positional form: CYCLE/DRILL, depth, unit, feed, clearance[, retract].
    double factor = unit_;
    c.depth = number(r, 1) * unit_;
    if (r.params.size() < 5 || !feed_word(r.params[2], factor)) {
      fail(ClCode::unsupported_cycle, r,
           "CYCLE/DRILL positional form must be DRILL, depth, MMPM|IPM|MMPR|IPR, feed, "
           "clearance[, retract]");
    }
    c.feed = number(r, 3) * factor;
    c.rapto = number(r, 4) * unit_;
    if (r.params.size() > 5) c.rtrcto = number(r, 5) * unit_;
    if (r.params.size() > 6) fail(ClCode::unsupported_cycle, r.params[6], "extra CYCLE/DRILL value");
    has_depth = has_rapto = has_feed = true;
  } else {
    for (; i < r.params.size(); ++i) {
      const ClParam& p = r.params[i];
      double factor = unit_;
      if (word_is(p, "FEDTO")) {
        c.depth = number(r, ++i) * unit_;
        has_depth = true;
      } else if (word_is(p, "RAPTO")) {
        c.rapto = number(r, ++i) * unit_;
        has_rapto = true;
      } else if (word_is(p, "RTRCTO")) {
        c.rtrcto = number(r, ++i) * unit_;
      } else if (word_is(p, "DWELL")) {
        c.dwell = number(r, ++i);
      } else if (feed_word(p, factor)) {
        c.feed = number(r, ++i) * factor;
        has_feed = true;
      } else {
        fail(ClCode::unsupported_cycle, p,
             "CYCLE/DRILL," + std::string(p.text) +
                 " is not expanded (peck, chip-break and other variants differ between CAM "
                 "systems); post this operation with another post-processor");
      }
    }
  }
  if (!has_depth || !has_rapto || !has_feed) {
    fail(ClCode::unsupported_cycle, r, "CYCLE/DRILL needs FEDTO, RAPTO and a feed");
  }
  if (!(c.feed > 0)) fail(ClCode::wrong_parameters, r, "CYCLE/DRILL feed must be positive");
  cycle_ = c;
  last_cycle_ = c;
}

// G81/G82-like: rapid above the hole at the retract height, rapid to the
// clearance plane, feed to depth, dwell, rapid back to the retract height.
void ClReader::drill(const Vec& p, const SourceRef& src) {
  const Cycle& c = *cycle_;
  const Vec z = Vec::UnitZ();
  const double retract = c.rtrcto.value_or(c.rapto);
  const Vec top = p + retract * z;
  const Vec clear = p + c.rapto * z;
  const Vec bottom = p - c.depth * z;
  const Vec start = position_.value_or(top);
  queue_.push_back(program::StraightTraverse{start, top, src});
  if ((clear - top).norm() > 0) queue_.push_back(program::StraightTraverse{top, clear, src});
  set_feed(Feed{c.feed, c.mode}, src);
  queue_.push_back(program::StraightFeed{clear, bottom, src});
  if (c.dwell > 0) queue_.push_back(program::Dwell{c.dwell, src});
  queue_.push_back(program::StraightTraverse{bottom, top, src});
  position_ = top;
}

void ClReader::finish_nurbs() {
  nurbs_active_ = false;
  std::string error;
  const auto curve = nx_nurbs(*position_, knots_, cntrl_, error);
  if (!curve) fail(ClCode::bad_nurbs, nurbs_source_.line, nurbs_source_.column, error);
  scratch_.clear();
  if (!flatten(*curve, options_.chord_tolerance, scratch_)) {
    fail(ClCode::bad_nurbs, nurbs_source_.line, nurbs_source_.column,
         "NURBS needs more than a million lines within the chord tolerance");
  }
  Vec previous = *position_;
  for (const Vec& p : scratch_) {
    if (nurbs_rapid_) {
      queue_.push_back(program::StraightTraverse{previous, p, nurbs_source_});
    } else {
      queue_.push_back(program::StraightFeed{previous, p, nurbs_source_});
    }
    previous = p;
  }
  position_ = previous;
}

}  // namespace vcpost::cldata
