// Q parameter formulas as the TNC's FORMULA key writes them
// ("Q1 = Q2 * 3 + SIN Q4", "Q5 = ( Q1 + 2 ) / 4", "QL3 = SQ QR1 - 3^3"):
// parsed into postfix steps (block.h's FormulaStep) by the block parser,
// evaluated by the interpreter. The rules (docs/heidenhain.md): ^ before
// * / % before + -, left to right; a function or a sign applies to the
// operand right after it (a number, a parameter, PI, a function or a
// parenthesised formula); angles in degrees.
#pragma once

#include <functional>
#include <vector>

#include "postproc/heidenhain/block.h"
#include "postproc/heidenhain/lexer.h"

namespace vcpost::heidenhain {

namespace syntax {
// Reads a formula from the lexer's cursor to the end of the block or a ';'
// comment into `out` (cleared first). Throws KlartextError (Code::E3328)
// at the first byte that does not fit.
void parse_formula(Lexer& lexer, std::vector<FormulaStep>& out);
}  // namespace syntax

// The value of a parsed formula; `parameter` gives a Q, QL or QR
// parameter's value (and fails for one out of range). Throws KlartextError
// (Code::E3318) at the step out of its domain: division by zero, the
// root or logarithm of a negative number, ASIN/ACOS beyond 1, a result past
// 1e12.
double evaluate_formula(const Block& block, const std::vector<FormulaStep>& steps,
                        const std::function<double(const Value&, std::uint32_t)>& parameter);

}  // namespace vcpost::heidenhain
