#pragma once
// The units a report's rows are shown in: one rule for the terminal, the page, its CSV and
// Python's report tables (issue 32: units that cannot slip between them).
#include <mechgraph/graph.hpp>
#include <mechgraph/evaluator.hpp>

#include <string>
#include <vector>

namespace mechgraph::cli {

/// The unit a report row without one shows a dimension in when the scene has no `units:` for it
/// and the port no unit of its own: mm, deg, mm/deg^n, mm^2, mm^2*deg, mm^2*s; "" (SI) otherwise.
std::string reader_unit(const Dimension& d);

/// The unit each row of `report` shows its values in ("" : SI): the row's own; else the unit the
/// table already shows that dimension in (one unit per dimension in a table); else the scene's
/// `units:` or the port's own unit; else reader_unit. A row with no cell: its own. The one rule of the
/// terminal, the page, the CSV and Python's report tables.
std::vector<std::string> report_row_units(const ResolvedReport& report, const RunResult& result, const Graph& graph);

}  // namespace mechgraph::cli
