#include "report_tables.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/units.hpp>

#include <algorithm>

namespace mechgraph::python {

std::vector<ReportTableValues> report_table_values(const Graph& graph, const RunResult& result) {
  std::vector<ReportTableValues> tables;
  for (const ResolvedReport& report : graph.reports) {
    ReportTableValues table{report.title, report.columns, {}};
    std::vector<std::pair<Dimension, std::string>> chosen;  // one unit per dimension in a table
    for (const ResolvedReport::Row& row : report.rows) {
      ReportTableValues::Row out{row.label, row.unit, {}};
      bool unit_known = false;
      for (const auto& cell : row.cells) {
        if (!cell) {
          out.values.emplace_back();
          continue;
        }
        const OutputValue& o = result.outputs.at(cell->output);
        const double value = report_cell_value(result, row, *cell);
        if (!unit_known) {
          const auto known = std::find_if(chosen.begin(), chosen.end(), [&](const auto& c) { return c.first == o.dimension; });
          if (!row.unit.empty()) out.unit = row.unit;
          else if (known != chosen.end()) out.unit = known->second;
          else out.unit = graph.display_units.unit_for(o.dimension, o.display_unit);
          if (out.unit.empty() && !o.dimension.dimensionless()) out.unit = o.dimension.si_unit();
          if (known == chosen.end()) chosen.emplace_back(o.dimension, out.unit);
          unit_known = true;
        }
        out.values.push_back(out.unit.empty() ? value : to_unit(value, o.dimension, out.unit));
      }
      table.rows.push_back(std::move(out));
    }
    tables.push_back(std::move(table));
  }
  return tables;
}

}  // namespace mechgraph::python
