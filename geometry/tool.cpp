#include "geometry/tool.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/text.h"

namespace vcpost::geometry {
namespace {

std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> parts;
  for (std::size_t start = 0;;) {
    const std::size_t end = text.find(separator, start);
    parts.push_back(text.substr(start, end - start));
    if (end == std::string_view::npos) return parts;
    start = end + 1;
  }
}

double parse_size(std::string_view text, std::string_view what, std::string_view spec) {
  const std::optional<double> value = finite_number(text);
  if (!value) {
    throw std::invalid_argument("tool '" + std::string(spec) + "': " + std::string(what) + " '" +
                                std::string(text) + "' is not a number");
  }
  return *value;
}

}  // namespace

// parse_tool throws std::invalid_argument: each caller names the option or
// column and turns it into a vcpost::Error (E1601 in tools/tool_table.cpp,
// E2001 in cli/deff_command.cpp, vcpost::api::Error in the library).
Tool parse_tool(std::string_view spec) {
  const auto parts = split(spec, ':');
  const std::string_view kind = parts[0];
  const std::size_t expected = kind == "bull" ? 3 : 2;
  if (kind != "ball" && kind != "bull" && kind != "flat") {
    throw std::invalid_argument("tool '" + std::string(spec) + "': unknown kind '" +
                                std::string(kind) + "' (expected ball:D, bull:D:rc or flat:D)");
  }
  if (parts.size() != expected) {
    throw std::invalid_argument("tool '" + std::string(spec) + "': expected " +
                                (kind == "bull" ? "bull:D:rc" : std::string(kind) + ":D"));
  }
  const double diameter = parse_size(parts[1], "diameter", spec);
  if (!(diameter > 0 && diameter <= 5000)) {  // none larger: a sign or unit slip (1e300)
    throw std::invalid_argument("tool '" + std::string(spec) +
                                "': diameter must be > 0 and at most 5000 mm");
  }
  if (kind == "ball") return Tool::ball(diameter);
  if (kind == "flat") return Tool::flat(diameter);
  const double corner = parse_size(parts[2], "corner radius", spec);
  if (corner <= 0 || corner > diameter / 2) {
    throw std::invalid_argument("tool '" + std::string(spec) +
                                "': corner radius must lie in (0, D/2]");
  }
  // A corner that fills the radius is a ball end.
  if (corner == diameter / 2) return Tool::ball(diameter);
  return Tool::bull_nose(diameter, corner);
}

std::string_view to_string(ToolKind kind) {
  switch (kind) {
    case ToolKind::ball:
      return "ball";
    case ToolKind::bull_nose:
      return "bull";
    case ToolKind::flat:
      return "flat";
  }
  return "?";
}

std::string to_string(const Tool& tool) {
  std::ostringstream out;
  out << to_string(tool.kind) << ':' << tool.diameter;
  if (tool.kind == ToolKind::bull_nose) out << ':' << tool.corner_radius;
  return out.str();
}

}  // namespace vcpost::geometry
