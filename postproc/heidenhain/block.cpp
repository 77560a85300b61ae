// The block parser: a block's text -> its kind, keyword, words, comments
// and the statements with a syntax of their own (FN, LBL, CYCL DEF, BEGIN
// PGM ...). Built on the lexer; evaluates nothing.
#include "postproc/heidenhain/block.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "postproc/heidenhain/formula.h"
#include "postproc/heidenhain/lexer.h"

namespace vcpost::heidenhain {

void Block::clear() {
  number.reset();
  number_span.reset();
  skippable = false;
  kind = BlockKind::empty;
  keyword_begin = 0;
  keyword = {};
  words.clear();
  comments.clear();
  program_name = units = tool_name = sub_keyword = {};
  label.reset();
  cycle_number.reset();
  cycle_parameters.clear();
  fn = FnStatement{};
  formula.clear();
  s_span.reset();
}

const Word* Block::find(Name key) const {
  for (const Word& w : words) {
    if (w.key == key) return &w;
  }
  return nullptr;
}

std::pair<std::uint32_t, std::uint32_t> Block::position(std::uint32_t at) const {
  at = std::min<std::uint32_t>(at, static_cast<std::uint32_t>(text.size()));
  std::uint32_t line_number = line;
  std::uint32_t line_start = 0;
  for (std::uint32_t k = 0; k < at; ++k) {
    if (text[k] == '\n') {
      ++line_number;
      line_start = k + 1;
    }
  }
  return {line_number, at - line_start + 1};
}

namespace {

using syntax::is_blank;
using syntax::is_digit;
using syntax::is_upper;

class BlockParser : public syntax::Lexer {
 public:
  explicit BlockParser(Block& b) : Lexer(b), b_(b) {}

  void parse() {
    skip_line_blanks();
    if (peek() == '/') {
      b_.skippable = true;
      seek(pos() + 1);
    }
    if (is_digit(peek())) read_block_number();
    skip_line_blanks();
    if (peek() == '/') {  // "5 /L ...": the skip mark after the number
      b_.skippable = true;
      seek(pos() + 1);
      skip_line_blanks();
    }
    if (at_end()) return;
    if (peek() == ';' || peek() == '*') {
      b_.kind = BlockKind::comment;
      read_comment();
      return;
    }
    b_.keyword_begin = static_cast<std::uint32_t>(pos());
    const std::string_view key = read_letters();
    if (key.empty()) {
      check_word_byte(pos());
      fail(Code::E3304, pos(), std::string("a block starts with '") + peek() + "'");
    }
    keyword(key);
  }

 private:
  Block& b_;

  void skip_line_blanks() {
    while (peek() == ' ' || peek() == '\t') seek(pos() + 1);
  }

  void read_block_number() {
    const std::size_t first = pos();
    double number = 0;
    while (is_digit(peek())) seek(pos() + 1);
    const std::size_t last = pos();
    if (last - first > 9) fail(Code::E3303, first, "block number too long");
    for (std::size_t k = first; k < last; ++k) number = number * 10 + (text()[k] - '0');
    // A number runs into a keyword only where the program has none ("5L"
    // is no block): digits must be followed by a blank, '/', ';' or the end.
    if (!at_end() && !is_blank(peek()) && peek() != ';' && peek() != '/') {
      seek(first);
      return;
    }
    b_.number = static_cast<std::uint32_t>(number);
    b_.number_span = ByteSpan{b_.offset + first, b_.offset + last};
  }

  void read_comment() {
    const std::size_t at = pos();
    seek(at + 1);
    b_.comments.push_back({rest_of_line(), static_cast<std::uint32_t>(at + 1)});
  }

  // The second word of a two-word keyword ("TOOL CALL"): true when it is `want`.
  bool next_is(std::string_view want) {
    const std::size_t back = pos();
    skip_blanks();
    if (read_letters() == want) return true;
    seek(back);
    return false;
  }

  void set_keyword(BlockKind kind) {
    b_.kind = kind;
    b_.keyword = text().substr(b_.keyword_begin, pos() - b_.keyword_begin);
  }

  // A keyword's parser: reads what follows it and returns true, or false
  // (the cursor where it was) when the words after it make no block of its
  // own ("CALL" without LBL): the block is then BlockKind::other.
  using KeywordParser = bool (*)(BlockParser& parser, std::string_view key, BlockKind kind);
  struct KeywordRule {
    Name word;  // name(): the letters packed, compared as one number
    BlockKind kind;
    KeywordParser parse;
  };

  template <bool (BlockParser::*parse)(std::string_view, BlockKind)>
  static bool thunk(BlockParser& parser, std::string_view key, BlockKind kind) {
    return (parser.*parse)(key, kind);
  }

  // The first word of every block vcpost reads, sorted by its packed name
  // (checked at compile time) for a binary search on numbers: this runs
  // for every block.
  static const KeywordRule* find_keyword(std::string_view letters) {
    if (letters.size() > 8) return nullptr;
    const Name key = name(letters);
    static constexpr KeywordRule rules[] = {
        {name("C"), BlockKind::circle, &thunk<&BlockParser::motion_words>},
        {name("L"), BlockKind::line, &thunk<&BlockParser::motion_words>},
        {name("M"), BlockKind::misc, &thunk<&BlockParser::m_block>},
        {name("Q"), BlockKind::formula, &thunk<&BlockParser::formula>},
        {name("CC"), BlockKind::centre, &thunk<&BlockParser::motion_words>},
        {name("CP"), BlockKind::circle_polar, &thunk<&BlockParser::motion_words>},
        {name("CR"), BlockKind::circle_radius, &thunk<&BlockParser::motion_words>},
        {name("CT"), BlockKind::circle_tangent, &thunk<&BlockParser::motion_words>},
        {name("FN"), BlockKind::fn, &thunk<&BlockParser::fn>},
        {name("LN"), BlockKind::line_normal, &thunk<&BlockParser::motion_words>},
        {name("LP"), BlockKind::line_polar, &thunk<&BlockParser::motion_words>},
        {name("QL"), BlockKind::formula, &thunk<&BlockParser::formula>},
        {name("QR"), BlockKind::formula, &thunk<&BlockParser::formula>},
        {name("BLK"), BlockKind::blk_form, &thunk<&BlockParser::blk_form>},
        {name("CHF"), BlockKind::chamfer, &thunk<&BlockParser::chamfer>},
        {name("DEP"), BlockKind::departure, &thunk<&BlockParser::contour_link>},
        {name("END"), BlockKind::end_pgm, &thunk<&BlockParser::program_block>},
        {name("LBL"), BlockKind::label, &thunk<&BlockParser::label_block>},
        {name("RND"), BlockKind::rounding, &thunk<&BlockParser::motion_words>},
        {name("SEL"), BlockKind::select_program, &thunk<&BlockParser::select>},
        {name("APPR"), BlockKind::approach, &thunk<&BlockParser::contour_link>},
        {name("CALL"), BlockKind::call_label, &thunk<&BlockParser::call>},
        {name("CYCL"), BlockKind::cycle_def, &thunk<&BlockParser::cycle>},
        {name("STOP"), BlockKind::misc, &thunk<&BlockParser::motion_words>},
        {name("TOOL"), BlockKind::tool_call, &thunk<&BlockParser::tool_block>},
        {name("BEGIN"), BlockKind::begin_pgm, &thunk<&BlockParser::program_block>},
        {name("PLANE"), BlockKind::plane, &thunk<&BlockParser::plane>},
        {name("FUNCTION"), BlockKind::function, &thunk<&BlockParser::function>},
    };
    static_assert(std::ranges::is_sorted(rules, {}, &KeywordRule::word));
    const auto* it = std::ranges::lower_bound(rules, key, {}, &KeywordRule::word);
    return it != std::end(rules) && it->word == key ? it : nullptr;
  }

  void keyword(std::string_view key) {
    // L, nearly every block of a CAM program, without the search.
    if (key == "L") {
      motion_words(key, BlockKind::line);
      return;
    }
    if (const KeywordRule* rule = find_keyword(key)) {
      if (rule->parse(*this, key, rule->kind)) return;
    }
    // Another Klartext statement (APPR, FL, SPL, SEL PGM, CALL PGM ...) or
    // no Klartext at all: the interpreter says which.
    set_keyword(BlockKind::other);
    rest_as_sub_keyword();
  }

  bool motion_words(std::string_view /*key*/, BlockKind kind) {
    set_keyword(kind);
    words();
    return true;
  }

  // CHF <length>: the value stands without a letter.
  bool chamfer(std::string_view key, BlockKind kind) {
    set_keyword(kind);
    skip_blanks();
    Word w;
    w.key = name(key);
    w.begin = static_cast<std::uint32_t>(pos());
    w.has_value = read_value(w.value, w.sign);
    w.end = static_cast<std::uint32_t>(pos());
    if (w.has_value) b_.words.push_back(w);
    words();
    return true;
  }

  // A block of M words only: the M is the first word.
  bool m_block(std::string_view /*key*/, BlockKind kind) {
    seek(b_.keyword_begin);
    set_keyword(kind);
    words();
    return true;
  }

  bool program_block(std::string_view key, BlockKind kind) {
    if (!next_is("PGM")) return false;
    set_keyword(key == "BEGIN" ? BlockKind::begin_pgm : kind);
    program_header();
    return true;
  }

  bool blk_form(std::string_view /*key*/, BlockKind kind) {
    if (!next_is("FORM")) return false;
    set_keyword(kind);
    skip_blanks();
    double part = 0;
    if (read_unsigned(part)) {
      b_.cycle_number = part;
    } else {
      b_.sub_keyword = read_letters();  // CYLINDER, ROTATION ...
    }
    words();
    return true;
  }

  bool tool_block(std::string_view /*key*/, BlockKind kind) {
    if (next_is("CALL")) {
      set_keyword(kind);
    } else if (next_is("DEF")) {
      set_keyword(BlockKind::tool_def);
    } else {
      return false;
    }
    tool();
    return true;
  }

  bool label_block(std::string_view /*key*/, BlockKind kind) {
    set_keyword(kind);
    skip_blanks();
    b_.label = label();
    words();
    return true;
  }

  bool call(std::string_view key, BlockKind kind) {
    if (next_is("PGM")) return program_path(BlockKind::call_program);
    if (next_is("SELECTED")) {
      set_keyword(BlockKind::call_selected);
      words();
      return true;
    }
    return next_is("LBL") && label_block(key, kind);
  }

  bool select(std::string_view /*key*/, BlockKind kind) {
    return next_is("PGM") && program_path(kind);
  }

  // CALL PGM / SEL PGM: the path up to a comment, without its quotes.
  bool program_path(BlockKind kind) {
    set_keyword(kind);
    rest_as_sub_keyword();
    std::string_view path = b_.sub_keyword;
    if (path.size() >= 2 && path.front() == '"' && path.back() == '"')
      path = path.substr(1, path.size() - 2);
    b_.sub_keyword = path;
    return true;
  }

  bool cycle(std::string_view /*key*/, BlockKind kind) {
    if (next_is("DEF")) {
      set_keyword(kind);
      cycle_def();
      return true;
    }
    if (!next_is("CALL")) return false;
    set_keyword(BlockKind::cycle_call);
    if (next_is("POS")) b_.sub_keyword = "POS";
    words();
    return true;
  }

  // APPR LT, DEP LCT ...: the path's form as sub_keyword, then words.
  bool contour_link(std::string_view /*key*/, BlockKind kind) {
    set_keyword(kind);
    skip_blanks();
    b_.sub_keyword = read_letters();
    words();
    return true;
  }

  bool plane(std::string_view /*key*/, BlockKind kind) {
    set_keyword(kind);
    skip_blanks();
    b_.sub_keyword = read_letters();
    words();
    return true;
  }

  bool function(std::string_view /*key*/, BlockKind kind) {
    set_keyword(kind);
    rest_as_sub_keyword();
    return true;
  }

  // Q1 = <formula>: the target, then the formula in postfix order.
  bool formula(std::string_view /*key*/, BlockKind kind) {
    set_keyword(kind);
    seek(b_.keyword_begin);
    value_into(b_.fn.target, "the Q parameter set");
    expect('=', "'=' after the Q parameter");
    syntax::parse_formula(*this, b_.formula);
    if (peek() == ';') read_comment();
    return true;
  }

  bool fn(std::string_view /*key*/, BlockKind kind) {
    set_keyword(kind);
    fn_statement();
    return true;
  }

  // The rest of the block up to a comment, trimmed, as sub_keyword.
  void rest_as_sub_keyword() {
    skip_blanks();
    const std::size_t first = pos();
    while (!at_end() && peek() != ';') seek(pos() + 1);
    std::size_t last = pos();
    while (last > first && is_blank(text()[last - 1])) --last;
    b_.sub_keyword = text().substr(first, last - first);
    if (peek() == ';') read_comment();
  }

  void program_header() {
    skip_blanks();
    const std::size_t first = pos();
    while (!at_end() && !is_blank(peek()) && peek() != ';') {
      check_word_byte(pos());
      seek(pos() + 1);
    }
    b_.program_name = text().substr(first, pos() - first);
    skip_blanks();
    b_.units = read_letters();
    skip_blanks();
    if (peek() == ';') read_comment();
  }

  void tool() {
    skip_blanks();
    if (peek() == '"') {
      b_.tool_name = read_quoted();
    } else if (is_digit(peek()) || peek() == 'Q') {
      Word w;
      w.key = name("T");
      w.begin = static_cast<std::uint32_t>(pos());
      w.has_value = read_value(w.value, w.sign);
      w.end = static_cast<std::uint32_t>(pos());
      b_.words.push_back(w);
    }
    words();
    if (const Word* s = b_.find(name("S")))
      b_.s_span = ByteSpan{b_.offset + s->begin, b_.offset + s->end};
  }

  Label label() {
    Label l;
    l.begin = static_cast<std::uint32_t>(pos());
    if (peek() == '"') {
      l.name = read_quoted();
      return l;
    }
    double number = 0;
    if (!read_unsigned(number) || number != static_cast<double>(static_cast<long>(number)))
      fail(Code::E3303, pos(), "a label is a number or a \"name\"");
    l.number = static_cast<long>(number);
    return l;
  }

  void expect(char c, std::string_view what) {
    skip_blanks();
    if (peek() != c) fail(Code::E3308, pos(), std::string("expected ") + std::string(what));
    seek(pos() + 1);
    skip_blanks();
  }

  std::uint32_t value_into(std::optional<Value>& out, std::string_view what) {
    skip_blanks();
    const auto at = static_cast<std::uint32_t>(pos());
    Value v;
    char sign = 0;
    if (!read_value(v, sign))
      fail(Code::E3308, pos(), "expected " + std::string(what) + " (a number or Q parameter)");
    out = v;
    return at;
  }

  // FN n: Q.. = a [op b] | FN 9-12: IF a op b GOTO LBL target.
  void fn_statement() {
    skip_blanks();
    double number = 0;
    if (!read_unsigned(number)) fail(Code::E3308, pos(), "FN needs its number (FN 0: ...)");
    FnStatement& f = b_.fn;
    f.number = static_cast<int>(number);
    expect(':', "':' after FN " + std::to_string(f.number));
    if (f.number >= 9 && f.number <= 12) {
      if (read_letters() != "IF") fail(Code::E3308, pos(), "expected IF");
      f.a_begin = value_into(f.a, "the first operand");
      skip_blanks();
      read_letters();  // EQU, NE, GT, LT: the FN number says which
      f.b_begin = value_into(f.b, "the second operand");
      skip_blanks();
      if (read_letters() != "GOTO" || !next_is("LBL"))
        fail(Code::E3308, pos(), "expected GOTO LBL");
      skip_blanks();
      f.jump = label();
      return words();
    }
    if (f.number > 13) return rest_as_sub_keyword();  // FN 14 and on: the interpreter says
    value_into(f.target, "the Q parameter set");
    if (!f.target->is_parameter()) fail(Code::E3309, pos(), "FN sets a Q parameter (Q, QL or QR)");
    expect('=', "'='");
    if (f.number >= 5 && f.number <= 7) read_letters();  // SQRT, SIN, COS
    f.a_begin = value_into(f.a, "an operand");
    if (f.number != 0 && (f.number <= 4 || f.number == 8 || f.number == 13)) {
      skip_blanks();
      if (read_letters().empty()) {
        if (peek() != '+' && peek() != '-' && peek() != '*')
          fail(Code::E3308, pos(), "expected the operator of FN " + std::to_string(f.number));
        seek(pos() + 1);
      }
      f.b_begin = value_into(f.b, "the second operand");
    }
    words();
  }

  void cycle_def() {
    skip_blanks();
    double number = 0;
    if (!read_unsigned(number)) fail(Code::E3308, pos(), "CYCL DEF needs its number");
    // hyperMILL writes "CYCL DEF9 .0": the part after a blank.
    const std::size_t back = pos();
    skip_blanks();
    double part = 0;
    if (peek() == '.' && read_unsigned(part)) {
      number += part;
    } else {
      seek(back);
    }
    b_.cycle_number = number;
    const int major = static_cast<int>(number);
    if (major == 7 || major == 19 || major == 8 || major == 10 || major == 11 || major == 26)
      return words();
    if (major < 200) return rest_as_sub_keyword();  // 9.x, 32.x: read by the interpreter
    cycle_parameters();
  }

  // Q<n>=<value> assignments among the cycle's name words and comments.
  void cycle_parameters() {
    for (;;) {
      skip_blanks();
      if (at_end()) return;
      const char c = peek();
      if (c == ';') {
        read_comment();
        continue;
      }
      const std::size_t at = pos();
      if (c == 'Q' && at + 1 < text().size() && is_digit(text()[at + 1])) {
        seek(at + 1);
        double number = 0;
        read_unsigned(number);
        if (peek() == '=') {
          seek(pos() + 1);
          CycleParameter p;
          p.number = static_cast<int>(number);
          p.begin = static_cast<std::uint32_t>(at);
          char sign = 0;
          if (!read_value(p.value, sign))
            fail(Code::E3303, pos(), "Q" + std::to_string(p.number) + "= needs a value");
          b_.cycle_parameters.push_back(p);
          continue;
        }
      }
      // A word of the cycle's name ("DRILLING", "HSC-MODE:0"): skipped.
      while (!at_end() && !is_blank(peek()) && peek() != ';') {
        check_word_byte(pos());
        seek(pos() + 1);
      }
    }
  }

  // Words up to the end of the block: <name>[sign][value], comments.
  void words() {
    for (;;) {
      skip_blanks();
      if (at_end()) return;
      const char c = peek();
      if (c == ';') {
        read_comment();
        continue;
      }
      if (!is_upper(c)) {
        check_word_byte(pos());
        fail(Code::E3307, pos(), std::string("unexpected '") + c + "'");
      }
      word();
    }
  }

  void word() {
    Word w;
    w.begin = static_cast<std::uint32_t>(pos());
    std::string_view letters = read_letters();
    // FQ1, FQL2, FQR3: the feed of a parameter (its Q starts the value).
    if (is_digit(peek())) {
      const std::size_t bank = letters.ends_with("QL") || letters.ends_with("QR") ? 2
                               : letters.ends_with('Q')                           ? 1
                                                                                  : 0;
      if (bank != 0 && letters.size() > bank) {
        letters.remove_suffix(bank);
        seek(pos() - bank);
      }
    }
    if (letters.size() > 8)
      fail(Code::E3307, w.begin, "unknown word '" + std::string(letters) + "'");
    w.key = name(letters);
    w.has_value = read_value(w.value, w.sign);
    if (!w.has_value && w.sign == 0 && (w.key == name("F") || w.key == name("MB"))) {
      // "F MAX" as FMAX; "M140 MB MAX" keeps MB with MAX after it.
      const std::size_t back = pos();
      skip_blanks();
      if (read_letters() == "MAX") {
        if (w.key == name("F"))
          w.key = name("FMAX");
        else
          w.sign = '*';  // MB MAX
      } else {
        seek(back);
      }
    }
    w.end = static_cast<std::uint32_t>(pos());
    if (!at_end() && !is_blank(peek()) && peek() != ';' && !is_upper(peek())) {
      check_word_byte(pos());
      fail(Code::E3303, pos(), "'" + std::string(letters) + "' followed by '" + peek() + "'");
    }
    b_.words.push_back(w);
  }
};

}  // namespace

std::uint64_t split_block(std::string_view text, std::uint64_t offset, std::uint32_t line,
                          Block& out) {
  std::uint64_t pos = offset;
  std::uint32_t lines = 0;
  std::uint64_t end = offset;
  std::string_view eol;
  for (;;) {
    const auto* nl =
        static_cast<const char*>(std::memchr(text.data() + pos, '\n', text.size() - pos));
    const std::uint64_t line_end = nl ? static_cast<std::uint64_t>(nl - text.data()) : text.size();
    std::uint64_t text_end = line_end;
    if (text_end > pos && text[text_end - 1] == '\r') --text_end;
    ++lines;
    pos = nl ? line_end + 1 : text.size();
    end = text_end;
    eol = text.substr(text_end, pos - text_end);
    if (end - offset > kMaxBlockLength) {
      throw KlartextError(
          Diagnostic{Code::E3301,
                     line,
                     1,
                     "block longer than " + std::to_string(kMaxBlockLength) + " bytes",
                     {}});
    }
    // A line whose last byte (blanks aside) is '~' goes on in the next one.
    std::uint64_t last = text_end;
    while (last > offset && (text[last - 1] == ' ' || text[last - 1] == '\t')) --last;
    if (last == offset || text[last - 1] != '~' || pos >= text.size()) break;
  }
  out.text = text.substr(offset, end - offset);
  out.eol = eol;
  out.offset = offset;
  out.end = end;
  out.line = line;
  out.lines = lines;
  return pos;
}

void parse_block(Block& out) {
  out.clear();
  BlockParser(out).parse();
}

}  // namespace vcpost::heidenhain
