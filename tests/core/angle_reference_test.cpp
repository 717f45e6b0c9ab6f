// Which angle a value counts, as a label shows it (core/include/mechgraph/host/angle_reference.hpp):
// the rule the terminal, the CSV headers, the sweep's header and Python share.
#include <mechgraph/host/angle_reference.hpp>
#include <mechgraph/units.hpp>

#include <catch2/catch.hpp>

using mechgraph::host::unit_with_reference;
using mechgraph::host::unit_without_reference;

TEST_CASE("angle reference: units of degrees carry it, others and radians do not", "[host][units]") {
  CHECK(unit_with_reference("deg", "crank") == "deg (crank)");
  CHECK(unit_with_reference("mm/deg^2", "cam") == "mm/deg^2 (cam)");
  CHECK(unit_with_reference("rad", "crank") == "rad");
  CHECK(unit_with_reference("mm", "cam") == "mm");
  CHECK(unit_with_reference("deg", "") == "deg");
  CHECK(unit_with_reference("", "cam").empty());
}

TEST_CASE("angle reference: taken off again, the unit parses to the same scale", "[host][units]") {
  for (const char* unit : {"deg", "mm/deg", "mm/deg^2", "mm^2*deg", "m/deg^3"}) {
    INFO(unit);
    const std::string tagged = unit_with_reference(unit, "crank");
    CHECK(tagged != unit);
    CHECK(unit_without_reference(tagged) == unit);
    const mechgraph::UnitScale a = mechgraph::parse_unit(unit_without_reference(tagged)), b = mechgraph::parse_unit(unit);
    CHECK(a.scale == b.scale);
    CHECK(a.dimension == b.dimension);
  }
  // Nothing else is cut: no reference, a unit without degrees, text that only looks like one.
  CHECK(unit_without_reference("deg") == "deg");
  CHECK(unit_without_reference("mm (cam)") == "mm (cam)");
  CHECK(unit_without_reference("deg (crank") == "deg (crank");
  CHECK(unit_without_reference("") == "");
}
