// The third stage of the G-code reader: words -> Block. A BlockParser reads
// one line into a Block on the Lexer's cursor, and takes values that are
// not plain literals from its ExpressionReader: the block-delete slash, N,
// words with their byte spans, comments and (MSG,..), parameter
// assignments, O-word control and Fanuc/Mazak macro statements
// (block.cpp), and the Sinumerik 840D statements (block_siemens.cpp).
// read_block() and peek_control() of block.h are its entry points.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "postproc/gcode/block.h"
#include "postproc/gcode/expression.h"

namespace vcpost::gcode::syntax {

class BlockParser : public ExpressionReader {
 public:
  using ExpressionReader::ExpressionReader;

  void read(Block& out);  // the whole line
  Control peek();         // only the O-word prefix (see peek_control)

 private:
  // ---- block.cpp: the words of every dialect -----------------------------
  void read_items(Block& out);
  void read_comment(Block& out);
  void read_sequence_number(Block& out);
  void read_word(Block& out, char letter);
  void read_assignment(Block& out);
  void read_o_word(Block& out);
  bool read_o_name(std::string& name, bool throwing);
  static ControlKind o_keyword(std::string_view key);
  bool read_macro_statement(Block& out);

  // The word's value within kMaxWordMagnitude, then stored.
  void push_word(Block& out, const Word& w) const {
    if (!in_range(w.value)) out_of_range(w.value, w.begin, std::string(1, w.letter) + " word");
    out.words.push_back(w);
  }

  // ---- block_siemens.cpp: Sinumerik 840D statements ------------------------
  bool looks_siemens() const;         // MSG( MCALL CYCLE8x( CR= at the cursor
  bool r_assignment_follows() const;  // "R12 = ..." (not an R word)
  void read_r_assignment(Block& out);
  void read_siemens_keyword(Block& out);
  Word read_keyword_word(char letter, std::size_t start, const char* no_equals);  // CR=, TURN=
  std::string read_quoted_call(std::size_t start, const std::string& key);
  // `strings`: a quoted argument is taken as empty (CYCLE800's "TC1").
  std::vector<std::optional<double>> read_call_arguments(std::size_t start, const std::string& key,
                                                         bool strings = false);
  void skip_parenthesised();
  bool read_cycle(const std::string& name, std::size_t start, SiemensCycle& cycle);
};

}  // namespace vcpost::gcode::syntax
