#pragma once
// `mechgraph report`: one self-contained HTML page of a run (no network: styles and SVG plots
// inline) with the CSV behind every plot and table beside it. Plots are drawn by gnuplot (Debian's
// gnuplot-nox, svg terminal without its mouse script): tables that share a port name are overlaid
// channel by channel (every node's derivative panel together), a single table's channels of one dimension
// share a plot (a computed against a prescribed motion), closed curves are drawn to scale,
// labelled series become bar charts (contributions); small tables are shown as tables.
#include "provenance.hpp"

#include <mechgraph/evaluator.hpp>
#include <mechgraph/graph.hpp>

#include <filesystem>

namespace mechgraph::cli {

/// Writes report.html and its CSVs into `dir` (an empty staging folder). Throws IoError when gnuplot
/// is missing or fails, naming the figure.
void write_report_page(const std::filesystem::path& dir, const Graph& graph, const RunResult& result,
                       const PluginRegistry& registry, const RunInputs& inputs);

}  // namespace mechgraph::cli
