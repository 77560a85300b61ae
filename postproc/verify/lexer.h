// The lexical layer of verification: program text -> lines -> tokens, with
// no evaluation. Deliberately independent of gcode::read_block: a second
// reading of the same bytes, so that a slip in one cannot hide in the other.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace vcpost::verify {

struct Line {
  std::string_view text;  // without its terminator
  std::string_view eol;   // "\n", "\r\n" or "" (last line without one)
  std::uint32_t number = 0;
};

// All lines of `text`; a final terminator does not start another line.
std::vector<Line> split_lines(std::string_view text);

// The number of lines split_lines() gives, without keeping them.
std::uint32_t count_lines(std::string_view text);

// The number of the first line longer than `limit` bytes (its terminator
// and a '\r' before it not counted), 0 when none is. Looks no further into
// a line than just past the limit: a text of one endless line costs no
// more than that.
std::uint32_t first_line_longer_than(std::string_view text, std::size_t limit);

// The line that starts at `offset` (< text.size()), numbered `number`;
// returns the offset just after it (after its terminator).
std::size_t line_at(std::string_view text, std::size_t offset, std::uint32_t number, Line& line);

// The line that ends at `end` (> 0: just after its terminator, or
// text.size()), numbered `number`; returns the offset of its first byte.
std::size_t line_before(std::string_view text, std::size_t end, std::uint32_t number, Line& line);

enum class TokenKind {
  blank,     // a run of spaces and tabs
  comment,   // "(...)" (to the end of the line when unclosed) or ";..." to the end
  word,      // a letter and its value at bracket depth 0, S #<rpm>, F[#1*2]
  name,      // a run of letters, or a letter without a value (GOTO, EQ, THEN)
  other,     // any other byte: % / # = [ ] digits outside words ...
  argument,  // an S or F word that sets no speed or feed (a G65 macro's argument, G25/G26 S)
};

struct Token {
  TokenKind kind = TokenKind::other;
  std::string_view text;           // the token's bytes
  std::uint32_t column = 0;        // 1-based
  char letter() const;             // word: upper-case letter; 0 otherwise
  std::string_view value() const;  // word: the bytes after the letter (blanks trimmed in front)
  bool is_sf() const { return letter() == 'S' || letter() == 'F'; }
};

// Cuts one line (no terminator) into tokens; concatenated, their texts are
// the line. Never throws.
void tokenize(std::string_view line, std::vector<Token>& out);

// A plain positive number as vcpost writes S and F: digits with at most one
// decimal point, at least one digit, value > 0 (no sign, no blanks, no
// expression or parameter).
bool is_plain_positive(std::string_view value);

}  // namespace vcpost::verify
