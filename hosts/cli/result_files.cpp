#include "result_files.hpp"

#include <mechgraph/csv.hpp>
#include <mechgraph/text_escape.hpp>

#include "cli.hpp"
#include "declared_port.hpp"
#include "dxf_writer.hpp"
#include "output_file.hpp"
#include "results_folder.hpp"

#include <mechgraph/errors.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/shown_number.hpp>
#include <mechgraph/units.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <stdexcept>

namespace mechgraph::cli {

// The text of a table's and a series' CSV (below), written whole by write_table_csv / write_csv.
void write_table_rows(std::ostream& out, const Table& t, const DisplayUnits& units, const DeclaredPort& declared);
void write_table_rows(std::ostream& out, const Table& t, const std::vector<std::string>& column_units, const DeclaredPort& declared);
void write_series_rows(std::ostream& out, const OutputValue& o, const DisplayUnits& units, const DeclaredPort& declared);

void write_json(std::ostream& os, const Graph& graph, const RunResult& result, const PluginRegistry& registry,
                const RunInputs& inputs) {
  JsonWriter json(os);
  json.begin_object();
  json.key("title").value(graph.title);
  json.key("outputs").begin_object();
  for (const OutputValue& o : result.outputs) {
    json.key(o.label).begin_object();
    switch (o.value.kind()) {
      case ValueKind::scalar: json.key("value").value(o.value.as_scalar()); break;
      case ValueKind::series:
        json.key("value").numbers(o.value.as_series().values);
        json.key("axis").numbers(o.value.as_series().axis);
        json.key("axis_unit").value(o.value.as_series().axis_dimension.si_unit());
        if (!o.value.as_series().labels.empty()) {
          json.key("labels").begin_array();
          for (const std::string& l : o.value.as_series().labels) json.value(l);
          json.end_array();
          // Named elements (a chain's contributions) also by name, in the display unit (percent).
          if (o.value.as_series().labels.size() == o.value.as_series().values.size()) {
            // Labels may repeat (two links named "bearing"): numbered then, never a key twice.
            const std::vector<std::string> keys = distinct_keys(o.value.as_series().labels);
            json.key("by_label").begin_object();
            for (std::size_t i = 0; i < o.value.as_series().values.size(); ++i) {
              const double v = o.value.as_series().values[i];
              json.key(keys[i]).value(o.display_unit.empty() ? v : to_unit(v, o.dimension, o.display_unit));
            }
            json.end_object();
            json.key("by_label_unit").value(o.display_unit.empty() ? o.dimension.si_unit() : o.display_unit);
          }
        }
        break;
      case ValueKind::handle: json.key("value").null().key("handle").value(o.value.as_handle()->kind()); break;
      case ValueKind::table: {
        // {"axis": name, "columns": {name: {"unit": SI unit, "values": [...]}, ...}}, axis first.
        const Table& t = o.value.as_table();
        std::vector<std::string> names{t.axis.name};
        for (const Table::Column& c : t.channels) names.push_back(c.name);
        const std::vector<std::string> keys = distinct_keys(names);  // a channel named like the axis
        json.key("value").begin_object().key("axis").value(keys[0]).key("columns").begin_object();
        // A channel with declared codes also gives them ({"value", "name", "doc"}) and each row's name.
        const Presentation& presentation = declared_port(graph, o.label).presentation();
        auto column = [&](const Table::Column& c, const std::string& key) {
          json.key(key).begin_object().key("unit").value(c.dimension.si_unit()).key("values").numbers(c.values);
          if (const ChannelDecl* decl = presentation.find(c.name); decl && !decl->codes.empty()) {
            json.key("codes").begin_array();
            for (const Code& code : decl->codes)
              json.begin_object().key("value").value(code.value).key("name").value(code.name).key("doc").value(code.doc).end_object();
            json.end_array();
            json.key("names").begin_array();
            for (double v : c.values) json.value(std::string(decl->code_name(v)));
            json.end_array();
          }
          json.end_object();
        };
        column(t.axis, keys[0]);
        for (std::size_t k = 0; k < t.channels.size(); ++k) column(t.channels[k], keys[k + 1]);
        json.end_object().end_object();
        break;
      }
    }
    json.key("unit").value(o.value.kind() == ValueKind::table ? std::string("table") : o.dimension.si_unit());
    json.end_object();
  }
  json.end_object();
  json.key("evaluated").begin_array();
  for (const NodeRun& r : result.runs)
    if (!r.reused) json.value(r.node);
  json.end_array();
  json.key("reused").begin_array();
  for (const NodeRun& r : result.runs)
    if (r.reused) json.value(r.node);
  json.end_array();
  json.key("nodes").begin_object();
  for (const NodeRun& r : result.runs) {
    json.key(r.node).begin_object();
    json.key("type").value(r.type);
    json.key("seconds").value(r.seconds);
    json.key("work").begin_object();
    for (const auto& [counter, amount] : r.work) json.key(counter).value(amount);
    json.end_object();
    json.end_object();
  }
  json.end_object();
  json.key("effects").begin_array();
  for (const std::string& e : graph.effects) json.value(e);
  json.end_array();
  json.key("notes").begin_object();
  for (const NodeRun& r : result.runs) {
    if (r.notes.empty()) continue;
    json.key(r.node).begin_array();
    for (const std::string& n : r.notes) json.value(n);
    json.end_array();
  }
  json.end_object();
  write_provenance(json, graph, registry, inputs);
  json.end_object();
  os << "\n";
}




std::vector<std::vector<std::string>> report_cells(const ResolvedReport& report, const RunResult& result, const Graph& graph) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> header{"", "unit"};
  for (const std::string& c : report.columns) header.push_back(c);
  rows.push_back(std::move(header));
  const std::vector<std::string> row_units = report_row_units(report, result, graph);
  std::size_t row_index = 0;
  for (const auto& row : report.rows) {
    std::vector<std::string> cells{row.label, row.unit};
    // A row's cells are one quantity side by side: one of them at rounding level beside the others
    // reads 0 (shown_number.hpp).
    double largest = 0.0;
    for (const auto& cell : row.cells)
      if (cell) largest = std::max(largest, std::abs(report_cell_value(result, row, *cell)));
    for (const auto& cell : row.cells) {
      if (!cell) {
        cells.push_back("-");
        continue;
      }
      const OutputValue& o = result.outputs[cell->output];
      const double value = report_cell_value(result, row, *cell);
      const std::string& unit = row_units[row_index];
      if (cells[1] == row.unit && o.dimension.si_unit() != "1") {
        const PortSpec* spec = cell->output < graph.outputs.size() ? graph.outputs[cell->output].spec : nullptr;
        const NodeInfo* info = spec ? &graph.nodes[graph.outputs[cell->output].node].info() : nullptr;
        cells[1] = unit_with_reference(unit.empty() ? o.dimension.si_unit() : unit, info ? angle_reference(*info, *spec) : "");
      }
      const double shown = unit.empty() ? value : to_unit(value, o.dimension, unit);
      cells.push_back(shown_number(shown, value, noise_floor(o.dimension, largest)));
    }
    rows.push_back(std::move(cells));
    ++row_index;
  }
  return rows;
}

void print_report(std::ostream& os, const ResolvedReport& report, const RunResult& result, const Graph& graph) {
  // Labels are the scene's text: no control sequence reaches the terminal.
  auto rows = report_cells(report, result, graph);
  for (auto& r : rows)
    for (std::string& cell : r) cell = terminal_text(cell, TerminalLines::one);
  std::vector<std::size_t> width(rows.front().size(), 0);
  for (const auto& r : rows)
    for (std::size_t i = 0; i < r.size(); ++i) width[i] = std::max(width[i], r[i].size());
  auto print_row = [&](const std::vector<std::string>& r) {
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (i == 0) os << std::left << std::setw(static_cast<int>(width[i])) << r[i];
      else os << "  " << std::right << std::setw(static_cast<int>(width[i])) << r[i];
    }
    os << "\n";
  };
  if (!report.title.empty()) os << terminal_text(report.title) << "\n\n";
  print_row(rows.front());
  std::size_t total = 0;
  for (std::size_t w : width) total += w + 2;
  os << std::string(total - 2, '-') << "\n";
  for (std::size_t r = 1; r < rows.size(); ++r) print_row(rows[r]);
}

// A CSV cell: the one escaping function (RFC 4180 quoting, formula-like text neutralised).
std::string csv_cell(const std::string& text) { return csv_field(text); }

void write_report_csv(const std::filesystem::path& file, const ResolvedReport& report, const RunResult& result,
                      const Graph& graph) {
  auto rows = report_cells(report, result, graph);
  rows.front()[0] = "quantity";
  write_file_whole(file, true, [&](std::ostream& out) {
    for (const auto& r : rows) {
      for (std::size_t i = 0; i < r.size(); ++i) out << (i ? "," : "") << csv_cell(r[i]);
      out << "\n";
    }
  });
}

// Short series inline ([a, b, c] unit), long ones as a count (their CSV is in --out).
void print_series(std::ostream& os, const OutputValue& o) {
  const auto& values = o.value.as_series().values;
  const auto& labels = o.value.as_series().labels;
  if (labels.size() == values.size() && !values.empty()) {
    // Named elements: "shaft 9.4 %, retaining ring 7.8 %, ...".
    for (std::size_t i = 0; i < values.size(); ++i)
      os << (i ? ", " : "") << terminal_text(labels[i], TerminalLines::one) << " " << format_value(values[i], o.dimension, o.display_unit);
    return;
  }
  if (values.size() > 12) {
    os << "series of " << values.size() << " points (see --out for the CSV)";
    return;
  }
  os << "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::string text = format_value(values[i], o.dimension, o.display_unit);
    os << (i ? ", " : "") << text.substr(0, text.find(' '));
  }
  const std::string unit = o.display_unit.empty() ? o.dimension.si_unit() : o.display_unit;
  os << "]" << (unit == "1" ? "" : " " + unit);
}

// One CSV per table: the axis, then each channel; header `name [unit]`, in the scene's display
// units (SI where the scene names none), or in the units the caller gives per column.
void write_table_csv(const std::filesystem::path& file, const Table& t, const DisplayUnits& units, const DeclaredPort& declared) {
  write_file_whole(file, true, [&](std::ostream& out) { write_table_rows(out, t, units, declared); });
}

void write_table_csv(const std::filesystem::path& file, const Table& t, const std::vector<std::string>& column_units,
                     const DeclaredPort& declared) {
  write_file_whole(file, true, [&](std::ostream& out) { write_table_rows(out, t, column_units, declared); });
}

void write_table_rows(std::ostream& out, const Table& t, const DisplayUnits& units, const DeclaredPort& declared) {
  std::vector<std::string> unit{units.unit_for(t.axis.dimension)};
  for (const Table::Column& c : t.channels) unit.push_back(units.unit_for(c.dimension));
  write_table_rows(out, t, unit, declared);
}

void write_table_rows(std::ostream& out, const Table& t, const std::vector<std::string>& unit, const DeclaredPort& declared) {
  std::vector<const Table::Column*> columns{&t.axis};
  for (const Table::Column& c : t.channels) columns.push_back(&c);
  if (unit.size() != columns.size())
    throw std::logic_error("write_table_rows: " + std::to_string(unit.size()) + " units for " + std::to_string(columns.size()) + " columns");
  // A channel with declared codes is followed by their names.
  std::vector<const ChannelDecl*> named(columns.size(), nullptr);
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (const ChannelDecl* decl = declared.channel(columns[k]->name); decl && !decl->codes.empty()) named[k] = decl;
  for (std::size_t k = 0; k < columns.size(); ++k) {
    const std::string shown = unit[k].empty() ? columns[k]->dimension.si_unit() : unit[k];
    out << (k ? "," : "") << csv_field(columns[k]->name + " [" + unit_with_reference(shown, declared.column_tag(*columns[k])) + "]");
    if (named[k]) out << "," << csv_field(columns[k]->name + "_name");
  }
  out << "\n" << std::setprecision(17);
  for (std::size_t i = 0; i < t.axis.values.size(); ++i) {
    for (std::size_t k = 0; k < columns.size(); ++k) {
      const double v = columns[k]->values[i];
      out << (k ? "," : "") << (unit[k].empty() ? v : to_unit(v, columns[k]->dimension, unit[k]));
      if (named[k]) out << "," << csv_field(std::string(named[k]->code_name(v)));
    }
    out << "\n";
  }
}

void write_csv(const std::filesystem::path& file, const OutputValue& o, const DisplayUnits& units, const DeclaredPort& declared) {
  write_file_whole(file, true, [&](std::ostream& out) { write_series_rows(out, o, units, declared); });
}

void write_series_rows(std::ostream& out, const OutputValue& o, const DisplayUnits& units, const DeclaredPort& declared) {
  const Series& s = o.value.as_series();
  const std::string axis_unit = units.unit_for(s.axis_dimension), value_unit = units.unit_for(o.dimension);
  const std::string axis_shown = axis_unit.empty() ? s.axis_dimension.si_unit() : axis_unit;
  const std::string value_shown = value_unit.empty() ? o.dimension.si_unit() : value_unit;
  out << csv_field("axis [" + unit_with_reference(axis_shown, declared.values_tag(s.axis_dimension)) + "]") << ","
      << csv_field(o.label + " [" + unit_with_reference(value_shown, declared.values_tag(o.dimension)) + "]") << "\n";
  out << std::setprecision(17);
  for (std::size_t i = 0; i < s.values.size(); ++i)
    out << (axis_unit.empty() ? s.axis[i] : to_unit(s.axis[i], s.axis_dimension, axis_unit)) << ","
        << (value_unit.empty() ? s.values[i] : to_unit(s.values[i], o.dimension, value_unit)) << "\n";
}


void write_result_files(const std::filesystem::path& dir, const Graph& graph, const RunResult& result,
                        const PluginRegistry& registry, const RunInputs& inputs) {
  write_file_whole(dir / "results.json", true, [&](std::ostream& os) { write_json(os, graph, result, registry, inputs); });
  for (const OutputValue& o : result.outputs)
    if (o.value.kind() == ValueKind::series) write_csv(dir / (o.label + ".csv"), o, graph.display_units, declared_port(graph, o.label));
    else if (o.value.kind() == ValueKind::table) {
      const DeclaredPort declared = declared_port(graph, o.label);
      write_table_csv(dir / (o.label + ".csv"), o.value.as_table(), graph.display_units, declared);
      if (is_drawable_curve(o.value.as_table(), declared.presentation())) {
        // The producing node's notes go into the drawing too (a drawing says which way it turns).
        const std::string node = o.label.substr(0, o.label.find('.'));
        std::vector<std::string> notes;
        for (const NodeRun& r : result.runs)
          if (r.node == node) notes = r.notes;
        write_dxf(dir / (o.label + ".dxf"), o.value.as_table(), declared.presentation(), notes);
      }
    }
}

}  // namespace mechgraph::cli
