#include "postproc/cldata/nurbs.h"

#include "geometry/model.h"

namespace vcpost::cldata {

std::optional<BSpline> nx_nurbs(const Eigen::Vector3d& start, std::span<const double> span_ends,
                                std::span<const Eigen::Vector4d> cntrl, std::string& error) {
  const auto spans = static_cast<long>(span_ends.size());
  const long count = 1 + static_cast<long>(cntrl.size());
  const long degree = count - spans;
  if (spans < 1 || degree < 1 || degree > 9) {
    error = std::to_string(span_ends.size()) + " KNOT values and " + std::to_string(cntrl.size()) +
            " CNTRL points do not make a B-spline of degree 1 to 9";
    return std::nullopt;
  }
  double previous = 0;
  for (const double k : span_ends) {
    if (!(k > previous)) {
      error = "KNOT values must increase from 0";
      return std::nullopt;
    }
    previous = k;
  }
  BSpline c;
  c.degree = static_cast<int>(degree);
  c.control.reserve(static_cast<std::size_t>(count));
  c.control.push_back(Eigen::Vector4d(start.x(), start.y(), start.z(), 1.0));
  for (const Eigen::Vector4d& h : cntrl) {
    if (!(h[3] > 0)) {
      error = "CNTRL weight must be positive";
      return std::nullopt;
    }
    // A point kilometres away pulls the curve out and back: millions of
    // lines within the chord tolerance, for a path no machine can run.
    if (!((h.head<3>() / h[3]).cwiseAbs().maxCoeff() <= geometry::kMaxReachMm)) {
      error =
          "a CNTRL point lies beyond 100000 mm (100 m) from the origin; the path must fit "
          "a machine";
      return std::nullopt;
    }
    c.control.push_back(h);
  }
  c.knots.assign(static_cast<std::size_t>(degree + 1), 0.0);
  c.knots.insert(c.knots.end(), span_ends.begin(), span_ends.end() - 1);
  c.knots.insert(c.knots.end(), static_cast<std::size_t>(degree + 1), span_ends.back());
  return c;
}

}  // namespace vcpost::cldata
