// Fuzz target: the unit parser (`9.5 mm`, `30 N/mm`, `kg*m^2`). It may refuse a text only with
// UnitError; what it accepts must be finite and must convert back to its own unit exactly enough.
#include <mechgraph/units.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const mechgraph::Quantity q = mechgraph::parse_quantity(text);
    if (!std::isfinite(q.value)) __builtin_trap();  // a number the parser let through must be finite
  } catch (const mechgraph::UnitError&) {
  }
  try {
    const mechgraph::UnitScale u = mechgraph::parse_unit(text);
    if (!std::isfinite(u.scale) || !(u.scale > 0.0) || !std::isfinite(u.offset)) __builtin_trap();
    const double back = mechgraph::to_unit(u.scale * 1.0, u.dimension, text);  // 1 unit in SI, back in the unit
    if (u.offset == 0.0 && std::abs(back - 1.0) > 1e-12) __builtin_trap();
  } catch (const mechgraph::UnitError&) {
  }
  return 0;
}
