// The lossless writer: the input program with only S and F words changed or
// added; every other byte (comments, blanks, N numbers, case, line endings)
// is copied unchanged. With no patches the output is the input, byte for
// byte.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "postproc/gcode/block.h"

namespace vcpost::gcode {

// How a spindle speed (a patch of letter S) is written.
// s_word: the S word.
// synced: LinuxCNC's analog output synchronized with motion, M67 E<n>
//   Q<value>, for a spindle whose speed command is motion.analog-out-<n>:
//   it takes the place of the block's S word (which would stop the path),
//   or is appended.
//   The output changes at the start of the block's own motion, or of the
//   next one after a block without motion.
// start: the S word (the spindle's start) and M68 E<n> Q<value> appended
//   (immediate: the output holds the speed before the spindle starts, as
//   the S word would).
// A block that has its M67/M68 E<n> word already (a program posted before)
// keeps it and its S word, with the new value in both.
// A block whose words leave no room for the analog word (a Q or E word of
// another use, another M62-M68) keeps an S word.
enum class SpeedForm : std::uint8_t { s_word, synced, start };

// Set word `letter` (S or F) of the block whose first byte is at
// `block_offset` (Block::offset, program::SourceRef::offset) to `value`
// (the number as it shall be written, e.g. "12000" or "850.5"). An existing
// word keeps its letter's case and position and gets the new value (an
// expression value is replaced by the number); a block without the word
// gets it appended after its last word, before a trailing comment.
struct WordPatch {
  std::uint64_t block_offset = 0;
  char letter = 'S';
  std::string value;
  SpeedForm form = SpeedForm::s_word;  // letter S only
  int output = 0;                      // the analog output n of synced and start
};

// The value of a word whose value is a plain number ("M67", "E 0"); none
// for an expression or parameter.
std::optional<double> literal_of(std::string_view line, Span word);

// A line's analog-output words for output n: its M67/M68 E<n> word with
// its E and Q words, and whether an analog word fits the block (room: the
// block has one already, or no E, Q or M62-M68 word of another use).
struct AnalogWords {
  std::optional<Span> m, e, q;
  bool immediate = false;  // M68 (else M67)
  bool room = false;
};
AnalogWords analog_words(std::string_view line, int output);

// Streams the patched program to `sink` in pieces. Patches must be sorted
// by block_offset (several per block allowed, one per letter); throws
// std::invalid_argument for unsorted patches, an offset that is no line
// start, or a letter other than S and F.
void write_patched(std::string_view text, std::span<const WordPatch> patches,
                   const std::function<void(std::string_view)>& sink);

// Convenience: the whole patched program as a string.
std::string patched(std::string_view text, std::span<const WordPatch> patches);

}  // namespace vcpost::gcode
