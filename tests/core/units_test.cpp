#include <mechgraph/units.hpp>

#include <catch2/catch.hpp>

#include <numbers>

using namespace mechgraph;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinRel;

TEST_CASE("quantities parse into SI", "[units]") {
  CHECK_THAT(parse_quantity("9.5 mm").value, WithinRel(9.5e-3, 1e-15));
  CHECK(parse_quantity("9.5 mm").dimension == dim::length);
  CHECK_THAT(parse_quantity("140 deg").value, WithinRel(140.0 * std::numbers::pi / 180.0, 1e-15));
  CHECK_THAT(parse_quantity("5600 rpm").value, WithinRel(5600.0 * 2.0 * std::numbers::pi / 60.0, 1e-15));
  CHECK(parse_quantity("5600 rpm").dimension == dim::angular_speed);
  CHECK_THAT(parse_quantity("-0.04mm").value, WithinRel(-4e-5, 1e-15));
  CHECK_THAT(parse_quantity("1 in").value, WithinRel(0.0254, 1e-15));
  CHECK_THAT(parse_quantity("25 um").value, WithinRel(25e-6, 1e-15));
  CHECK_THAT(parse_quantity("30 N/mm").value, WithinRel(30e3, 1e-15));
  CHECK(parse_quantity("30 N/mm").dimension == dim::stiffness);
  CHECK_THAT(parse_quantity("7850 kg/m^3").value, WithinRel(7850.0, 1e-15));
  CHECK(parse_quantity("7850 kg/m^3").dimension == dim::density);
  CHECK(parse_quantity("80 GPa").dimension == dim::stress);
  CHECK_THAT(parse_quantity("80 GPa").value, WithinRel(80e9, 1e-15));
  CHECK(parse_quantity("85 g").dimension == dim::mass);
  CHECK(parse_quantity("2 ms").dimension == dim::time);
  CHECK(parse_quantity("1 mm^2*s").dimension == dim::area * dim::time);
  CHECK_THAT(parse_quantity("1 mm^2*s").value, WithinRel(1e-6, 1e-15));
  CHECK(parse_quantity("3 rad/s").dimension == dim::angular_speed);
  CHECK(parse_quantity("1.5").dimension.dimensionless());
  CHECK_THAT(parse_quantity("20 degC").value, WithinRel(293.15, 1e-15));
  CHECK_THAT(parse_quantity("8 arcmin").value, WithinRel(8.0 / 60.0 * std::numbers::pi / 180.0, 1e-15));
}

TEST_CASE("display units convert back from SI", "[units]") {
  CHECK_THAT(to_unit(9.5e-3, dim::length, "mm"), WithinRel(9.5, 1e-15));
  CHECK_THAT(to_unit(std::numbers::pi, dim::angle, "deg"), WithinRel(180.0, 1e-15));
  CHECK_THAT(to_unit(293.15, dim::temperature, "degC"), Catch::Matchers::WithinAbs(20.0, 1e-12));
  CHECK_THROWS_WITH(to_unit(1.0, dim::length, "deg"), Contains("angle") && Contains("length"));
}

TEST_CASE("bad quantities are errors that say where and what", "[units]") {
  try {
    parse_quantity("9 mmm");
    FAIL("expected an error");
  } catch (const UnitError& e) {
    CHECK_THAT(e.what(), Contains("unknown unit 'mmm'") && Contains("valid units are") && Contains("mm"));
    CHECK(e.column() == 2);
  }
  CHECK_THROWS_WITH(parse_quantity("mm"), Contains("expected a number"));
  CHECK_THROWS_WITH(parse_quantity(""), Contains("found nothing"));
  CHECK_THROWS_WITH(parse_quantity("1 N/mm/s"), Contains("only one '/'"));
  CHECK_THROWS_WITH(parse_quantity("1 m^x"), Contains("integer power"));
  CHECK_THROWS_WITH(parse_quantity("1e999 mm"), Contains("range"));
  CHECK_THROWS_WITH(parse_quantity("1 degC*m"), Contains("degC"));
}

TEST_CASE("dimensions print as SI units", "[units]") {
  CHECK(dim::length.si_unit() == "m");
  CHECK(dim::force.si_unit() == "N");
  CHECK(dim::stress.si_unit() == "Pa");
  CHECK((dim::area * dim::time).si_unit() == "m^2*s");
  CHECK((dim::length / dim::angle.pow(2)).si_unit() == "m/rad^2");
  CHECK(dim::frequency.si_unit() == "1/s");
  CHECK(dim::none.si_unit() == "1");
  CHECK(dim::velocity.describe() == "length/time");
}

TEST_CASE("units found by fuzzing: huge powers, dimension overflow, values beyond a double", "[units][fuzz]") {
  // tests/fuzz found "g*g*mm^222": 1e-666 underflowed the scale to 0 and 222 wrapped the 8-bit
  // length exponent. Each is now a UnitError with its column.
  CHECK_THROWS_WITH(mechgraph::parse_unit("g*g*mm^222"), Catch::Matchers::Contains("power of a unit must lie within -16..16"));
  CHECK_THROWS_WITH(mechgraph::parse_unit("m^16*m^16"), Catch::Matchers::Contains("exponent beyond -16..16"));
  CHECK_THROWS_WITH(mechgraph::parse_unit("cm^16*cm^16/mm^16"), Catch::Matchers::Contains("exponent beyond"));
  CHECK_THROWS_WITH(mechgraph::parse_quantity("1e308 GPa"), Catch::Matchers::Contains("beyond the range of a double"));
  CHECK(mechgraph::parse_unit("mm^16").scale == Approx(1e-48).epsilon(1e-14).margin(0));
  CHECK(mechgraph::parse_quantity("1e300 mm").value == Approx(1e297).epsilon(1e-14).margin(0));
}
