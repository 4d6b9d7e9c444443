// Infix text of GiNaC expressions in the syntax of schema mbgen-inspect/1 (and of .mdl expressions):
// parameter names, integers and ratios (127/1000), + - * / ^ and parentheses; never negative or fractional
// exponents without parentheses (x^(-1) is written 1/x, x^(1/2) stays x^(1/2)), never floating-point
// notation. Beyond that syntax only what a model itself can contain appears: the constant `pi` and calls
// such as sin(x), cos(x).
#pragma once

#include <ginac/ginac.h>

#include <string>

namespace mbgen::emit {

std::string infix_text(const GiNaC::ex& e);

// The same expression as LaTeX math (inspect --format latex): operands in the same deterministic order and signs
// (GiNaC's own LaTeX printer follows hash values, which differ from run to run), ratios as \frac, parameter names
// with their subscripts escaped.
std::string latex_text(const GiNaC::ex& e);

}  // namespace mbgen::emit
