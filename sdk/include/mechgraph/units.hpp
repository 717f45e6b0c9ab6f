#pragma once
// Units live only at the boundary: scene text is parsed into SI here, and reports format SI
// values back into a display unit here. Nothing inside a node ever sees a non-SI number.
#include <mechgraph/dimension.hpp>

#include <stdexcept>
#include <string>
#include <string_view>

namespace mechgraph {

/// A number with its dimension, in SI.
struct Quantity {
  double value = 0.0;
  Dimension dimension{};
};

/// A unit expression resolved to SI: value_si = (value + offset) * scale.
struct UnitScale {
  double scale = 1.0;
  double offset = 0.0;  // only for affine temperature units (degC)
  Dimension dimension{};
};

/// Thrown by the parsers; `column` is the 0-based offset into the text where the problem is.
class UnitError : public std::runtime_error {
 public:
  UnitError(const std::string& what, std::size_t column) : std::runtime_error(what), column_(column) {}
  std::size_t column() const { return column_; }

 private:
  std::size_t column_;
};

/// Parses a unit expression: symbols joined by '*' or '/', each with an optional integer power
/// ('^2', '^-1'), e.g. "mm", "N/mm", "kg/m^3", "m^2*s", "rad/s". "" is dimensionless.
UnitScale parse_unit(std::string_view text);

/// Parses "9.5 mm", "140 deg", "5600 rpm", "1e-3", "-0.04mm" into SI.
Quantity parse_quantity(std::string_view text);

/// Converts an SI value to a display unit; throws UnitError if the dimensions differ or it overflows.
double to_unit(double value_in_si, Dimension dimension, std::string_view unit);

/// The unit symbols the parser knows, for error messages ("valid units are ...").
std::string known_unit_symbols();

}  // namespace mechgraph
