#include "postproc/samplegen/toolpath.h"

#include <charconv>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <string_view>

namespace vcpost::samplegen {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// Calls visit(pass, pass_start, position) for every point of the pattern:
// position = ball-centre xy (raster) or (u,v) (iso). Returns the count.
template <typename Visit>
std::uint64_t walk(const PathSpec& spec, Visit&& visit) {
  if (!(spec.stepover > 0) || !(spec.step > 0)) {
    throw std::invalid_argument("toolpath: stepover and step must be positive");
  }
  std::uint64_t count = 0;
  int pass = 0;
  auto emit_line = [&](const Vector2d& base, const Vector2d& dir, double t0, double t1) {
    const double length = t1 - t0;
    if (!(length > 1e-9)) return;
    const auto segments =
        static_cast<std::uint64_t>(std::max(1.0, std::ceil(length / spec.step - 1e-9)));
    const bool reverse = spec.zigzag && pass % 2 == 1;
    for (std::uint64_t i = 0; i <= segments; ++i) {
      const std::uint64_t k = reverse ? segments - i : i;
      const double t = t0 + length * static_cast<double>(k) / static_cast<double>(segments);
      visit(pass, i == 0, Vector2d(base + t * dir));
      ++count;
    }
    ++pass;
  };
  const Eigen::AlignedBox2d& w = spec.window;
  if (spec.pattern == Pattern::raster) {
    const double a = spec.angle_deg * std::numbers::pi / 180;
    const Vector2d d(std::cos(a), std::sin(a)), n(-std::sin(a), std::cos(a));
    double smin = INFINITY, smax = -INFINITY;
    for (int c = 0; c < 4; ++c) {
      const double s = n.dot(w.corner(static_cast<Eigen::AlignedBox2d::CornerType>(c)));
      smin = std::min(smin, s);
      smax = std::max(smax, s);
    }
    for (std::uint64_t k = 0;; ++k) {
      const double s = smin + static_cast<double>(k) * spec.stepover;
      if (s > smax + 1e-9 * spec.stepover) break;
      const Vector2d base = s * n;
      double t0 = -INFINITY, t1 = INFINITY;
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
  return count;
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
  return walk(spec, [](int, bool, const Vector2d&) {});
}

std::uint64_t generate(const SampleSurface& surface, const PathSpec& spec, int decimals,
                       const std::function<void(const PathPoint&)>& sink) {
  const double r = spec.tool_radius;
  std::optional<Vector2d> previous;
  PathPoint p;
  return walk(spec, [&](int pass, bool start, const Vector2d& position) {
    Vector2d uv;
    if (spec.pattern == Pattern::raster) {
      uv = surface.drop(position, r, previous.value_or(position));
    } else {
      uv = position;
    }
    const Vector3d centre = surface.point(uv) + r * surface.normal(uv);
    p.pass = pass;
    p.pass_start = start;
    for (int k = 0; k < 3; ++k) p.tip[k] = round_trip(centre[k] - (k == 2 ? r : 0.0), decimals);
    p.center = p.tip + Vector3d(0, 0, r);
    p.uv = surface.closest(p.center, uv);
    p.cc = surface.point(p.uv);
    p.normal = surface.normal(p.uv);
    p.distance_error = (p.center - p.cc).norm() - r;
    sink(p);
    ++p.index;
    previous = uv;
  });
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
    gline(cat({"(", comment, ")"}));
    gline("(ball-end mill D" + fixed(spec_.tool_diameter, 3) +
          " mm, CL point = tool tip, written by vcpost-samplegen)");
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
    cline("CUTTER/" + fixed(spec_.tool_diameter, dec) + "," + fixed(spec_.tool_diameter / 2, dec));
    cline("SPINDL/" + fixed(spec_.spindle_rpm, dec) + ",RPM,CLW");
    cline("FROM/" + x + "," + y + "," + safe);
    cline("FEDRAT/" + fixed(spec_.feed, dec) + ",MMPM");
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
  // Built by appending: GCC 12 warns falsely (-Wrestrict) on "literal" + string.
  if (point.index == 0) {
    std::string first("G1 ");
    if (block.empty()) {
      first.append(1, 'Z').append(z);
    } else {
      first.append(block);
    }
    block = first.append(" F").append(fixed(spec_.feed, 0));
  } else if (block.empty()) {
    block.assign(1, 'X').append(x);  // the same point again: still one block per point
  }
  gline(block);
  cline("GOTO/" + x + "," + y + "," + z);
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
    o = std::to_chars(o, buf + 120, gcode_ ? gcode_line_ : 0).ptr;
    *o++ = ',';
    o = std::to_chars(o, buf + 160, cl_ ? cl_line_ : 0).ptr;
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
