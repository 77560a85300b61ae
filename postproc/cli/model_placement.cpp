#include "postproc/cli/model_placement.h"

#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <vector>

#include "postproc/cli/commands.h"

namespace vcpost::cli {
namespace {

using geometry::RigidTransform;

[[noreturn]] void refuse(const std::string& name, const std::string& why) {
  throw CommandError(Code::E4112, "--model-transform: '" + name + "': " + why);
}

// One element's text: from `<tag` at `from` to its closing tag (or the end
// of a self-closed tag).
struct Element {
  std::string_view text;
  std::size_t end = 0;  // just past it
};

std::optional<Element> next_element(std::string_view xml, const std::string& tag,
                                    std::size_t from) {
  const std::string open = "<" + tag;
  for (std::size_t at = xml.find(open, from); at != std::string_view::npos;
       at = xml.find(open, at + 1)) {
    const char after = at + open.size() < xml.size() ? xml[at + open.size()] : '>';
    if (after != ' ' && after != '>' && after != '/' && after != '\n' && after != '\t') continue;
    const std::size_t head_end = xml.find('>', at);
    if (head_end == std::string_view::npos) return std::nullopt;
    if (xml[head_end - 1] == '/') return Element{xml.substr(at, head_end + 1 - at), head_end + 1};
    const std::string close = "</" + tag + ">";
    const std::size_t stop = xml.find(close, head_end);
    if (stop == std::string_view::npos) return std::nullopt;
    return Element{xml.substr(at, stop + close.size() - at), stop + close.size()};
  }
  return std::nullopt;
}

std::optional<std::string> attribute(std::string_view element, const std::string& name) {
  const std::string head(element.substr(0, element.find('>')));
  const std::regex pattern("\\s" + name + "=\"([^\"]*)\"");
  std::smatch m;
  if (!std::regex_search(head, m, pattern)) return std::nullopt;
  return m[1].str();
}

// The text of the first <tag>...</tag> inside `element`.
std::optional<std::string> child_text(std::string_view element, const std::string& tag) {
  const auto child = next_element(element, tag, 1);
  if (!child) return std::nullopt;
  const std::size_t open_end = child->text.find('>');
  const std::size_t close = child->text.rfind("</");
  if (close == std::string_view::npos || close < open_end) return std::string();
  return std::string(child->text.substr(open_end + 1, close - open_end - 1));
}

double number_of(std::string_view element, const std::string& name, const std::string& file) {
  const auto text = attribute(element, name);
  if (!text) return 0;  // VERICUT leaves zero out as often as it writes it
  try {
    std::size_t used = 0;
    const double value = std::stod(*text, &used);
    if (used == text->size() && std::isfinite(value)) return value;
  } catch (const std::exception&) {
  }
  refuse(file, "'" + *text + "' is not a number in " + std::string(element.substr(0, 40)));
}

// A VERICUT placement: turns about X by I, Y by J, Z by K (fixed axes, in
// that order), then the shift: the first <Position> and <Rotation> inside
// `element`.
RigidTransform placement_of(std::string_view element, const std::string& file) {
  RigidTransform t;
  if (const auto rotation = next_element(element, "Rotation", 1)) {
    t = geometry::turn_about(0, number_of(rotation->text, "I", file))
            .then(geometry::turn_about(1, number_of(rotation->text, "J", file)))
            .then(geometry::turn_about(2, number_of(rotation->text, "K", file)));
  }
  if (const auto position = next_element(element, "Position", 1)) {
    t.shift = {number_of(position->text, "X", file), number_of(position->text, "Y", file),
               number_of(position->text, "Z", file)};
  }
  return t;
}

// A component or coordinate system: its parent and its place in it.
struct Node {
  std::string attach;
  RigidTransform place;
};

// Its placement in the frame of the first ancestor the project does not
// define (a machine component), and that ancestor's name.
std::pair<RigidTransform, std::string> chain(const Node& node,
                                             const std::map<std::string, Node>& components,
                                             const std::string& file) {
  RigidTransform total = node.place;
  std::string parent = node.attach;
  for (std::size_t depth = 0;; ++depth) {
    const auto it = components.find(parent);
    if (it == components.end()) return {total, parent};
    if (depth > components.size()) refuse(file, "the components' <Attach> chain loops");
    total = total.then(it->second.place);
    parent = it->second.attach;
  }
}

}  // namespace

ProjectPlacement read_vcproject_placement(std::string_view xml, const std::string& name) {
  // Components of the set-up (those with a Type: the machine's list of
  // visible components repeats names without one).
  std::map<std::string, Node> components;
  std::optional<std::string_view> design;
  std::string design_name;
  for (auto c = next_element(xml, "Component", 0); c; c = next_element(xml, "Component", c->end)) {
    const auto type = attribute(c->text, "Type");
    const auto component = attribute(c->text, "Name");
    if (!type || !component) continue;
    // Only the component's own placement: the part before its models.
    const std::string_view own = c->text.substr(0, c->text.find("<STL"));
    components[*component] = {child_text(own, "Attach").value_or(""), placement_of(own, name)};
    if (*type == "design") {
      if (design) refuse(name, "more than one design component: give the steps instead");
      design = c->text;
      design_name = *component;
    }
  }
  if (!design) refuse(name, "no component of Type=\"design\"");
  const auto stl = next_element(*design, "STL", 1);
  if (!stl) refuse(name, "the design component '" + design_name + "' holds no <STL> model");
  if (next_element(*design, "STL", stl->end)) {
    refuse(name, "the design component '" + design_name +
                     "' holds more than one <STL> model: give the steps instead");
  }
  const std::string unit = attribute(stl->text, "Unit").value_or("millimeter");
  if (unit != "millimeter") refuse(name, "the design STL's unit is '" + unit + "', not millimeter");

  // The program's frame: the coordinate system "Program Zero" goes to, or the only one.
  std::map<std::string, Node> systems;
  for (auto s = next_element(xml, "CSystem", 0); s; s = next_element(xml, "CSystem", s->end)) {
    if (const auto system = attribute(s->text, "Name"))
      systems[*system] = {child_text(s->text, "Attach").value_or(""), placement_of(s->text, name)};
  }
  std::string zero;
  for (auto t = next_element(xml, "Table", 0); t; t = next_element(xml, "Table", t->end)) {
    if (attribute(t->text, "Name") == "Program Zero") {
      zero = child_text(t->text, "To").value_or("");
      break;
    }
  }
  if (systems.empty()) refuse(name, "no coordinate system (<CSystem>) for the program's zero");
  if (!systems.contains(zero)) {
    if (systems.size() > 1) {
      refuse(name, "several coordinate systems and no \"Program Zero\" table naming one of them");
    }
    zero = systems.begin()->first;
  }

  const Node design_node = components[design_name];
  // The STL within its component, the component up its chain.
  const auto [model, model_root] =
      chain({design_node.attach, placement_of(stl->text, name).then(design_node.place)}, components,
            name);
  const auto [system, system_root] = chain(systems[zero], components, name);
  if (model_root != system_root) {
    refuse(name, "the design model hangs from '" + model_root + "' and the coordinate system '" +
                     zero + "' from '" + system_root +
                     "': their relation is in the machine file, not the project");
  }
  return {model.then(system.inverse()), child_text(stl->text, "File").value_or(""), zero};
}

ModelPlacement parse_model_placement(const std::string& text) {
  static constexpr std::string_view kProject = "vcproject:";
  if (text.rfind(kProject, 0) != 0)
    return {geometry::parse_rigid_transform(text), "placed by " + text};
  const std::string file = text.substr(kProject.size());
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CommandError(Code::E2002, "--model-transform: cannot read '" + file + "'");
  std::ostringstream xml;
  xml << in.rdbuf();
  const ProjectPlacement p = read_vcproject_placement(xml.str(), file);
  return {p.transform, "placed as " + file + " places " + p.model_file + " in " + p.csystem + " (" +
                           geometry::to_string(p.transform) + ")"};
}

void place_model(LoadedModel& loaded, const ModelPlacement& placement) {
  loaded.model = std::make_unique<geometry::TransformedModel>(
      std::shared_ptr<const geometry::SurfaceModel>(std::move(loaded.model)), placement.transform);
  loaded.description += ", " + placement.words;
}

}  // namespace vcpost::cli
