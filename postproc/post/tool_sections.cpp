#include "postproc/post/tool_sections.h"

#include <algorithm>
#include <sstream>

#include "postproc/post/post_job.h"

namespace vcpost::post {

bool posts_shape(tools::ToolShape shape) {
  return shape == tools::ToolShape::ball || shape == tools::ToolShape::bull_nose;
}

std::vector<std::string> unused_tool_choices(const tools::ToolChoices& choices,
                                             const std::vector<ToolSection>& sections) {
  std::vector<int> used;
  for (const ToolSection& s : sections)
    if (s.tool) used.push_back(*s.tool);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::string tools;
  for (const int t : used) tools += (tools.empty() ? "T" : ", T") + std::to_string(t);
  std::vector<std::string> warnings;
  const auto check = [&](const std::string& option, int number) {
    if (std::binary_search(used.begin(), used.end(), number)) return;
    warnings.push_back(option + " names T" + std::to_string(number) +
                       ", which no tool change of the program selects (its tools: " +
                       (tools.empty() ? std::string("none numbered") : tools) + ")");
  };
  if (choices.post_tools)
    for (const int t : *choices.post_tools) check("--post-tools", t);
  for (const auto& [t, vc] : choices.vc_by_tool) check("--vc", t);
  for (const auto& [t, stock] : choices.stock_by_tool) check("--stock", t);
  for (const tools::ToolEntry& e : choices.table.numbered())
    if (e.origin == tools::ToolOrigin::command_line) check("--tool", *e.number);
  return warnings;
}

namespace {

// An allowance the tool can take: one value for a ball (its offset is along
// the normal, the same every way), and no negative value reaching past the
// tool's radius (nothing of the tool would be left to touch).
void check_stock(const geometry::Allowance& stock, const tools::ToolEntry& tool,
                 const std::string& name) {
  std::ostringstream message;
  if (tool.shape == tools::ToolShape::ball && !stock.is_uniform()) {
    message << "--stock " << stock.radial << ":" << stock.axial << " for " << name
            << ", a ball-end mill: a ball has one allowance, along the surface normal; give one "
               "value";
    throw PostError(Code::E6003, message.str());
  }
  const double radius = tool.diameter / 2;
  if (!(radius + stock.radial > 0) || !(radius + stock.axial > 0)) {
    message << "--stock " << stock.radial;
    if (!stock.is_uniform()) message << ":" << stock.axial;
    message << " for " << name << " (" << tool.describe()
            << "): a negative allowance as deep as the tool's radius " << radius
            << " mm leaves no tool to touch the model";
    throw PostError(Code::E6002, message.str());
  }
}

}  // namespace

ToolSection decide_section(std::uint32_t index, std::optional<int> number, std::uint32_t first_line,
                           const tools::ToolEntry* tool, const tools::ToolChoices& choices,
                           double ap_mm) {
  ToolSection s;
  s.index = index;
  s.tool = number;
  s.first_line = first_line;
  if (tool) s.entry = *tool;
  const std::string name = number ? "T" + std::to_string(*number) : std::string("the first tool");
  const bool chosen = !choices.post_tools ||
                      (number && std::find(choices.post_tools->begin(), choices.post_tools->end(),
                                           *number) != choices.post_tools->end());
  if (!tool) {
    s.reason = "unknown tool: nothing names " + name + " (give --tool " +
               (number ? name + "=" : std::string()) + "ball:D or --tools)";
    return s;
  }
  if (!chosen) {
    s.reason = "not in --post-tools";
    return s;
  }
  if (!posts_shape(tool->shape)) {
    s.reason =
        std::string(tools::to_string(tool->shape)) + " mill: speed kept" +
        (tool->shape == tools::ToolShape::flat ? " (ball and bull-nose mills are posted)" : "");
    if (tool->shape == tools::ToolShape::drill) s.reason = "drill: speed kept";
    if (tool->shape == tools::ToolShape::other) s.reason = "not a ball-end mill: speed kept";
    return s;
  }
  if (!tool->geometry()) {
    s.reason = "no usable size for " + name;
    return s;
  }
  const auto vc = choices.vc_of(number);
  if (!vc) {
    s.reason = "no --vc for " + name;
    return s;
  }
  if (ap_mm >= tool->diameter) {
    std::ostringstream message;
    message << "--ap " << ap_mm << " must be below the diameter of " << name << " ("
            << tool->describe() << ", from the " << tools::to_string(tool->origin)
            << (tool->where.empty() ? std::string() : " at " + tool->where) << ")";
    throw PostError(Code::E2001, message.str());
  }
  s.stock = choices.stock_of(number);
  check_stock(s.stock, *tool, name);
  s.postable = true;
  s.vc_nominal = *vc;
  s.reason =
      tool->shape == tools::ToolShape::ball ? "ball over the model" : "bull-nose over the model";
  return s;
}

}  // namespace vcpost::post
