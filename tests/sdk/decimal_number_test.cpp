// The SDK's number reader for C++ libraries without floating-point from_chars (libc++ 14: a plugin
// built with clang++ -stdlib=libc++ compiles it) against std::from_chars of this build: the same
// verdict, the same end and the same bits, on awkward texts and on many random ones.
#include "../../sdk/src/decimal_number.hpp"

#include <catch2/catch.hpp>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace {

// Both readers on `text`; a description of the first difference, empty when they agree.
std::string difference(const std::string& text) {
  double by_from_chars = 12345.0, by_strtod = 12345.0;
  const char* first = text.data();
  const char* last = first + text.size();
  const auto a = std::from_chars(first, last, by_from_chars);
  const auto b = mechgraph::detail::read_double_with_strtod(first, last, by_strtod);
  if (a.ec != b.ec) return "'" + text + "': the verdicts differ";
  if (a.ptr != b.ptr) return "'" + text + "': they stop at different characters";
  if (a.ec != std::errc()) return {};
  if (std::isnan(by_from_chars) && std::isnan(by_strtod) && std::signbit(by_from_chars) == std::signbit(by_strtod)) return {};
  if (std::bit_cast<std::uint64_t>(by_from_chars) != std::bit_cast<std::uint64_t>(by_strtod))
    return "'" + text + "': the values differ";
  return {};
}

}  // namespace

TEST_CASE("The strtod number reader agrees with from_chars on awkward texts", "[units][sdk]") {
  const std::vector<std::string> texts = {
      "0", "-0", "1", "-1", ".5", "5.", "-.5", "1e3", "1E3", "1e+3", "1e-3", "1e", "1e+", "1.5e-", "12abc", "3.0 mm",
      "inf", "-inf", "INF", "infinity", "Infinity", "infin", "nan", "-nan", "NaN", "nan(123)", "nan(", "in", "n",
      "1e400", "-1e400", "1e-400", "-1e-400", "1e308", "1.7976931348623157e308", "1.7976931348623159e308",
      "2.2250738585072014e-308", "2.2250738585072011e-308", "4.9406564584124654e-324", "2.4703282292062328e-324",
      "2.4703282292062327e-324", "5e-324", "3e-324", "0.1", "0.30000000000000004", "9007199254740993",
      "123456789012345678901234567890", "0.000000000000000000000000000001", "1" + std::string(400, '0'),
      "0." + std::string(400, '0') + "1", "", "-", ".", "+1", " 1", "\t1", "0x10", "-0x10", "0X1p3", "e5", "--1",
      "1..2", "1.2.3", "1_000", "١", "1\xff", "0e0", "0e-999999", "1e999999", "1e-999999"};
  for (const std::string& t : texts) {
    INFO(t);
    CHECK(difference(t).empty());
  }
}

TEST_CASE("The strtod number reader agrees with from_chars on random numbers", "[units][sdk]") {
  std::mt19937_64 random(20261129);
  std::uniform_int_distribution<std::uint64_t> bits;
  std::uniform_int_distribution<int> digit(0, 9), length(1, 25), exponent(-345, 330), coin(0, 1);
  char buffer[64];
  std::vector<std::string> failures;
  for (int i = 0; i < 20000 && failures.size() < 5; ++i) {
    // Any finite double, written shortest, with 17 digits and with 4 (rounded) digits.
    const double x = std::bit_cast<double>(bits(random));
    if (std::isfinite(x)) {
      const auto r = std::to_chars(buffer, buffer + sizeof buffer, x);
      for (const std::string& t : {std::string(buffer, r.ptr), [&] {
                                     std::snprintf(buffer, sizeof buffer, "%.17g", x);
                                     return std::string(buffer);
                                   }(),
                                   [&] {
                                     std::snprintf(buffer, sizeof buffer, "%.3e", x);
                                     return std::string(buffer);
                                   }()})
        if (std::string d = difference(t); !d.empty()) failures.push_back(d);
    }
    // Random digits with a random exponent: rounding, overflow, underflow and subnormals.
    std::string t = coin(random) ? "-" : "";
    const int n = length(random);
    for (int k = 0; k < n; ++k) {
      t += static_cast<char>('0' + digit(random));
      if (k == 0 && coin(random)) t += '.';
    }
    t += "e" + std::to_string(exponent(random));
    if (std::string d = difference(t); !d.empty()) failures.push_back(d);
  }
  std::string all;
  for (const std::string& f : failures) all += f + "\n";
  CAPTURE(all);
  CHECK(failures.empty());
}
