#pragma once
// The files and text a run leaves: results.json (outputs, work, notes, provenance), one CSV per
// series or table (in the scene's display units; closed curves also as DXF), and the report tables
// as text or as cells (for CSV and HTML). `run`, `report` and `sweep` share them.
#include "provenance.hpp"

#include <mechgraph/evaluator.hpp>
#include <mechgraph/graph.hpp>

#include "cli.hpp"
#include "declared_port.hpp"

#include <mechgraph/host/angle_reference.hpp>
#include <mechgraph/host/report_units.hpp>

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace mechgraph::cli {

/// The whole result as one JSON object: outputs (SI), evaluated and reused nodes, work, notes,
/// effects and provenance.
void write_json(std::ostream& os, const Graph& graph, const RunResult& result, const PluginRegistry& registry,
                const RunInputs& inputs);

// Angle references (the frame a port declares, "deg (shaft)"): host::angle_reference and
// host::unit_with_reference, the rule the sweep's header and Python share.
using host::angle_reference;
using host::unit_with_reference;



/// A report table as cells: the header row (label, unit, the columns), then a row per report row,
/// values formatted with 6 significant digits in the row's unit; a row without one shows its
/// dimension in the scene's display unit, else in the unit the table's first row of that
/// dimension used (its port's own, else reader_unit), one unit per dimension. Units of degrees
/// say which angle (the port's declared frame).
std::vector<std::vector<std::string>> report_cells(const ResolvedReport& report, const RunResult& result, const Graph& graph);
/// The same as aligned text under its title.
void print_report(std::ostream& os, const ResolvedReport& report, const RunResult& result, const Graph& graph);
/// The same as CSV: "name [unit]" is not used here, the unit is its own column.
void write_report_csv(const std::filesystem::path& file, const ResolvedReport& report, const RunResult& result,
                      const Graph& graph);

/// Short series inline ([a, b, c] unit), labelled ones by name, long ones as a count.
void print_series(std::ostream& os, const OutputValue& o);

/// One CSV per table / series output; header `name [unit]` in the scene's display units, a unit of
/// degrees followed by the angle its column declares it counts ("opening [deg (shaft)]").
void write_table_csv(const std::filesystem::path& file, const Table& t, const DisplayUnits& units,
                     const DeclaredPort& declared = {});
/// The same with each column's unit given: `column_units` holds the axis's and then each channel's
/// ("" keeps SI). A report writes its tables' CSVs in the units its page shows (deg, mm ...).
/// A channel with declared codes (presentation.hpp) is followed by a column "<channel>_name" with
/// each row's code name.
void write_table_csv(const std::filesystem::path& file, const Table& t, const std::vector<std::string>& column_units,
                     const DeclaredPort& declared = {});
void write_csv(const std::filesystem::path& file, const OutputValue& o, const DisplayUnits& units, const DeclaredPort& declared = {});

/// Every file of `run --out` into `dir`: results.json, a CSV per series/table output, a DXF per
/// closed curve.
void write_result_files(const std::filesystem::path& dir, const Graph& graph, const RunResult& result,
                        const PluginRegistry& registry, const RunInputs& inputs);

}  // namespace mechgraph::cli
