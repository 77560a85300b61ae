#include "postproc/gcode/writer.h"

#include <stdexcept>

#include "postproc/gcode/block.h"

namespace vcpost::gcode {

namespace {

// End of the code part of a line: before the first comment, trailing blanks
// excluded.
std::size_t code_end(std::string_view line) {
  std::size_t end = line.size();
  for (std::size_t i = 0; i < line.size(); ++i)
    if (line[i] == '(' || line[i] == ';') {
      end = i;
      break;
    }
  while (end > 0 && (line[end - 1] == ' ' || line[end - 1] == '\t')) --end;
  return end;
}

}  // namespace

void write_patched(std::string_view text, std::span<const WordPatch> patches,
                   const std::function<void(std::string_view)>& sink) {
  std::size_t copied = 0;
  std::size_t i = 0;
  while (i < patches.size()) {
    const std::uint64_t offset = patches[i].block_offset;
    // Internal invariant, not the user's input: patches come from the
    // interpreter's own block offsets, in order (invalid_argument: a bug).
    if (offset < copied || offset > text.size() || (offset > 0 && text[offset - 1] != '\n'))
      throw std::invalid_argument("write_patched: patch offset " + std::to_string(offset) +
                                  " is not the start of a later line");
    std::size_t line_end = text.find('\n', offset);
    if (line_end == std::string_view::npos) line_end = text.size();
    if (line_end > offset && text[line_end - 1] == '\r') --line_end;
    const std::string_view line = text.substr(offset, line_end - offset);
    // The patches of this block, applied left to right.
    struct Edit {
      std::size_t begin, end;
      std::string replacement;
    };
    Edit edits[2];
    int edit_count = 0;
    std::string appended;
    const bool spaced = line.find(' ') != std::string_view::npos;
    for (; i < patches.size() && patches[i].block_offset == offset; ++i) {
      const WordPatch& p = patches[i];
      // Internal invariant, not the user's input: the post job patches S and F only.
      if (p.letter != 'S' && p.letter != 'F' && p.letter != 's' && p.letter != 'f')
        throw std::invalid_argument("write_patched: only S and F words are patched");
      if (edit_count == 2)
        throw std::invalid_argument("write_patched: more than S and F in a block");
      if (const auto span = find_word_span(line, p.letter)) {
        edits[edit_count++] = Edit{span->begin + 1, span->end, p.value};
      } else {
        if (spaced) appended += ' ';
        appended += static_cast<char>(p.letter & ~0x20);
        appended += p.value;
      }
    }
    if (edit_count == 2 && edits[1].begin < edits[0].begin) std::swap(edits[0], edits[1]);
    sink(text.substr(copied, offset - copied));
    std::size_t at = 0;
    const std::size_t insert_at = code_end(line);
    for (int k = 0; k < edit_count; ++k) {
      sink(line.substr(at, edits[k].begin - at));
      sink(edits[k].replacement);
      at = edits[k].end;
    }
    if (!appended.empty()) {
      const std::size_t split = std::max(at, insert_at);
      sink(line.substr(at, split - at));
      sink(appended);
      at = split;
    }
    copied = offset + at;
  }
  sink(text.substr(copied));
}

std::string patched(std::string_view text, std::span<const WordPatch> patches) {
  std::string out;
  out.reserve(text.size() + patches.size() * 8);
  write_patched(text, patches, [&out](std::string_view piece) { out += piece; });
  return out;
}

}  // namespace vcpost::gcode
