#include "postproc/gcode/block.h"

#include <cctype>
#include <string_view>

#include "postproc/gcode/block_parser.h"
#include "postproc/gcode/diagnostics.h"

namespace vcpost::gcode {

void Block::clear() {
  text = {};
  eol = {};
  line = 0;
  offset = 0;
  deleted = false;
  tape_marker = false;
  n.reset();
  words.clear();
  comments.clear();
  assignments.clear();
  message.reset();
  control.kind = ControlKind::none;
  control.name.clear();
  control.column = 0;
  control.condition.reset();
  control.arguments.clear();
  siemens_cycle.kind = SiemensCycle::Kind::none;
  siemens_cycle.args.clear();
  noted_keywords.clear();
}

const Word* Block::find(char letter) const {
  for (const auto& w : words)
    if (w.letter == letter) return &w;
  return nullptr;
}

namespace syntax {
namespace {

// Words a line may hold, by letter (E: the output of LinuxCNC's M66-M68,
// checked with them; on Fanuc-like controls the thread lead, taken and
// ignored for milling).
bool is_word_letter(char c) {
  switch (c) {
    case 'A':
    case 'B':
    case 'C':
    case 'D':
    case 'F':
    case 'G':
    case 'H':
    case 'I':
    case 'J':
    case 'K':
    case 'L':
    case 'M':
    case 'P':
    case 'Q':
    case 'R':
    case 'S':
    case 'T':
    case 'U':
    case 'V':
    case 'W':
    case 'X':
    case 'Y':
    case 'Z':
    case 'E':
      return true;
    default:
      return false;
  }
}

}  // namespace

void BlockParser::read(Block& out) {
  skip_blanks();
  if (at_end()) return;
  if (s_[i_] == '%') {
    // RS274NGC: '%' stands alone on its line ("% G1 X5" and "% (note)"
    // are refused by rs274: "Bad character '%' used"). Other controls
    // write a name after it (Sinumerik %_N_PART_MPF).
    if (d_.kind == machines::Dialect::rs274ngc) {
      ++i_;
      skip_blanks();
      if (!at_end())
        fail(Code::E1001, i_,
             "'%' must stand alone on its line (the program's first and last), as rs274 "
             "requires; text after it would not be read");
    }
    out.tape_marker = true;
    return;
  }
  if (s_[i_] == '/') {
    if (d_.block_delete) {
      out.deleted = true;
      return;
    }
    ++i_;
  }
  read_items(out);
}

Control BlockParser::peek() {
  Control c;
  skip_blanks();
  if (!at_end() && s_[i_] == '/') ++i_;
  skip_blanks();
  if (!at_end() && upper(s_[i_]) == 'N') {
    ++i_;
    while (!at_end() && (is_digit(s_[i_]) || is_blank(s_[i_]))) ++i_;
  }
  if (at_end()) return c;
  const std::size_t start = i_;
  if (upper(s_[i_]) == 'O') {
    ++i_;
    if (d_.o_word_control) {
      if (!read_o_name(c.name, /*throwing=*/false)) return Control{};
      skip_blanks();
      const std::string key = read_letters();
      c.kind = o_keyword(key);
      // "O2000" alone: a program number (M98's target), as read_o_word says.
      if (key.empty() && c.name.find_first_not_of("0123456789") == std::string::npos)
        c.kind = ControlKind::program_number;
    } else {
      c.name = read_digits_text();
      c.kind = c.name.empty() ? ControlKind::none : ControlKind::program_number;
    }
    c.column = static_cast<std::uint32_t>(start + 1);
    return c;
  }
  if (d_.fanuc_macros && is_alpha(s_[i_])) {
    const std::string key = read_letters();
    if (key == "ELSE") c.kind = ControlKind::else_;
    if (key == "ENDIF") c.kind = ControlKind::endif;
    if (key == "IF") {
      // A multi-line IF ends its line with THEN (comments aside).
      std::string_view rest = s_.substr(i_);
      const auto then = find_keyword_outside_comments(rest, "THEN");
      if (then != std::string_view::npos && only_comments(rest.substr(then + 4)))
        c.kind = ControlKind::if_;
    }
  }
  return c;
}

ControlKind BlockParser::o_keyword(std::string_view key) {
  if (key == "SUB") return ControlKind::sub;
  if (key == "ENDSUB") return ControlKind::endsub;
  if (key == "CALL") return ControlKind::call;
  if (key == "RETURN") return ControlKind::return_;
  if (key == "IF") return ControlKind::if_;
  if (key == "ELSEIF") return ControlKind::elseif;
  if (key == "ELSE") return ControlKind::else_;
  if (key == "ENDIF") return ControlKind::endif;
  if (key == "WHILE") return ControlKind::while_;
  if (key == "ENDWHILE") return ControlKind::endwhile;
  if (key == "DO") return ControlKind::do_;
  if (key == "BREAK") return ControlKind::break_;
  if (key == "CONTINUE") return ControlKind::continue_;
  if (key == "REPEAT") return ControlKind::repeat;
  if (key == "ENDREPEAT") return ControlKind::endrepeat;
  return ControlKind::none;
}

// O-word name after 'O': digits, or <name> (normalised). false if none.
bool BlockParser::read_o_name(std::string& name, bool throwing) {
  skip_blanks();
  if (!at_end() && s_[i_] == '<') {
    const std::size_t open = i_;
    if (!read_angle_name(name)) {
      if (throwing) fail(Code::E1201, open, "O-word name not closed with '>'");
      return false;
    }
    return !name.empty();
  }
  while (!at_end() && (is_digit(s_[i_]) || is_blank(s_[i_]))) {
    if (is_digit(s_[i_])) name += s_[i_];
    ++i_;
  }
  // Leading zeros do not make another O number.
  const auto nz = name.find_first_not_of('0');
  if (!name.empty()) name = nz == std::string::npos ? "0" : name.substr(nz);
  if (name.empty() && throwing) fail(Code::E1003, i_, "O word without a number or <name>");
  return !name.empty();
}

void BlockParser::read_comment(Block& out) {
  const std::size_t open = i_;
  const std::string_view text = read_comment_text();
  out.comments.push_back(Comment{text, static_cast<std::uint32_t>(open + 1)});
  // (MSG,text): an operator message, as LinuxCNC (case-insensitive MSG).
  std::size_t k = 0;
  while (k < text.size() && is_blank(text[k])) ++k;
  if (text.size() >= k + 4 && upper(text[k]) == 'M' && upper(text[k + 1]) == 'S' &&
      upper(text[k + 2]) == 'G' && text[k + 3] == ',')
    out.message = std::string(text.substr(k + 4));
}

void BlockParser::read_items(Block& out) {
  while (true) {
    skip_blanks();
    if (at_end()) return;
    const char c = s_[i_];
    if (c == '(') {
      read_comment(out);
    } else if (c == ';') {
      for (std::size_t k = i_ + 1; k < s_.size(); ++k) check_byte(k);
      out.comments.push_back(Comment{s_.substr(i_ + 1), static_cast<std::uint32_t>(i_ + 1)});
      i_ = s_.size();
      return;
    } else if (c == '#') {
      read_assignment(out);
    } else if (is_alpha(c)) {
      const char letter = upper(c);
      if (!siemens() && i_ + 1 < s_.size() && is_alpha(s_[i_ + 1]) && looks_siemens())
        fail(Code::E1010, i_,
             "this is Sinumerik 840D syntax (MSG, MCALL, CYCLE.., CR=): read the program with "
             "--dialect sinumerik or --machine sinumerik-840d");
      if (siemens() && i_ + 1 < s_.size() && (is_alpha(s_[i_ + 1]) || s_[i_ + 1] == '_')) {
        read_siemens_keyword(out);
      } else if (siemens() && letter == 'R' && r_assignment_follows()) {
        read_r_assignment(out);
      } else if (d_.fanuc_macros && i_ + 1 < s_.size() && is_alpha(s_[i_ + 1])) {
        if (!read_macro_statement(out)) return;
      } else if (letter == 'O') {
        read_o_word(out);
      } else if (letter == 'N') {
        read_sequence_number(out);
      } else {
        read_word(out, letter);
      }
    } else {
      check_byte(i_);
      if (static_cast<unsigned char>(c) >= 0x80)
        fail(Code::E1001, i_, "non-ASCII byte outside a comment");
      fail(Code::E1001, i_, std::string("unexpected character '") + c + "'");
    }
  }
}

void BlockParser::read_sequence_number(Block& out) {
  const std::size_t start = i_;
  ++i_;
  skip_blanks();
  long n = 0;
  bool any = false;
  while (!at_end() && (is_digit(s_[i_]) || is_blank(s_[i_]))) {
    if (is_digit(s_[i_])) {
      if (n < 100000000) n = n * 10 + (s_[i_] - '0');
      any = true;
    }
    ++i_;
  }
  // LinuxCNC accepts N1.5 style subnumbers; skip them.
  if (!at_end() && s_[i_] == '.')
    while (++i_ < s_.size() && is_digit(s_[i_])) {
    }
  if (!any) fail(Code::E1003, start, "N without a sequence number");
  out.n = n;
}

void BlockParser::read_word(Block& out, char letter) {
  const std::size_t start = i_;
  if (!is_word_letter(letter))
    fail(Code::E1007, start, std::string("unknown word '") + letter + "'");
  ++i_;
  skip_blanks();
  Word w;
  w.letter = letter;
  w.column = static_cast<std::uint32_t>(start + 1);
  w.begin = static_cast<std::uint32_t>(start);
  if (at_end()) fail(Code::E1003, start, std::string(1, letter) + " word without a value");
  if (siemens() && s_[i_] == '=') {
    ++i_;
    skip_blanks();
    if (letter == 'T' && !at_end() && s_[i_] == '"') {
      // T="name": a tool by name; no number to select.
      while (++i_ < s_.size() && s_[i_] != '"') {
      }
      if (at_end()) fail(Code::E1201, start, "tool name not closed with '\"'");
      ++i_;
      return;
    }
    ac_seen_ = false;
    w.value = binary(0, start).number;
    w.absolute = ac_seen_;
    w.computed = true;
    w.decimal_point = true;
    w.end = static_cast<std::uint32_t>(i_);
    while (w.end > w.begin && is_blank(s_[w.end - 1])) --w.end;
    push_word(out, w);
    return;
  }
  const char c = s_[i_];
  if (is_digit(c) || c == '.' || ((c == '-' || c == '+') && literal_follows(i_ + 1))) {
    bool negative = false;
    if (c == '-' || c == '+') {
      negative = c == '-';
      ++i_;
      skip_blanks();
    }
    const double v = read_number(w.decimal_point, start, letter);
    w.value = negative ? -v : v;
  } else {
    w.value = unary(start).number;
    w.computed = true;
  }
  w.end = static_cast<std::uint32_t>(i_);
  // Trailing blanks belong to no word.
  while (w.end > w.begin && is_blank(s_[w.end - 1])) --w.end;
  push_word(out, w);
}

void BlockParser::read_assignment(Block& out) {
  const std::size_t hash = i_;
  Ref ref = parameter_ref();
  skip_blanks();
  if (at_end() || s_[i_] != '=')
    fail(Code::E1201, hash, "a parameter outside a word must be set with '='");
  ++i_;
  // Fanuc macros allow "#1 = #2 + 3" without brackets; RS274NGC takes one value.
  const Value v = d_.fanuc_macros ? binary(0, hash) : unary(hash);
  out.assignments.push_back(
      Assignment{ref.number, std::move(ref.name), v.number, static_cast<std::uint32_t>(hash + 1)});
}

void BlockParser::read_o_word(Block& out) {
  const std::size_t start = i_;
  ++i_;
  Control& c = out.control;
  c.column = static_cast<std::uint32_t>(start + 1);
  if (!d_.o_word_control) {
    skip_blanks();
    c.name = read_digits_text();
    if (c.name.empty()) fail(Code::E1003, start, "O without a program number");
    c.kind = ControlKind::program_number;
    return;
  }
  read_o_name(c.name, true);
  skip_blanks();
  const std::size_t key_at = i_;
  const std::string key = read_letters();
  c.kind = o_keyword(key);
  // "O0001" alone: a program number, as rs274 reads it.
  if (c.kind == ControlKind::none && key.empty() && !c.name.empty() &&
      c.name.find_first_not_of("0123456789") == std::string::npos)
    c.kind = ControlKind::program_number;
  if (c.kind == ControlKind::none)
    fail(Code::E1007, key_at, "unknown O-word keyword '" + key + "'");
  switch (c.kind) {
    case ControlKind::if_:
    case ControlKind::elseif:
    case ControlKind::while_:
    case ControlKind::repeat: {
      skip_blanks();
      if (at_end() || s_[i_] != '[') fail(Code::E1201, key_at, key + " needs a condition in [ ]");
      c.condition = bracket().number;
      break;
    }
    case ControlKind::call:
    case ControlKind::return_:
    case ControlKind::endsub: {
      skip_blanks();
      while (!at_end() && s_[i_] == '[') {
        c.arguments.push_back(bracket().number);
        skip_blanks();
      }
      break;
    }
    default:
      break;
  }
  // Nothing but comments may follow an O-word.
  while (true) {
    skip_blanks();
    if (at_end()) return;
    if (s_[i_] == '(') {
      read_comment(out);
    } else if (s_[i_] == ';') {
      i_ = s_.size();
    } else {
      fail(Code::E1001, i_, "only comments may follow an O-word");
    }
  }
}

// Fanuc/Mazak macro statements: IF [..] THEN/GOTO, ELSE, ENDIF, GOTO n,
// WHILE [..] DOm, ENDm. Returns false when the rest of the line is skipped.
bool BlockParser::read_macro_statement(Block& out) {
  const std::size_t start = i_;
  const std::string key = read_letters();
  Control& c = out.control;
  c.column = static_cast<std::uint32_t>(start + 1);
  if (key == "IF") {
    skip_blanks();
    if (at_end() || s_[i_] != '[') fail(Code::E1201, start, "IF needs a condition in [ ]");
    const bool taken = bracket().number != 0.0;
    skip_blanks();
    const std::size_t key_at = i_;
    const std::string then = read_letters();
    if (then == "GOTO") {
      c.kind = ControlKind::fanuc_goto;
      c.condition = taken ? 1.0 : 0.0;
      c.name = "GOTO";
      return false;
    }
    if (then != "THEN") fail(Code::E1201, key_at, "IF [..] must be followed by THEN or GOTO");
    skip_blanks();
    if (at_end() || s_[i_] == '(' || s_[i_] == ';') {
      c.kind = ControlKind::if_;
      c.condition = taken ? 1.0 : 0.0;
      read_items(out);
      return false;
    }
    if (!taken) {
      i_ = s_.size();
      return false;
    }
    return true;  // the statement after THEN is read as the rest of the block
  }
  if (key == "ELSE") {
    c.kind = ControlKind::else_;
    return true;
  }
  if (key == "ENDIF") {
    c.kind = ControlKind::endif;
    return true;
  }
  if (key == "GOTO" || key == "WHILE" || (key.rfind("END", 0) == 0 && key.size() == 3) ||
      key == "DO") {
    c.kind = ControlKind::fanuc_goto;
    c.condition = 1.0;
    c.name = key;
    i_ = s_.size();
    return false;
  }
  i_ = start;
  if (upper(s_[i_]) == 'O') {
    read_o_word(out);
    return true;
  }
  if (upper(s_[i_]) == 'N') {
    read_sequence_number(out);
    return true;
  }
  read_word(out, upper(s_[i_]));
  return true;
}

}  // namespace syntax

void read_block(std::string_view line, std::uint32_t line_number, std::uint64_t offset,
                const Dialect& dialect, const Parameters& parameters, Block& out) {
  out.clear();
  out.text = line;
  out.line = line_number;
  out.offset = offset;
  if (line.size() > kMaxLineLength)
    throw GcodeError(Diagnostic{
        Code::E1006, line_number, 1,
        "line longer than " + std::to_string(kMaxLineLength) + " bytes, the reader's limit"});
  syntax::BlockParser reader(line, line_number, dialect, &parameters);
  reader.read(out);
}

Control peek_control(std::string_view line, const Dialect& dialect) {
  if (line.size() > kMaxLineLength) return {};
  syntax::BlockParser reader(line, 0, dialect, nullptr);
  return reader.peek();
}

}  // namespace vcpost::gcode
