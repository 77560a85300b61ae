// The second stage of the G-code reader: values. An ExpressionReader reads,
// on the Lexer's cursor, what a word's value may be beyond a literal:
// [..] expressions with their operators (RS274NGC and Fanuc macro B,
// Sinumerik's ( ) and AC()), #parameters (numbered, <named>, Sinumerik R),
// and the functions (SIN .. ROUND, ATAN[y]/[x], EXISTS). It only computes
// numbers: parameters are read from `Parameters`, never written (the block
// parser returns assignments for the interpreter to commit). Every result
// is finite (Code::E1205 otherwise).
#pragma once

#include <cmath>
#include <cstddef>
#include <string>

#include "postproc/gcode/block.h"
#include "postproc/gcode/dialect.h"
#include "postproc/gcode/lexer.h"
#include "postproc/gcode/parameters.h"

namespace vcpost::gcode::syntax {

// Values read inside each other at most: signs (X---1), parameter signs
// (##1), brackets and functions each open one. The reader recurses once per
// level, so a line of 65,536 signs would overflow the stack; real programs
// nest a few levels.
inline constexpr int kMaxValueNesting = 100;
// Sinumerik R parameters vcpost keeps (a control has R0 to R99 by default,
// more by machine data).
inline constexpr int kMaxRParameter = 99999;

class ExpressionReader : public Lexer {
 public:
  // `p` may be null when nothing is evaluated (peek_control).
  ExpressionReader(std::string_view s, std::uint32_t line, const Dialect& d, const Parameters* p)
      : Lexer(s, line), d_(d), p_(p) {}

 protected:
  const Dialect& d_;
  const Parameters* p_;   // null when only peeking (nothing is evaluated)
  bool ac_seen_ = false;  // AC(..) read in the current word's expression
  int nesting_ = 0;       // values being read inside each other (unary())
  // Sinumerik: the block's R assignments read so far, which the words after
  // them see (the control assigns in the order written; null elsewhere).
  const std::vector<Assignment>* earlier_ = nullptr;

  bool siemens() const { return d_.kind == machines::Dialect::sinumerik; }

  // A value at the cursor: signs, then [expr], #parameter, a literal, a
  // function, (expr) and R<n> in Sinumerik. `word_start` places errors.
  Value unary(std::size_t word_start);
  // Operators of precedence `min_precedence` and up, left to right.
  Value binary(int min_precedence, std::size_t open);
  Value bracket() { return enclosed(']', "'[' not closed with ']'"); }  // [ expression ]
  Value paren() { return enclosed(')', "'(' not closed with ')'"); }    // Sinumerik: ( expression )

  // A parameter reference after '#': its number, or its normalised name.
  struct Ref {
    int number = 0;
    std::string name;
  };
  Ref parameter_ref();
  // Sinumerik: the number after the 'R' at `start` (R0 to kMaxRParameter).
  int read_r_number(std::size_t start);

  // Values of words and cycle arguments within kMaxWordMagnitude. (The
  // message is worded only on failure: this runs for every word.)
  static bool in_range(double v) { return std::abs(v) <= kMaxWordMagnitude; }
  [[noreturn]] void out_of_range(double v, std::size_t at, const std::string& what) const;
  double bounded(double v, std::size_t at, const std::string& what) const {
    if (!in_range(v)) out_of_range(v, at, what);
    return v;
  }

 private:
  enum class Op {
    none,
    power,
    times,
    divide,
    mod,
    plus,
    minus,
    eq,
    ne,
    gt,
    ge,
    lt,
    le,
    and_,
    or_,
    xor_
  };
  Value enclosed(char close, const char* not_closed);
  Op peek_op(std::size_t& length) const;
  static int precedence(Op op);
  // An operation whose result overflows (or is not a number) fails here, so
  // no parameter or word ever holds an infinity or a NaN.
  Value apply(Op op, Value a, Value b, std::size_t at) const {
    return finite(apply_unchecked(op, a, b, at), at);
  }
  Value apply_unchecked(Op op, Value a, Value b, std::size_t at) const;
  Value finite(Value v, std::size_t at) const;

  Value function() {
    const std::size_t start = i_;
    return finite(function_unchecked(), start);
  }
  Value function_unchecked();
  std::string dialect_hint(const std::string& name) const;
  std::string read_name();  // after "#<": the normalised name up to '>'
  Value parameter_value();
  double r_value(int number) const;
};

}  // namespace vcpost::gcode::syntax
