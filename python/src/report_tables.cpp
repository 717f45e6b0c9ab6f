#include "report_tables.hpp"

#include <report_units.hpp>

#include <mechgraph/errors.hpp>
#include <mechgraph/units.hpp>

#include <algorithm>

namespace mechgraph::python {

std::vector<ReportTableValues> report_table_values(const Graph& graph, const RunResult& result) {
  std::vector<ReportTableValues> tables;
  for (const ResolvedReport& report : graph.reports) {
    ReportTableValues table{report.title, report.columns, {}};
    // The units of the terminal and the page: one rule (hosts/cli/result_files.hpp).
    const std::vector<std::string> units = cli::report_row_units(report, result, graph);
    for (std::size_t r = 0; r < report.rows.size(); ++r) {
      const ResolvedReport::Row& row = report.rows[r];
      ReportTableValues::Row out{row.label, units[r], {}};
      for (const auto& cell : row.cells) {
        if (!cell) {
          out.values.emplace_back();
          continue;
        }
        const OutputValue& o = result.outputs.at(cell->output);
        const double value = report_cell_value(result, row, *cell);
        out.values.push_back(units[r].empty() ? value : to_unit(value, o.dimension, units[r]));
        if (out.unit.empty() && !o.dimension.dimensionless()) out.unit = o.dimension.si_unit();  // SI, named
      }
      table.rows.push_back(std::move(out));
    }
    tables.push_back(std::move(table));
  }
  return tables;
}

}  // namespace mechgraph::python
