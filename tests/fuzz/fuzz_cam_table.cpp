// Fuzz target: cam.table's CSV reader and the spline it builds. A table may be refused only with
// NodeError (naming the line); a table it accepts gives a finite lift and derivatives everywhere.
#include "table_law.hpp"

#include <mechgraph/errors.hpp>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto table = mechgraph::cams::parse_lift_table(text, "fuzz.csv", std::numbers::pi / 180.0, 1e-3);
    const mechgraph::cams::TableLaw law(table, 0.017);
    for (int i = 0; i <= 64; ++i) {
      const double phi = -std::numbers::pi + 2.0 * std::numbers::pi * i / 64.0;
      const mechgraph::LiftDerivatives d = law.at(phi);
      if (!std::isfinite(d.lift) || !std::isfinite(d.velocity) || !std::isfinite(d.acceleration) || !std::isfinite(d.jerk))
        __builtin_trap();
    }
  } catch (const mechgraph::NodeError&) {
  }
  return 0;
}
