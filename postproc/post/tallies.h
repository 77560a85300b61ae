// How near vc runs to its nominal value, as cutting time in bands around
// it: the one definition of the 5 % and 10 % bands that the post summary
// and the report both give.
#pragma once

#include <cmath>

namespace vcpost::post {

struct VcBandTimes {
  double within_5 = 0;   // s with |vc / nominal - 1| <= 5 %
  double within_10 = 0;  // s with |vc / nominal - 1| <= 10 %
  double below = 0;      // s more than 5 % under nominal
  double above = 0;      // s more than 5 % over nominal

  void add(double vc, double nominal, double weight_s) {
    constexpr double slack = 1e-12;  // a vc on a band's edge counts as inside
    const double deviation = vc / nominal - 1;
    if (std::abs(deviation) <= 0.05 + slack) within_5 += weight_s;
    if (std::abs(deviation) <= 0.10 + slack) within_10 += weight_s;
    if (deviation < -0.05 - slack) below += weight_s;
    if (deviation > 0.05 + slack) above += weight_s;
  }
};

}  // namespace vcpost::post
