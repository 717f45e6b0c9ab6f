// number_prefix_end (core/include/mechgraph/number_prefix.hpp): where the number that starts a
// value's text ends, as parse_quantity reads it, in no locale.
#include <mechgraph/number_prefix.hpp>
#include <mechgraph/units.hpp>

#include <catch2/catch.hpp>

#include <charconv>
#include <clocale>
#include <cstdlib>
#include <random>
#include <string>

using namespace mechgraph;

TEST_CASE("number_prefix_end: the number that starts a value's text", "[core][units]") {
  CHECK(number_prefix_end("8.5 mm") == 3);
  CHECK(number_prefix_end(" \t+8.5mm") == 6);
  CHECK(number_prefix_end("-0.25") == 5);
  CHECK(number_prefix_end("1e400 m") == 5);  // beyond a double: its digits still end there
  CHECK(number_prefix_end("mm") == 0);
  CHECK(number_prefix_end("") == 0);
  CHECK(number_prefix_end("   ") == 0);
  CHECK(number_prefix_end("+") == 0);
  CHECK(number_prefix_end(".5 rpm") == 2);
  // A hexadecimal text: its "0", as parse_quantity reads it (which then finds no unit "x10").
  CHECK(number_prefix_end("0x10 mm") == 1);
  CHECK_THROWS_AS(parse_quantity("0x10 mm"), UnitError);
}

TEST_CASE("unit_after_number: the unit a value was written in", "[core][units]") {
  CHECK(unit_after_number("8.5 mm") == "mm");
  CHECK(unit_after_number(" +8.5mm ") == "mm");
  CHECK(unit_after_number("4000 N/mm\t") == "N/mm");
  CHECK(unit_after_number("3.5") == "");
  CHECK(unit_after_number("3.5  ") == "");
  CHECK(unit_after_number("roller") == "");  // no number: no unit
  CHECK(unit_after_number("") == "");
}

TEST_CASE("number_prefix_end: where strtod ends in the C locale, for decimal numbers (second method)", "[core][units]") {
  // The test process runs in the "C" locale, where strtod reads a decimal point: the same ends
  // for numbers of every size written as the scene language writes them, with a unit after.
  REQUIRE(std::string(std::setlocale(LC_NUMERIC, nullptr)) == "C");
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0);
  for (int k = 0; k < 20000; ++k) {
    const double x = (k % 2 ? -1.0 : 1.0) * std::pow(10.0, exponent(random));
    char buffer[64];
    const auto printed = std::to_chars(buffer, buffer + 40, x, k % 3 ? std::chars_format::general : std::chars_format::scientific);
    const std::string text = std::string(buffer, printed.ptr) + (k % 4 ? " mm" : "deg");
    char* end = nullptr;
    std::strtod(text.c_str(), &end);
    REQUIRE(number_prefix_end(text) == static_cast<std::size_t>(end - text.c_str()));
  }
}
