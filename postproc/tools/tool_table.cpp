#include "postproc/tools/tool_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>

#include "core/text.h"

namespace vcpost::tools {
namespace {

// Ranks the sources: lower wins (the header's order).
int rank(const ToolEntry& entry) {
  if (entry.origin == ToolOrigin::command_line) return entry.number ? 0 : 2;
  if (entry.origin == ToolOrigin::tools_file) return 1;
  return 3;
}

std::string quoted(std::string_view text) { return "'" + std::string(text) + "'"; }

double parse_number(std::string_view text, const std::string& what) {
  const std::optional<double> value = finite_number(text);
  if (!value) throw ToolTableError(Code::E1601, what + ": " + quoted(text) + " is not a number");
  return *value;
}

}  // namespace

std::string_view to_string(ToolShape shape) {
  switch (shape) {
    case ToolShape::ball:
      return "ball";
    case ToolShape::bull_nose:
      return "bull";
    case ToolShape::flat:
      return "flat";
    case ToolShape::drill:
      return "drill";
    case ToolShape::other:
      break;
  }
  return "other";
}

std::optional<ToolShape> shape_from_word(std::string_view word) {
  for (const ToolShape shape : {ToolShape::ball, ToolShape::bull_nose, ToolShape::flat,
                                ToolShape::drill, ToolShape::other}) {
    if (word == to_string(shape)) return shape;
  }
  return std::nullopt;
}

std::string_view to_string(ToolOrigin origin) {
  switch (origin) {
    case ToolOrigin::command_line:
      return "command line";
    case ToolOrigin::tools_file:
      return "tools file";
    case ToolOrigin::cl_record:
      return "CL record";
    case ToolOrigin::comment:
      break;
  }
  return "comment";
}

std::optional<geometry::Tool> ToolEntry::geometry() const {
  if (!(diameter > 0) || !std::isfinite(diameter)) return std::nullopt;
  switch (shape) {
    case ToolShape::ball:
      return geometry::Tool::ball(diameter);
    case ToolShape::flat:
      return geometry::Tool::flat(diameter);
    case ToolShape::bull_nose:
      // A corner that fills the radius is a ball end (as geometry::parse_tool).
      if (corner_radius && *corner_radius == diameter / 2) return geometry::Tool::ball(diameter);
      if (corner_radius && *corner_radius > 0 && *corner_radius < diameter / 2)
        return geometry::Tool::bull_nose(diameter, *corner_radius);
      return std::nullopt;
    case ToolShape::drill:
    case ToolShape::other:
      break;
  }
  return std::nullopt;
}

std::string ToolEntry::describe() const {
  std::ostringstream out;
  out << (number ? "T" + std::to_string(*number) : std::string("every tool")) << ' '
      << to_string(shape);
  if (diameter > 0) out << " D" << diameter;
  if (shape == ToolShape::bull_nose && corner_radius) out << " R" << *corner_radius;
  return out.str();
}

void ToolTable::add(ToolEntry entry) {
  if (!entry.number) {
    every_tool_ = std::move(entry);
    return;
  }
  auto same = std::find_if(numbered_.begin(), numbered_.end(),
                           [&](const ToolEntry& e) { return e.number == entry.number; });
  if (same == numbered_.end()) {
    numbered_.push_back(std::move(entry));
    return;
  }
  if (same->origin == ToolOrigin::command_line && entry.origin == ToolOrigin::command_line) {
    throw ToolTableError(Code::E1606,
                         "--tool: tool T" + std::to_string(*entry.number) + " is given twice");
  }
  if (rank(entry) <= rank(*same)) *same = std::move(entry);
}

const ToolEntry* ToolTable::resolve(std::optional<int> number, const ToolEntry* program) const {
  const ToolEntry* best = nullptr;
  auto consider = [&](const ToolEntry* candidate) {
    if (candidate && (!best || rank(*candidate) < rank(*best))) best = candidate;
  };
  if (number) {
    for (const ToolEntry& e : numbered_) {
      if (e.number == number) consider(&e);
    }
  }
  if (every_tool_) consider(&*every_tool_);
  consider(program);
  return best;
}

std::optional<double> ToolChoices::vc_of(std::optional<int> number) const {
  if (number) {
    const auto it = vc_by_tool.find(*number);
    if (it != vc_by_tool.end()) return it->second;
  }
  return vc;
}

geometry::Allowance ToolChoices::stock_of(std::optional<int> number) const {
  if (number) {
    const auto it = stock_by_tool.find(*number);
    if (it != stock_by_tool.end()) return it->second;
  }
  return stock.value_or(geometry::Allowance{});
}

int parse_tool_number(std::string_view text, std::string_view option) {
  const std::string_view original = text;
  text = trim(text, " ");
  if (!text.empty() && (text.front() == 'T' || text.front() == 't')) text.remove_prefix(1);
  int value = -1;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc{} || end != text.data() + text.size() || value < 0) {
    throw ToolTableError(Code::E1602, std::string(option) + ": " + quoted(original) +
                                          " is not a tool number (T2 or 2)");
  }
  return value;
}

ToolEntry parse_tool_option(std::string_view text) {
  ToolEntry entry;
  entry.origin = ToolOrigin::command_line;
  std::string_view spec = text;
  if (const std::size_t eq = text.find('='); eq != std::string_view::npos) {
    entry.number = parse_tool_number(text.substr(0, eq), "--tool");
    spec = text.substr(eq + 1);
  }
  entry.name = std::string(spec);
  const std::size_t colon = spec.find(':');
  const std::string_view word = spec.substr(0, colon);
  const auto shape = shape_from_word(word);
  if (!shape) {
    throw ToolTableError(Code::E1601, "--tool " + quoted(text) + ": unknown shape " + quoted(word) +
                                          " (expected ball:D, bull:D:rc, flat:D, drill:D or other, "
                                          "optionally after T<n>=)");
  }
  entry.shape = *shape;
  if (entry.shape == ToolShape::other) {
    if (colon != std::string_view::npos)
      entry.diameter = parse_number(spec.substr(colon + 1), "--tool " + quoted(text));
    return entry;
  }
  if (entry.shape == ToolShape::ball || entry.shape == ToolShape::flat ||
      entry.shape == ToolShape::bull_nose) {
    try {
      const geometry::Tool tool = geometry::parse_tool(spec);
      entry.diameter = tool.diameter;
      entry.corner_radius = tool.corner_radius;
    } catch (const std::invalid_argument& e) {
      throw ToolTableError(Code::E1601, std::string("--tool: ") + e.what());
    }
    return entry;
  }
  if (colon == std::string_view::npos)
    throw ToolTableError(Code::E1601, "--tool " + quoted(text) + ": expected drill:D");
  entry.diameter = parse_number(spec.substr(colon + 1), "--tool " + quoted(text));
  if (!(entry.diameter > 0))
    throw ToolTableError(Code::E1601, "--tool " + quoted(text) + ": diameter must be > 0");
  return entry;
}

std::vector<int> parse_tool_list(std::string_view text) {
  std::vector<int> out;
  for (std::size_t start = 0;;) {
    const std::size_t end = text.find(',', start);
    out.push_back(parse_tool_number(text.substr(start, end - start), "--post-tools"));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return out;
}

void add_vc_option(std::string_view text, ToolChoices& choices) {
  std::optional<int> number;
  std::string_view value = text;
  if (const std::size_t eq = text.find('='); eq != std::string_view::npos) {
    number = parse_tool_number(text.substr(0, eq), "--vc");
    value = text.substr(eq + 1);
  }
  const double vc = parse_number(value, "--vc " + quoted(text));
  if (!(vc > 0)) throw ToolTableError(Code::E1603, "--vc " + quoted(text) + ": must be > 0 m/min");
  if (number) {
    if (!choices.vc_by_tool.emplace(*number, vc).second)
      throw ToolTableError(Code::E1606,
                           "--vc: tool T" + std::to_string(*number) + " is given twice");
  } else {
    if (choices.vc)
      throw ToolTableError(Code::E1606,
                           "--vc: given twice for every tool (use T<n>=vc for one tool)");
    choices.vc = vc;
  }
}

// The largest allowance taken, mm: more is a unit slip (inch as mm, um as mm).
constexpr double kMaxStockMm = 100;

void add_stock_option(std::string_view text, ToolChoices& choices) {
  const std::string what = "--stock " + quoted(text);
  std::optional<int> number;
  std::string_view value = text;
  if (const std::size_t eq = text.find('='); eq != std::string_view::npos) {
    try {
      number = parse_tool_number(text.substr(0, eq), "--stock");
    } catch (const ToolTableError& e) {
      throw ToolTableError(Code::E2012, e.what());
    }
    value = text.substr(eq + 1);
  }
  const auto mm = [&](std::string_view part) {
    double v = 0;
    try {
      v = parse_number(part, what);
    } catch (const ToolTableError& e) {
      throw ToolTableError(Code::E2012, e.what());
    }
    if (!(std::abs(v) < kMaxStockMm))
      throw ToolTableError(Code::E2012, what + ": an allowance of 100 mm or more (a unit slip?)");
    return v;
  };
  geometry::Allowance allowance;
  if (const std::size_t colon = value.find(':'); colon != std::string_view::npos) {
    allowance = {mm(value.substr(0, colon)), mm(value.substr(colon + 1))};
  } else {
    allowance = geometry::Allowance::uniform(mm(value));
  }
  if (number) {
    if (!choices.stock_by_tool.emplace(*number, allowance).second)
      throw ToolTableError(Code::E2012,
                           "--stock: tool T" + std::to_string(*number) + " is given twice");
  } else {
    if (choices.stock)
      throw ToolTableError(Code::E2012,
                           "--stock: given twice for every tool (use T<n>=MM for one tool)");
    choices.stock = allowance;
  }
}

}  // namespace vcpost::tools
