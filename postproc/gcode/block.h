// The syntax layer: one line of program text -> one Block. Lossless: the
// block keeps its original bytes (`text`, `eol`) and every word its byte span
// and column, so the writer can patch one word and copy everything else.
// Parameters and expressions are evaluated here (they only compute numbers);
// what they set is returned as assignments for the interpreter to commit.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "postproc/gcode/dialect.h"
#include "postproc/gcode/parameters.h"

namespace vcpost::gcode {

// A word: letter (upper case) and value in program units, as written
// (G and M values are the number, e.g. 61.1). Bytes [begin, end) of the line
// hold the letter and its value (blanks inside included).
struct Word {
  char letter = 0;
  double value = 0.0;
  std::uint32_t column = 0;  // 1-based column of the letter
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
  bool decimal_point = false;  // a literal number with '.' (Fanuc integer rule)
  bool computed = false;       // value from a parameter or expression
  bool absolute = false;       // Sinumerik I=AC(..): an absolute centre
};

struct Comment {
  std::string_view text;  // without the parentheses or ';'
  std::uint32_t column = 0;
};

struct Assignment {
  int number = 0;    // numbered parameter, or 0 for a named one
  std::string name;  // named parameter, normalised (lower case, no blanks)
  double value = 0.0;
  std::uint32_t column = 0;
};

// O-word control (RS274NGC) and Fanuc/Mazak macro flow.
enum class ControlKind {
  none,
  sub,
  endsub,
  call,
  return_,  // o<name> sub / endsub / call [args] / return
  if_,
  elseif,
  else_,
  endif,  // o<name> if [cond] ... (also Fanuc IF..THEN..ENDIF)
  while_,
  endwhile,
  do_,
  break_,
  continue_,
  repeat,
  endrepeat,
  program_number,  // Fanuc/Mazak "O1234" program header
  fanuc_goto,      // GOTO n, IF [..] GOTO n, WHILE/DO/END
};

struct Control {
  ControlKind kind = ControlKind::none;
  std::string name;  // o-word name ("100" or "name"), program number
  std::uint32_t column = 0;
  std::optional<double> condition;  // if/elseif/while/repeat count; GOTO: taken or not
  std::vector<double> arguments;    // call arguments, return value
};

// A Sinumerik drilling cycle statement: CYCLE81(...) runs once where the
// tool is; MCALL CYCLE81(...) runs it after every later positioning until a
// bare MCALL. Empty arguments (",,") are nullopt. CYCLE800(...) (swivel)
// tilts the working plane; its quoted swivel data set name is nullopt.
struct SiemensCycle {
  enum class Kind { none, call, modal_call, modal_off, swivel } kind = Kind::none;
  int number = 0;  // 81 .. 89, 800
  std::vector<std::optional<double>> args;
  std::uint32_t column = 0;
};

struct Block {
  std::string_view text;  // the line, without its terminator
  std::string_view eol;   // "\n", "\r\n", "\r" or "" (last line)
  std::uint32_t line = 0;
  std::uint64_t offset = 0;  // byte offset of text[0] in the program
  bool deleted = false;      // '/' block skipped by the block-delete switch
  bool tape_marker = false;  // a '%' line
  std::optional<long> n;     // sequence number
  std::vector<Word> words;   // every word but N and O, in order
  std::vector<Comment> comments;
  std::vector<Assignment> assignments;
  std::optional<std::string> message;  // (MSG, ...)
  Control control;
  SiemensCycle siemens_cycle;
  // Sinumerik keywords passed through (SOFT, FFWON, CYCLE832 ...): name, column.
  std::vector<std::pair<std::string, std::uint32_t>> noted_keywords;

  void clear();
  const Word* find(char letter) const;  // first word with this letter
};

// Longest line the reader accepts (longer ones are Code::E1006).
inline constexpr std::size_t kMaxLineLength = 65536;

// Largest magnitude of a word's or a cycle argument's value (Code::E1003
// beyond): 10^12 mm is far past any machine, and keeps every sum, square and
// arc the interpreter forms from such values finite.
inline constexpr double kMaxWordMagnitude = 1e12;

// Reads `line` (no terminator) into `out` (cleared first; text, line and
// offset set by the caller or here). Throws GcodeError with the line and
// column of the first problem. `parameters` is only read.
void read_block(std::string_view line, std::uint32_t line_number, std::uint64_t offset,
                const Dialect& dialect, const Parameters& parameters, Block& out);

// Only the O-word prefix of a line, without evaluating anything: the kind
// and name, for scanning to a matching endsub/endif/else. kind = none when
// the line is no O-word line. Never throws.
Control peek_control(std::string_view line, const Dialect& dialect);

// Byte span [begin, end) of the first `letter` word of a line outside
// comments, for the writer; nullopt if there is none. Never throws.
struct Span {
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
};
// End of a word's value that starts at `k` (after its letter and the blanks
// after it), as the reader reads it: unary signs (blanks between them),
// then a [expression], a #parameter or a literal with blanks between its
// digits; `k` when no value starts there. The writer's spans and verify's
// lexer both use it.
std::size_t word_value_end(std::string_view line, std::size_t k);
std::optional<Span> find_word_span(std::string_view line, char letter);

}  // namespace vcpost::gcode
