#pragma once
// A number in a message, a note or scene text, the same in every locale. printf's %g and %f write
// the decimal point of the program's LC_NUMERIC: a program (or Python code) that sets a German
// locale gets "4,5 mm" from them, and a text meant to be read back as a number reads 4. The
// standard defines std::to_chars with a precision as printf in the "C" locale, so these give
// printf's text as the C locale writes it, whatever locale the process is in.
//
// Header-only and hidden: every library that includes it keeps its own copy, and none exports it
// (libmechgraph_sdk.so.1's exports do not change). It needs floating-point std::to_chars with a
// precision: libstdc++ 11 or later, libc++ 14 or later.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

namespace mechgraph {

namespace printf_detail {
// A NaN as glibc's printf writes it: libc++'s to_chars writes "-nan(ind)" and "nan(snan)".
[[gnu::visibility("hidden")]] inline std::string nan_text(double x) { return std::signbit(x) ? "-nan" : "nan"; }
}  // namespace printf_detail

/// printf's "%.<significant>g" of `x` in the C locale ("0.25", "1e+06", "inf", "nan");
/// `significant` is clamped to 1..40 (0 means 1, as in printf).
[[gnu::visibility("hidden")]] inline std::string printf_g(double x, int significant = 6) {
  if (std::isnan(x)) return printf_detail::nan_text(x);
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general,
                                       std::clamp(significant, 1, 40));
  return ec == std::errc() ? std::string(buffer, end) : std::string("?");
}

/// printf's "%.<decimals>f" of `x` in the C locale ("12.5"); `decimals` is clamped to 0..40.
[[gnu::visibility("hidden")]] inline std::string printf_f(double x, int decimals) {
  if (std::isnan(x)) return printf_detail::nan_text(x);
  char buffer[400];  // the largest double has 309 digits before the point
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::fixed,
                                       std::clamp(decimals, 0, 40));
  return ec == std::errc() ? std::string(buffer, end) : std::string("?");
}

}  // namespace mechgraph
