// The tool descriptions CAM posts write as G-code comments, read into tool
// table entries. Formats (real lines in tests/postproc/tools, with where
// they were found):
//   Fusion 360 / HSM / Inventor CAM  (T1 D=6. CR=3. - ZMIN=-5. - ball end mill)
//                                    (T2 6mm ball D=6 CR=3 TAPER=15deg - ... - type)
//   Mastercam                        ( 1/16 FLAT ENDMILL TOOL - 1 DIA. OFF. - 1 LEN.
//                                      - 1 DIA. - .0625)   (name words give the shape)
//   Carbide Create                   (TOOL/MILL,3.17, 0.00, 0.00, 0.00): D, corner
//                                    radius, length, taper half-angle (no number)
//   PyCAM                            a block of ';' lines, read by pycam_settings.h
//   hyperMILL (Heidenhain Klartext)  * - T626960718 | JJ-T4R0.5-N-ES_H6ZM / DM=4.01 CR=0.5 TL=145
//                                    (the line before each TOOL CALL; also "- TOOL: T...";
//                                    the T is hyperMILL's tool id, not the TOOL CALL's:
//                                    no number. CR=0 flat unless the name says ball,
//                                    CR=DM/2 ball, else bull-nose)
// A comment that looks like one of these but cannot be read (no diameter,
// an unknown tool type, a ball whose CR is not D/2) gives a note instead of
// an entry: the tool stays unknown, it is never guessed into a ball.
// Lengths are in the program's units (G20/G21 in effect), which the comment
// does not say: the caller converts (in_program_units below).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "postproc/tools/tool_table.h"

namespace vcpost::tools {

enum class CommentFormat { fusion, mastercam, carbide, pycam, hypermill };
std::string_view to_string(CommentFormat format);

struct CommentTool {
  CommentFormat format = CommentFormat::fusion;
  // Set when the comment could be read: origin comment, number set when the
  // comment names it (Fusion, Mastercam; Carbide's belongs to the next tool
  // change), lengths in the program's units.
  std::optional<ToolEntry> entry;
  std::string note;  // when entry is empty: why the comment was not read
};

// Reads one comment's text (without its parentheses or ';'). Nothing for a
// comment that is no tool description of a known format. Never throws.
std::optional<CommentTool> read_tool_comment(std::string_view text);

// The shape a CAM tool-type name gives ("ball end mill", "BULL ENDMILL",
// "spot drill", ...), case-insensitive; nothing for a name it does not know.
std::optional<ToolShape> shape_from_type_name(std::string_view name);

}  // namespace vcpost::tools
