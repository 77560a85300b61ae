// The tool table of a program: for every tool number, the tool's shape and
// size and where vcpost learnt it. A program is cut in sections, one per
// tool change; the post job looks each section's tool up here to decide
// whether it posts the section (a ball-end mill over the model) or keeps
// its S and F as they are (drills, flat and face mills, unknown tools).
//
// Sources, strongest first (resolve() applies the order):
//   1. the command line per number:  --tool T8=ball:14   (origin command_line)
//   2. a tools file:                 --tools FILE.toml   (origin tools_file)
//   3. the command line for every tool: --tool ball:10   (origin command_line,
//      no number: today's meaning of a plain --tool is kept)
//   4. the program: CL CUTTER/TLDATA records (origin cl_record), G-code tool
//      comments (origin comment); the caller passes that entry in.
// Units: lengths in mm. No I/O here (tools_file.h reads the file).
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.h"
#include "geometry/offset_model.h"
#include "geometry/tool.h"

namespace vcpost::tools {

enum class ToolShape { ball, bull_nose, flat, drill, other };

// "ball", "bull", "flat", "drill", "other" (the words of --tool and the file).
std::string_view to_string(ToolShape shape);
std::optional<ToolShape> shape_from_word(std::string_view word);

// Where a tool's description came from.
enum class ToolOrigin { command_line, tools_file, cl_record, comment };

// "command line", "tools file", "CL record", "comment".
std::string_view to_string(ToolOrigin origin);

struct ToolEntry {
  std::optional<int> number;  // T number; empty: every tool (plain --tool) or not numbered
  ToolShape shape = ToolShape::other;
  double diameter = 0;                  // D, mm; 0 when unknown
  std::optional<double> corner_radius;  // mm; ball D/2, flat 0; empty when unknown
  std::optional<int> teeth;
  std::string name;  // the tool's own name or the text that described it
  ToolOrigin origin = ToolOrigin::command_line;
  std::string where;  // "file:line" of the record, comment or table entry; empty for options

  // The tool as the working-diameter engine models it (ball, bull-nose or
  // flat with a known, consistent size); empty for drills, other tools and
  // unknown sizes.
  std::optional<geometry::Tool> geometry() const;
  // "T2 ball D10" and the like, for messages and reports.
  std::string describe() const;
};

// A bad option value or tools-file entry. The message names the option or
// file:line:col and carries a stable code (E16xx, see tools/README.md).
class ToolTableError : public vcpost::Error {
 public:
  ToolTableError(Code code, const std::string& message, SourceLocation where = {})
      : vcpost::Error(code, message, std::move(where)) {}
};

// The user's tools (command line and tools file); the program's own come in
// through resolve().
class ToolTable {
 public:
  // A numbered entry replaces one of the same number from a weaker or the
  // same origin (the later one wins); an entry without a number is the
  // plain --tool, every tool's default. Throws ToolTableError when the
  // command line gives one number twice (E1606).
  void add(ToolEntry entry);

  // The description that decides tool `number` (empty: the section before
  // any tool change) given what the program says of it (`program`, may be
  // null): strongest source first, as in the header comment. Null when
  // nothing describes the tool.
  const ToolEntry* resolve(std::optional<int> number, const ToolEntry* program) const;

  const std::vector<ToolEntry>& numbered() const { return numbered_; }
  const std::optional<ToolEntry>& every_tool() const { return every_tool_; }
  bool empty() const { return numbered_.empty() && !every_tool_; }

 private:
  std::vector<ToolEntry> numbered_;
  std::optional<ToolEntry> every_tool_;
};

// What the user chose per tool beyond the table.
struct ToolChoices {
  ToolTable table;
  std::optional<double> vc;                          // m/min, every tool's (plain --vc)
  std::map<int, double> vc_by_tool;                  // --vc T2=150
  std::optional<std::vector<int>> post_tools;        // --post-tools T2,T8; empty: the default rule
  std::optional<geometry::Allowance> stock;          // every tool's (plain --stock)
  std::map<int, geometry::Allowance> stock_by_tool;  // --stock T3=0.2:0.1

  // The nominal cutting speed of tool `number`: its own, else the plain --vc.
  std::optional<double> vc_of(std::optional<int> number) const;
  // The allowance of tool `number`: its own, else the plain --stock, else none.
  geometry::Allowance stock_of(std::optional<int> number) const;
};

// ---- Option values. Each throws ToolTableError naming the option.

// --tool: "ball:10", "bull:12:2", "flat:8", "drill:5", "other" for every
// tool, or "T8=ball:14" (also "8=ball:14") for tool 8.
ToolEntry parse_tool_option(std::string_view text);

// A tool number as written on the command line: "T2" or "2" (>= 0).
int parse_tool_number(std::string_view text, std::string_view option);

// --post-tools: "T2,T8" (numbers as in parse_tool_number, comma separated).
std::vector<int> parse_tool_list(std::string_view text);

// --vc: "150" (every tool) or "T2=150"; m/min, > 0. Adds to `choices`.
void add_vc_option(std::string_view text, ToolChoices& choices);

// --stock: "0.3" or "-1.245" (every tool), "T3=0.2", "T3=0.2:0.1" (radial
// and axial, for bull-nose and flat end mills); mm, finite, |value| below
// 100 mm. Adds to `choices`; E2012 for bad text or a tool given twice.
void add_stock_option(std::string_view text, ToolChoices& choices);

}  // namespace vcpost::tools
