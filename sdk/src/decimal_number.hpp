#pragma once
// A decimal number read as std::from_chars reads a double, by the C library's strtod_l in the "C"
// locale: for a C++ library without floating-point from_chars (libc++ before LLVM 20; a plugin
// built with clang++ -stdlib=libc++ compiles the SDK's C++ layer). strtod_l rounds correctly as
// from_chars does. What from_chars refuses and strtod would take (leading spaces, '+') is refused
// first; of a hexadecimal text only its "0" is read, as from_chars reads it; errno is left as it
// was. Compiled everywhere, so the tests compare it with from_chars
// (tests/sdk/decimal_number_test.cpp) on the host's own library too.
#include <cerrno>
#include <charconv>
#include <cmath>
#include <locale.h>
#include <stdlib.h>
#include <string>
#include <system_error>

namespace mechgraph::detail {

inline std::from_chars_result read_double_with_strtod(const char* first, const char* last, double& value) {
  const char* digits = first != last && *first == '-' ? first + 1 : first;
  const bool decimal_start = digits != last && ((*digits >= '0' && *digits <= '9') || *digits == '.' ||
                                                *digits == 'i' || *digits == 'I' || *digits == 'n' || *digits == 'N');
  const bool hex = last - digits >= 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X');
  if (!decimal_start) return {first, std::errc::invalid_argument};
  if (hex) {  // from_chars reads the "0" and stops at the 'x'
    value = digits != first ? -0.0 : 0.0;
    return {digits + 1, std::errc()};
  }
  const std::string text(first, last);  // strtod needs the terminating NUL
  static const locale_t c_locale = newlocale(LC_ALL_MASK, "C", locale_t{});
  if (c_locale == locale_t{}) return {first, std::errc::not_enough_memory};  // strtod_l needs one
  char* end = nullptr;
  const int errno_before = errno;  // from_chars leaves errno alone: so does this
  errno = 0;
  const double parsed = strtod_l(text.c_str(), &end, c_locale);
  const bool out_of_range = errno == ERANGE;
  errno = errno_before;
  if (end == text.c_str()) return {first, std::errc::invalid_argument};
  const char* ptr = first + (end - text.c_str());
  // As from_chars: out of range when it overflows, or when a nonzero number rounds to zero
  // ("1e-400"); a subnormal result is a number.
  if (out_of_range && (std::isinf(parsed) || parsed == 0.0)) return {ptr, std::errc::result_out_of_range};
  value = parsed;
  return {ptr, std::errc()};
}

}  // namespace mechgraph::detail
