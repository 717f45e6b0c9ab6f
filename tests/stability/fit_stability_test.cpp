// Stability table of the Fit and Spring interfaces at the ends of their ranges. Independent
// values: the ISO 286-1 standard tolerance grades (IT table) at the smallest and the largest
// nominal sizes it covers; a spring's rate and stress formulas at the index limits.
#include "test_support.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <string>

using namespace mechgraph;
using namespace mechgraph::testing;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;

namespace {

RunResult fit(const std::string& size, const std::string& hole, const std::string& shaft) {
  return run_yaml("nodes:\n  f: { type: fit.iso286, params: { size: " + size + ", hole: " + hole + ", shaft: " + shaft +
                      " } }\noutputs: [f.hole_upper, f.hole_lower, f.shaft_upper, f.shaft_lower, f.clearance_min, f.clearance_max]\n",
                  project_registry());
}

}  // namespace

TEST_CASE("stability: ISO 286 fits at the smallest and largest sizes match the IT table", "[stability][fits]") {
  struct Row {
    const char* size;
    const char* hole;
    const char* shaft;
    double it_hole_um, it_shaft_um;  // ISO 286-1, table 1
  };
  const Row rows[] = {
      {"1 mm", "H7", "h6", 10, 6},          // up to 3 mm
      {"1 mm", "H11", "h11", 60, 60},
      {"3150 mm", "H7", "h6", 210, 135},    // over 2500 up to 3150 mm
      {"3150 mm", "H11", "h11", 1350, 1350},
  };
  for (const Row& row : rows) {
    INFO(row.size << " " << row.hole << "/" << row.shaft);
    const RunResult r = fit(row.size, row.hole, row.shaft);
    // H: lower deviation 0; h: upper deviation 0 -- the zones are the IT grades themselves.
    CHECK_THAT(scalar_output(r, "f.hole_lower"), WithinAbs(0.0, 1e-15));
    CHECK_THAT(scalar_output(r, "f.hole_upper"), WithinAbs(row.it_hole_um * 1e-6, 1e-12));
    CHECK_THAT(scalar_output(r, "f.shaft_upper"), WithinAbs(0.0, 1e-15));
    CHECK_THAT(scalar_output(r, "f.shaft_lower"), WithinAbs(-row.it_shaft_um * 1e-6, 1e-12));
    CHECK_THAT(scalar_output(r, "f.clearance_max"), WithinAbs((row.it_hole_um + row.it_shaft_um) * 1e-6, 1e-12));
  }
  // Beyond the table: refused naming the size and the limit.
  CHECK_THROWS_WITH(fit("3151 mm", "H7", "h6"), Contains("'size'") && Contains("3150"));
}
