// append_printf_g15 (core/include/mechgraph/printf_g15.hpp) against glibc's snprintf "%.15g".
#include <mechgraph/printf_g15.hpp>

#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

using namespace mechgraph;

namespace {

std::string by_printf(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.15g", x);
  return buffer;
}

std::string by_g15(double x) {
  std::string out = "row,";  // appended, as a row is written
  append_printf_g15(out, x);
  return out.substr(4);
}

}  // namespace

TEST_CASE("printf_g15: the text of snprintf's %.15g, at the edges of its range and on ties", "[core][printf_g15]") {
  const double cases[] = {1.0, -1.0, 0.1, 8.682898997505212, 134.72494982285508, 0.16637924865811543, 6162.0407036911765,
                          1e-5, 1e-4, 9.99999999999999e-5, 0.0001234567890123456, 99999999999999.99, 99999999999999.9,
                          999999999999999.0, 999999999999999.9, 1e15, 1e14, 123456789012345.6, 0.5, 2.5, 1e-6,
                          // ties at the 16th digit, exactly representable: half to even
                          100000000000000.5, 100000000000001.5, 123456789012344.5, 123456789012345.5, 0.000125,
                          std::nextafter(1e-5, 0.0), std::nextafter(1e15, 0.0), std::nextafter(1.0, 2.0),
                          std::nextafter(1.0, 0.0), std::nextafter(0.1, 1.0), 0.0, -0.0, 5e-324, 1e300, -1e-300,
                          std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (double x : cases) {
    INFO(by_printf(x));
    CHECK(by_g15(x) == by_printf(x));
    CHECK(by_g15(-x) == by_printf(-x));
  }
  CHECK(by_g15(100000000000000.5) == "100000000000000");  // a tie to the even digit
  CHECK(by_g15(100000000000001.5) == "100000000000002");
  CHECK(by_g15(1e-5) == "1e-05");
  CHECK(by_g15(99999999999999.99) == "100000000000000");
}

TEST_CASE("printf_g15: the text of snprintf's %.15g over many decades and every bit pattern", "[core][printf_g15]") {
  std::mt19937_64 random(20261130);
  std::uniform_real_distribution<double> decade(-8.0, 17.0);
  for (int i = 0; i < 1000000; ++i) {
    // Log-uniform from 1e-8 to 1e17 (the integer path's range and beyond), then a random pattern of bits.
    double x = std::pow(10.0, decade(random)) * ((random() & 1) ? -1.0 : 1.0);
    if (i % 4 == 3) x = std::bit_cast<double>(random());
    if (std::isnan(x)) continue;
    const std::string want = by_printf(x), got = by_g15(x);
    if (got != want) {
      INFO(want);
      REQUIRE(got == want);
    }
  }
  // Values with few digits, as a cell holds: k / 10^j.
  for (std::int64_t k = 1; k < 200000; k += 7)
    for (double scale : {1.0, 1e-3, 1e-5, 1e3, 1e9}) {
      const double x = static_cast<double>(k) * scale;
      if (by_g15(x) != by_printf(x)) {
        INFO(by_printf(x));
        REQUIRE(by_g15(x) == by_printf(x));
      }
    }
}
