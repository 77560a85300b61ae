#include "revolved_reference_support.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

namespace vcpost::testing {
namespace {

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kRatio = 0.6180339887498949;  // (sqrt 5 - 1) / 2

// Least value of a convex f with |f'| <= 1 on [lo, hi] by golden section,
// to an error of at most `relative` of its size (or 1e-13 `scale`): the
// bracket holds the minimiser, so the least value is within the bracket's
// width below the least one seen.
template <class F>
double golden_min_value(const F& f, double lo, double hi, double relative, double scale) {
  double x1 = hi - kRatio * (hi - lo), x2 = lo + kRatio * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < 100; ++i) {
    if (hi - lo <= std::max(relative * std::min(std::abs(f1), std::abs(f2)), 1e-13 * scale)) break;
    if (f1 <= f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - kRatio * (hi - lo), f1 = f(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + kRatio * (hi - lo), f2 = f(x2);
    }
  }
  return std::min(f1, f2);
}

// A local maximum of f on [lo, hi] by golden section, as (argument, value);
// when `early`, stops at the first value >= 0 (the question is "any >= 0?").
template <class F>
std::pair<double, double> golden_max(const F& f, double lo, double hi, int iterations,
                                     bool early = true) {
  double x1 = hi - kRatio * (hi - lo), x2 = lo + kRatio * (hi - lo);
  double f1 = f(x1);
  if (early && f1 >= 0) return {x1, f1};
  double f2 = f(x2);
  for (int i = 0; i < iterations && !(early && (f1 >= 0 || f2 >= 0)); ++i) {
    if (f1 >= f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - kRatio * (hi - lo), f1 = f(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + kRatio * (hi - lo), f2 = f(x2);
    }
  }
  return f1 >= f2 ? std::pair{x1, f1} : std::pair{x2, f2};
}

enum class Piece { face, corner, shank };

// One horizontal circle of the tool: P = (rho cos t, rho sin t, z), outward
// normal (s cos t, s sin t, nz).
struct Circle {
  double rho, z, s, nz;
};

class Reference {
 public:
  Reference(double diameter, double corner, double ap, double ae, const Vector3d& normal,
            const Vector3d& feed, bool left, ReferenceResolution resolution)
      : radius_(diameter / 2), corner_(corner), flat_(radius_ - corner), resolution_(resolution) {
    n_ = normal.normalized();
    f_ = (feed - feed.dot(n_) * n_).normalized();
    offset_ = (left ? ae : -ae) * n_.cross(f_);
    tilt_ = std::hypot(n_.x(), n_.y());
    // The lowest tool point along N is on the corner's lowest circle (the
    // face's rim for the flat mill), rc below it along N.
    c0_ = -flat_ * tilt_ - corner_ + ap;
    pieces_.push_back({Piece::face, flat_});
    if (corner_ > 0) pieces_.push_back({Piece::corner, kPi / 2});
    // The shank's highest point in the stock: -R tilt + nz z = c0.
    const double top = (c0_ + radius_ * tilt_) / n_.z();
    if (top > 0) pieces_.push_back({Piece::shank, top});
  }

  ReferenceExtremes extremes() const {
    ReferenceExtremes out;
    const std::optional<Level> top = extreme_level(true);
    if (!top) return out;
    const std::optional<Level> bottom = extreme_level(false);
    const Circle highest = circle(*top);
    out.any = true;
    out.d_max = 2 * highest.rho;
    out.d_min = 2 * circle(bottom ? *bottom : *top).rho;
    out.shank = pieces_[top->piece].piece == Piece::shank && highest.z > 1e-9 * radius_;
    return out;
  }

 private:
  struct PieceRange {
    Piece piece;
    double length;  // of its parameter
  };
  // A circle of the stack: piece and its parameter scaled to [0, 1]. The
  // pieces meet in circles that belong to both, with either normal (the
  // flat mill's edge is on the face and on the shank).
  struct Level {
    int piece;
    double t;
  };

  Circle circle(const Level& level) const {
    const double u = std::clamp(level.t, 0.0, 1.0) * pieces_[level.piece].length;
    switch (pieces_[level.piece].piece) {
      case Piece::face:
        return {u, -corner_, 0, -1};
      case Piece::corner:
        return {flat_ + corner_ * std::sin(u), -corner_ * std::cos(u), std::sin(u), -std::cos(u)};
      case Piece::shank:
        return {radius_, u, 1, 0};
    }
    return {};
  }

  // >= 0 when p is not strictly inside the tool swept along the line
  // through the offset parallel to F: the least over the line of a convex
  // function that is < 0 exactly inside the tool.
  double outside_previous(const Vector3d& p) const {
    const Vector3d q = p - offset_;
    const double fxy2 = f_.x() * f_.x() + f_.y() * f_.y();
    // Inside the tool the line is within R of the axis: |t - t_axis| < R / |F_xy|.
    const double t_axis = (q.x() * f_.x() + q.y() * f_.y()) / fxy2;
    const double window = radius_ / std::sqrt(fxy2) + radius_;
    const auto depth = [&](double t) {
      const Vector3d x = q - t * f_;
      const double rho = std::hypot(x.x(), x.y());
      if (corner_ == 0) return std::max(rho - radius_, -x.z());
      return std::hypot(std::max(0.0, rho - flat_), std::min(0.0, x.z())) - corner_;
    };
    return golden_min_value(depth, t_axis - window, t_axis + window, 1e-3, radius_);
  }

  // min of the three conditions' margins, >= 0 exactly where engaged.
  double margin(const Circle& c, double theta) const {
    const double ct = std::cos(theta), st = std::sin(theta);
    const Vector3d p(c.rho * ct, c.rho * st, c.z);
    const double stock = c0_ - n_.dot(p);
    const double lead = radius_ * (c.s * (f_.x() * ct + f_.y() * st) + c.nz * f_.z());
    const double cheap = std::min(stock, lead);
    return cheap < 0 ? cheap : std::min(cheap, outside_previous(p));
  }

  struct Arc {
    double lo, hi;
  };

  // The angles where a cos t + b sin t + k >= 0: false when none, else
  // `arc` holds them (all: a whole turn).
  static bool arc_where(double a, double b, double k, Arc& arc) {
    const double amplitude = std::hypot(a, b);
    if (k >= amplitude) {
      arc = {-kPi, kPi};
      return true;
    }
    if (k < -amplitude) return false;
    const double centre = std::atan2(b, a), half = std::acos(-k / amplitude);
    arc = {centre - half, centre + half};
    return true;
  }

  // The arcs of a circle in the stock and on the leading side: at most two.
  std::vector<Arc> allowed(const Circle& c) const {
    Arc stock{}, lead{};
    if (!arc_where(-c.rho * n_.x(), -c.rho * n_.y(), c0_ - n_.z() * c.z, stock) ||
        !arc_where(c.s * f_.x(), c.s * f_.y(), c.nz * f_.z(), lead)) {
      return {};
    }
    std::vector<Arc> out;
    for (const double turn : {-2 * kPi, 0.0, 2 * kPi}) {
      const Arc both{std::max(stock.lo, lead.lo + turn), std::min(stock.hi, lead.hi + turn)};
      if (both.hi >= both.lo) out.push_back(both);
    }
    return out;
  }

  // The circle's largest margin (or the first value >= 0 met), searched on
  // its arcs in the stock and on the leading side; a negative number when
  // there are none.
  struct Found {
    double value, theta;  // the margin found and where
  };
  Found circle_margin(int piece, double t) const {
    const Circle c = circle({piece, t});
    const std::vector<Arc> arcs = allowed(c);
    if (arcs.empty()) return {-1e-9 * radius_, 0};
    if (c.rho == 0) return {margin(c, 0), 0};
    Found best{-kInf, 0};
    struct Peak {
      double value, lo, hi;
    };
    std::vector<Peak> peaks;
    for (const Arc& arc : arcs) {
      const double length = arc.hi - arc.lo;
      const int k =
          std::max(8, static_cast<int>(std::ceil(resolution_.angles * length / (2 * kPi))));
      std::vector<double> v(k + 1);
      for (int j = 0; j <= k; ++j) {
        const double theta = arc.lo + length * j / k;
        v[j] = margin(c, theta);
        if (v[j] >= 0) return {v[j], theta};
        if (v[j] > best.value) best = {v[j], theta};
      }
      // Every sampled local maximum (the ends included) brackets one of the
      // margin's.
      for (int j = 0; j <= k; ++j) {
        if ((j == 0 || v[j] > v[j - 1]) && (j == k || v[j] >= v[j + 1])) {
          peaks.push_back({v[j], arc.lo + length * std::max(j - 1, 0) / k,
                           arc.lo + length * std::min(j + 1, k) / k});
        }
      }
    }
    std::sort(peaks.begin(), peaks.end(),
              [](const Peak& a, const Peak& b) { return a.value > b.value; });
    for (std::size_t i = 0; i < std::min<std::size_t>(peaks.size(), 8); ++i) {
      const auto [theta, value] =
          golden_max([&](double angle) { return margin(c, angle); }, peaks[i].lo, peaks[i].hi, 50);
      if (value >= 0) return {value, theta};
      if (value > best.value) best = {value, theta};
    }
    return best;
  }

  // The bisection between an engaged level of a piece (engaged at angle
  // theta) and a free one: the engaged end of the final bracket. Near the
  // end the engaged arc shrinks to a point, narrower than the circle's
  // samples: each level is first searched for the margin's peak next to
  // the last engaged angle, which follows it.
  Level bisect(int piece, double in, double out, double theta) const {
    const double step = 2 * kPi / resolution_.angles;
    for (int i = 0; i < 60 && std::abs(in - out) > 1e-15; ++i) {
      const double mid = 0.5 * (in + out);
      const Circle c = circle({piece, mid});
      auto [at, value] = golden_max([&](double angle) { return margin(c, angle); }, theta - step,
                                    theta + step, 60, false);
      if (value < 0) {
        const Found found = circle_margin(piece, mid);
        value = found.value;
        at = found.theta;
      }
      if (value >= 0) {
        in = mid;
        theta = at;
      } else {
        out = mid;
      }
    }
    return {piece, in};
  }

  // The highest (top) or lowest engaged level of one piece; empty when none.
  std::optional<Level> extreme_in_piece(int piece, bool top) const {
    const int levels = resolution_.levels;
    const auto t_at = [&](int k) { return static_cast<double>(top ? levels - k : k) / levels; };
    const auto m_at = [&](double t) { return circle_margin(piece, t).value; };
    std::vector<double> m;
    for (int k = 0; k <= levels; ++k) {
      const double t = t_at(k);
      const Found found = circle_margin(piece, t);
      m.push_back(found.value);
      if (m[k] >= 0) return k == 0 ? Level{piece, t} : bisect(piece, t, t_at(k - 1), found.theta);
      // The previous level a sampled local maximum: an engaged sliver may
      // lie between its neighbours.
      if (k >= 1 && m[k - 1] > m[k] && (k == 1 || m[k - 1] >= m[k - 2])) {
        const int outer = std::max(k - 2, 0);
        const auto peak = golden_max(m_at, t_at(outer), t_at(k), 45);
        if (peak.second >= 0) {
          return bisect(piece, peak.first, t_at(outer), circle_margin(piece, peak.first).theta);
        }
      }
    }
    return std::nullopt;
  }

  // The highest (top) or lowest engaged level of the stack: r grows along
  // it, so the first piece from that end with an engaged level holds it.
  std::optional<Level> extreme_level(bool top) const {
    const int count = static_cast<int>(pieces_.size());
    for (int i = 0; i < count; ++i) {
      if (const auto level = extreme_in_piece(top ? count - 1 - i : i, top)) return level;
    }
    return std::nullopt;
  }

  double radius_, corner_, flat_;
  ReferenceResolution resolution_;
  Vector3d n_, f_, offset_;
  double tilt_ = 0, c0_ = 0;
  std::vector<PieceRange> pieces_;
};

}  // namespace

ReferenceExtremes reference_extremes(double diameter, double corner_radius, double ap, double ae,
                                     const Vector3d& normal, const Vector3d& feed,
                                     bool previous_on_left, ReferenceResolution resolution) {
  return Reference(diameter, corner_radius, ap, ae, normal, feed, previous_on_left, resolution)
      .extremes();
}

}  // namespace vcpost::testing
