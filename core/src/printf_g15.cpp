// "%.15g" by 128-bit integer arithmetic: see printf_g15.hpp for the method and its range.
#include <mechgraph/printf_g15.hpp>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>

namespace mechgraph {
namespace {

// std::to_chars with a precision: printf's "%.15g" by the standard's definition.
void append_by_to_chars(std::string& out, double x) {
  char buffer[40];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, 15);
  out.append(buffer, end);
}

constexpr std::uint64_t power_of_ten(int k) {
  std::uint64_t p = 1;
  for (int i = 0; i < k; ++i) p *= 10;
  return p;
}

}  // namespace

void append_printf_g15(std::string& out, double x) {
  const double a = std::abs(x);
  if (!(a >= 1e-5 && a < 1e15)) {  // zero, NaN and the far ranges (subnormals among them)
    append_by_to_chars(out, x);
    return;
  }
  // a = m 2^e exactly, m with its leading bit, e <= 0 in this range.
  const auto bits = std::bit_cast<std::uint64_t>(a);
  const std::uint64_t m = (bits & ((std::uint64_t{1} << 52) - 1)) | (std::uint64_t{1} << 52);
  const int e = static_cast<int>(bits >> 52) - 1075;
  const int shift = -e;  // 0 .. about 70
  // X from the binary exponent (floor((e + 52) log10 2), off by one at most), then corrected so
  // that the integer part of a 10^(14 - X) has 15 digits.
  const int binary_exponent = e + 52;
  int lead = (binary_exponent * 78913) >> 18;  // 78913 / 2^18 = log10(2) to 6 digits; >> floors
  __extension__ typedef unsigned __int128 u128;  // GCC and Clang on 64-bit targets
  constexpr std::uint64_t low = power_of_ten(14), high = power_of_ten(15);
  std::uint64_t n = 0;
  u128 remainder = 0;
  for (int attempt = 0; attempt < 3; ++attempt) {
    const int k = 14 - lead;  // 0 .. 19 in this range
    if (k < 0 || k > 19) {
      append_by_to_chars(out, x);
      return;
    }
    static constexpr std::uint64_t powers[20] = {
        power_of_ten(0),  power_of_ten(1),  power_of_ten(2),  power_of_ten(3),  power_of_ten(4),
        power_of_ten(5),  power_of_ten(6),  power_of_ten(7),  power_of_ten(8),  power_of_ten(9),
        power_of_ten(10), power_of_ten(11), power_of_ten(12), power_of_ten(13), power_of_ten(14),
        power_of_ten(15), power_of_ten(16), power_of_ten(17), power_of_ten(18), power_of_ten(19)};
    const u128 scaled = static_cast<u128>(m) * powers[k];  // < 2^53 * 10^19 < 2^117: exact
    const u128 whole = shift >= 128 ? 0 : scaled >> shift;
    remainder = shift == 0 ? 0 : scaled & ((u128{1} << shift) - 1);
    if (whole >= high) {
      ++lead;
    } else if (whole < low) {
      --lead;
    } else {
      n = static_cast<std::uint64_t>(whole);
      break;
    }
  }
  if (n == 0) {  // never met: the estimate is off by one at most
    append_by_to_chars(out, x);
    return;
  }
  // Round half to even on the exact remainder.
  if (shift > 0) {
    const u128 half = u128{1} << (shift - 1);
    if (remainder > half || (remainder == half && (n & 1) != 0)) ++n;
  }
  if (n == high) {  // 999...9 rounded up: one more decimal place
    n = low;
    ++lead;
  }
  if (lead >= 15) {  // 99999999999999.99... rounded up to 1e15: "%g"'s scientific form
    append_by_to_chars(out, x);
    return;
  }
  // The 15 digits, two at a time from the right, then the layout into one buffer, appended once.
  static constexpr char pairs[] =
      "00010203040506070809101112131415161718192021222324252627282930313233343536373839404142434445464748495051525354555657"
      "585960616263646566676869707172737475767778798081828384858687888990919293949596979899";
  char digits[16];
  std::uint64_t rest = n;
  for (int i = 13; i >= 1; i -= 2) {
    const auto two = static_cast<std::size_t>(rest % 100) * 2;
    rest /= 100;
    digits[i] = pairs[two];
    digits[i + 1] = pairs[two + 1];
  }
  digits[0] = static_cast<char>('0' + rest);  // n < 10^15: one digit left
  std::size_t count = 15;
  while (count > 1 && digits[count - 1] == '0') --count;
  char text[32];
  char* at = text;
  if (x < 0.0) *at++ = '-';
  if (lead < -4) {  // scientific: d.ddde-05 (lead is -5 in this range)
    *at++ = digits[0];
    if (count > 1) {
      *at++ = '.';
      at = std::copy(digits + 1, digits + count, at);
    }
    *at++ = 'e';
    *at++ = '-';
    *at++ = static_cast<char>('0' + (-lead) / 10);
    *at++ = static_cast<char>('0' + (-lead) % 10);
  } else if (lead >= 0) {
    const std::size_t whole_digits = static_cast<std::size_t>(lead) + 1;
    if (count <= whole_digits) {
      at = std::copy(digits, digits + count, at);
      at = std::fill_n(at, whole_digits - count, '0');
    } else {
      at = std::copy(digits, digits + whole_digits, at);
      *at++ = '.';
      at = std::copy(digits + whole_digits, digits + count, at);
    }
  } else {
    *at++ = '0';
    *at++ = '.';
    at = std::fill_n(at, -lead - 1, '0');
    at = std::copy(digits, digits + count, at);
  }
  out.append(text, static_cast<std::size_t>(at - text));
}

}  // namespace mechgraph
