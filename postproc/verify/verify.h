// `vcpost verify` as a library call: proves that an output program differs
// from its input only in S and F words (G-code in, G-code out), only in
// speeds and block numbers (Klartext in, Klartext out), or that it moves
// like the CL data it was written from (CL in, G-code or Klartext out).
//
// G-code in, G-code out: two independent proofs.
//  1. Lexical: both texts are cut into lines and each line into tokens
//     (words, blanks, comments, other bytes). Outside S/F words every byte
//     must be equal: the same lines, line endings, words, blanks, comments.
//     An S/F word may change its value (to a plain positive number) or be
//     added where the input's block had none (as gcode::write_patched adds
//     it); it may not be removed or repeated, and nothing inside a comment
//     may change.
//  2. Semantic: both programs are run through the interpreter with the same
//     dialect; the event streams without SetSpindleSpeed/SetFeedRate must be
//     identical (positions compared exactly, source lines too).
// CL in, G-code out: the CL events and the output's events must hold the
// same motions one to one (rapid/feed/arc; end points and arc centres
// within the tolerance, arc plane and direction equal) and the same spindle
// on/off, tool changes and cutter compensation sides (each change of side;
// a tool change and the program's end turn it off, as the writer does) in
// the same order; S and F values are free.
//
// No I/O: texts in, a Result out. Units: mm.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "postproc/gcode/dialect.h"

namespace vcpost::verify {

// The findings' codes are rows of the one code table (E71xx: vcpost::Code);
// all are errors (a verification either holds or fails).
using vcpost::Code;

// One S or F word that the output changed or added (an analog speed word
// counts as an S word: letter 'S', its text "M67 E0 Q9870").
struct Change {
  std::uint32_t line = 0;        // output line, 1-based
  std::uint32_t column = 0;      // output column of the word's letter, 1-based
  std::uint32_t input_line = 0;  // input line (G-code) or CL record line
  char letter = 'S';             // 'S' or 'F' (upper case)
  std::string old_text;          // the input's word (e.g. "S12000"); empty when added
  std::string new_text;          // the output's word (e.g. "S9870")
  bool added = false;            // the input's block (CL position) had no such word
};

struct Violation {
  Code code = Code::E7103;
  std::uint32_t line = 0;        // output line, 1-based (0: no place, e.g. end of file)
  std::uint32_t column = 0;      // output column, 1-based
  std::uint32_t input_line = 0;  // the input's line (CL record) it was compared with
  std::string message;
};

enum class InputKind { gcode, cldata, klartext };

struct Result {
  InputKind kind = InputKind::gcode;
  std::vector<Change> changes;  // in output order (empty with Options::on_change)
  std::uint64_t s_changes = 0, f_changes = 0;
  std::vector<Violation> violations;  // at most Options::max_violations, in output order
  std::uint64_t violation_count = 0;  // all of them
  std::uint64_t motions = 0;          // motions compared by the semantic proof
  double tolerance_mm = 0;            // CL: the end-point tolerance applied
  std::uint64_t inserted_blocks = 0;  // Klartext: TOOL CALL S blocks the output adds
  bool ok() const { return violation_count == 0; }
};

struct Options {
  gcode::Dialect dialect = gcode::rs274ngc_dialect();  // of both (G-code) or the output (CL)
  // CL only: largest per-axis distance of an output end point (arc centre)
  // from the CL's, mm. Raised to half a step of the output's grid
  // (0.5 * 10^-output_decimals) when smaller: a correct output written
  // with that many decimals is off by up to that much on each axis. An arc
  // centre (start + I/J/K, both rounded) is allowed half a step more.
  double tolerance_mm = 0.0005;
  int output_decimals = 4;
  // CL only: digits of the output's F (mm/min); S is an integer. A CL value
  // that the output writes rounded to that grid is no change.
  int output_feed_decimals = 1;
  // CL only: compare CUTCOM with the output's G40/G41/G42; false for a
  // profile that writes CUTCOM as comments (output.cutter_compensation).
  bool cutter_compensation = true;
  // CL only: the output changes tools by hand (output.tool_change =
  // "manual"): M5 when the spindle turns, then T<n> M0, compared as the
  // CL's tool change (a spindle stop before it when the CL's spindle turns).
  bool manual_tool_change = false;
  // CL only: the output writes each tilted frame as a set-up of its own
  // (output.tilted_plane = "setup"): no frame of its own, the points in the
  // frame's coordinates, the spindle stopped (M5) and started again around
  // the set-up's M0. Else the output's frame at each motion must be the
  // CL's (the same tool axis and turn) and the points are compared where
  // they lie on the part.
  bool setups = false;
  // The spindle speed on LinuxCNC's analog output n (the profile's
  // output.speed_word "M67 E<n>", also set in `dialect`): G-code in, an
  // output word M67/M68 E<n> Q<rpm> is a speed word, as the writer puts it
  // (gcode::SpeedForm): in the place of the input's S word, or added after
  // the block's last word (beside the S word at the spindle's start); its Q
  // may change as an S word does.
  std::optional<int> speed_output;
  std::size_t max_violations = 1000;  // kept in Result::violations (all are counted)
  // When set, each change is handed here, in output order, instead of being
  // kept in Result::changes (memory stays flat on long programs).
  std::function<void(const Change&)> on_change;
};

// G-code input vs G-code output. Throws vcpost::Error (the reader's code;
// what() "file:line:col: error[E....]: message") when the input does not
// interpret (an output that does not is a violation).
Result verify_gcode(std::string_view input, std::string_view output, const Options& options,
                    const std::string& input_name = "input");

// APT CL input vs G-code output. Throws the CL reader's cldata::ClError
// (a vcpost::Error: its code, file:line:col and hint) when the CL data do
// not read.
Result verify_cl(std::string_view cl_text, std::string_view output, const Options& options,
                 const std::string& input_name = "input");

// Klartext input vs the Klartext vcpost posted from it: only block numbers,
// TOOL CALL S values, inserted `TOOL CALL S` blocks (each right before a
// block that moves) and plain F digits differ, and both programs read
// into the same events but speeds and feeds (docs/heidenhain-output.md).
// Throws vcpost::Error (the reader's code; what() "file:line:col:
// error[E....]: message", the file input_name) when the input does not read.
Result verify_klartext(std::string_view input, std::string_view output, const Options& options,
                       const std::string& input_name = "input");

// APT CL input vs Klartext output: as verify_cl, the output read back by
// the Klartext reader.
Result verify_cl_klartext(std::string_view cl_text, std::string_view output, const Options& options,
                          const std::string& input_name = "input");

// "<file>:<line>:<col>: error[E7103]: <message> (input line N)".
std::string format(const Violation& violation, std::string_view output_name);

// "S12000 -> S9870" or "+ S9870".
std::string describe(const Change& change);

}  // namespace vcpost::verify
