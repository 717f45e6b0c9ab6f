// Numbers as a person reads them: six significant digits, rounding noise beside larger values of the
// same quantity shown as 0, an angle also read against a full turn (core/include/mechgraph/shown_number.hpp).
#include <mechgraph/shown_number.hpp>

#include <catch2/catch.hpp>

#include <clocale>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <limits>
#include <numbers>

using namespace mechgraph;

TEST_CASE("shown_number: six significant digits, and 0 for -0", "[core][shown_number]") {
  CHECK(shown_number(52.7388382490334, 0.92, 0.0) == "52.7388");
  CHECK(shown_number(-1.5e-5, -1.5e-5, 0.0) == "-1.5e-05");
  CHECK(shown_number(-0.0, -0.0, 0.0) == "0");
  CHECK(shown_number(0.0, 0.0, 1.0) == "0");
}

TEST_CASE("shown_number: a value below the noise floor reads 0, one at the floor keeps its digits", "[core][shown_number]") {
  // Beside 0.92 rad (52.7 deg), a midpoint of 6.1e-13 rad (3.5e-11 deg) is the operands' rounding.
  const double floor = noise_floor(dim::angle, 0.92);
  CHECK(floor == Approx(noise_ratio * 2.0 * std::numbers::pi).epsilon(1e-15).margin(0));  // a turn is larger
  CHECK(shown_number(3.5e-11, 3.5e-11 * std::numbers::pi / 180.0, floor) == "0");
  CHECK(shown_number(-2.2e-14, -2.2e-14 * std::numbers::pi / 180.0, floor) == "0");
  // 1e-8 rad beside a turn is 1.6e-9 of it: kept (0.00057 arc seconds is a real, if tiny, angle).
  CHECK(shown_number(1e-8 * 180.0 / std::numbers::pi, 1e-8, floor) == "5.72958e-07");
  // A length has no natural scale: alone it keeps every digit, beside 280 um it is read against them.
  CHECK(noise_floor(dim::length, 0.0) == 0.0);
  CHECK(shown_number(1.1e-11, 1.1e-11, noise_floor(dim::length, 0.0)) == "1.1e-11");
  CHECK(shown_number(1.1e-8, 1.1e-14, noise_floor(dim::length, 2.8e-4)) == "0");
  CHECK(shown_number(1.09797e-5, 1.09797e-11, noise_floor(dim::length, 2.8e-4)) == "1.09797e-05");  // 4e-8 of it
  // Not finite: shown as it is (a node never gives one; a file being read may).
  CHECK(noise_floor(dim::length, std::numeric_limits<double>::infinity()) == 0.0);
  CHECK(shown_number(std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN(), 1.0) == "nan");
}

TEST_CASE("table_largest: the largest finite magnitude of the columns of one dimension", "[core][shown_number]") {
  Table t;
  t.axis = {"h", dim::length, {0.001, 0.00127, 0.0}, "mm"};
  t.channels.push_back({"a", dim::angle, {-0.92, 0.92, -1.13}, "deg"});
  t.channels.push_back({"b", dim::angle, {6.1e-13, std::numeric_limits<double>::infinity(), 6.1e-13}, "deg"});
  CHECK(table_largest(t, dim::angle) == 1.13);
  CHECK(table_largest(t, dim::length) == 0.00127);
  CHECK(table_largest(t, dim::mass) == 0.0);
}

TEST_CASE("shown_number: printf's %.6g as the C locale writes it (second method)", "[core][shown_number]") {
  // The test process runs in the "C" locale: snprintf there is the reference the text must equal,
  // which a program's locale (a decimal comma) no longer changes.
  REQUIRE(std::string(std::setlocale(LC_NUMERIC, nullptr)) == "C");
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0);
  for (int k = 0; k < 20000; ++k) {
    const double x = (k % 2 ? -1.0 : 1.0) * std::pow(10.0, exponent(random)) * (k % 5 ? 1.0 : 0.999999951);
    char expected[40];
    std::snprintf(expected, sizeof expected, "%.6g", x);
    REQUIRE(shown_number(x, x, 0.0) == expected);
  }
}
