#include "report_units.hpp"

#include <algorithm>

namespace mechgraph::cli {

std::string reader_unit(const Dimension& d) {
  // A length and its derivatives over an angle, lengths, angles and areas the way a drawing gives
  // them; everything else stays SI (N, m/s, Hz ...).
  const Dimension per_angle[] = {dim::length / dim::angle, dim::length / dim::angle.pow(2), dim::length / dim::angle.pow(3)};
  const char* per_angle_unit[] = {"mm/deg", "mm/deg^2", "mm/deg^3"};
  for (std::size_t n = 0; n < 3; ++n)
    if (d == per_angle[n]) return per_angle_unit[n];
  if (d == dim::length) return "mm";
  if (d == dim::angle) return "deg";
  if (d == dim::area) return "mm^2";
  if (d == dim::area * dim::angle) return "mm^2*deg";
  if (d == dim::area * dim::time) return "mm^2*s";
  return {};
}

std::vector<std::string> report_row_units(const ResolvedReport& report, const RunResult& result, const Graph& graph) {
  // 0.0085 mm/deg^2 and 0.0439 m/rad^2 never stand one under the other.
  std::vector<std::pair<Dimension, std::string>> chosen;
  std::vector<std::string> units;
  for (const auto& row : report.rows) {
    const auto first = std::find_if(row.cells.begin(), row.cells.end(), [](const auto& c) { return c.has_value(); });
    if (first == row.cells.end()) {
      units.push_back(row.unit);
      continue;
    }
    const OutputValue& o = result.outputs[(*first)->output];
    const auto known = std::find_if(chosen.begin(), chosen.end(), [&](const auto& c) { return c.first == o.dimension; });
    std::string unit = row.unit;
    if (unit.empty() && known != chosen.end()) unit = known->second;
    if (unit.empty()) unit = graph.display_units.unit_for(o.dimension, o.display_unit);
    if (unit.empty()) unit = reader_unit(o.dimension);
    if (known == chosen.end()) chosen.emplace_back(o.dimension, unit);
    units.push_back(unit);
  }
  return units;
}

}  // namespace mechgraph::cli
