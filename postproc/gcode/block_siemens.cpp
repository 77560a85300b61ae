// The Sinumerik 840D statements of the block parser (block_parser.h):
// MSG("..."), CR= and TURN=, R parameter assignments, CYCLE81-CYCLE89 and
// MCALL, CYCLE800 (the swivel of the working plane), the modes passed through, and the frames and
// program flow vcpost refuses.
#include <string_view>

#include "postproc/gcode/block_parser.h"

namespace vcpost::gcode::syntax {

// A Sinumerik statement at i_: MSG( MCALL CYCLE8x( CR=.
bool BlockParser::looks_siemens() const {
  std::string key;
  for (std::size_t k = i_; k < s_.size() && key.size() < 8 && (is_alpha(s_[k]) || is_digit(s_[k]));
       ++k)
    key += upper(s_[k]);
  std::size_t k = i_ + key.size();
  while (k < s_.size() && is_blank(s_[k])) ++k;
  const char next = k < s_.size() ? s_[k] : '\0';
  return (key == "MSG" && next == '(') || key == "MCALL" ||
         (key.rfind("CYCLE", 0) == 0 && next == '(') || (key == "CR" && next == '=');
}

// "R12 = ..." at i_ (an R parameter assignment, not an R word).
bool BlockParser::r_assignment_follows() const {
  std::size_t k = i_ + 1;
  if (k >= s_.size() || !is_digit(s_[k])) return false;
  while (k < s_.size() && is_digit(s_[k])) ++k;
  while (k < s_.size() && is_blank(s_[k])) ++k;
  return k < s_.size() && s_[k] == '=';
}

void BlockParser::read_r_assignment(Block& out) {
  const std::size_t start = i_;
  ++i_;
  const int number = read_r_number(start);
  skip_blanks();
  ++i_;  // '='
  // The control assigns in the order written: "R1=5 R2=R1*2" sets R2 to
  // 10, "R1=7 G0 X=R1" goes to X7 (words read after it see the new value).
  earlier_ = &out.assignments;
  const Value v = binary(0, start);
  out.assignments.push_back(Assignment{0, "_r" + std::to_string(number), v.number,
                                       static_cast<std::uint32_t>(start + 1)});
}

// A quoted string after '(' (MSG("...")): its text; i_ after the ')'.
std::string BlockParser::read_quoted_call(std::size_t start, const std::string& key) {
  skip_blanks();
  if (at_end() || s_[i_] != '(') fail(Code::E1201, start, key + " needs (\"text\")");
  ++i_;
  skip_blanks();
  std::string text;
  if (!at_end() && s_[i_] == '"') {
    ++i_;
    while (!at_end() && s_[i_] != '"') text += s_[i_++];
    if (at_end()) fail(Code::E1201, start, "string not closed with '\"'");
    ++i_;
  }
  skip_blanks();
  if (at_end() || s_[i_] != ')') fail(Code::E1201, start, key + "( not closed with ')'");
  ++i_;
  return text;
}

// Arguments "(a, , c)" of a cycle call; empty ones are nullopt.
std::vector<std::optional<double>> BlockParser::read_call_arguments(std::size_t start,
                                                                    const std::string& key,
                                                                    bool strings) {
  std::vector<std::optional<double>> args;
  skip_blanks();
  if (at_end() || s_[i_] != '(') fail(Code::E1201, start, key + " needs its arguments in ( )");
  ++i_;
  while (true) {
    skip_blanks();
    if (at_end()) fail(Code::E1201, start, key + "( not closed with ')'");
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
    if (strings && s_[i_] == '"') {
      // A name (CYCLE800's swivel data set "TC1"): not a number vcpost uses.
      ++i_;
      while (!at_end() && s_[i_] != '"') ++i_;
      if (at_end()) fail(Code::E1201, start, "string not closed with '\"'");
      ++i_;
      args.emplace_back();
    } else {
      args.emplace_back(bounded(binary(0, start).number, start, key + " argument"));
    }
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
    fail(Code::E1201, i_, "',' or ')' expected in the arguments of " + key);
  }
  return args;
}

void BlockParser::skip_parenthesised() {
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
  fail(Code::E1201, i_ == 0 ? 0 : i_ - 1, "'(' not closed with ')'");
}

// "KEY = expression" after a keyword that began at `start`: the word of
// `letter` it stands for, spanning the keyword and its value.
Word BlockParser::read_keyword_word(char letter, std::size_t start, const char* no_equals) {
  skip_blanks();
  if (at_end() || s_[i_] != '=') fail(Code::E1201, start, no_equals);
  ++i_;
  Word w;
  w.letter = letter;
  w.column = static_cast<std::uint32_t>(start + 1);
  w.begin = static_cast<std::uint32_t>(start);
  w.value = binary(0, start).number;
  w.decimal_point = true;
  w.computed = true;
  w.end = static_cast<std::uint32_t>(i_);
  return w;
}

void BlockParser::read_siemens_keyword(Block& out) {
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
    push_word(out, read_keyword_word('R', start, "CR needs '=' and a radius"));
    return;
  }
  if (key == "TURN") {
    // TURN=n: n full turns more than the helix's end point says; the P
    // (turns) word of RS274NGC arcs, which counts them all.
    Word w = read_keyword_word('P', start, "TURN needs '=' and a count");
    w.value += 1.0;
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
        fail(Code::E1404, at, "MCALL " + name + ": vcpost follows MCALL of CYCLE81-CYCLE89 only");
      cycle.kind = SiemensCycle::Kind::modal_call;
    }
    return;
  }
  if (read_cycle(key, start, cycle)) {
    cycle.kind = SiemensCycle::Kind::call;
    return;
  }
  if (key == "CYCLE800") {
    cycle.kind = SiemensCycle::Kind::swivel;
    cycle.number = 800;
    cycle.column = static_cast<std::uint32_t>(start + 1);
    cycle.args = read_call_arguments(start, key, true);
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
        fail(Code::E1404, start,
             "SUPA (machine coordinates without any frame) is not followed; use G53");
      skip_parenthesised();
      out.noted_keywords.emplace_back(key, column);
      return;
    }
  }
  static constexpr std::string_view kFrames[] = {"TRANS",  "ATRANS", "ROT",    "AROT",
                                                 "SCALE",  "ASCALE", "MIRROR", "AMIRROR",
                                                 "TRAORI", "ROTS",   "AROTS"};
  for (const auto frame : kFrames)
    if (key == frame)
      fail(Code::E1404, start,
           key +
               " moves, rotates, scales or mirrors the coordinate frame; vcpost does not follow "
               "frames: remove it or post without it");
  static constexpr std::string_view kFlow[] = {
      "GOTOF", "GOTOB", "GOTO",  "GOTOC",  "LOOP",  "ENDLOOP", "WHILE", "ENDWHILE", "FOR", "ENDFOR",
      "IF",    "ELSE",  "ENDIF", "REPEAT", "UNTIL", "CALL",    "PCALL", "RET",      "DEF", "PROC"};
  for (const auto flow : kFlow)
    if (key == flow)
      fail(Code::E1301, start,
           key +
               ": Sinumerik program flow and subprograms are not followed by vcpost; expand them "
               "in CAM");
  fail(Code::E1007, start, "unknown Sinumerik word or statement '" + key + "'");
}

bool BlockParser::read_cycle(const std::string& name, std::size_t start, SiemensCycle& cycle) {
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
}  // namespace vcpost::gcode::syntax
