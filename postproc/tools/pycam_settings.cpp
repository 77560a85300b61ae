#include "postproc/tools/pycam_settings.h"

#include <cmath>

#include "core/text.h"

namespace vcpost::tools {
namespace {

constexpr std::string_view kStart = "PYCAM_TOOLPATH_SETTINGS: START";
constexpr std::string_view kEnd = "PYCAM_TOOLPATH_SETTINGS: END";

CommentTool pycam_note(std::string why) {
  CommentTool out;
  out.format = CommentFormat::pycam;
  out.note = std::move(why);
  return out;
}

// A line of an open block: "[Tool]", "shape = SphericalCutter", "", END.
bool settings_line(std::string_view t) {
  return t.empty() || t == kEnd || (t.size() >= 2 && t.front() == '[' && t.back() == ']') ||
         t.find(" = ") != std::string_view::npos;
}

}  // namespace

bool PycamSettings::takes(std::string_view text) const {
  const std::string_view t = trim(text);
  return open_ ? settings_line(t) : t == kStart;
}

std::optional<CommentTool> PycamSettings::cut_short() {
  if (!open_) return std::nullopt;
  open_ = false;
  if (!any_tool_) return std::nullopt;
  return pycam_note("a settings block without its END line");
}

std::optional<CommentTool> PycamSettings::read(std::string_view text, const std::string& where) {
  const std::string_view t = trim(text);
  if (!open_) {
    if (t != kStart) return std::nullopt;
    *this = PycamSettings{};
    open_ = true;
    return std::nullopt;
  }
  if (t != kEnd) {
    if (t.size() >= 2 && t.front() == '[' && t.back() == ']') {
      in_tool_ = t == "[Tool]";
      any_tool_ = any_tool_ || in_tool_;
    } else if (const std::size_t equals = t.find(" = ");
               in_tool_ && equals != std::string_view::npos) {
      const std::string_view key = trim(t.substr(0, equals));
      const std::string_view value = trim(t.substr(equals + 3));
      if (key == "shape") {
        shape_ = std::string(value);
        shape_where_ = where;
      } else if (key == "tool_radius" || key == "torus_radius") {
        const auto v = finite_number(value);  // Python's str(float): "0.79375", "1e-05"
        if (!v) bad_value_ = std::string(key) + " = " + std::string(value);
        (key == "tool_radius" ? radius_ : torus_) = v;
      }
    }
    return std::nullopt;
  }
  open_ = false;
  if (!any_tool_) return std::nullopt;
  if (!bad_value_.empty()) return pycam_note(bad_value_ + " is not a length");
  if (!radius_ || *radius_ <= 0 || *radius_ > 1e6)
    return pycam_note("no tool_radius in (0, 1e6] in [Tool]");
  const double d = 2 * *radius_;
  ToolEntry e;
  e.diameter = d;
  e.name = shape_;
  e.origin = ToolOrigin::comment;
  e.where = shape_where_;
  if (shape_ == "SphericalCutter") {
    e.shape = ToolShape::ball;
    e.corner_radius = *radius_;
  } else if (shape_ == "CylindricalCutter") {
    e.shape = ToolShape::flat;
    e.corner_radius = 0.0;
  } else if (shape_ == "ToroidalCutter") {
    if (!torus_ || !(*torus_ > 0) || !(*torus_ < *radius_))
      return pycam_note("a ToroidalCutter whose torus_radius is not in (0, tool_radius)");
    e.shape = ToolShape::bull_nose;
    e.corner_radius = *torus_;
  } else {
    return pycam_note("unknown shape '" + shape_.substr(0, 60) + "'");
  }
  CommentTool out;
  out.format = CommentFormat::pycam;
  out.entry = std::move(e);
  return out;
}

}  // namespace vcpost::tools
