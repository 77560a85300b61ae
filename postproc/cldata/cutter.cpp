#include "postproc/cldata/cutter.h"

#include <cmath>
#include <string>

namespace vcpost::cldata {

namespace {

constexpr double length_tol = 1e-3;  // mm: CL files print 3 to 6 decimals
constexpr double angle_tol = 1e-3;   // degrees

std::string number(double v) {
  std::string s = std::to_string(v);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

// Ball, bull-nose or flat from diameter and corner radius, or the reason
// why not.
void classify(ClCutter& c, double d, double r) {
  if (!(d > 0)) {
    c.why_not = "diameter " + number(d) + " is not positive";
  } else if (r < -length_tol || r > d / 2 + length_tol) {
    c.why_not = "corner radius " + number(r) + " outside [0, d/2]";
  } else if (std::abs(r) <= length_tol) {
    c.tool = geometry::Tool::flat(d);
  } else if (std::abs(r - d / 2) <= length_tol) {
    c.tool = geometry::Tool::ball(d);
  } else {
    c.tool = geometry::Tool::bull_nose(d, r);
  }
}

}  // namespace

ClCutter cutter_from_apt(std::span<const double> params) {
  ClCutter c;
  c.source_word = "CUTTER";
  c.params.assign(params.begin(), params.end());
  const double d = params[0];
  const double r = params.size() > 1 ? params[1] : 0.0;
  if (params.size() > 2) {
    const double e = params[2];
    const double f = params.size() > 3 ? params[3] : r;
    const double a = params.size() > 4 ? params[4] : 0.0;
    const double b = params.size() > 5 ? params[5] : 0.0;
    if (std::abs(a) > angle_tol || std::abs(b) > angle_tol) {
      c.why_not = "end angle " + number(a) + " deg, taper " + number(b) +
                  " deg (a drill point or tapered cutter)";
      return c;
    }
    if (std::abs(e - (d / 2 - r)) > length_tol || std::abs(f - r) > length_tol) {
      c.why_not = "corner centre (e " + number(e) + ", f " + number(f) +
                  ") is not that of a ball, bull-nose or flat mill";
      return c;
    }
  }
  classify(c, d, r);
  return c;
}

ClCutter cutter_from_tldata_mill(std::span<const double> params) {
  ClCutter c;
  c.source_word = "TLDATA/MILL";
  c.params.assign(params.begin(), params.end());
  const double taper = params.size() > 3 ? params[3] : 0.0;
  const double tip = params.size() > 4 ? params[4] : 0.0;
  if (std::abs(taper) > angle_tol || std::abs(tip) > angle_tol) {
    c.why_not = "taper " + number(taper) + " deg, tip angle " + number(tip) +
                " deg (not a ball, bull-nose or flat mill)";
    return c;
  }
  classify(c, params[0], params[1]);
  return c;
}

}  // namespace vcpost::cldata
