// Numbers as a person reads them: see shown_number.hpp for the rule and why.
#include "mechgraph/shown_number.hpp"

#include <mechgraph/printf_number.hpp>
#include <mechgraph/units.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mechgraph {

double noise_floor(const Dimension& dimension, double largest_si) {
  double scale = std::isfinite(largest_si) ? std::abs(largest_si) : 0.0;
  if (dimension == dim::angle) scale = std::max(scale, 2.0 * std::numbers::pi);  // a full turn
  return noise_ratio * scale;
}

double table_largest(const Table& table, const Dimension& dimension) {
  double largest = 0.0;
  auto scan = [&](const Table::Column& c) {
    if (c.dimension != dimension) return;
    for (double v : c.values)
      if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
  };
  scan(table.axis);
  for (const Table::Column& c : table.channels) scan(c);
  return largest;
}

std::string shown_number(double shown, double si, double floor) {
  if (shown == 0.0 || (std::isfinite(si) && std::abs(si) < floor)) return "0";
  // printf's "%.6g" as the C locale writes it, whatever the program's locale (a Python session
  // may have set one with a decimal comma).
  return printf_g(shown, 6);
}

std::string format_value(double si, Dimension dimension, const std::string& unit) {
  double shown = si;
  std::string label = unit;
  if (unit.empty()) {
    label = dimension.si_unit();
    if (label == "1") label.clear();
  } else {
    shown = to_unit(si, dimension, unit);
  }
  const std::string number = shown_number(shown, si, noise_floor(dimension, 0.0));
  return label.empty() ? number : number + " " + label;
}

}  // namespace mechgraph
