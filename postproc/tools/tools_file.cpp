#include "postproc/tools/tools_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>

namespace vcpost::tools {
namespace {

constexpr std::string_view kKeys[] = {"number",        "shape", "diameter",
                                      "corner_radius", "teeth", "name"};

class FileReader {
 public:
  explicit FileReader(const std::string& file) : file_(file) {}

  [[noreturn]] void fail(Code code, const toml::source_region& where,
                         const std::string& message) const {
    const SourceLocation at{file_, where.begin.line, where.begin.column};
    throw ToolTableError(code, format_diagnostic(code, at, message), at);
  }

  ToolEntry entry(const toml::table& tool, const toml::source_region& where) const {
    for (const auto& item : tool) {
      const toml::key& key = item.first;
      if (std::find(std::begin(kKeys), std::end(kKeys), key.str()) == std::end(kKeys)) {
        fail(Code::E1604, key.source(),
             "unknown key '" + std::string(key.str()) +
                 "' in [[tool]] (known: number, shape, diameter, corner_radius, teeth, name)");
      }
    }
    ToolEntry e;
    e.origin = ToolOrigin::tools_file;
    e.where = file_ + ":" + std::to_string(where.begin.line);
    const auto number = integer(tool, "number", where, true);
    if (*number < 0) fail(Code::E1605, tool.get("number")->source(), "number must be >= 0");
    e.number = static_cast<int>(*number);
    const toml::node* shape = tool.get("shape");
    if (!shape || !shape->is_string())
      fail(Code::E1604, shape ? shape->source() : where,
           "[[tool]] needs shape = \"ball\" (a string)");
    const auto parsed = shape_from_word(**shape->as_string());
    if (!parsed) {
      fail(Code::E1605, shape->source(),
           "shape '" + **shape->as_string() + "' is not ball, bull, flat, drill or other");
    }
    e.shape = *parsed;
    const auto diameter = real(tool, "diameter", where, e.shape != ToolShape::other);
    if (diameter) {
      if (!(*diameter > 0))
        fail(Code::E1605, tool.get("diameter")->source(), "diameter must be > 0");
      e.diameter = *diameter;
    }
    const auto corner = real(tool, "corner_radius", where, e.shape == ToolShape::bull_nose);
    if (e.shape == ToolShape::ball) e.corner_radius = e.diameter / 2;
    if (e.shape == ToolShape::flat) e.corner_radius = 0.0;
    if (corner) {
      const toml::source_region at = tool.get("corner_radius")->source();
      if (e.shape == ToolShape::bull_nose && !(*corner > 0 && *corner < e.diameter / 2))
        fail(Code::E1605, at, "corner_radius of a bull-nose mill must lie in (0, diameter/2)");
      if (e.corner_radius && std::abs(*corner - *e.corner_radius) > 1e-9) {
        fail(Code::E1605, at,
             "corner_radius of a " + std::string(to_string(e.shape)) + " mill must be " +
                 (e.shape == ToolShape::ball ? "diameter/2" : "0"));
      }
      e.corner_radius = *corner;
    }
    if (const auto teeth = integer(tool, "teeth", where, false)) {
      if (*teeth < 1) fail(Code::E1605, tool.get("teeth")->source(), "teeth must be >= 1");
      e.teeth = static_cast<int>(*teeth);
    }
    if (const toml::node* name = tool.get("name")) {
      if (!name->is_string()) fail(Code::E1604, name->source(), "name must be a string");
      e.name = **name->as_string();
    }
    return e;
  }

 private:
  std::optional<std::int64_t> integer(const toml::table& t, std::string_view key,
                                      const toml::source_region& where, bool required) const {
    const toml::node* n = t.get(key);
    if (!n) {
      if (required) fail(Code::E1604, where, "[[tool]] needs " + std::string(key));
      return std::nullopt;
    }
    if (!n->is_integer()) fail(Code::E1604, n->source(), std::string(key) + " must be an integer");
    return **n->as_integer();
  }
  std::optional<double> real(const toml::table& t, std::string_view key,
                             const toml::source_region& where, bool required) const {
    const toml::node* n = t.get(key);
    if (!n) {
      if (required) fail(Code::E1604, where, "[[tool]] needs " + std::string(key) + " (mm)");
      return std::nullopt;
    }
    if (!n->is_number())
      fail(Code::E1604, n->source(), std::string(key) + " must be a number (mm)");
    const double value =
        n->is_integer() ? static_cast<double>(**n->as_integer()) : **n->as_floating_point();
    if (!std::isfinite(value)) fail(Code::E1605, n->source(), std::string(key) + " must be finite");
    return value;
  }

  const std::string& file_;
};

}  // namespace

void load_tools_file(std::string_view text, const std::string& file_name, ToolTable& table) {
  const FileReader reader(file_name);
  toml::table root;
  try {
    root = toml::parse(text, file_name);
  } catch (const toml::parse_error& e) {
    reader.fail(Code::E1604, e.source(), std::string(e.description()));
  }
  std::set<int> seen;
  for (const auto& [key, value] : root) {
    if (key.str() != "tool" || !value.is_array_of_tables()) {
      reader.fail(
          Code::E1604, key.source(),
          "unknown key '" + std::string(key.str()) + "' (a tools file holds [[tool]] tables)");
    }
    for (const toml::node& node : *value.as_array()) {
      const toml::table& tool = *node.as_table();
      ToolEntry e = reader.entry(tool, tool.source());
      if (!seen.insert(*e.number).second) {
        reader.fail(Code::E1605, tool.source(),
                    "tool T" + std::to_string(*e.number) + " is given twice");
      }
      table.add(std::move(e));
    }
  }
}

}  // namespace vcpost::tools
