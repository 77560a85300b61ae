// Sets of angles (unions of closed intervals) on which sinusoidal
// constraints hold: the parts of a circle on the tool that satisfy the
// engagement conditions.
#pragma once

#include <array>
#include <cmath>
#include <numbers>

#include "geometry/sinusoid.h"

namespace vcpost::geometry {

class AngleSet {
 public:
  static constexpr int capacity = 8;

  AngleSet() = default;
  explicit AngleSet(AngleInterval range) {
    if (!range.empty()) add(range);
  }

  int size() const { return count_; }
  const AngleInterval& operator[](int i) const { return parts_[static_cast<std::size_t>(i)]; }
  bool empty() const { return count_ == 0; }

  // Adds an interval that does not overlap the others.
  void add(AngleInterval part) {
    if (count_ < capacity && !part.empty()) parts_[static_cast<std::size_t>(count_++)] = part;
  }

  // Keeps the angles where f(t) <= bound.
  void keep_where(const Sinusoid& f, double bound) {
    keep_where_polar(
        std::sqrt(f.a * f.a + f.b * f.b), [&] { return std::atan2(f.b, f.a); }, f.c, bound);
  }

  // Keeps the angles where m cos(t - t0) + offset <= bound, m >= 0, t0 =
  // phase(), called only when the bound cuts the circle: for callers that
  // know t0 without an atan2 (a family of circles with one phase).
  template <class Phase>
  void keep_where_polar(double m, const Phase& phase, double offset, double bound) {
    const double k = m > 0 ? (bound - offset) / m : (bound - offset >= 0 ? 1.0 : -2.0);
    if (k >= 1) return;  // holds everywhere
    if (k < -1) {
      count_ = 0;
      return;
    }
    // m cos(t - t0) <= m k  <=>  t in [t0 + acos k, t0 + 2 pi - acos k] (mod 2 pi)
    const double half = std::acos(k), t0 = phase();
    intersect_periodic(t0 + half, 2 * std::numbers::pi - 2 * half);
  }

  // Removes the angles of `other` (treating it as open, so the result stays closed).
  void remove(const AngleSet& other) {
    for (int j = 0; j < other.count_; ++j) {
      AngleSet next;
      const AngleInterval cut = other[j];
      for (int i = 0; i < count_; ++i) {
        const AngleInterval part = (*this)[i];
        if (cut.hi <= part.lo || cut.lo >= part.hi) {
          next.add(part);
          continue;
        }
        if (cut.lo > part.lo) next.add({part.lo, cut.lo});
        if (cut.hi < part.hi) next.add({cut.hi, part.hi});
      }
      *this = next;
    }
  }

 private:
  // Intersects with the periodic arc [start, start + length] + 2 pi k.
  void intersect_periodic(double start, double length) {
    constexpr double two_pi = 2 * std::numbers::pi;
    AngleSet next;
    for (int i = 0; i < count_; ++i) {
      const AngleInterval part = (*this)[i];
      const double first = start - two_pi * std::ceil((start + length - part.lo) / two_pi);
      for (double s = first; s <= part.hi; s += two_pi) {
        const AngleInterval piece{std::max(part.lo, s), std::min(part.hi, s + length)};
        if (!piece.empty()) next.add(piece);
      }
    }
    *this = next;
  }

  std::array<AngleInterval, capacity> parts_{};
  int count_ = 0;
};

}  // namespace vcpost::geometry
