// What a program says of its own tools, collected as it is read: G-code
// tool comments and CL cutter records (CUTTER, TLDATA), and which of them
// describes the tool of each section (the stretch between tool changes).
//
// A description that names its tool number (Fusion's `(T2 D=..)`, a
// Mastercam `TOOL - 2` line) belongs to that number wherever it stands (a
// later one replaces it). One that names none (a CL CUTTER, Carbide's
// `(TOOL/MILL,..)`) belongs to the next tool change when one comes before
// the next motion, else to the section under way. A section's tool is
// fixed at its first motion: what the program says later does not change it.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "postproc/tools/pycam_settings.h"
#include "postproc/tools/tool_comment.h"
#include "postproc/tools/tool_table.h"

namespace vcpost::tools {

class ProgramTools {
 public:
  // A comment of the program (text inside the parentheses or after ';') at
  // `where` ("file:line"); `inches`: G20 in effect (lengths are converted
  // to mm). Comments of no known tool format are ignored; ones that look
  // like a tool line but do not read leave a note.
  void on_comment(std::string_view text, const std::string& where, bool inches);
  // A description read elsewhere (a CL cutter record: lengths in mm).
  void on_entry(ToolEntry entry);
  void on_tool_change(int number);
  void on_motion();

  // The tool number of the section under way (empty before any tool change).
  std::optional<int> number() const { return number_; }
  // What the program says of the section's tool (null: nothing).
  const ToolEntry* current() const;
  // Notes on tool comments that could not be read ("file:line: ..."), in order.
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  // A comment read as a tool description (or a note) at `where`.
  void take(CommentTool found, const std::string& where, bool inches);

  PycamSettings pycam_;  // PyCAM's tool is a block of comments
  std::map<int, ToolEntry> numbered_;
  std::optional<ToolEntry> pending_;  // unnumbered, waiting for a tool change or a motion
  std::optional<ToolEntry> section_;  // unnumbered, of the section under way
  std::optional<int> number_;
  bool moved_ = false;  // a motion since the last tool change
  std::vector<std::string> notes_;
};

}  // namespace vcpost::tools
