#pragma once
// A scene's report tables (`report:`) as numbers for the Python module's DataFrames: one row per
// report row with its label, its unit and one value per column (none for an empty cell). A row is
// shown in its own `unit:`, else in the unit the table shows its dimension in: the scene's
// display units (`units:`), else the unit of the first row of that dimension (its port's own),
// else SI. The command line's printed table rounds to 6 digits; these are the doubles.
#include <mechgraph/evaluator.hpp>
#include <mechgraph/graph.hpp>

#include <optional>
#include <string>
#include <vector>

namespace mechgraph::python {

struct ReportTableValues {
  std::string title;
  std::vector<std::string> columns;
  struct Row {
    std::string label;
    std::string unit;                            // "" when dimensionless
    std::vector<std::optional<double>> values;  // per column
  };
  std::vector<Row> rows;
};

/// The report tables of a run of `graph` (empty when the run asked for its own outputs).
std::vector<ReportTableValues> report_table_values(const Graph& graph, const RunResult& result);

}  // namespace mechgraph::python
