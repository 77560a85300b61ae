#include "postproc/samplegen/toolpath.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <string_view>

#include "postproc/samplegen/tool_placement.h"

namespace vcpost::samplegen {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// One pass of the pattern: the positions base + t*dir, t from t0 to t1 in
// `segments` equal steps (from t1 down to t0 when `reverse`); a position is
// the tool axis's xy (raster) or (u,v) (iso).
struct Line {
  int pass = 0;
  Vector2d base, dir;
  double t0 = 0, t1 = 0;
  std::uint64_t segments = 1;
  bool reverse = false;
  Vector2d at(std::uint64_t i) const {  // the i-th nominal position, in path order
    const std::uint64_t k = reverse ? segments - i : i;
    return base + (t0 + (t1 - t0) * static_cast<double>(k) / static_cast<double>(segments)) * dir;
  }
  Vector2d along(double s) const {  // s in [0, segments]: between the nominal positions
    const double k = reverse ? static_cast<double>(segments) - s : s;
    return base + (t0 + (t1 - t0) * k / static_cast<double>(segments)) * dir;
  }
};

// Calls visit(line) for every pass of the pattern, in order.
template <typename Visit>
void walk(const PathSpec& spec, Visit&& visit) {
  if (!(spec.stepover > 0) || !(spec.step > 0)) {
    // Internal invariant, not the user's input: samplegen's own parameters.
    throw std::invalid_argument("toolpath: stepover and step must be positive");
  }
  int pass = 0;
  auto emit_line = [&](const Vector2d& base, const Vector2d& dir, double t0, double t1) {
    const double length = t1 - t0;
    if (!(length > 1e-9)) return;
    Line line;
    line.pass = pass;
    line.base = base;
    line.dir = dir;
    line.t0 = t0;
    line.t1 = t1;
    line.segments = static_cast<std::uint64_t>(std::max(1.0, std::ceil(length / spec.step - 1e-9)));
    line.reverse = spec.zigzag && pass % 2 == 1;
    visit(line);
    ++pass;
  };
  const Eigen::AlignedBox2d& w = spec.window;
  if (spec.pattern == Pattern::raster) {
    const double a = spec.angle_deg * std::numbers::pi / 180;
    const Vector2d d(std::cos(a), std::sin(a)), n(-std::sin(a), std::cos(a));
    double smin = HUGE_VAL, smax = -HUGE_VAL;
    for (int c = 0; c < 4; ++c) {
      const double s = n.dot(w.corner(static_cast<Eigen::AlignedBox2d::CornerType>(c)));
      smin = std::min(smin, s);
      smax = std::max(smax, s);
    }
    for (std::uint64_t k = 0;; ++k) {
      const double s = smin + static_cast<double>(k) * spec.stepover;
      if (s > smax + 1e-9 * spec.stepover) break;
      const Vector2d base = s * n;
      double t0 = -HUGE_VAL, t1 = HUGE_VAL;
      bool empty = false;
      for (int i = 0; i < 2; ++i) {
        if (std::abs(d[i]) < 1e-15) {
          if (base[i] < w.min()[i] || base[i] > w.max()[i]) empty = true;
          continue;
        }
        double ta = (w.min()[i] - base[i]) / d[i], tb = (w.max()[i] - base[i]) / d[i];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
      }
      if (spec.window_radius) {
        const double h2 = *spec.window_radius * *spec.window_radius - s * s;
        if (h2 <= 0) continue;
        t0 = std::max(t0, -std::sqrt(h2));
        t1 = std::min(t1, std::sqrt(h2));
      }
      if (!empty) emit_line(base, d, t0, t1);
    }
  } else {
    const bool along_u = spec.pattern == Pattern::iso_u;
    const int across = along_u ? 1 : 0, along = along_u ? 0 : 1;
    Vector2d dir = Vector2d::Zero();
    dir[along] = 1;
    for (std::uint64_t k = 0;; ++k) {
      const double s = w.min()[across] + static_cast<double>(k) * spec.stepover;
      if (s > w.max()[across] + 1e-9 * spec.stepover) break;
      Vector2d base = Vector2d::Zero();
      base[across] = s;
      emit_line(base, dir, w.min()[along], w.max()[along]);
    }
  }
}

double distance_to_segment(const Vector3d& q, const Vector3d& a, const Vector3d& b) {
  const Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0 ? std::clamp((q - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + t * ab - q).norm();
}

// A curve of tool positions (ball centres on the offset surface, or bull-nose
// and flat tool origins), s -> the tool resting there (`guess`: a nearby
// placement), and the refinement of its chords.
using ContactAt = std::function<ToolPlacement(double s, const ToolPlacement& guess)>;

struct Knot {
  double s;
  ToolPlacement at;
};

class ChordRefiner {
 public:
  explicit ChordRefiner(double tolerance) : tolerance_(tolerance) {}

  // Calls emit(placement) for the points strictly between a and b that keep
  // every chord within the tolerance of the curve (checked at each chord's
  // middle: the sagitta of a smooth curve); none when the tolerance is 0.
  void refine(const ContactAt& contact, const Knot& a, const Knot& b,
              const std::function<void(const ToolPlacement&)>& emit, int depth = 4) const {
    if (!(tolerance_ > 0) || depth == 0) return;
    const Vector3d middle = contact((a.s + b.s) / 2, a.at).origin;
    const double deviation = distance_to_segment(middle, a.at.origin, b.at.origin);
    if (deviation <= tolerance_) return;
    // The sagitta goes with the square of the chord: n equal parts cut it n^2 times.
    const int n = std::clamp(static_cast<int>(std::ceil(std::sqrt(deviation / tolerance_))), 2, 64);
    Knot previous = a;
    for (int j = 1; j <= n; ++j) {
      Knot next = b;
      if (j < n) {
        next.s = a.s + (b.s - a.s) * j / n;
        next.at = contact(next.s, previous.at);
      }
      refine(contact, previous, next, emit, depth - 1);
      if (j < n) emit(next.at);
      previous = next;
    }
  }

 private:
  double tolerance_;
};

// The tool of a PathSpec as the placement sees it.
struct ToolShape {
  double flat_radius = 0;    // R0
  double corner_radius = 0;  // rc
  explicit ToolShape(const PathSpec& spec)
      : flat_radius(spec.corner_radius ? spec.tool_radius - *spec.corner_radius : 0),
        corner_radius(spec.corner_radius.value_or(spec.tool_radius)) {}
  bool ball() const { return !(flat_radius > 0); }
};

// The ball resting on the surface at the contact uv (iso patterns).
ToolPlacement ball_at(const SampleSurface& surface, double r, const Vector2d& uv) {
  ToolPlacement placement;
  placement.uv = uv;
  placement.origin = surface.point(uv) + r * surface.normal(uv);
  return placement;
}

// Concatenation without operator+ (GCC 12 warns falsely, -Wrestrict, on
// "literal" + std::string).
std::string cat(std::initializer_list<std::string_view> parts) {
  std::string s;
  for (auto p : parts) s.append(p);
  return s;
}

char* put(char* out, double v, int decimals) {
  if (v == 0 || std::abs(v) < 0.5 * std::pow(10.0, -decimals)) v = 0;  // no "-0.000000"
  return std::to_chars(out, out + 64, v, std::chars_format::fixed, decimals).ptr;
}

// A length as Fusion 360's posts write it: up to 3 decimals, trailing
// zeros dropped, the point kept ("10.", "2.5", "0.125").
std::string fusion_number(double v) {
  std::string text = fixed(v, 3);
  while (text.back() == '0') text.pop_back();
  return text;
}

// The tool's type as Fusion 360's comments name it (vcpost reads the shape
// from it: postproc/tools/tool_comment.cpp).
std::string_view tool_type(const ProgramSpec& spec) {
  if (!spec.corner_radius) return "ball end mill";
  return *spec.corner_radius > 0 ? "bull nose end mill" : "flat end mill";
}

}  // namespace

std::string fixed(double v, int decimals) {
  char buf[80];
  return std::string(buf, put(buf, v, decimals));
}

double round_trip(double v, int decimals) {
  char buf[80];
  char* end = put(buf, v, decimals);
  double r = 0;
  std::from_chars(buf, end, r);
  return r;
}

std::uint64_t count_points(const PathSpec& spec) {
  std::uint64_t count = 0;
  walk(spec, [&](const Line& line) { count += line.segments + 1; });
  return count;
}

std::uint64_t generate(const SampleSurface& surface, const PathSpec& spec, int decimals,
                       const std::function<void(const PathPoint&)>& sink) {
  const ToolShape tool(spec);
  const bool raster = spec.pattern == Pattern::raster;
  if (!raster && !tool.ball()) {
    // Internal invariant: the command line refuses it first.
    throw std::invalid_argument("toolpath: iso-parametric patterns are written for a ball only");
  }
  const double rc = tool.corner_radius;
  const auto drop = [&](const Vector2d& xy, const ToolPlacement& guess) {
    return drop_tool(surface, tool.flat_radius, rc, xy, guess.uv);
  };
  const ChordRefiner refiner(spec.chord_tolerance);
  PathPoint p;
  bool started = false;
  Knot last{};  // the last point emitted (s unused across passes)
  auto emit = [&](int pass, bool start, bool link, const ToolPlacement& at) {
    p.pass = pass;
    p.pass_start = start;
    p.link = link;
    for (int k = 0; k < 3; ++k) p.tip[k] = round_trip(at.origin[k] - (k == 2 ? rc : 0.0), decimals);
    // The corner's centre as written: the touching core-disc point kept
    // where the exact placement had it (for a ball the centre, offset 0).
    p.offset = at.offset;
    p.center = p.tip + Vector3d(at.offset.x(), at.offset.y(), rc);
    p.uv = surface.closest(p.center, at.uv);
    p.cc = surface.point(p.uv);
    p.normal = surface.normal(p.uv);
    p.distance_error = (p.center - p.cc).norm() - rc;
    sink(p);
    ++p.index;
    last = {0, at};
  };
  walk(spec, [&](const Line& line) {
    const ContactAt contact = [&](double s, const ToolPlacement& guess) -> ToolPlacement {
      const Vector2d position = line.along(s);
      return raster ? drop(position, guess) : ball_at(surface, rc, position);
    };
    ToolPlacement first_guess;
    first_guess.uv = line.at(0);
    Knot knot{0, contact(0, started ? last.at : first_guess)};
    bool start = true;
    if (started) {
      // The straight link from the previous pass, held on the offset surface:
      // a raster's dropped from above the chord (its xy stays in the
      // window), an iso path's the surface's nearest to the chord's points.
      const Knot from = last;
      const ContactAt link = [&](double s, const ToolPlacement& guess) -> ToolPlacement {
        const Vector3d c = from.at.origin + s * (knot.at.origin - from.at.origin);
        return raster ? drop(c.head<2>(), guess)
                      : ball_at(surface, rc, surface.closest(c, guess.uv));
      };
      refiner.refine(link, {0, from.at}, {1, knot.at}, [&](const ToolPlacement& at) {
        emit(line.pass, start, true, at);
        start = false;
      });
    }
    emit(line.pass, start, false, knot.at);
    started = true;
    for (std::uint64_t i = 1; i <= line.segments; ++i) {
      const Knot next{static_cast<double>(i), contact(static_cast<double>(i), knot.at)};
      refiner.refine(contact, knot, next,
                     [&](const ToolPlacement& at) { emit(line.pass, false, false, at); });
      emit(line.pass, false, false, next.at);
      knot = next;
    }
  });
  return p.index;
}

ProgramWriter::ProgramWriter(ProgramSpec spec, std::ostream* gcode, std::ostream* cl,
                             std::ostream* truth)
    : spec_(std::move(spec)), gcode_(gcode), cl_(cl), truth_(truth) {}

void ProgramWriter::gline(const std::string& text) {
  if (gcode_ == nullptr) return;
  *gcode_ << text << '\n';
  ++gcode_line_;
}

void ProgramWriter::cline(const std::string& text) {
  if (cl_ == nullptr) return;
  *cl_ << text << '\n';
  ++cl_line_;
}

void ProgramWriter::add(const PathPoint& point) {
  const int dec = spec_.decimals;
  const std::string x = fixed(point.tip.x(), dec), y = fixed(point.tip.y(), dec),
                    z = fixed(point.tip.z(), dec);
  if (!started_) {
    started_ = true;
    const std::string safe = fixed(spec_.safe_z, dec);
    gline("%");
    std::string comment = spec_.title;  // G-code comments cannot nest parentheses
    for (char& ch : comment) {
      if (ch == '(') ch = '[';
      if (ch == ')') ch = ']';
    }
    gline(cat({"(", comment, "; CL point = tool tip, written by vcpost-samplegen)"}));
    // The tool as Fusion 360's posts describe it, a form vcpost reads: the
    // sample posts with no --tool.
    const double corner = spec_.corner_radius.value_or(spec_.tool_diameter / 2);
    const std::string d = fusion_number(spec_.tool_diameter);
    const std::string r = fusion_number(corner);
    gline(cat({"(T", std::to_string(spec_.tool_number), " D=", d, " CR=", r, " - ",
               tool_type(spec_), ")"}));
    gline("G21 G90 G17 G94 G40");
    gline(cat({"T", std::to_string(spec_.tool_number), " M6"}));
    gline(cat({"S", fixed(spec_.spindle_rpm, 0), " M3"}));
    gline("G0 Z" + safe);
    gline("G0 X" + x + " Y" + y);
    last_[0] = x;
    last_[1] = y;
    last_[2] = safe;
    cline("PARTNO/" + spec_.title);
    cline("UNITS/MM");
    cline(cat({"LOADTL/", std::to_string(spec_.tool_number)}));
    cline("CUTTER/" + fixed(spec_.tool_diameter, dec) + "," + fixed(corner, dec));
    cline("SPINDL/" + fixed(spec_.spindle_rpm, dec) + ",RPM,CLW");
    cline("FROM/" + x + "," + y + "," + safe);
    if (truth_ != nullptr) {
      *truth_ << "point,pass,gcode_line,cl_line,tip_x,tip_y,tip_z,cc_x,cc_y,cc_z,n_x,n_y,n_z,"
                 "distance_error\n";
    }
  }
  std::string block;
  const std::string words[3] = {x, y, z};
  const char letters[3] = {'X', 'Y', 'Z'};
  for (int k = 0; k < 3; ++k) {
    if (words[k] != last_[k]) {
      if (!block.empty()) block += ' ';
      block += letters[k] + words[k];
      last_[k] = words[k];
    }
  }
  // The approach is a rapid straight down to the first point (the samples
  // model the finished surface alone: a feed plunge would cut air), then
  // every point a feed move. Built by appending: GCC 12 warns falsely
  // (-Wrestrict) on "literal" + string.
  if (point.index <= 1) {
    std::string first(point.index == 0 ? "G0 " : "G1 ");
    if (block.empty()) {
      first.append(1, 'Z').append(z);
    } else {
      first.append(block);
    }
    block = first;
    if (point.index == 1) block.append(" F").append(fixed(spec_.feed, 0));
  } else if (block.empty()) {
    block.assign(1, 'X').append(x);  // the same point again: still one block per point
  }
  gline(block);
  if (point.index == 0) cline("RAPID");
  cline("GOTO/" + x + "," + y + "," + z);
  const std::uint64_t gcode_line = gcode_ ? gcode_line_ : 0, cl_line = cl_ ? cl_line_ : 0;
  if (point.index == 0) cline("FEDRAT/" + fixed(spec_.feed, dec) + ",MMPM");
  last_tip_ = point.tip;
  if (truth_ != nullptr) {
    char buf[512];
    char* o = buf;
    auto num = [&](double v, int d) {
      o = put(o, v, d);
      *o++ = ',';
    };
    o = std::to_chars(o, buf + 40, point.index).ptr;
    *o++ = ',';
    o = std::to_chars(o, buf + 80, point.pass).ptr;
    *o++ = ',';
    o = std::to_chars(o, buf + 120, gcode_line).ptr;
    *o++ = ',';
    o = std::to_chars(o, buf + 160, cl_line).ptr;
    *o++ = ',';
    for (int k = 0; k < 3; ++k) num(point.tip[k], dec);
    for (int k = 0; k < 3; ++k) num(point.cc[k], 10);
    for (int k = 0; k < 3; ++k) num(point.normal[k], 12);
    o = std::to_chars(o, buf + sizeof buf, point.distance_error, std::chars_format::scientific, 3)
            .ptr;
    *o++ = '\n';
    truth_->write(buf, o - buf);
  }
}

void ProgramWriter::finish() {
  if (!started_) return;
  const int dec = spec_.decimals;
  gline("G0 Z" + fixed(spec_.safe_z, dec));
  gline("M5");
  gline("M30");
  gline("%");
  cline("RAPID");
  cline("GOTO/" + fixed(last_tip_.x(), dec) + "," + fixed(last_tip_.y(), dec) + "," +
        fixed(spec_.safe_z, dec));
  cline("SPINDL/OFF");
  cline("FINI");
}

}  // namespace vcpost::samplegen
