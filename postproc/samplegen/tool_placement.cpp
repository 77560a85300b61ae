#include "postproc/samplegen/tool_placement.h"

#include <array>
#include <cmath>
#include <numbers>

namespace vcpost::samplegen {

using Eigen::Vector2d;
using Eigen::Vector3d;

Vector3d origin_touching(const Vector3d& x, const Vector3d& n, double flat_radius,
                         double corner_radius) {
  Vector3d origin = x + corner_radius * n;  // the corner circle's centre
  const double horizontal = n.head<2>().norm();
  if (horizontal > 0) origin += flat_radius * Vector3d(n.x(), n.y(), 0) / horizontal;
  return origin;
}

namespace {

// A ball of radius rc dropped with its centre above a core-disc point: the
// point's offset d from the axis, the contact, the centre's height and that
// height's gradient over xy (the offset surface's slope, -N_xy / N_z).
struct DiscPoint {
  Vector2d d = Vector2d::Zero();
  Vector2d uv = Vector2d::Zero();
  double height = -HUGE_VAL;
  Vector2d slope = Vector2d::Zero();
};

// The highest point of the core disc's drop heights (see drop_tool).
class DiscSearch {
 public:
  DiscSearch(const SampleSurface& surface, double flat_radius, double corner_radius,
             const Vector2d& axis)
      : surface_(surface), r0_(flat_radius), rc_(corner_radius), axis_(axis) {}

  DiscPoint at(const Vector2d& d, const Vector2d& guess) const {
    DiscPoint p;
    p.d = d;
    p.uv = surface_.drop(axis_ + d, rc_, guess);
    const Vector3d n = surface_.normal(p.uv);
    p.height = surface_.point(p.uv).z() + rc_ * n.z();
    p.slope = -n.head<2>() / n.z();
    return p;
  }

  DiscPoint highest(const Vector2d& guess) const {
    const DiscPoint centre = at(Vector2d::Zero(), guess);
    const DiscPoint rim = highest_on_rim(centre.uv);
    DiscPoint inner = centre;
    Vector2d uv = centre.uv;
    for (int k = 0; k < 6; ++k) {  // a crest under the flat part: 7 inner points
      const DiscPoint p = at(0.5 * r0_ * direction(k * std::numbers::pi / 3), uv);
      uv = p.uv;
      if (p.height > inner.height) inner = p;
    }
    // The top is inside the disc when an inner point is higher than the
    // rim, or when the rim's best has the slope pointing inwards (the
    // ground rises towards the axis there). A crest under the flat part
    // that neither shows would be narrower than R0/2: not on these
    // surfaces, whose curvature radii are many times R0.
    DiscPoint best = rim;
    if (inner.height > rim.height) best = higher(best, ascend(inner));
    if (rim.slope.dot(rim.d) < 0) best = higher(best, ascend(rim));
    return best;
  }

 private:
  static constexpr int kRimSamples = 24;

  static Vector2d direction(double angle) { return {std::cos(angle), std::sin(angle)}; }
  // b when higher than a by more than rounding (a on a tie: the callers
  // pass the better converged first).
  static const DiscPoint& higher(const DiscPoint& a, const DiscPoint& b) {
    return b.height > a.height + 1e-12 ? b : a;
  }
  // The height's derivative along the rim at angle t (d = R0 (cos t, sin t)).
  double along_rim(const DiscPoint& p) const { return p.slope.dot(Vector2d(-p.d.y(), p.d.x())); }

  // The rim sampled, then the best sample's bracket (where the derivative
  // along the rim changes sign) refined by regula falsi (Illinois): the
  // highest point of a smooth rim to 1e-12 rad.
  DiscPoint highest_on_rim(const Vector2d& guess) const {
    const double step = 2 * std::numbers::pi / kRimSamples;
    std::array<DiscPoint, kRimSamples> rim;
    Vector2d uv = guess;
    int best = 0;
    for (int k = 0; k < kRimSamples; ++k) {
      rim[k] = at(r0_ * direction(k * step), uv);
      uv = rim[k].uv;
      if (rim[k].height > rim[best].height) best = k;
    }
    const double slope = along_rim(rim[best]);
    if (slope == 0) return rim[best];
    const int other = (best + (slope > 0 ? 1 : kRimSamples - 1)) % kRimSamples;
    const double t_best = best * step, t_other = t_best + (slope > 0 ? step : -step);
    if (along_rim(rim[other]) * slope >= 0) return rim[best];  // no sign change: keep the sample
    return refine_rim(rim[best], t_best, rim[other], t_other);
  }

  // Near the top the height is flat to rounding (1e-15 mm for 1e-7 rad):
  // the answer is the point where the derivative is nearest 0, not the
  // highest sample.
  DiscPoint refine_rim(DiscPoint a, double ta, DiscPoint b, double tb) const {
    double fa = along_rim(a), fb = along_rim(b);
    DiscPoint best = std::abs(fa) < std::abs(fb) ? a : b;
    double best_f = std::min(std::abs(fa), std::abs(fb));
    int kept = 0;  // which end stayed last time (Illinois halves its value)
    for (int it = 0; it < 60 && std::abs(tb - ta) > 1e-12; ++it) {
      const double t = (ta * fb - tb * fa) / (fb - fa);
      const DiscPoint c = at(r0_ * direction(t), std::abs(t - ta) < std::abs(t - tb) ? a.uv : b.uv);
      const double fc = along_rim(c);
      if (std::abs(fc) < best_f) best = c, best_f = std::abs(fc);
      if (fc == 0) break;
      if (fc * fa > 0) {
        a = c, ta = t, fa = fc;
        if (kept == 1) fb /= 2;
        kept = 1;
      } else {
        b = c, tb = t, fb = fc;
        if (kept == -1) fa /= 2;
        kept = -1;
      }
    }
    return best;
  }

  // Projected gradient ascent on the disc, Barzilai-Borwein steps: a local
  // highest point near `from` (a crest's top inside the disc converges
  // fast, the height being about quadratic there). The last point, unless
  // the steps wandered lower (then the highest met): at the top the heights
  // differ by rounding only, the position still converges.
  DiscPoint ascend(const DiscPoint& from) const {
    DiscPoint q = from, best = from;
    double alpha = r0_ / std::max(q.slope.norm(), 1e-12);  // a first step of R0
    for (int it = 0; it < 40; ++it) {
      Vector2d next = q.d + alpha * q.slope;
      if (next.norm() > r0_) next *= r0_ / next.norm();
      const Vector2d s = next - q.d;
      if (s.norm() <= 1e-12 * r0_) break;
      const DiscPoint p = at(next, q.uv);
      const double curvature = -s.dot(p.slope - q.slope);
      alpha = curvature > 0 ? s.squaredNorm() / curvature : r0_ / std::max(p.slope.norm(), 1e-12);
      q = p;
      best = higher(best, q);
    }
    return q.height >= best.height - 1e-12 * r0_ ? q : best;
  }

  const SampleSurface& surface_;
  double r0_, rc_;
  Vector2d axis_;
};

}  // namespace

ToolPlacement drop_tool(const SampleSurface& surface, double flat_radius, double corner_radius,
                        const Vector2d& xy, const Vector2d& guess) {
  ToolPlacement placement;
  if (!(flat_radius > 0)) {
    placement.uv = surface.drop(xy, corner_radius, guess);
    placement.origin = surface.point(placement.uv) + corner_radius * surface.normal(placement.uv);
    return placement;
  }
  const DiscPoint top = DiscSearch(surface, flat_radius, corner_radius, xy).highest(guess);
  placement.uv = top.uv;
  placement.origin = Vector3d(xy.x(), xy.y(), top.height);
  placement.offset = top.d;
  return placement;
}

}  // namespace vcpost::samplegen
