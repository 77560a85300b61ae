#include "postproc/gcode/expression.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace vcpost::gcode::syntax {

Value ExpressionReader::unary(std::size_t word_start) {
  struct Level {
    int& n;
    explicit Level(int& count) : n(count) { ++n; }
    ~Level() { --n; }
    Level(const Level&) = delete;
    Level& operator=(const Level&) = delete;
  } level(nesting_);
  if (nesting_ > kMaxValueNesting)
    fail(Code::E1201, i_,
         "value nested more than " + std::to_string(kMaxValueNesting) +
             " deep (signs, '#' and brackets inside each other), the reader's limit");
  skip_blanks();
  if (at_end()) fail(Code::E1201, word_start, "value missing at end of line");
  const char c = s_[i_];
  if (c == '-' || c == '+') {
    ++i_;
    Value v = unary(word_start);
    if (c == '-') v.number = -v.number;
    return v;
  }
  if (c == '[') {
    if (!d_.numbered_parameters && !d_.named_parameters)
      fail(Code::E1206, i_, "expressions are not part of this dialect");
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
    const std::size_t start = i_++;
    return Value{r_value(read_r_number(start)), false};
  }
  if (is_alpha(c)) return function();
  fail(Code::E1201, i_, std::string("unexpected '") + c + "' where a value is expected");
}

// The expression between the opening character at the cursor and `close`.
Value ExpressionReader::enclosed(char close, const char* not_closed) {
  const std::size_t open = i_;
  ++i_;
  Value v = binary(0, open);
  skip_blanks();
  if (at_end() || s_[i_] != close) fail(Code::E1201, open, not_closed);
  ++i_;
  return v;
}

ExpressionReader::Op ExpressionReader::peek_op(std::size_t& length) const {
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

int ExpressionReader::precedence(Op op) {
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

Value ExpressionReader::binary(int min_precedence, std::size_t open) {
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

Value ExpressionReader::finite(Value v, std::size_t at) const {
  if (!std::isfinite(v.number))
    fail(Code::E1205, at, "the expression's result is too large to be a number");
  return v;
}

void ExpressionReader::out_of_range(double v, std::size_t at, const std::string& what) const {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", v);
  fail(Code::E1003, at, what + " value " + text + " is out of range (at most 1e12 either way)");
}

Value ExpressionReader::apply_unchecked(Op op, Value a, Value b, std::size_t at) const {
  const double x = a.number;
  const double y = b.number;
  auto truth = [](bool t) { return Value{t ? 1.0 : 0.0, false}; };
  switch (op) {
    case Op::power:
      if (x < 0 && y != std::floor(y))
        fail(Code::E1205, at, "negative base to a non-integer power");
      return Value{std::pow(x, y), false};
    case Op::times:
      return Value{x * y, false};
    case Op::divide:
      if (y == 0.0) fail(Code::E1205, at, "division by zero");
      return Value{x / y, false};
    case Op::mod: {
      if (y == 0.0) fail(Code::E1205, at, "MOD by zero");
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

Value ExpressionReader::function_unchecked() {
  const std::size_t start = i_;
  const std::string name = read_letters();
  skip_blanks();
  if (name == "EXISTS" && d_.named_parameters) {
    // EXISTS[#<name>]
    if (at_end() || s_[i_] != '[') fail(Code::E1201, start, "EXISTS without '['");
    ++i_;
    skip_blanks();
    if (i_ + 1 >= s_.size() || s_[i_] != '#' || s_[i_ + 1] != '<')
      fail(Code::E1201, start, "EXISTS needs a named parameter #<name>");
    ++i_;
    const std::string key = read_name();
    skip_blanks();
    if (at_end() || s_[i_] != ']') fail(Code::E1201, start, "EXISTS not closed");
    ++i_;
    return Value{p_->exists(key) ? 1.0 : 0.0, false};
  }
  const bool round_brackets = siemens() && !at_end() && s_[i_] == '(';
  if (at_end() || (s_[i_] != '[' && !round_brackets))
    fail(Code::E1201, start, "unknown word or function '" + name + "'" + dialect_hint(name));
  const double x = round_brackets ? paren().number : bracket().number;
  if (round_brackets && name == "AC") {
    ac_seen_ = true;
    return Value{x, false};
  }
  if (round_brackets && name == "IC")
    fail(Code::E1404, start, "IC() (incremental for one word) is not followed; use G91");
  constexpr double deg = std::numbers::pi / 180.0;
  if (name == "ATAN") {
    skip_blanks();
    if (at_end() || s_[i_] != '/') fail(Code::E1201, start, "ATAN needs the form ATAN[y]/[x]");
    ++i_;
    skip_blanks();
    if (at_end() || s_[i_] != '[') fail(Code::E1201, start, "ATAN needs [x] after '/'");
    const double y = bracket().number;
    return Value{std::atan2(x, y) / deg, false};
  }
  if (name == "ABS") return Value{std::abs(x), false};
  if (name == "ACOS" || name == "ASIN") {
    if (x < -1.0 || x > 1.0) fail(Code::E1205, start, name + " argument outside [-1, 1]");
    return Value{(name == "ACOS" ? std::acos(x) : std::asin(x)) / deg, false};
  }
  if (name == "COS") return Value{std::cos(x * deg), false};
  if (name == "SIN") return Value{std::sin(x * deg), false};
  if (name == "TAN") return Value{std::tan(x * deg), false};
  if (name == "EXP") return Value{std::exp(x), false};
  if (name == "LN") {
    if (x <= 0.0) fail(Code::E1205, start, "LN of a number <= 0");
    return Value{std::log(x), false};
  }
  if (name == "SQRT") {
    if (x < 0.0) fail(Code::E1205, start, "SQRT of a negative number");
    return Value{std::sqrt(x), false};
  }
  if (name == "FIX") return Value{std::floor(x), false};
  if (name == "FUP") return Value{std::ceil(x), false};
  if (name == "ROUND") return Value{std::round(x), false};
  fail(Code::E1201, start, "unknown function '" + name + "'");
}

// For a word that is plainly another dialect's: which --dialect reads it.
std::string ExpressionReader::dialect_hint(const std::string& name) const {
  if (siemens()) return "";
  if (name == "MSG" || name.rfind("CYCLE", 0) == 0 || name == "CR" || name == "MCALL")
    return "; this is Sinumerik 840D syntax: read it with --dialect sinumerik or --machine "
           "sinumerik-840d";
  return "";
}

// After "#<": the normalised name up to '>'.
std::string ExpressionReader::read_name() {
  const std::size_t open = i_;
  std::string key;
  if (!read_angle_name(key)) fail(Code::E1201, open, "named parameter not closed with '>'");
  if (key.empty()) fail(Code::E1201, open, "empty parameter name");
  return key;
}

ExpressionReader::Ref ExpressionReader::parameter_ref() {
  const std::size_t hash = i_;
  ++i_;
  skip_blanks();
  if (!at_end() && s_[i_] == '<') {
    if (!d_.named_parameters)
      fail(Code::E1206, hash,
           "named parameters are not part of this dialect; an RS274NGC (LinuxCNC) program is read "
           "with --dialect rs274ngc");
    return Ref{0, read_name()};
  }
  if (!d_.numbered_parameters) fail(Code::E1206, hash, "parameters are not part of this dialect");
  const double v = unary(hash).number;
  const double r = std::round(v);
  if (std::abs(v - r) > 1e-6 || r < 0 || r > 1e6)
    fail(Code::E1203, hash, "parameter number must be a whole number");
  return Ref{static_cast<int>(r), {}};
}

int ExpressionReader::read_r_number(std::size_t start) {
  const std::size_t first = i_;
  while (!at_end() && is_digit(s_[i_])) ++i_;
  const std::string_view digits = s_.substr(first, i_ - first);
  long number = 0;
  for (const char d : digits) {
    number = number * 10 + (d - '0');
    if (number > kMaxRParameter)
      fail(Code::E1203, start,
           "R" + std::string(digits) + " is beyond R" + std::to_string(kMaxRParameter) +
               ", the last R parameter vcpost keeps (a control has R0 to R99 unless its machine "
               "data gives more)");
  }
  return static_cast<int>(number);
}

double ExpressionReader::r_value(int number) const {
  const std::string key = "_r" + std::to_string(number);
  if (earlier_)
    for (auto a = earlier_->rbegin(); a != earlier_->rend(); ++a)
      if (a->name == key) return a->value;
  const Access a = p_->read(key);
  return a.ok ? a.value.number : 0.0;
}

Value ExpressionReader::parameter_value() {
  const std::size_t hash = i_;
  const Ref ref = parameter_ref();
  const Access a = ref.name.empty() ? p_->read(ref.number) : p_->read(ref.name);
  if (!a.ok) fail(a.code, hash, a.message);
  return a.value;
}
}  // namespace vcpost::gcode::syntax
