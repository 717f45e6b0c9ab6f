// Numbers as a person reads them: see shown_number.hpp for the rule and why.
#include "mechgraph/shown_number.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
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
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", shown);
  return buffer;
}

}  // namespace mechgraph
