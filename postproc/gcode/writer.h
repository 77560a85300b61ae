// The lossless writer: the input program with only S and F words changed or
// added; every other byte (comments, blanks, N numbers, case, line endings)
// is copied unchanged. With no patches the output is the input, byte for
// byte.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>

namespace vcpost::gcode {

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
};

// Streams the patched program to `sink` in pieces. Patches must be sorted
// by block_offset (several per block allowed, one per letter); throws
// std::invalid_argument for unsorted patches, an offset that is no line
// start, or a letter other than S and F.
void write_patched(std::string_view text, std::span<const WordPatch> patches,
                   const std::function<void(std::string_view)>& sink);

// Convenience: the whole patched program as a string.
std::string patched(std::string_view text, std::span<const WordPatch> patches);

}  // namespace vcpost::gcode
