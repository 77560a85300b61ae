// PyCAM's tool description: not one comment but a settings block, one
// `;` comment per line, that PyCAM 0.5 writes at the top of its G-code
// (real lines in tests/postproc/tools/pycam_settings_test.cpp):
//   ;PYCAM_TOOLPATH_SETTINGS: START
//   ;[Tool]
//   ;torus_radius = 0.25
//   ;shape = CylindricalCutter
//   ;tool_radius = 0.79375
//   ;...
//   ;PYCAM_TOOLPATH_SETTINGS: END
// Shapes: SphericalCutter (ball), CylindricalCutter (flat), ToroidalCutter
// (bull-nose: tool_radius the outer radius, torus_radius the corner).
// torus_radius is written for every shape; only the toroidal uses it. The
// block names no tool number: it belongs to the next tool change.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "postproc/tools/tool_comment.h"

namespace vcpost::tools {

class PycamSettings {
 public:
  // Whether `text` (a comment's text) is this reader's: the block's start,
  // or a line of an open block (a [section], `key = value`, empty, END).
  bool takes(std::string_view text) const;

  // Reads one comment `takes` accepted, at `where` ("file:line"). At END,
  // the tool of the block's [Tool] section: an entry (lengths in the
  // program's units, `where` its shape line) or a note. Nothing before the
  // end or for a block without a [Tool] section.
  std::optional<CommentTool> read(std::string_view text, const std::string& where);

  // Closes a block cut short by a comment that is no settings line: a
  // note when it had a [Tool] section, else nothing.
  std::optional<CommentTool> cut_short();

 private:
  bool open_ = false;
  bool in_tool_ = false;  // inside the [Tool] section
  bool any_tool_ = false;
  std::string shape_, shape_where_;
  std::optional<double> radius_, torus_;
  std::string bad_value_;  // a tool value that is no number
};

}  // namespace vcpost::tools
