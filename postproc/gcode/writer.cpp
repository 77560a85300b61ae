#include "postproc/gcode/writer.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <vector>

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

std::optional<double> literal_of(std::string_view line, Span word) {
  std::size_t k = word.begin + 1;
  while (k < word.end && (line[k] == ' ' || line[k] == '\t')) ++k;
  const std::string digits(line.substr(k, word.end - k));
  if (digits.empty() || digits.find_first_not_of("+-.0123456789") != std::string::npos)
    return std::nullopt;
  char* stop = nullptr;
  const double v = std::strtod(digits.c_str(), &stop);
  if (stop != digits.c_str() + digits.size()) return std::nullopt;
  return v;
}

AnalogWords analog_words(std::string_view line, int output) {
  AnalogWords words;
  words.e = find_word_span(line, 'E');
  words.q = find_word_span(line, 'Q');
  bool other = false;  // another HAL I/O code (M62-M68) in the block
  for (std::size_t from = 0; from < line.size();) {
    const auto m = find_word_span(line.substr(from), 'M');
    if (!m) break;
    const Span at{static_cast<std::uint32_t>(m->begin + from),
                  static_cast<std::uint32_t>(m->end + from)};
    from = at.end;
    const auto code = literal_of(line, at);
    if (!code || *code < 62 || *code > 68) continue;
    const auto e = words.e ? literal_of(line, *words.e) : std::nullopt;
    if ((*code == 67 || *code == 68) && e && *e == output && !words.m) {
      words.m = at;
      words.immediate = *code == 68;
    } else {
      other = true;
    }
  }
  words.room = !other && (words.m ? words.q.has_value() : !words.e && !words.q);
  return words;
}

namespace {

// One replacement of a byte range of a line.
struct Edit {
  std::size_t begin, end;
  std::string replacement;
};

// "M67 E0 Q9000" (blanks between its words where the line has blanks).
std::string analog_word(std::string_view m, int output, const std::string& value, bool spaced) {
  const char* blank = spaced ? " " : "";
  return std::string(m) + blank + "E" + std::to_string(output) + blank + "Q" + value;
}

}  // namespace

void write_patched(std::string_view text, std::span<const WordPatch> patches,
                   const std::function<void(std::string_view)>& sink) {
  std::size_t copied = 0;
  std::size_t i = 0;
  std::vector<Edit> edits;
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
    edits.clear();
    std::string appended;
    const bool spaced = line.find(' ') != std::string_view::npos;
    int letters = 0;
    for (; i < patches.size() && patches[i].block_offset == offset; ++i) {
      const WordPatch& p = patches[i];
      const char letter = static_cast<char>(p.letter & ~0x20);
      // Internal invariant, not the user's input: the post job patches S and F only.
      if (letter != 'S' && letter != 'F')
        throw std::invalid_argument("write_patched: only S and F words are patched");
      if (++letters > 2) throw std::invalid_argument("write_patched: more than S and F in a block");
      const auto span = find_word_span(line, p.letter);
      SpeedForm form = letter == 'S' ? p.form : SpeedForm::s_word;
      AnalogWords analog;
      if (form != SpeedForm::s_word) {
        analog = analog_words(line, p.output);
        if (!analog.room) form = SpeedForm::s_word;
      }
      if (form != SpeedForm::s_word && analog.m) {
        // The block has its analog word already (a program posted before):
        // it gets the value, and an S word there too.
        edits.push_back(Edit{analog.q->begin + 1u, analog.q->end, p.value});
        if (span) edits.push_back(Edit{span->begin + 1u, span->end, p.value});
        continue;
      }
      // The analog word in the S word's place, or after the last word.
      std::string word = std::string(1, letter) + p.value;
      if (form == SpeedForm::synced) {
        // A block of only the S word ("S9000") spells the analog word out.
        const bool alone = span && span->begin == 0 && span->end == code_end(line);
        word = analog_word("M67", p.output, p.value, spaced || alone);
      }
      if (span) {
        edits.push_back(form == SpeedForm::synced ? Edit{span->begin, span->end, word}
                                                  : Edit{span->begin + 1u, span->end, p.value});
      } else {
        if (spaced) appended += ' ';
        appended += word;
      }
      if (form == SpeedForm::start) {
        if (spaced) appended += ' ';
        appended += analog_word("M68", p.output, p.value, spaced);
      }
    }
    std::sort(edits.begin(), edits.end(),
              [](const Edit& a, const Edit& b) { return a.begin < b.begin; });
    sink(text.substr(copied, offset - copied));
    std::size_t at = 0;
    const std::size_t insert_at = code_end(line);
    for (const Edit& edit : edits) {
      sink(line.substr(at, edit.begin - at));
      sink(edit.replacement);
      at = edit.end;
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
