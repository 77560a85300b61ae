// The words for a tool section's facts: its name, its gouge and lift
// depths, the offset that dominates it. One wording per fact, shared by the
// end-of-run lines of `vcpost post` and the error that refuses a program
// which does not match its model.
#pragma once

#include <string>
#include <string_view>

#include "postproc/post/tool_sections.h"

namespace vcpost::post {

// A length in mm with three decimals ("5.000").
std::string mm3(double value);

// "T2 ball D10.000 (--tool)", "(no tool change) unknown".
std::string section_name(const ToolSection& s);

// "gouge depth min 0.010, median 0.500, max 1.200 mm (345 points)";
// `what` names the depth ("gouge depth", "lift height").
std::string depth_words(const DepthStatistics& depth, std::string_view what);

// "97 % of the points near the model sit 5.000 mm into it: likely ...".
std::string offset_words(const OffsetDiagnosis& offset);

// For a toolpath that sits above the model and never touches it: "100 % of
// the points near the model sit 0.050 mm above it: likely stock to leave of
// about 0.050 mm ...". The causes of `offset` (> 0) where the offset is the
// tool radius (`radius_mm`: the CL point), else stock, the tool diameter or
// the contact tolerance.
std::string lift_words(const OffsetDiagnosis& offset, double radius_mm);

}  // namespace vcpost::post
