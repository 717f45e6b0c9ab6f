#pragma once
// printf's "%.15g" of a double, exactly, in a few hundred instructions where std::to_chars with a
// precision takes about 1,200: a sweep's rows repeat every input of every case at 15 digits
// (CaseTable::append_shown), six to a row and millions of rows.
//
// How (core/src/printf_g15.cpp). A normal x with 1e-5 <= |x| < 1e15 is m 2^e exactly (m < 2^53,
// -70 <= e <= 0). Its 15 significant digits are N = round(m 10^k / 2^-e) with k = 14 - X, X the
// decimal exponent of its leading digit: m 10^k < 2^117 is an exact 128-bit integer, the shift
// leaves N and a remainder that says exactly whether x lies below, on or above the halfway point
// (a tie rounds to the even N, as glibc's printf does in the default rounding mode). Then the
// layout of "%g": trailing zeros dropped, scientific notation when X < -4 or X >= 15 (never here:
// the range keeps X in -5 .. 14). Any other x (zero, subnormal, outside the range, not finite)
// goes to std::to_chars, whose text the standard defines as printf's.
#include <string>

namespace mechgraph {

/// Appends printf's "%.15g" of x to `out`.
void append_printf_g15(std::string& out, double x);

}  // namespace mechgraph
