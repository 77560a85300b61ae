#include "postproc/heidenhain/formula.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/units.h"

namespace vcpost::heidenhain {

namespace {

using Op = FormulaStep::Op;

// The largest value a step may give: as FN's results (far past any machine).
constexpr double kLimit = 1e12;
// Parentheses nested deeper than this are no program's (and would run the
// recursive parser deep).
constexpr int kMaxNesting = 64;

struct FunctionName {
  std::string_view word;
  Op op;
};

// The FORMULA key's functions, sorted for a binary search.
constexpr FunctionName kFunctions[] = {
    {"ABS", Op::abs}, {"ACOS", Op::acos}, {"ASIN", Op::asin},  {"ATAN", Op::atan},
    {"COS", Op::cos}, {"EXP", Op::exp},   {"FRAC", Op::frac},  {"INT", Op::int_part},
    {"LN", Op::ln},   {"LOG", Op::log},   {"NEG", Op::negate}, {"SGN", Op::sgn},
    {"SIN", Op::sin}, {"SQ", Op::sq},     {"SQRT", Op::sqrt},  {"TAN", Op::tan},
};
static_assert(std::ranges::is_sorted(kFunctions, {}, &FunctionName::word));

class FormulaParser {
 public:
  FormulaParser(syntax::Lexer& lexer, std::vector<FormulaStep>& out) : l_(lexer), out_(out) {}

  void parse() {
    out_.clear();
    sum(0);
    l_.skip_blanks();
    if (!l_.at_end() && l_.peek() != ';') {
      if (l_.peek() == ')') l_.fail(Code::E3328, l_.pos(), "')' without its '('");
      l_.check_word_byte(l_.pos());
      l_.fail(Code::E3328, l_.pos(),
              std::string("expected an operator (+ - * / % ^) before '") + l_.peek() + "'");
    }
  }

 private:
  syntax::Lexer& l_;
  std::vector<FormulaStep>& out_;

  void push(Op op, std::size_t at) {
    out_.push_back({op, Value{}, static_cast<std::uint32_t>(at)});
  }

  // sum := product { (+|-) product }
  void sum(int depth) {
    product(depth);
    for (;;) {
      l_.skip_blanks();
      const char c = l_.peek();
      if (c != '+' && c != '-') return;
      const std::size_t at = l_.pos();
      l_.seek(at + 1);
      product(depth);
      push(c == '+' ? Op::add : Op::subtract, at);
    }
  }

  // product := power { (*|/|%) power }
  void product(int depth) {
    power(depth);
    for (;;) {
      l_.skip_blanks();
      const char c = l_.peek();
      if (c != '*' && c != '/' && c != '%') return;
      const std::size_t at = l_.pos();
      l_.seek(at + 1);
      power(depth);
      push(c == '*' ? Op::multiply : c == '/' ? Op::divide : Op::modulo, at);
    }
  }

  // power := operand { ^ operand }
  void power(int depth) {
    operand(depth);
    for (;;) {
      l_.skip_blanks();
      if (l_.peek() != '^') return;
      const std::size_t at = l_.pos();
      l_.seek(at + 1);
      operand(depth);
      push(Op::power, at);
    }
  }

  // operand := [+|-] ( number | Q.. | PI | ( sum ) | FUNCTION operand )
  void operand(int depth) {
    l_.skip_blanks();
    const std::size_t at = l_.pos();
    if (depth > kMaxNesting) l_.fail(Code::E3328, at, "a formula nested too deep");
    const char c = l_.peek();
    if ((c == '+' || c == '-') && !value_follows(at + 1)) {
      // A sign before a parenthesis, a function or PI.
      l_.seek(at + 1);
      operand(depth + 1);
      if (c == '-') push(Op::negate, at);
      return;
    }
    FormulaStep step{Op::value, Value{}, static_cast<std::uint32_t>(at)};
    char sign = 0;
    if (l_.read_value(step.value, sign)) {
      out_.push_back(step);
      return;
    }
    if (l_.peek() == '(') {
      l_.seek(l_.pos() + 1);
      sum(depth + 1);
      l_.skip_blanks();
      if (l_.peek() != ')') l_.fail(Code::E3328, l_.pos(), "expected ')'");
      l_.seek(l_.pos() + 1);
      return;
    }
    const std::string_view word = l_.read_letters();
    if (word == "PI") {
      step.value.number = std::numbers::pi;
      out_.push_back(step);
      return;
    }
    const auto* f = std::ranges::lower_bound(kFunctions, word, {}, &FunctionName::word);
    if (!word.empty() && f != std::end(kFunctions) && f->word == word) {
      operand(depth + 1);
      push(f->op, at);
      return;
    }
    if (!word.empty())
      l_.fail(Code::E3328, at,
              "'" + std::string(word) +
                  "' is no function of a formula (SQ SQRT SIN COS TAN ASIN ACOS ATAN ABS INT "
                  "FRAC SGN LN LOG EXP NEG PI)");
    if (l_.at_end() || l_.peek() == ';') l_.fail(Code::E3328, at, "the formula ends early");
    l_.check_word_byte(l_.pos());
    l_.fail(Code::E3328, at,
            std::string("expected a number, a Q parameter or '(' at '") + l_.peek() + "'");
  }

  // A digit, '.' or Q right after a sign: the sign belongs to the value.
  bool value_follows(std::size_t at) const {
    const std::string_view t = l_.text();
    return at < t.size() && (syntax::is_digit(t[at]) || t[at] == '.' || t[at] == 'Q');
  }
};

[[noreturn]] void fail_at(const Block& block, std::uint32_t at, std::string message) {
  const auto [line, column] = block.position(at);
  throw KlartextError(Diagnostic{Code::E3318, line, column, std::move(message), {}});
}

}  // namespace

namespace syntax {
void parse_formula(Lexer& lexer, std::vector<FormulaStep>& out) {
  FormulaParser(lexer, out).parse();
}
}  // namespace syntax

double evaluate_formula(const Block& block, const std::vector<FormulaStep>& steps,
                        const std::function<double(const Value&, std::uint32_t)>& parameter) {
  // The stack never holds more values than the formula has steps.
  std::vector<double> stack;
  stack.reserve(steps.size());
  for (const FormulaStep& s : steps) {
    if (s.op == Op::value) {
      stack.push_back(s.value.is_parameter() ? parameter(s.value, s.at) : s.value.number);
      continue;
    }
    const bool binary = s.op >= Op::add;
    const double b = stack.back();
    if (binary) stack.pop_back();
    double& a = stack.back();  // the left operand, or the only one
    const double x = binary ? a : b;
    double r = 0;
    switch (s.op) {
      case Op::negate:
        r = -x;
        break;
      case Op::sq:
        r = x * x;
        break;
      case Op::sqrt:
        if (x < 0) fail_at(block, s.at, "SQRT of a negative number");
        r = std::sqrt(x);
        break;
      case Op::sin:
        r = std::sin(x * kDeg);
        break;
      case Op::cos:
        r = std::cos(x * kDeg);
        break;
      case Op::tan:
        if (std::abs(std::cos(x * kDeg)) < 1e-12) fail_at(block, s.at, "TAN of 90 degrees");
        r = std::tan(x * kDeg);
        break;
      case Op::asin:
      case Op::acos:
        if (std::abs(x) > 1) fail_at(block, s.at, "ASIN/ACOS of a value beyond -1..1");
        r = (s.op == Op::asin ? std::asin(x) : std::acos(x)) / kDeg;
        break;
      case Op::atan:
        r = std::atan(x) / kDeg;
        break;
      case Op::abs:
        r = std::abs(x);
        break;
      case Op::int_part:
        r = std::trunc(x);
        break;
      case Op::frac:
        r = x - std::trunc(x);
        break;
      case Op::sgn:
        r = x > 0 ? 1.0 : x < 0 ? -1.0 : 0.0;
        break;
      case Op::ln:
      case Op::log:
        if (x <= 0) fail_at(block, s.at, "the logarithm of a number not above 0");
        r = s.op == Op::ln ? std::log(x) : std::log10(x);
        break;
      case Op::exp:
        r = std::exp(std::min(x, 100.0));
        break;
      case Op::add:
        r = a + b;
        break;
      case Op::subtract:
        r = a - b;
        break;
      case Op::multiply:
        r = a * b;
        break;
      case Op::divide:
      case Op::modulo:
        if (b == 0) fail_at(block, s.at, "division by zero");
        r = s.op == Op::divide ? a / b : std::fmod(a, b);
        break;
      case Op::power:
        r = std::pow(a, b);
        break;
      case Op::value:
        break;
    }
    if (!(std::abs(r) <= kLimit)) fail_at(block, s.at, "a formula's value out of range");
    a = r;
  }
  return stack.back();
}

}  // namespace vcpost::heidenhain
