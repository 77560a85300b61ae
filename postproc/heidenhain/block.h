// The syntax layer of the Klartext reader: the text of one block (a line,
// with the lines a trailing '~' continues) -> one Block. Lossless: the block
// keeps its bytes and every word its byte span, so a writer can patch one
// word (TOOL CALL's S) or the block number and copy every other byte.
// Nothing is evaluated here: Q parameters stay references for the
// interpreter (interpreter.h), which also gives the words their meaning.
//
// What a writer needs of a block (hwriter's interface, all offsets are
// byte offsets in the whole program text):
//   offset          first byte of the block ('/' or the block number included)
//   end             the byte after its last byte; its line terminator is not
//                   part of it (`eol` is), its '~' continuation lines are
//   line, lines     its first line (1-based) and how many lines it spans
//   number          the block number as written (hyperMILL counts from 1;
//                   a program may have none); number_span: its digits
//   kind            L, C, CC, TOOL CALL, ..., END PGM (BlockKind)
//   s_span          TOOL CALL: the S word ("S5961", letter to last digit)
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace vcpost::heidenhain {

enum class BlockKind : std::uint8_t {
  empty,           // a blank line or a bare block number
  comment,         // a ';' or '*' line
  begin_pgm,       // BEGIN PGM name MM|INCH
  end_pgm,         // END PGM name MM|INCH
  blk_form,        // BLK FORM 0.1 / 0.2: the stock box
  tool_call,       // TOOL CALL [n|"name"] [axis] [S] [F] [DL] [DR]
  tool_def,        // TOOL DEF n: the next tool, prepared
  line,            // L
  line_normal,     // LN (3-D line with surface normal: the normal is not used)
  line_polar,      // LP
  centre,          // CC: circle centre and pole
  circle,          // C: arc about CC
  circle_radius,   // CR
  circle_tangent,  // CT
  circle_polar,    // CP
  approach,        // APPR LT|LN|CT|LCT (PLT ... polar): the contour approach
  departure,       // DEP LT|LN|CT|LCT: the contour departure
  rounding,        // RND
  chamfer,         // CHF
  fn,              // FN n: ... (Q parameter arithmetic and jumps)
  formula,         // Q1 = Q2 * 3 + SIN Q4 (the FORMULA key's assignment)
  label,           // LBL n | LBL "name"
  call_label,      // CALL LBL n [REP m]
  call_program,    // CALL PGM path (sub_keyword: the path)
  select_program,  // SEL PGM path
  call_selected,   // CALL SELECTED
  cycle_def,       // CYCL DEF n[.m]
  cycle_call,      // CYCL CALL [POS ...]
  plane,           // PLANE ...
  function,        // FUNCTION ...
  misc,            // M words alone, STOP
  other,           // anything else Klartext writes that vcpost refuses by name
};

// A word's name: up to eight upper-case letters packed into an integer, so
// names compare as numbers (name("FMAX")).
using Name = std::uint64_t;
constexpr Name name(std::string_view letters) {
  Name n = 0;
  for (const char c : letters) n = (n << 8) | static_cast<unsigned char>(c);
  return n;
}

// A value as written: a literal, or a Q parameter (Q, QL or QR) with an
// optional sign ("+Q120", "-Q5"). Not evaluated here.
struct Value {
  enum class Bank : std::uint8_t { literal, q, ql, qr };
  double number = 0.0;  // the literal, or the parameter's number
  Bank bank = Bank::literal;
  bool negate = false;
  bool is_parameter() const { return bank != Bank::literal; }
};

// A word: its name (L, X, IX, PA, DR, FMAX, M, ...), an optional value and,
// for words written as a sign only (DR+, R+ in CR is a value), that sign.
// [begin, end) are offsets in the block's text.
struct Word {
  Name key = 0;
  bool has_value = false;
  char sign = 0;  // '+' or '-' written right after the name, else 0
  Value value;
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
};

// A label as written: LBL 5 or LBL "name".
struct Label {
  long number = -1;       // -1: a named label
  std::string_view name;  // without the quotes
  std::uint32_t begin = 0;
  bool operator==(const Label& o) const { return number == o.number && name == o.name; }
};

struct Comment {
  std::string_view text;  // after ';' or '*' up to the end of its line ('~' included)
  std::uint32_t begin = 0;
};

// A Q parameter assignment of a cycle's continuation lines ("Q200=5").
struct CycleParameter {
  int number = 0;
  Value value;
  std::uint32_t begin = 0;
};

// FN n: the operation, its target parameter and its operands; FN 9-12 also
// the comparison's jump target.
struct FnStatement {
  int number = 0;
  std::optional<Value> target;  // FN 0-8, 13: the Q parameter set
  std::optional<Value> a, b;    // operands
  std::uint32_t a_begin = 0, b_begin = 0;
  std::optional<Label> jump;  // FN 9-12: GOTO LBL
};

// One step of a Q parameter formula in postfix order: a value pushed, or an
// operator or function applied to the values on top of the stack.
struct FormulaStep {
  enum class Op : std::uint8_t {
    value,  // push `value`
    // unary, on the top value
    negate,
    sq,
    sqrt,
    sin,
    cos,
    tan,
    asin,
    acos,
    atan,
    abs,
    int_part,
    frac,
    sgn,
    ln,
    log,
    exp,
    // binary, on the two top values (left below right)
    add,
    subtract,
    multiply,
    divide,
    modulo,
    power,
  };
  Op op = Op::value;
  Value value;           // Op::value: a literal, Q, QL or QR (PI is a literal)
  std::uint32_t at = 0;  // its byte in the block, for errors
};

struct ByteSpan {
  std::uint64_t begin = 0;
  std::uint64_t end = 0;
};

struct Block {
  std::string_view text;  // the block's bytes: [offset, end)
  std::string_view eol;   // the terminator after its last line ("\n", "\r\n", "" at the end)
  std::uint64_t offset = 0;
  std::uint64_t end = 0;
  std::uint32_t line = 0;
  std::uint32_t lines = 1;
  std::optional<std::uint32_t> number;
  std::optional<ByteSpan> number_span;
  bool skippable = false;  // written with '/' (runs: the block-skip switch is taken off)
  BlockKind kind = BlockKind::empty;
  std::uint32_t keyword_begin = 0;  // where its keyword starts in text
  std::string_view keyword;         // the keyword(s) as written ("TOOL CALL", "L", "CYCL DEF")
  std::vector<Word> words;
  std::vector<Comment> comments;
  // BEGIN/END PGM: the name and the units word; TOOL CALL/DEF: the tool
  // name (without quotes) when it is called by name; PLANE, FUNCTION: the
  // first word after the keyword (SPATIAL, RESET ...).
  std::string_view program_name, units, tool_name, sub_keyword;
  std::optional<Label> label;          // LBL, CALL LBL
  std::optional<double> cycle_number;  // CYCL DEF: 7.1, 200, 32.0 ...
  std::vector<CycleParameter> cycle_parameters;
  FnStatement fn;                    // FN n; a formula's target in fn.target
  std::vector<FormulaStep> formula;  // Q.. = <formula>
  std::optional<ByteSpan> s_span;    // TOOL CALL's S word

  void clear();
  // The first word named `key`, or null.
  const Word* find(Name key) const;
  // Line and 1-based column of a byte of the block's text.
  std::pair<std::uint32_t, std::uint32_t> position(std::uint32_t at) const;
};

// Longest block the reader takes (its ~ lines together); longer ones are
// Code::E3301.
inline constexpr std::size_t kMaxBlockLength = 65536;

// The block of `text` that starts at `offset` (a block start, `line` its
// 1-based line): sets `out`'s text, eol, offset, end, line and lines (a line,
// with the lines a trailing '~' continues) and returns the offset of the
// next block. The reader and the writers of Klartext cut a text into blocks
// with it. Throws KlartextError (Code::E3301) for a block longer
// than kMaxBlockLength.
std::uint64_t split_block(std::string_view text, std::uint64_t offset, std::uint32_t line,
                          Block& out);

// Reads the block `out.text` (set with offset, end, line, lines and eol by
// the caller, e.g. split_block) into `out`'s other fields. Throws KlartextError at the line
// and column of the first problem.
void parse_block(Block& out);

}  // namespace vcpost::heidenhain
