// How far a section's tool sits from the model: gouge and lift depths
// (min/median/max) and, when most points sit at one offset, the likely
// causes. Accumulated point by point (memory does not grow with the path:
// a histogram of 1 um bins). Internal to the post module.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "postproc/post/tool_sections.h"

namespace vcpost::post {

class OffsetHistogram {
 public:
  // tolerance: the contact tolerance (mm); radius: the tool's (mm); stock:
  // the allowance the distances are measured from, and the section's tool
  // number, for the option the diagnosis names.
  OffsetHistogram(double tolerance_mm, double radius_mm, geometry::Allowance stock = {},
                  std::optional<int> tool = std::nullopt);

  // A point near the model: its signed distance from the surface minus R
  // (geometry::BallContact::distance_error), mm.
  void add(double distance_error_mm);

  DepthStatistics gouge() const;  // over the points deeper than the tolerance
  DepthStatistics lift() const;   // over the points higher than the tolerance
  // Set when at least half the points near the model lie within +-0.02 mm
  // of one offset of at least 0.05 mm and 3 tolerances (when none is within
  // the tolerance: of more than the tolerance).
  std::optional<OffsetDiagnosis> diagnosis() const;

 private:
  static constexpr double kBin = 0.001;   // mm
  static constexpr double kRange = 50.0;  // mm either side; beyond, the end bins
  std::size_t bin_of(double value) const;
  double value_of(std::size_t bin) const;
  // Whether every value `bin` holds is a gouge (a lift) beyond the tolerance.
  bool beyond_tolerance(std::size_t bin, bool gouge) const;
  DepthStatistics depths(bool gouge) const;

  double tolerance_, radius_;
  geometry::Allowance stock_;
  std::optional<int> tool_;
  std::vector<std::uint32_t> bins_;
  std::uint64_t points_ = 0;
  double gouge_min_ = 0, gouge_max_ = 0, lift_min_ = 0, lift_max_ = 0;  // |depth|, mm
  std::uint64_t gouges_ = 0, lifts_ = 0;
  // Of those, the ones in a bin not wholly beyond the tolerance (depths just
  // beyond it): the median's walk starts past them.
  std::uint64_t gouges_in_tolerance_bin_ = 0, lifts_in_tolerance_bin_ = 0;
};

}  // namespace vcpost::post
