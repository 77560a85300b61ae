#include "postproc/gcode/block.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <optional>

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

namespace {

constexpr bool is_blank(char c) { return c == ' ' || c == '\t'; }
constexpr bool is_digit(char c) { return c >= '0' && c <= '9'; }
constexpr bool is_alpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
constexpr char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c; }

// Exact powers of ten (10^22 is the largest exact double).
constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                             1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// Words a line may hold, by letter (E only in Fanuc-like dialects: thread
// lead, taken and ignored for milling).
bool is_word_letter(char c, const Dialect& d) {
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
      return true;
    case 'E':
      return d.kind != DialectKind::rs274ngc;
    default:
      return false;
  }
}

class LineReader {
 public:
  LineReader(std::string_view s, std::uint32_t line, const Dialect& d, const Parameters* p)
      : s_(s), line_(line), d_(d), p_(p) {}

  [[noreturn]] void fail(Code code, std::size_t at, std::string message) const {
    throw GcodeError(Diagnostic{code, Severity::error, line_, static_cast<std::uint32_t>(at + 1),
                                std::move(message)});
  }

  void read(Block& out) {
    skip_blanks();
    if (at_end()) return;
    if (s_[i_] == '%') {
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

  Control peek() {
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
        c.kind = o_keyword(read_letters());
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

 private:
  std::string_view s_;
  std::size_t i_ = 0;
  std::uint32_t line_;
  const Dialect& d_;
  const Parameters* p_;   // null when only peeking (nothing is evaluated)
  bool ac_seen_ = false;  // AC(..) read in the current word's expression

  bool at_end() const { return i_ >= s_.size(); }
  bool siemens() const { return d_.kind == DialectKind::sinumerik; }

  // A Sinumerik statement at i_: MSG( MCALL CYCLE8x( CR=.
  bool looks_siemens() const {
    std::string key;
    for (std::size_t k = i_;
         k < s_.size() && key.size() < 8 && (is_alpha(s_[k]) || is_digit(s_[k])); ++k)
      key += upper(s_[k]);
    std::size_t k = i_ + key.size();
    while (k < s_.size() && is_blank(s_[k])) ++k;
    const char next = k < s_.size() ? s_[k] : '\0';
    return (key == "MSG" && next == '(') || key == "MCALL" ||
           (key.rfind("CYCLE", 0) == 0 && next == '(') || (key == "CR" && next == '=');
  }

  // ---- Sinumerik 840D statements ---------------------------------------

  // "R12 = ..." at i_ (an R parameter assignment, not an R word).
  bool r_assignment_follows() const {
    std::size_t k = i_ + 1;
    if (k >= s_.size() || !is_digit(s_[k])) return false;
    while (k < s_.size() && is_digit(s_[k])) ++k;
    while (k < s_.size() && is_blank(s_[k])) ++k;
    return k < s_.size() && s_[k] == '=';
  }

  void read_r_assignment(Block& out) {
    const std::size_t start = i_;
    ++i_;
    int number = 0;
    while (!at_end() && is_digit(s_[i_]) && number < 100000)
      number = number * 10 + (s_[i_++] - '0');
    skip_blanks();
    ++i_;  // '='
    const Value v = binary(0, start);
    out.assignments.push_back(Assignment{0, "_r" + std::to_string(number), v.number,
                                         static_cast<std::uint32_t>(start + 1)});
  }

  // A quoted string after '(' (MSG("...")): its text; i_ after the ')'.
  std::string read_quoted_call(std::size_t start, const std::string& key) {
    skip_blanks();
    if (at_end() || s_[i_] != '(') fail(Code::bad_expression, start, key + " needs (\"text\")");
    ++i_;
    skip_blanks();
    std::string text;
    if (!at_end() && s_[i_] == '"') {
      ++i_;
      while (!at_end() && s_[i_] != '"') text += s_[i_++];
      if (at_end()) fail(Code::bad_expression, start, "string not closed with '\"'");
      ++i_;
    }
    skip_blanks();
    if (at_end() || s_[i_] != ')') fail(Code::bad_expression, start, key + "( not closed with ')'");
    ++i_;
    return text;
  }

  // Arguments "(a, , c)" of a cycle call; empty ones are nullopt.
  std::vector<std::optional<double>> read_call_arguments(std::size_t start,
                                                         const std::string& key) {
    std::vector<std::optional<double>> args;
    skip_blanks();
    if (at_end() || s_[i_] != '(')
      fail(Code::bad_expression, start, key + " needs its arguments in ( )");
    ++i_;
    while (true) {
      skip_blanks();
      if (at_end()) fail(Code::bad_expression, start, key + "( not closed with ')'");
      if (s_[i_] == ')') {
        if (!args.empty()) args.emplace_back();  // "a,)" : a trailing empty argument
        ++i_;
        break;
      }
      if (s_[i_] == ',') {
        args.emplace_back();
        ++i_;
        continue;
      }
      args.emplace_back(bounded(binary(0, start).number, start, key + " argument"));
      skip_blanks();
      if (!at_end() && s_[i_] == ',') {
        ++i_;
        skip_blanks();
        if (!at_end() && s_[i_] == ')') {
          args.emplace_back();
          ++i_;
          break;
        }
        continue;
      }
      if (!at_end() && s_[i_] == ')') {
        ++i_;
        break;
      }
      fail(Code::bad_expression, i_, "',' or ')' expected in the arguments of " + key);
    }
    return args;
  }

  void skip_parenthesised() {
    skip_blanks();
    if (at_end() || s_[i_] != '(') return;
    int depth = 0;
    for (; !at_end(); ++i_) {
      if (s_[i_] == '"') {
        while (++i_ < s_.size() && s_[i_] != '"') {
        }
        continue;
      }
      if (s_[i_] == '(') ++depth;
      if (s_[i_] == ')' && --depth == 0) {
        ++i_;
        return;
      }
    }
    fail(Code::bad_expression, i_ == 0 ? 0 : i_ - 1, "'(' not closed with ')'");
  }

  void read_siemens_keyword(Block& out) {
    const std::size_t start = i_;
    std::string key;
    while (!at_end() && (is_alpha(s_[i_]) || is_digit(s_[i_]) || s_[i_] == '_'))
      key += upper(s_[i_++]);
    const auto column = static_cast<std::uint32_t>(start + 1);
    if (key == "MSG") {
      out.message = read_quoted_call(start, key);
      return;
    }
    if (key == "CR") {
      // CR=<radius>: the arc radius (the R word of the other dialects).
      skip_blanks();
      if (at_end() || s_[i_] != '=') fail(Code::bad_expression, start, "CR needs '=' and a radius");
      ++i_;
      Word w;
      w.letter = 'R';
      w.column = column;
      w.begin = static_cast<std::uint32_t>(start);
      w.value = binary(0, start).number;
      w.decimal_point = true;
      w.computed = true;
      w.end = static_cast<std::uint32_t>(i_);
      push_word(out, w);
      return;
    }
    if (key == "TURN") {
      // TURN=n: n full turns more than the helix's end point says; the P
      // (turns) word of RS274NGC arcs, which counts them all.
      skip_blanks();
      if (at_end() || s_[i_] != '=')
        fail(Code::bad_expression, start, "TURN needs '=' and a count");
      ++i_;
      Word w;
      w.letter = 'P';
      w.column = column;
      w.begin = static_cast<std::uint32_t>(start);
      w.value = binary(0, start).number + 1.0;
      w.decimal_point = true;
      w.computed = true;
      w.end = static_cast<std::uint32_t>(i_);
      push_word(out, w);
      return;
    }
    SiemensCycle& cycle = out.siemens_cycle;
    if (key == "MCALL") {
      skip_blanks();
      cycle.kind = SiemensCycle::Kind::modal_off;
      cycle.column = column;
      if (!at_end() && is_alpha(s_[i_])) {
        const std::size_t at = i_;
        std::string name;
        while (!at_end() && (is_alpha(s_[i_]) || is_digit(s_[i_]))) name += upper(s_[i_++]);
        if (!read_cycle(name, at, cycle))
          fail(Code::unsupported_code, at,
               "MCALL " + name + ": vcpost follows MCALL of CYCLE81-CYCLE89 only");
        cycle.kind = SiemensCycle::Kind::modal_call;
      }
      return;
    }
    if (read_cycle(key, start, cycle)) {
      cycle.kind = SiemensCycle::Kind::call;
      return;
    }
    // Modes that leave the path as written: passed through, named once.
    static constexpr std::string_view kNoted[] = {
        "SOFT",     "BRISK",     "FFWON",  "FFWOF",   "CFC",     "CFTCP",   "CFIN",    "COMPON",
        "COMPCURV", "COMPCAD",   "COMPOF", "DIAMOF",  "TRAFOOF", "UPATH",   "SPATH",   "STOPRE",
        "CYCLE832", "WORKPIECE", "FGROUP", "G_GROUP", "ORIWKS",  "ORIAXES", "ORIVECT", "TOFFON",
        "TOFFOF",   "FNORM",     "FLIN",   "FCUB",    "PTP",     "CP",      "SUPA"};
    for (const auto noted : kNoted) {
      if (key == noted) {
        if (key == "SUPA")
          fail(Code::unsupported_code, start,
               "SUPA (machine coordinates without any frame) is not followed; use G53");
        skip_parenthesised();
        out.noted_keywords.emplace_back(key, column);
        return;
      }
    }
    static constexpr std::string_view kFrames[] = {"TRANS",    "ATRANS", "ROT",    "AROT",
                                                   "SCALE",    "ASCALE", "MIRROR", "AMIRROR",
                                                   "CYCLE800", "TRAORI", "ROTS",   "AROTS"};
    for (const auto frame : kFrames)
      if (key == frame)
        fail(Code::unsupported_code, start,
             key +
                 " moves, rotates, scales or mirrors the coordinate frame; vcpost does not follow "
                 "frames: remove it or post without it");
    static constexpr std::string_view kFlow[] = {"GOTOF",   "GOTOB", "GOTO",     "GOTOC",  "LOOP",
                                                 "ENDLOOP", "WHILE", "ENDWHILE", "FOR",    "ENDFOR",
                                                 "IF",      "ELSE",  "ENDIF",    "REPEAT", "UNTIL",
                                                 "CALL",    "PCALL", "RET",      "DEF",    "PROC"};
    for (const auto flow : kFlow)
      if (key == flow)
        fail(Code::unsupported_flow, start,
             key +
                 ": Sinumerik program flow and subprograms are not followed by vcpost; expand them "
                 "in CAM");
    fail(Code::unknown_word, start, "unknown Sinumerik word or statement '" + key + "'");
  }

  bool read_cycle(const std::string& name, std::size_t start, SiemensCycle& cycle) {
    static constexpr std::string_view kCycles[] = {"CYCLE81", "CYCLE82", "CYCLE83", "CYCLE84",
                                                   "CYCLE85", "CYCLE86", "CYCLE89"};
    for (const auto c : kCycles) {
      if (name == c) {
        cycle.number = (name[5] - '0') * 10 + (name[6] - '0');
        cycle.column = static_cast<std::uint32_t>(start + 1);
        cycle.args = read_call_arguments(start, name);
        return true;
      }
    }
    return false;
  }

  void skip_blanks() {
    while (i_ < s_.size() && is_blank(s_[i_])) ++i_;
  }

  static std::size_t find_keyword_outside_comments(std::string_view rest, std::string_view key) {
    bool in_comment = false;
    for (std::size_t k = 0; k < rest.size(); ++k) {
      const char c = rest[k];
      if (in_comment) {
        in_comment = c != ')';
        continue;
      }
      if (c == '(') {
        in_comment = true;
        continue;
      }
      if (c == ';') return std::string_view::npos;
      if (k + key.size() <= rest.size()) {
        bool match = true;
        for (std::size_t m = 0; m < key.size() && match; ++m) match = upper(rest[k + m]) == key[m];
        if (match) return k;
      }
    }
    return std::string_view::npos;
  }

  static bool only_comments(std::string_view rest) {
    bool in_comment = false;
    for (char c : rest) {
      if (in_comment) {
        in_comment = c != ')';
      } else if (c == '(') {
        in_comment = true;
      } else if (c == ';') {
        return true;
      } else if (!is_blank(c)) {
        return false;
      }
    }
    return true;
  }

  std::string read_letters() {
    std::string key;
    while (!at_end() && is_alpha(s_[i_])) key += upper(s_[i_++]);
    return key;
  }

  std::string read_digits_text() {
    std::string text;
    while (!at_end() && is_digit(s_[i_])) text += s_[i_++];
    return text;
  }

  static ControlKind o_keyword(std::string_view key) {
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
  bool read_o_name(std::string& name, bool throwing) {
    skip_blanks();
    if (!at_end() && s_[i_] == '<') {
      const std::size_t open = i_;
      ++i_;
      while (!at_end() && s_[i_] != '>' && s_[i_] != '(') {  // '(': as in read_name
        if (!is_blank(s_[i_]))
          name += static_cast<char>(std::tolower(static_cast<unsigned char>(s_[i_])));
        ++i_;
      }
      if (at_end() || s_[i_] == '(') {
        if (throwing) fail(Code::bad_expression, open, "O-word name not closed with '>'");
        return false;
      }
      ++i_;
      return !name.empty();
    }
    while (!at_end() && (is_digit(s_[i_]) || is_blank(s_[i_]))) {
      if (is_digit(s_[i_])) name += s_[i_];
      ++i_;
    }
    // Leading zeros do not make another O number.
    const auto nz = name.find_first_not_of('0');
    if (!name.empty()) name = nz == std::string::npos ? "0" : name.substr(nz);
    if (name.empty() && throwing) fail(Code::bad_number, i_, "O word without a number or <name>");
    return !name.empty();
  }

  void check_byte(std::size_t at) const {
    const auto c = static_cast<unsigned char>(s_[at]);
    if (c == 0) fail(Code::nul_byte, at, "NUL byte in the program text");
    if (c < 0x20 && c != '\t' && c != '\r' && c != '\f')
      fail(Code::nul_byte, at, "control byte 0x" + hex(c) + " in the program text");
  }

  static std::string hex(unsigned c) {
    const char* digits = "0123456789ABCDEF";
    return {digits[(c >> 4) & 15], digits[c & 15]};
  }

  void read_comment(Block& out) {
    const std::size_t open = i_;
    ++i_;
    const std::size_t begin = i_;
    while (!at_end() && s_[i_] != ')') {
      if (s_[i_] == '(') fail(Code::nested_comment, i_, "'(' inside a comment");
      check_byte(i_);
      ++i_;
    }
    if (at_end()) fail(Code::unclosed_comment, open, "comment opened here is not closed");
    const std::string_view text = s_.substr(begin, i_ - begin);
    ++i_;
    out.comments.push_back(Comment{text, static_cast<std::uint32_t>(open + 1)});
    // (MSG,text): an operator message, as LinuxCNC (case-insensitive MSG).
    std::size_t k = 0;
    while (k < text.size() && is_blank(text[k])) ++k;
    if (text.size() >= k + 4 && upper(text[k]) == 'M' && upper(text[k + 1]) == 'S' &&
        upper(text[k + 2]) == 'G' && text[k + 3] == ',')
      out.message = std::string(text.substr(k + 4));
  }

  void read_items(Block& out) {
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
          fail(Code::dialect_mismatch, i_,
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
          fail(Code::bad_character, i_, "non-ASCII byte outside a comment");
        fail(Code::bad_character, i_, std::string("unexpected character '") + c + "'");
      }
    }
  }

  void read_sequence_number(Block& out) {
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
    if (!any) fail(Code::bad_number, start, "N without a sequence number");
    out.n = n;
  }

  void read_word(Block& out, char letter) {
    const std::size_t start = i_;
    if (!is_word_letter(letter, d_))
      fail(Code::unknown_word, start, std::string("unknown word '") + letter + "'");
    ++i_;
    skip_blanks();
    Word w;
    w.letter = letter;
    w.column = static_cast<std::uint32_t>(start + 1);
    w.begin = static_cast<std::uint32_t>(start);
    if (at_end()) fail(Code::bad_number, start, std::string(1, letter) + " word without a value");
    if (siemens() && s_[i_] == '=') {
      ++i_;
      skip_blanks();
      if (letter == 'T' && !at_end() && s_[i_] == '"') {
        // T="name": a tool by name; no number to select.
        while (++i_ < s_.size() && s_[i_] != '"') {
        }
        if (at_end()) fail(Code::bad_expression, start, "tool name not closed with '\"'");
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

  bool literal_follows(std::size_t k) const {
    while (k < s_.size() && is_blank(s_[k])) ++k;
    return k < s_.size() && (is_digit(s_[k]) || s_[k] == '.');
  }

  // A decimal literal without sign; blanks between digits are skipped
  // (Fanuc and LinuxCNC ignore them).
  double read_number(bool& decimal_point, std::size_t word_start, char letter) {
    if (const auto v = read_plain_number(decimal_point)) return *v;
    return read_general_number(decimal_point, word_start, letter);
  }

  // The common case, on the hot path: digits, an optional point, digits,
  // no blanks, at most 19 digits, exactly representable (mantissa below
  // 2^53, so mantissa / 10^k is correctly rounded). nullopt (and i_
  // unchanged) for anything else.
  std::optional<double> read_plain_number(bool& decimal_point) {
    const std::size_t n = s_.size();
    std::size_t k = i_;
    std::uint64_t mantissa = 0;
    auto digits = [&] {
      const std::size_t first = k;
      for (unsigned d; k < n && (d = static_cast<unsigned char>(s_[k]) - unsigned{'0'}) < 10; ++k)
        mantissa = mantissa * 10 + d;
      return k - first;
    };
    const std::size_t whole = digits();
    std::size_t fraction = 0;
    const bool point = k < n && s_[k] == '.';
    if (point) {
      ++k;
      fraction = digits();
    }
    constexpr std::uint64_t kExact = std::uint64_t{1} << 53;
    if (whole + fraction == 0 || whole + fraction > 19 || fraction > 22 || mantissa > kExact ||
        (k < n && (s_[k] == '.' || (is_blank(s_[k]) && literal_follows(k)))))
      return std::nullopt;  // no digits, long, or a blank or second point: the general path
    i_ = k;
    decimal_point = point;
    return static_cast<double>(mantissa) / kPow10[fraction];
  }

  double read_general_number(bool& decimal_point, std::size_t word_start, char letter) {
    std::uint64_t mantissa = 0;
    int digits = 0;
    int fraction = 0;
    bool point = false;
    bool any = false;
    char compact[80];
    std::size_t compact_length = 0;
    while (!at_end()) {
      const char c = s_[i_];
      if (is_digit(c)) {
        any = true;
        if (mantissa != 0 || c != '0') ++digits;
        mantissa = mantissa * 10 + static_cast<std::uint64_t>(c - '0');
        if (point) ++fraction;
      } else if (c == '.') {
        if (point) fail(Code::bad_number, i_, "second decimal point in a number");
        point = true;
      } else if (is_blank(c) && literal_follows(i_)) {
        ++i_;
        continue;
      } else {
        break;
      }
      if (compact_length < sizeof compact) compact[compact_length++] = c;
      ++i_;
    }
    if (!any) fail(Code::bad_number, word_start, std::string(1, letter) + " word without a number");
    decimal_point = point;
    if (digits <= 15 && fraction <= 22) return static_cast<double>(mantissa) / kPow10[fraction];
    if (compact_length >= sizeof compact) fail(Code::bad_number, word_start, "number too long");
    double v = 0.0;
    const auto r = std::from_chars(compact, compact + compact_length, v);
    if (r.ec != std::errc()) fail(Code::bad_number, word_start, "number out of range");
    return v;
  }

  // ---- expressions -------------------------------------------------------

  Value unary(std::size_t word_start) {
    skip_blanks();
    if (at_end()) fail(Code::bad_expression, word_start, "value missing at end of line");
    const char c = s_[i_];
    if (c == '-' || c == '+') {
      ++i_;
      Value v = unary(word_start);
      if (c == '-') v.number = -v.number;
      return v;
    }
    if (c == '[') {
      if (!d_.numbered_parameters && !d_.named_parameters)
        fail(Code::parameters_not_in_dialect, i_, "expressions are not part of this dialect");
      return bracket();
    }
    if (c == '#') return parameter_value();
    if (is_digit(c) || c == '.') {
      bool point = false;
      return Value{read_number(point, i_, '#'), false};
    }
    if (siemens() && c == '(') return paren();
    if (siemens() && upper(c) == 'R' && i_ + 1 < s_.size() && is_digit(s_[i_ + 1])) {
      // R parameter: 0 until set, as on the control.
      ++i_;
      int number = 0;
      while (!at_end() && is_digit(s_[i_]) && number < 100000)
        number = number * 10 + (s_[i_++] - '0');
      const Access a = p_->read("_r" + std::to_string(number));
      return Value{a.ok ? a.value.number : 0.0, false};
    }
    if (is_alpha(c)) return function();
    fail(Code::bad_expression, i_, std::string("unexpected '") + c + "' where a value is expected");
  }

  // Sinumerik: ( expression ).
  Value paren() {
    const std::size_t open = i_;
    ++i_;
    Value v = binary(0, open);
    skip_blanks();
    if (at_end() || s_[i_] != ')') fail(Code::bad_expression, open, "'(' not closed with ')'");
    ++i_;
    return v;
  }

  Value bracket() {
    const std::size_t open = i_;
    ++i_;
    Value v = binary(0, open);
    skip_blanks();
    if (at_end() || s_[i_] != ']') fail(Code::bad_expression, open, "'[' not closed with ']'");
    ++i_;
    return v;
  }

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

  Op peek_op(std::size_t& length) const {
    length = 0;
    if (at_end()) return Op::none;
    const char c = s_[i_];
    const char c1 = i_ + 1 < s_.size() ? upper(s_[i_ + 1]) : '\0';
    const char c2 = i_ + 2 < s_.size() ? upper(s_[i_ + 2]) : '\0';
    length = 1;
    if (c == '*') {
      if (c1 == '*') {
        length = 2;
        return Op::power;
      }
      return Op::times;
    }
    if (c == '/') return Op::divide;
    if (c == '+') return Op::plus;
    if (c == '-') return Op::minus;
    length = 2;
    const char c0 = upper(c);
    if (c0 == 'E' && c1 == 'Q') return Op::eq;
    if (c0 == 'N' && c1 == 'E') return Op::ne;
    if (c0 == 'G' && c1 == 'T') return Op::gt;
    if (c0 == 'G' && c1 == 'E') return Op::ge;
    if (c0 == 'L' && c1 == 'T') return Op::lt;
    if (c0 == 'L' && c1 == 'E') return Op::le;
    if (c0 == 'O' && c1 == 'R') return Op::or_;
    length = 3;
    if (c0 == 'M' && c1 == 'O' && c2 == 'D') return Op::mod;
    if (c0 == 'A' && c1 == 'N' && c2 == 'D') return Op::and_;
    if (c0 == 'X' && c1 == 'O' && c2 == 'R') return Op::xor_;
    length = 0;
    return Op::none;
  }

  static int precedence(Op op) {
    switch (op) {
      case Op::power:
        return 5;
      case Op::times:
      case Op::divide:
      case Op::mod:
        return 4;
      case Op::plus:
      case Op::minus:
        return 3;
      case Op::eq:
      case Op::ne:
      case Op::gt:
      case Op::ge:
      case Op::lt:
      case Op::le:
        return 2;
      case Op::and_:
      case Op::or_:
      case Op::xor_:
        return 1;
      case Op::none:
        return 0;
    }
    return 0;
  }

  Value binary(int min_precedence, std::size_t open) {
    Value lhs = unary(open);
    while (true) {
      skip_blanks();
      std::size_t length = 0;
      const std::size_t at = i_;
      const Op op = peek_op(length);
      if (op == Op::none || precedence(op) < min_precedence || precedence(op) == 0) return lhs;
      i_ += length;
      const Value rhs = binary(precedence(op) + 1, open);
      lhs = apply(op, lhs, rhs, at);
    }
  }

  // An operation whose result overflows (or is not a number) fails here, so
  // no parameter or word ever holds an infinity or a NaN.
  Value apply(Op op, Value a, Value b, std::size_t at) const {
    return finite(apply_unchecked(op, a, b, at), at);
  }

  Value finite(Value v, std::size_t at) const {
    if (!std::isfinite(v.number))
      fail(Code::math_domain, at, "the expression's result is too large to be a number");
    return v;
  }

  // The word's value within kMaxWordMagnitude, then stored. (The message
  // is worded only on failure: this runs for every word of the program.)
  void push_word(Block& out, const Word& w) const {
    if (!in_range(w.value)) out_of_range(w.value, w.begin, std::string(1, w.letter) + " word");
    out.words.push_back(w);
  }

  double bounded(double v, std::size_t at, const std::string& what) const {
    if (!in_range(v)) out_of_range(v, at, what);
    return v;
  }

  static bool in_range(double v) { return std::abs(v) <= kMaxWordMagnitude; }

  [[noreturn]] void out_of_range(double v, std::size_t at, const std::string& what) const {
    char text[32];
    std::snprintf(text, sizeof text, "%.15g", v);
    fail(Code::bad_number, at,
         what + " value " + text + " is out of range (at most 1e12 either way)");
  }

  Value apply_unchecked(Op op, Value a, Value b, std::size_t at) const {
    const double x = a.number;
    const double y = b.number;
    auto truth = [](bool t) { return Value{t ? 1.0 : 0.0, false}; };
    switch (op) {
      case Op::power:
        if (x < 0 && y != std::floor(y))
          fail(Code::math_domain, at, "negative base to a non-integer power");
        return Value{std::pow(x, y), false};
      case Op::times:
        return Value{x * y, false};
      case Op::divide:
        if (y == 0.0) fail(Code::math_domain, at, "division by zero");
        return Value{x / y, false};
      case Op::mod: {
        if (y == 0.0) fail(Code::math_domain, at, "MOD by zero");
        double r = std::fmod(x, y);
        if (r < 0) r += std::abs(y);  // LinuxCNC: result has the divisor's sign convention
        return Value{r, false};
      }
      case Op::plus:
        return Value{x + y, false};
      case Op::minus:
        return Value{x - y, false};
      // Fanuc: <vacant> equals only <vacant> in EQ/NE.
      case Op::eq:
        return truth(a.vacant || b.vacant ? a.vacant == b.vacant : x == y);
      case Op::ne:
        return truth(a.vacant || b.vacant ? a.vacant != b.vacant : x != y);
      case Op::gt:
        return truth(x > y);
      case Op::ge:
        return truth(x >= y);
      case Op::lt:
        return truth(x < y);
      case Op::le:
        return truth(x <= y);
      case Op::and_:
        return truth(x != 0.0 && y != 0.0);
      case Op::or_:
        return truth(x != 0.0 || y != 0.0);
      case Op::xor_:
        return truth((x != 0.0) != (y != 0.0));
      case Op::none:
        break;
    }
    return a;
  }

  Value function() {
    const std::size_t start = i_;
    return finite(function_unchecked(), start);
  }

  Value function_unchecked() {
    const std::size_t start = i_;
    const std::string name = read_letters();
    skip_blanks();
    if (name == "EXISTS" && d_.named_parameters) {
      // EXISTS[#<name>]
      if (at_end() || s_[i_] != '[') fail(Code::bad_expression, start, "EXISTS without '['");
      ++i_;
      skip_blanks();
      if (i_ + 1 >= s_.size() || s_[i_] != '#' || s_[i_ + 1] != '<')
        fail(Code::bad_expression, start, "EXISTS needs a named parameter #<name>");
      ++i_;
      const std::string key = read_name();
      skip_blanks();
      if (at_end() || s_[i_] != ']') fail(Code::bad_expression, start, "EXISTS not closed");
      ++i_;
      return Value{p_->read(key).ok ? 1.0 : 0.0, false};
    }
    const bool round_brackets = siemens() && !at_end() && s_[i_] == '(';
    if (at_end() || (s_[i_] != '[' && !round_brackets))
      fail(Code::bad_expression, start,
           "unknown word or function '" + name + "'" + dialect_hint(name));
    const double x = round_brackets ? paren().number : bracket().number;
    if (round_brackets && name == "AC") {
      ac_seen_ = true;
      return Value{x, false};
    }
    if (round_brackets && name == "IC")
      fail(Code::unsupported_code, start,
           "IC() (incremental for one word) is not followed; use G91");
    constexpr double deg = std::numbers::pi / 180.0;
    if (name == "ATAN") {
      skip_blanks();
      if (at_end() || s_[i_] != '/')
        fail(Code::bad_expression, start, "ATAN needs the form ATAN[y]/[x]");
      ++i_;
      skip_blanks();
      if (at_end() || s_[i_] != '[') fail(Code::bad_expression, start, "ATAN needs [x] after '/'");
      const double y = bracket().number;
      return Value{std::atan2(x, y) / deg, false};
    }
    if (name == "ABS") return Value{std::abs(x), false};
    if (name == "ACOS" || name == "ASIN") {
      if (x < -1.0 || x > 1.0) fail(Code::math_domain, start, name + " argument outside [-1, 1]");
      return Value{(name == "ACOS" ? std::acos(x) : std::asin(x)) / deg, false};
    }
    if (name == "COS") return Value{std::cos(x * deg), false};
    if (name == "SIN") return Value{std::sin(x * deg), false};
    if (name == "TAN") return Value{std::tan(x * deg), false};
    if (name == "EXP") return Value{std::exp(x), false};
    if (name == "LN") {
      if (x <= 0.0) fail(Code::math_domain, start, "LN of a number <= 0");
      return Value{std::log(x), false};
    }
    if (name == "SQRT") {
      if (x < 0.0) fail(Code::math_domain, start, "SQRT of a negative number");
      return Value{std::sqrt(x), false};
    }
    if (name == "FIX") return Value{std::floor(x), false};
    if (name == "FUP") return Value{std::ceil(x), false};
    if (name == "ROUND") return Value{std::round(x), false};
    fail(Code::bad_expression, start, "unknown function '" + name + "'");
  }

  // For a word that is plainly another dialect's: which --dialect reads it.
  std::string dialect_hint(const std::string& name) const {
    if (siemens()) return "";
    if (name == "MSG" || name.rfind("CYCLE", 0) == 0 || name == "CR" || name == "MCALL")
      return "; this is Sinumerik 840D syntax: read it with --dialect sinumerik or --machine "
             "sinumerik-840d";
    return "";
  }

  // After "#<": the normalised name up to '>'.
  std::string read_name() {
    const std::size_t open = i_;
    ++i_;
    std::string key;
    // '(' starts a comment even inside a name on LinuxCNC ("Unclosed
    // comment found" in rs274): the name ends unclosed there.
    while (!at_end() && s_[i_] != '>' && s_[i_] != '(') {
      if (!is_blank(s_[i_]))
        key += static_cast<char>(std::tolower(static_cast<unsigned char>(s_[i_])));
      ++i_;
    }
    if (at_end() || s_[i_] == '(')
      fail(Code::bad_expression, open, "named parameter not closed with '>'");
    ++i_;
    if (key.empty()) fail(Code::bad_expression, open, "empty parameter name");
    return key;
  }

  struct Ref {
    int number = 0;
    std::string name;
  };

  Ref parameter_ref() {
    const std::size_t hash = i_;
    ++i_;
    skip_blanks();
    if (!at_end() && s_[i_] == '<') {
      if (!d_.named_parameters)
        fail(
            Code::parameters_not_in_dialect, hash,
            "named parameters are not part of this dialect; an RS274NGC (LinuxCNC) program is read "
            "with --dialect rs274ngc");
      return Ref{0, read_name()};
    }
    if (!d_.numbered_parameters)
      fail(Code::parameters_not_in_dialect, hash, "parameters are not part of this dialect");
    const double v = unary(hash).number;
    const double r = std::round(v);
    if (std::abs(v - r) > 1e-6 || r < 0 || r > 1e6)
      fail(Code::parameter_out_of_range, hash, "parameter number must be a whole number");
    return Ref{static_cast<int>(r), {}};
  }

  Value parameter_value() {
    const std::size_t hash = i_;
    const Ref ref = parameter_ref();
    const Access a = ref.name.empty() ? p_->read(ref.number) : p_->read(ref.name);
    if (!a.ok) fail(a.code, hash, a.message);
    return a.value;
  }

  void read_assignment(Block& out) {
    const std::size_t hash = i_;
    Ref ref = parameter_ref();
    skip_blanks();
    if (at_end() || s_[i_] != '=')
      fail(Code::bad_expression, hash, "a parameter outside a word must be set with '='");
    ++i_;
    // Fanuc macros allow "#1 = #2 + 3" without brackets; RS274NGC takes one value.
    const Value v = d_.fanuc_macros ? binary(0, hash) : unary(hash);
    out.assignments.push_back(Assignment{ref.number, std::move(ref.name), v.number,
                                         static_cast<std::uint32_t>(hash + 1)});
  }

  void read_o_word(Block& out) {
    const std::size_t start = i_;
    ++i_;
    Control& c = out.control;
    c.column = static_cast<std::uint32_t>(start + 1);
    if (!d_.o_word_control) {
      skip_blanks();
      c.name = read_digits_text();
      if (c.name.empty()) fail(Code::bad_number, start, "O without a program number");
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
      fail(Code::unknown_word, key_at, "unknown O-word keyword '" + key + "'");
    switch (c.kind) {
      case ControlKind::if_:
      case ControlKind::elseif:
      case ControlKind::while_:
      case ControlKind::repeat: {
        skip_blanks();
        if (at_end() || s_[i_] != '[')
          fail(Code::bad_expression, key_at, key + " needs a condition in [ ]");
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
        fail(Code::bad_character, i_, "only comments may follow an O-word");
      }
    }
  }

  // Fanuc/Mazak macro statements: IF [..] THEN/GOTO, ELSE, ENDIF, GOTO n,
  // WHILE [..] DOm, ENDm. Returns false when the rest of the line is skipped.
  bool read_macro_statement(Block& out) {
    const std::size_t start = i_;
    const std::string key = read_letters();
    Control& c = out.control;
    c.column = static_cast<std::uint32_t>(start + 1);
    if (key == "IF") {
      skip_blanks();
      if (at_end() || s_[i_] != '[')
        fail(Code::bad_expression, start, "IF needs a condition in [ ]");
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
      if (then != "THEN")
        fail(Code::bad_expression, key_at, "IF [..] must be followed by THEN or GOTO");
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
};

}  // namespace

void read_block(std::string_view line, std::uint32_t line_number, std::uint64_t offset,
                const Dialect& dialect, const Parameters& parameters, Block& out) {
  out.clear();
  out.text = line;
  out.line = line_number;
  out.offset = offset;
  if (line.size() > kMaxLineLength)
    throw GcodeError(Diagnostic{
        Code::line_too_long, Severity::error, line_number, 1,
        "line longer than " + std::to_string(kMaxLineLength) + " bytes, the reader's limit"});
  LineReader reader(line, line_number, dialect, &parameters);
  reader.read(out);
}

Control peek_control(std::string_view line, const Dialect& dialect) {
  if (line.size() > kMaxLineLength) return {};
  LineReader reader(line, 0, dialect, nullptr);
  return reader.peek();
}

std::size_t word_value_end(std::string_view s, std::size_t k) {
  const std::size_t start = k;
  while (k < s.size() && (s[k] == '-' || s[k] == '+')) {  // unary signs, as unary() reads them
    ++k;
    while (k < s.size() && is_blank(s[k])) ++k;
  }
  if (k < s.size() && s[k] == '[') {
    int depth = 0;
    for (; k < s.size(); ++k) {
      if (s[k] == '[') ++depth;
      if (s[k] == ']' && --depth == 0) return k + 1;
    }
    return s.size();
  }
  if (k < s.size() && s[k] == '#') {
    ++k;
    if (k < s.size() && s[k] == '<') {
      while (k < s.size() && s[k] != '>') ++k;
      return k < s.size() ? k + 1 : k;
    }
    while (k < s.size() && is_blank(s[k])) ++k;
    // The parameter's number is a value itself (#5, ##1, #[1+2], #++1).
    const std::size_t end = word_value_end(s, k);
    return end > k ? end : start;
  }
  const std::size_t digits = k;
  while (k < s.size() && (is_digit(s[k]) || s[k] == '.' ||
                          (is_blank(s[k]) && k > digits && k + 1 < s.size() &&
                           (is_digit(s[k + 1]) || s[k + 1] == '.'))))
    ++k;
  return k > digits ? k : start;
}

std::optional<Span> find_word_span(std::string_view line, char letter) {
  letter = upper(letter);
  std::size_t i = 0;
  int depth = 0;
  while (i < line.size()) {
    const char c = line[i];
    if (c == '(') {
      while (i < line.size() && line[i] != ')') ++i;
      ++i;
      continue;
    }
    if (c == ';') return std::nullopt;
    if (c == '[') ++depth;
    if (c == ']') --depth;
    if (c == '#' && i + 1 < line.size() && line[i + 1] == '<') {
      while (i < line.size() && line[i] != '>') ++i;
      continue;
    }
    const bool word_start = depth == 0 && upper(c) == letter &&
                            (i == 0 || !is_alpha(line[i - 1])) &&
                            !(i + 1 < line.size() && is_alpha(line[i + 1]));
    if (word_start) {
      std::size_t k = i + 1;
      while (k < line.size() && is_blank(line[k])) ++k;
      k = word_value_end(line, k);
      return Span{static_cast<std::uint32_t>(i),
                  static_cast<std::uint32_t>(std::min(k, line.size()))};
    }
    ++i;
  }
  return std::nullopt;
}

}  // namespace vcpost::gcode
