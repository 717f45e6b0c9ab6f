// printf_g and printf_f against printf itself (a second method): this process runs in the "C"
// locale, where snprintf's text is the one they must give in every locale.
#include <mechgraph/printf_number.hpp>

#include <catch2/catch.hpp>

#include <clocale>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

std::string by_snprintf(const char* format, int precision, double x) {
  char buffer[512];
  const int n = std::snprintf(buffer, sizeof buffer, format, precision, x);
  REQUIRE((n > 0 && n < static_cast<int>(sizeof buffer)));
  return buffer;
}

std::vector<double> awkward_values() {
  const double inf = std::numeric_limits<double>::infinity();
  return {0.0, -0.0, 1.0, -1.0, 0.5, 0.25, 0.125, 2.5, 0.05, 0.15, 1e-5, 9.9999995e-5, 123456.5, 999999.5, 1e6, 1e15,
          1e16, 1e17, 1e21, 1e22, 1e100, 1e300, std::numeric_limits<double>::max(), std::numeric_limits<double>::min(),
          std::numeric_limits<double>::denorm_min(), 5e-324, 2.2250738585072009e-308, std::nextafter(1.0, 2.0),
          std::nextafter(1.0, 0.0), 4.35, 0.1 + 0.2, 1.0 / 3.0, inf, -inf};
}

}  // namespace

TEST_CASE("printf_g: printf's %.*g as the C locale writes it", "[sdk][printf_number]") {
  REQUIRE(std::string(std::setlocale(LC_NUMERIC, nullptr)) == "C");
  for (const double x : awkward_values())
    for (int precision = 1; precision <= 17; ++precision) {
      INFO(x << " %." << precision << "g");
      CHECK(mechgraph::printf_g(x, precision) == by_snprintf("%.*g", precision, x));
    }
  std::mt19937_64 random(29);
  std::uniform_real_distribution<double> exponent(-310.0, 309.0);
  std::uniform_int_distribution<int> digits(1, 17);
  for (int k = 0; k < 20000; ++k) {
    const double x = (k % 2 ? -1.0 : 1.0) * std::pow(10.0, exponent(random));
    const int precision = digits(random);
    INFO(x << " %." << precision << "g");
    REQUIRE(mechgraph::printf_g(x, precision) == by_snprintf("%.*g", precision, x));
  }
  CHECK(mechgraph::printf_g(0.1) == "0.1");  // six digits by default
  CHECK(mechgraph::printf_g(1.0 / 3.0) == "0.333333");
  CHECK(mechgraph::printf_g(0.25, 0) == "0.2");  // precision 0 counts as 1, as in printf
  for (const double nan : {std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::quiet_NaN(), 0.0 * std::numeric_limits<double>::infinity()}) {
    CHECK(mechgraph::printf_g(nan) == by_snprintf("%.*g", 6, nan));
    CHECK(mechgraph::printf_f(nan, 2) == by_snprintf("%.*f", 2, nan));
  }
  CHECK(mechgraph::printf_g(-std::numeric_limits<double>::quiet_NaN()) == "-nan");
  for (int precision = 18; precision <= 40; ++precision) {  // more digits than a double holds
    CHECK(mechgraph::printf_g(0.1, precision) == by_snprintf("%.*g", precision, 0.1));
    CHECK(mechgraph::printf_g(-1.0 / 3.0, precision) == by_snprintf("%.*g", precision, -1.0 / 3.0));
  }
}

TEST_CASE("printf_f: printf's %.*f as the C locale writes it, the largest double included", "[sdk][printf_number]") {
  REQUIRE(std::string(std::setlocale(LC_NUMERIC, nullptr)) == "C");
  for (const double x : awkward_values())
    for (int decimals = 0; decimals <= 6; ++decimals) {
      INFO(x << " %." << decimals << "f");
      CHECK(mechgraph::printf_f(x, decimals) == by_snprintf("%.*f", decimals, x));
    }
  std::mt19937_64 random(31);
  std::uniform_real_distribution<double> exponent(-8.0, 20.0);
  for (int k = 0; k < 20000; ++k) {
    const double x = (k % 2 ? -1.0 : 1.0) * std::pow(10.0, exponent(random));
    const int decimals = k % 5;
    INFO(x << " %." << decimals << "f");
    REQUIRE(mechgraph::printf_f(x, decimals) == by_snprintf("%.*f", decimals, x));
  }
  CHECK(mechgraph::printf_f(2.25, 1) == "2.2");  // ties to even on the binary value, as printf
  CHECK(mechgraph::printf_f(-0.04, 1) == "-0.0");
  CHECK(mechgraph::printf_f(std::numeric_limits<double>::max(), 40) == by_snprintf("%.*f", 40, std::numeric_limits<double>::max()));
  CHECK(mechgraph::printf_f(-std::numeric_limits<double>::max(), 40).size() == 1 + 309 + 1 + 40);
}
