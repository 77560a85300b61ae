#include "postproc/post/section_words.h"

#include <cmath>
#include <sstream>

namespace vcpost::post {

std::string mm3(double value) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(3);
  out << value;
  return out.str();
}

std::string section_name(const ToolSection& s) {
  std::string name = s.tool ? "T" + std::to_string(*s.tool) : std::string("(no tool change)");
  if (s.entry) {
    name += " " + std::string(tools::to_string(s.entry->shape));
    if (s.entry->diameter > 0) name += " D" + mm3(s.entry->diameter);
    name += " (" + std::string(tools::to_string(s.entry->origin)) +
            (s.entry->where.empty() ? std::string() : " " + s.entry->where) + ")";
  } else {
    name += " unknown";
  }
  return name;
}

std::string depth_words(const DepthStatistics& depth, std::string_view what) {
  return std::string(what) + " min " + mm3(depth.min) + ", median " + mm3(depth.median) + ", max " +
         mm3(depth.max) + " mm (" + std::to_string(depth.points) + " points)";
}

std::string offset_words(const OffsetDiagnosis& offset) {
  return std::to_string(static_cast<int>(std::round(offset.share * 100))) +
         " % of the points near the model sit " + mm3(std::abs(offset.offset_mm)) + " mm " +
         (offset.offset_mm > 0 ? "above" : "into") + " it: likely " + offset.causes;
}

std::string lift_words(const OffsetDiagnosis& offset, double radius_mm) {
  const std::string share = std::to_string(static_cast<int>(std::round(offset.share * 100))) +
                            " % of the points near the model sit " + mm3(offset.offset_mm) +
                            " mm above it: likely ";
  // The offset is the tool radius: the program's points are the ball centre
  // (OffsetHistogram says so in its causes).
  if (std::abs(offset.offset_mm - radius_mm) <= 0.05) return share + offset.causes;
  return share + "stock to leave of about " + mm3(offset.offset_mm) + " mm (post with " +
         offset.option + ", or post the finishing program), or a tool diameter " +
         mm3(2 * offset.offset_mm) +
         " mm smaller than the program's (give the program's tool), or a contact tolerance too "
         "tight for it (--contact-tolerance above " +
         mm3(offset.offset_mm) + " mm posts it as it is)";
}

}  // namespace vcpost::post
