// The cutter as CL data describe it (APT CUTTER/, NX TLDATA/MILL, the Creo
// comment `$$-> CUTTER /`) and the geometry::Tool it becomes when it is one
// of the shapes the working-diameter engine models.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/tool.h"
#include "postproc/program/events.h"

namespace vcpost::cldata {

// No milling cutter is larger (as geometry::parse_tool says): a sign or
// unit slip otherwise.
inline constexpr double kLargestCutterDiameterMm = 5000;

struct ClCutter {
  std::string source_word;             // "CUTTER", "TLDATA/MILL", "$$-> CUTTER"
  std::vector<double> params;          // as written, lengths converted to mm, angles in degrees
  std::optional<geometry::Tool> tool;  // set when the shape is a ball, bull-nose or flat mill
  std::string why_not;                 // when tool is empty: why (for a warning)
  program::SourceRef source;           // the record that defined it
  double diameter() const { return params.empty() ? 0.0 : params.front(); }
};

// APT CUTTER/d[,r[,e,f,a,b,h]] (ISO 4343 / APT 7-parameter cutter): d
// diameter, r corner radius, e and f the corner centre's distance from the
// axis and height above the tip, a the end-face angle, b the side taper, h
// the height (lengths in mm). A ball has r = d/2, a flat mill r = 0, a
// bull-nose 0 < r < d/2; e, f, a, b must then be d/2 - r, r, 0, 0 (within
// 1e-3 mm / 1e-3 deg) or the shape is not modelled (drill points, tapers).
// REQUIRES: 1 <= params.size() <= 7 (the caller reports other counts).
ClCutter cutter_from_apt(std::span<const double> params);

// NX TLDATA/MILL,d,r,l,b,a[,...]: d diameter, r lower radius, l length,
// b taper angle, a tip angle (degrees); further parameters of the 7- and
// 10-parameter NX mills are kept but only d, r, b, a decide the shape.
// REQUIRES: params.size() >= 2.
ClCutter cutter_from_tldata_mill(std::span<const double> params);

}  // namespace vcpost::cldata
