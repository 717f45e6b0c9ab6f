#include "sweep_rows.hpp"

#include "cli.hpp"

#include <mechgraph/csv.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/units.hpp>

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace mechgraph::cli {
namespace {

std::string with_unit(const std::string& name, const std::string& unit) {
  return unit.empty() || unit == "1" ? name : name + " [" + unit + "]";
}

// The shortest text that reads back to the same double (std::to_chars: exact, and fast).
std::string exact(double x) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, end);
}

// The unit a port's values are shown in: its display unit, else SI.
std::string unit_of(const RequestedOutput& o) {
  return o.spec->display_unit.empty() ? o.spec->dimension.si_unit() : o.spec->display_unit;
}

}  // namespace

int exit_code_of(CaseFailure failure) {
  switch (failure) {
    case CaseFailure::none: return ok;
    case CaseFailure::scene: return usage_error;
    case CaseFailure::evaluation: return evaluation_error;
  }
  return evaluation_error;
}

SweepRows::SweepRows(const Graph& graph, const CaseTable& table, RowFormat format)
    : graph_(graph), table_(table), format_(format) {}

SweepRows::Column SweepRows::column(std::size_t output, std::optional<std::size_t> element) const {
  Column c{output, element};
  const RequestedOutput& o = graph_.outputs[output];
  if (!o.spec->display_unit.empty()) {
    const UnitScale u = parse_unit(o.spec->display_unit);
    c.scale = u.scale;
    c.offset = u.offset;
  }
  return c;
}

std::vector<std::string> SweepRows::output_headers(const CaseResult* success, std::vector<Column>& columns) const {
  std::vector<std::string> names;
  for (std::size_t j = 0; j < graph_.outputs.size(); ++j) {
    const RequestedOutput& o = graph_.outputs[j];
    if (o.spec->kind == ValueKind::scalar) {
      names.push_back(with_unit(o.label, unit_of(o)));
      columns.push_back(column(j, std::nullopt));
    } else if (o.spec->kind == ValueKind::series && success) {
      const Series& s = success->outputs[j].value.as_series();
      for (std::size_t e = 0; e < s.values.size(); ++e) {
        const std::string element = e < s.labels.size() ? s.labels[e] : std::to_string(e);
        names.push_back(with_unit(o.label + "[" + element + "]", unit_of(o)));
        columns.push_back(column(j, e));
      }
    }
  }
  return names;
}

void SweepRows::settle(const CaseResult* success) {
  if (settled_) return;
  header_ = {"case"};
  for (const SweepVariable& v : table_.variables) header_.push_back(with_unit(v.name, v.unit));
  const std::vector<std::string> outputs = output_headers(success, columns_);
  header_.insert(header_.end(), outputs.begin(), outputs.end());
  header_.push_back("exit");
  header_.push_back("error");
  settled_ = true;
}

void SweepRows::adopt(const std::vector<std::string>& header) {
  // The file's header must be what this sweep would write: the series columns tell their length.
  std::vector<Column> columns;
  std::vector<std::string> expected = {"case"};
  for (const SweepVariable& v : table_.variables) expected.push_back(with_unit(v.name, v.unit));
  const std::size_t fixed = expected.size();
  if (header.size() < fixed + 2 || !std::equal(expected.begin(), expected.end(), header.begin()) ||
      header[header.size() - 2] != "exit" || header.back() != "error")
    throw UsageError("the file being resumed has other columns than this sweep writes (" + csv_row(header) + ")");
  for (std::size_t j = 0, h = fixed; j < graph_.outputs.size(); ++j) {
    const RequestedOutput& o = graph_.outputs[j];
    if (o.spec->kind == ValueKind::scalar) {
      if (h >= header.size() - 2 || header[h] != with_unit(o.label, unit_of(o)))
        throw UsageError("the file being resumed has no column for '" + o.label + "' where this sweep writes it");
      columns.push_back(column(j, std::nullopt));
      ++h;
    } else if (o.spec->kind == ValueKind::series) {
      for (std::size_t e = 0; h < header.size() - 2 && header[h].rfind(o.label + "[", 0) == 0; ++e, ++h) columns.push_back(column(j, e));
    }
  }
  if (fixed + columns.size() + 2 != header.size())
    throw UsageError("the file being resumed has columns this sweep does not write");
  header_ = header;
  columns_ = std::move(columns);
  settled_ = true;
}

std::string SweepRows::format(const std::vector<std::string>& cells, const std::vector<bool>& numeric) const {
  if (format_ == RowFormat::csv) return csv_row(cells) + "\n";
  std::ostringstream os;
  JsonWriter json(os);
  json.begin_object();
  for (std::size_t c = 0; c < cells.size(); ++c) {
    json.key(header_[c]);
    if (cells[c].empty()) json.null();
    else if (c == 0 || c + 2 == cells.size()) json.value(std::strtol(cells[c].c_str(), nullptr, 10));  // case, exit
    else if (numeric[c]) json.value(std::strtod(cells[c].c_str(), nullptr));  // %.17g text: the same double
    else json.value(cells[c]);
  }
  json.end_object();
  return os.str() + "\n";
}

std::string SweepRows::line(const CaseResult& result, int exit_code) const {
  std::vector<std::string> cells = {std::to_string(result.index)};
  std::vector<bool> numeric = {true};
  for (std::size_t v = 0; v < table_.variables.size(); ++v) {
    cells.push_back(table_.shown(result.index, v));
    numeric.push_back(table_.cases[result.index][v].si.has_value());
  }
  std::string error = result.error;
  if (result.failure == CaseFailure::none) {
    std::vector<std::string> values;
    for (const Column& c : columns_) {
      const Value& value = result.outputs[c.output].value;
      const RequestedOutput& o = graph_.outputs[c.output];
      if (!c.element) {
        values.push_back(exact(shown(value.as_scalar(), c)));
      } else if (*c.element < value.as_series().values.size()) {
        values.push_back(exact(shown(value.as_series().values[*c.element], c)));
      } else {
        error = "output '" + o.label + "' has " + std::to_string(value.as_series().values.size()) +
                " elements in this case, fewer than the sweep's columns";
        exit_code = evaluation_error;
        break;
      }
    }
    if (error.empty()) {
      for (std::size_t c = 0; c < columns_.size(); ++c) {
        const std::size_t j = columns_[c].output;
        const bool last_of_series = columns_[c].element && (c + 1 == columns_.size() || columns_[c + 1].output != j);
        if (last_of_series && result.outputs[j].value.as_series().values.size() != *columns_[c].element + 1) {
          error = "output '" + graph_.outputs[j].label + "' has " + std::to_string(result.outputs[j].value.as_series().values.size()) +
                  " elements in this case, the sweep's columns have " + std::to_string(*columns_[c].element + 1);
          exit_code = evaluation_error;
        }
      }
    }
    if (error.empty()) {
      cells.insert(cells.end(), values.begin(), values.end());
      numeric.insert(numeric.end(), values.size(), true);
    }
  }
  if (!error.empty() || result.failure != CaseFailure::none) {
    cells.resize(1 + table_.variables.size());
    cells.insert(cells.end(), columns_.size(), "");
    numeric.resize(cells.size(), true);
  }
  cells.push_back(std::to_string(exit_code));
  numeric.push_back(true);
  cells.push_back(error);
  numeric.push_back(false);
  return format(cells, numeric);
}

}  // namespace mechgraph::cli
