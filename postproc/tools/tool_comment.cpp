#include "postproc/tools/tool_comment.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <regex>
#include <vector>

#include "core/text.h"

namespace vcpost::tools {
namespace {

// A decimal as CAM posts write it: "6.", ".25", "-19.8", "3".
std::optional<double> number(std::string_view text) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  return finite_number(text);
}

// The value of `key=` (key at the start of a blank-separated token), up to the next blank.
std::optional<std::string_view> field(std::string_view text, std::string_view key) {
  for (std::size_t at = text.find(key); at != std::string_view::npos; at = text.find(key, at + 1)) {
    if (at > 0 && !std::isspace(static_cast<unsigned char>(text[at - 1]))) continue;
    std::string_view rest = text.substr(at + key.size());
    return rest.substr(0, std::min(rest.find(' '), rest.size()));
  }
  return std::nullopt;
}

CommentTool note(CommentFormat format, std::string why) {
  CommentTool out;
  out.format = format;
  out.note = std::move(why);
  return out;
}

ToolEntry entry_of(std::optional<int> number_of_tool, ToolShape shape, double diameter,
                   std::optional<double> corner, std::string name) {
  ToolEntry e;
  e.number = number_of_tool;
  e.shape = shape;
  e.diameter = diameter;
  if (shape == ToolShape::ball) corner = diameter / 2;
  if (shape == ToolShape::flat) corner = 0.0;
  e.corner_radius = corner;
  e.name = std::move(name);
  e.origin = ToolOrigin::comment;
  return e;
}

// Fusion 360 / HSM: T<n> [name] D=<d> [CR=<r>] [TAPER=<a>deg] [- ZMIN=<z>] - <type>.
std::optional<CommentTool> fusion(std::string_view text) {
  const std::string_view t = trim(text);
  if (t.size() < 3 || (t[0] != 'T' && t[0] != 't') ||
      !std::isdigit(static_cast<unsigned char>(t[1]))) {
    return std::nullopt;
  }
  std::size_t digits = 1;
  while (digits < t.size() && std::isdigit(static_cast<unsigned char>(t[digits]))) ++digits;
  if (digits == t.size() || !std::isspace(static_cast<unsigned char>(t[digits])))
    return std::nullopt;
  const auto d_text = field(t, "D=");
  if (!d_text) return std::nullopt;  // "T1 ..." without D=: not this format
  int tool_number = 0;
  std::from_chars(t.data() + 1, t.data() + digits, tool_number);
  const auto diameter = number(*d_text);
  if (!diameter || *diameter <= 0)
    return note(CommentFormat::fusion, "D=" + std::string(*d_text) + " is not a diameter");
  std::optional<double> corner;
  if (const auto cr = field(t, "CR=")) {
    corner = number(*cr);
    if (!corner || *corner < 0)
      return note(CommentFormat::fusion, "CR=" + std::string(*cr) + " is not a corner radius");
  }
  double taper = 0;
  if (const auto tp = field(t, "TAPER=")) {
    std::string_view value = *tp;
    if (value.size() > 3 && to_upper(value.substr(value.size() - 3)) == "DEG")
      value.remove_suffix(3);
    const auto angle = number(value);
    if (!angle)
      return note(CommentFormat::fusion, "TAPER=" + std::string(*tp) + " is not an angle");
    taper = *angle;
  }
  const std::size_t dash = t.rfind(" - ");
  if (dash == std::string_view::npos)
    return note(CommentFormat::fusion, "T" + std::to_string(tool_number) + ": no tool type");
  const std::string_view type = trim(t.substr(dash + 3));
  const auto shape = shape_from_type_name(type);
  if (!shape) {
    return note(CommentFormat::fusion, "T" + std::to_string(tool_number) + ": unknown tool type '" +
                                           std::string(type) + "'");
  }
  const auto d_at = static_cast<std::size_t>(d_text->data() - t.data()) - 2;  // at "D="
  std::string name(trim(t.substr(digits, d_at - digits)));
  if (name.empty()) name = std::string(type);
  CommentTool out;
  out.format = CommentFormat::fusion;
  ToolShape final_shape = *shape;
  if (taper != 0 && final_shape != ToolShape::drill) final_shape = ToolShape::other;  // tapered
  if (final_shape == ToolShape::ball && corner &&
      std::abs(*corner - *diameter / 2) > 1e-3 * std::max(1.0, *diameter)) {
    return note(CommentFormat::fusion,
                "T" + std::to_string(tool_number) +
                    ": a ball end mill with CR=" + std::string(*field(t, "CR=")) + " (not D/2)");
  }
  if (final_shape == ToolShape::flat && corner && *corner > 0) corner.reset();  // CR ignored
  out.entry = entry_of(tool_number, final_shape, *diameter, corner, std::move(name));
  return out;
}

// Mastercam: <name> TOOL - <n> DIA. OFF. - <d> LEN. - <l> DIA. - <diameter>.
std::optional<CommentTool> mastercam(std::string_view text) {
  const std::string u = to_upper(text);
  if (u.find("DIA. OFF.") == std::string::npos) return std::nullopt;
  static const std::regex pattern(
      R"(^(.*?)\s*TOOL\s*-\s*(\d+)\s+DIA\.\s*OFF\.\s*-\s*\d+\s+LEN\.\s*-\s*\d+\s+DIA\.\s*-\s*([-+]?[0-9]*\.?[0-9]+)\s*$)");
  std::smatch m;
  if (!std::regex_search(u, m, pattern))
    return note(CommentFormat::mastercam, "a Mastercam tool line that does not read");
  const int tool_number = std::stoi(m[2].str());
  const std::string name(trim(std::string_view(text).substr(0, m[1].str().size())));
  const auto diameter = number(m[3].str());
  if (!diameter || *diameter <= 0)
    return note(CommentFormat::mastercam, "TOOL - " + m[2].str() + ": no diameter");
  const auto shape = shape_from_type_name(name);
  if (!shape) {
    return note(CommentFormat::mastercam,
                "TOOL - " + m[2].str() + ": no tool type in its name '" + name + "'");
  }
  CommentTool out;
  out.format = CommentFormat::mastercam;
  out.entry = entry_of(tool_number, *shape, *diameter, std::nullopt, name);
  return out;
}

// Carbide Create: TOOL/MILL,<d>,<corner radius>,<length>,<taper half-angle>.
std::optional<CommentTool> carbide(std::string_view text) {
  const std::string_view t = trim(text);
  if (t.size() < 5 || to_upper(t.substr(0, 5)) != "TOOL/") return std::nullopt;
  const std::string kind =
      to_upper(t.substr(5, t.find(',') - std::min(t.find(','), std::size_t{5})));
  std::vector<double> values;
  for (std::size_t at = t.find(','); at != std::string_view::npos;) {
    const std::size_t end = t.find(',', at + 1);
    const auto v = number(t.substr(at + 1, end == std::string_view::npos ? end : end - at - 1));
    if (!v) return note(CommentFormat::carbide, "TOOL/ values that are not numbers");
    values.push_back(*v);
    at = end;
  }
  if (values.empty() || values[0] <= 0)
    return note(CommentFormat::carbide, "TOOL/" + kind + " without a diameter");
  CommentTool out;
  out.format = CommentFormat::carbide;
  const double d = values[0];
  if (kind == "DRILL") {
    out.entry = entry_of(std::nullopt, ToolShape::drill, d, std::nullopt, std::string(t));
    return out;
  }
  if (kind != "MILL") return note(CommentFormat::carbide, "TOOL/" + kind + " is no known kind");
  const double r = values.size() > 1 ? values[1] : 0.0;
  const double taper = values.size() > 3 ? values[3] : 0.0;
  ToolShape shape = ToolShape::other;  // a taper: V-bit or engraver
  std::optional<double> corner;
  if (taper == 0) {
    // Carbide Create writes two decimals: 3.17 for the 6.35 mm ball's 3.175.
    if (r == 0) {
      shape = ToolShape::flat;
    } else if (std::abs(r - d / 2) <= 0.0051) {
      shape = ToolShape::ball;
    } else if (r > 0 && r < d / 2) {
      shape = ToolShape::bull_nose;
      corner = r;
    } else {
      return note(CommentFormat::carbide, "TOOL/MILL with a corner radius above D/2");
    }
  }
  out.entry = entry_of(std::nullopt, shape, d, corner, std::string(t));
  return out;
}

// hyperMILL's line before a TOOL CALL: "- [TOOL: ]T<id> | <name> / DM=<d> CR=<r> [TL=<l>]".
// Its tool list header ("T<id> | ..." without the dash) names no TOOL CALL
// and is not read: the line before each call is.
std::optional<CommentTool> hypermill(std::string_view text) {
  std::string_view t = trim(text);
  if (t.empty() || t.front() != '-') return std::nullopt;
  t = trim(t.substr(1));
  if (t.starts_with("TOOL:")) t = trim(t.substr(5));
  const std::size_t bar = t.find('|');
  if (t.size() < 2 || t[0] != 'T' || !std::isdigit(static_cast<unsigned char>(t[1])) ||
      bar == std::string_view::npos)
    return std::nullopt;
  const std::size_t slash = t.rfind(" / ");
  if (slash == std::string_view::npos || slash < bar)
    return note(CommentFormat::hypermill, "a hyperMILL tool line without ' / DM='");
  const std::string name(trim(t.substr(bar + 1, slash - bar - 1)));
  const std::string_view sizes = t.substr(slash + 3);
  const auto dm = field(sizes, "DM=");
  const auto cr = field(sizes, "CR=");
  const auto diameter = dm ? number(*dm) : std::nullopt;
  const auto corner = cr ? number(*cr) : std::nullopt;
  if (!diameter || *diameter <= 0 || !corner || *corner < 0)
    return note(CommentFormat::hypermill, name + ": DM= and CR= must be sizes");
  ToolShape shape = ToolShape::bull_nose;
  const auto named = shape_from_type_name(name);
  if (named && (*named == ToolShape::drill || *named == ToolShape::other)) {
    shape = *named;
  } else if (std::abs(*corner - *diameter / 2) <= 1e-3 * std::max(1.0, *diameter) ||
             named == ToolShape::ball) {
    if (std::abs(*corner - *diameter / 2) > 1e-3 * std::max(1.0, *diameter) && *corner > 0)
      return note(CommentFormat::hypermill, name + ": a ball whose CR is not DM/2");
    shape = ToolShape::ball;
  } else if (*corner == 0) {
    shape = ToolShape::flat;
  } else if (*corner > *diameter / 2) {
    return note(CommentFormat::hypermill, name + ": CR above DM/2");
  }
  CommentTool out;
  out.format = CommentFormat::hypermill;
  out.entry = entry_of(std::nullopt, shape, *diameter,
                       shape == ToolShape::bull_nose ? corner : std::nullopt, name);
  return out;
}

}  // namespace

std::string_view to_string(CommentFormat format) {
  switch (format) {
    case CommentFormat::fusion:
      return "Fusion 360/HSM";
    case CommentFormat::mastercam:
      return "Mastercam";
    case CommentFormat::carbide:
      return "Carbide Create";
    case CommentFormat::hypermill:
      return "hyperMILL";
    case CommentFormat::pycam:
      break;
  }
  return "PyCAM";
}

std::optional<ToolShape> shape_from_type_name(std::string_view name) {
  const std::string u = to_upper(name);
  auto has = [&](std::string_view word) { return u.find(word) != std::string::npos; };
  // Tools that are not cutting on a ball, torus or flat end first: a
  // "tapered ball mill" or a "ball lollipop" is not a ball end mill.
  static constexpr std::array<std::string_view, 19> others = {
      "TAPER",       "LOLLIPOP", "DOVETAIL", "THREAD", "FORM",  "CHAMFER", "SLOT",
      "ENGRAV",      "V-BIT",    "VBIT",     "V BIT",  "PROBE", "SAW",     "FACE MILL",
      "RADIUS MILL", "TAP",      "REAM",     "BOR",    "SINK"};
  const bool drill = has("DRILL");
  if (!drill) {
    for (const std::string_view word : others) {
      if (has(word)) return ToolShape::other;
    }
  }
  if (drill) return ToolShape::drill;
  if (has("BALL")) return ToolShape::ball;
  if (has("BULL") || has("TORUS")) return ToolShape::bull_nose;
  if (has("FLAT") || has("END MILL") || has("ENDMILL")) return ToolShape::flat;
  return std::nullopt;
}

std::optional<CommentTool> read_tool_comment(std::string_view text) {
  if (auto found = fusion(text)) return found;
  if (auto found = mastercam(text)) return found;
  if (auto found = hypermill(text)) return found;
  return carbide(text);
}

}  // namespace vcpost::tools
