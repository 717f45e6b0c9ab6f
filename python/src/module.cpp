// mechgraph._core: the pybind11 extension behind the Python package `mechgraph` (python/mechgraph).
// It holds the plugin registry (loaded by the command line's rules: --plugin-dir folders given to
// load_plugins(), MECHGRAPH_PLUGIN_PATH, the built-in folder beside libmechgraph), the scene
// sessions, and the conversions; the Pythonic surface (Result, DataFrames, errors) is Python code.
#include "case_values.hpp"
#include "input_columns.hpp"
#include "interruptible.hpp"
#include "python_values.hpp"
#include "report_tables.hpp"
#include "scene_session.hpp"
#include "unit_rule.hpp"
#include "value_arrays.hpp"

#include <mechgraph/host/study_run.hpp>
#include <mechgraph/uncertainty/sample_design.hpp>
#include <mechgraph/host/angle_reference.hpp>
#include <mechgraph/host/sweep_rows.hpp>

#include <mechgraph/host/plugin_search.hpp>
#include <mechgraph/host/scene_loading.hpp>
#include <mechgraph/host/usage_error.hpp>
#include <mechgraph/host/node_info_format.hpp>
#include <mechgraph/host/terminal_output.hpp>

#include <mechgraph/chunked_work.hpp>
#include <mechgraph/large_arrays.hpp>
#include <mechgraph/did_you_mean.hpp>
#include <mechgraph/error_subject.hpp>
#include <mechgraph/display_units.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/shown_number.hpp>
#include <mechgraph/units.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <spdlog/spdlog.h>

#include <atomic>
#include <charconv>
#include <cstdint>
#include <limits>
#include <cmath>
#include <mutex>
#include <sstream>
#include <thread>

namespace py = pybind11;
using namespace mechgraph;
using namespace mechgraph::python;

namespace {

// A study output's column in Study.samples: the column a sweep of the study's cases writes
// (sweep_rows.hpp: the display unit and the angle's frame, "[deg (cam)]"), so that the in-process
// study and mechgraph.dask.study, which reads a sweep's rows, name it alike.
std::string study_sample_column(const Graph& graph, const StudyColumn& c) {
  for (std::size_t j = 0; j < graph.outputs.size(); ++j)
    if (graph.outputs[j].label == c.label) return host::sweep_column_name(graph, j);
  const std::string unit = c.unit.empty() ? c.dimension.si_unit() : c.unit;
  return unit.empty() || unit == "1" ? c.label : c.label + " [" + unit + "]";
}

// The design's parameters in Study.samples: the columns a sweep of the study's cases writes
// (`lift [mm]`, its numbers in mm, each the double its row's text reads back to), so that no
// column holds SI under a bare name and both the in-process study and mechgraph.dask.study show
// the rows of `mechgraph sweep SCENE --study`.
// A column of numbers for Python: a numpy array (one copy), which pandas takes as it is. (A list
// made a float object a value: a study of 10^6 cases took seconds and 600 MB more to hand over.)
template <class T>
py::array_t<T> numpy_column(const std::vector<T>& values) {
  return py::array_t<T>(static_cast<py::ssize_t>(values.size()), values.data());
}

void add_study_parameters(py::dict& cases, const Graph& graph, const CaseTable& table, unsigned threads) {
  const host::SweepRows rows(graph, table, host::RowFormat::csv);
  const std::vector<std::string> names = rows.input_headers();
  // Each value as the row shows it, read back (the shortest digits in the column's unit), no
  // Python object touched until every column is made.
  const std::vector<std::vector<double>> columns = input_number_columns(rows, table.size(), nullptr, threads);
  for (std::size_t v = 0; v < names.size(); ++v) cases[py::str(names[v])] = numpy_column(columns[v]);
}

// ---- plugins ------------------------------------------------------------------------------------

std::mutex registry_mutex;
std::shared_ptr<const PluginRegistry> current_registry;

std::shared_ptr<const PluginRegistry> load_registry(const std::vector<std::string>& dirs, bool only) {
  host::PluginSearch options;
  options.plugin_dirs = dirs;
  options.only_plugin_dirs = only;
  auto registry = std::make_shared<const PluginRegistry>(host::load_plugins(options));
  std::lock_guard lock(registry_mutex);
  current_registry = registry;
  return registry;
}

std::shared_ptr<const PluginRegistry> registry() {
  {
    std::lock_guard lock(registry_mutex);
    if (current_registry) return current_registry;
  }
  return load_registry({}, false);
}

py::list plugin_list(const PluginRegistry& r) {
  py::list out;
  for (const PluginInfo& p : r.plugins()) {
    py::dict d;
    d["id"] = p.id;
    d["version"] = p.version;
    d["sdk_version"] = p.sdk_version;
    d["fingerprint"] = p.fingerprint;
    d["file"] = p.path.string();
    d["node_types"] = p.node_types;
    out.append(d);
  }
  return out;
}

// ---- values from Python -------------------------------------------------------------------------

// A `set=` entry through the one conversion of Python values (python_values.hpp): text, a number,
// or a 1-D array of numbers for a list parameter; with `unit` ("mm", from (9, "mm") or a pint
// quantity) when the Python side had one, `si` when it was marked SI. A number with its unit becomes
// the text "9 mm", read as --set reads it.
SetValue set_value(const std::string& name, const py::handle& value, const std::string& unit, bool si) {
  const std::string context = "set " + name;
  if (is_sequence(value)) {
    ColumnValues column = column_values(value, context);
    if (column.text) throw SceneError(context + ": an array goes to a list parameter as numbers, not as text");
    return {name, std::move(column.numbers), unit, si};
  }
  ScalarValue scalar = scalar_value(value, context);
  if (auto* text = std::get_if<std::string>(&scalar)) {
    if (!unit.empty())
      throw SceneError(context + ": text with a unit beside it; give the text alone (\"9 mm\") or a number with its unit (9, \"mm\")");
    return {name, std::move(*text), "", false};
  }
  const double x = std::get<double>(scalar);
  if (!unit.empty()) {
    if (!std::isfinite(x)) throw SceneError(context + ": " + (std::isnan(x) ? "NaN" : "an infinite value") + " is not a value");
    return {name, number_text(x) + " " + unit, "", false};
  }
  return {name, x, "", si};
}

// `set=` as the Python side hands it over: (name, value, unit, si) for each entry.
std::vector<SetValue> set_values(const py::list& sets) {
  std::vector<SetValue> out;
  for (const py::handle entry : sets) {
    const auto t = py::reinterpret_borrow<py::tuple>(entry);
    out.push_back(set_value(py::str(t[0]), t[1], t[2].cast<std::string>(), t[3].cast<bool>()));
  }
  return out;
}

// A sweep's cases from columns, each through the one conversion of Python values: numbers in the
// column's unit, or in SI when the column is marked SI; or text cells read as a cases file's are (a
// bare number takes the column's unit). Numbers without a unit for a parameter with a dimension
// are refused (unit_rule.hpp). Kept as a cases file is (CaseTable::Numbers with each value's text
// beside it): a number in a unit is its 17 digits, read as the cell "DIGITS UNIT" would be. A
// column with no unit takes that of its first number written with one, as a cases file's does;
// `shown_units` (one a column, or none) gives it instead: the whole sweep's, for a chunk of it.
CaseTable case_table(SceneSession& session, const std::vector<std::string>& names, const std::vector<std::string>& units,
                     const std::vector<bool>& si, const py::list& columns, const std::vector<std::string>& shown_units = {}) {
  CaseTable table;
  table.origin = "python";
  if (py::len(columns) != names.size() || units.size() != names.size() || si.size() != names.size()) throw SceneError("cases: " + std::to_string(names.size()) + " names for " +
                                                         std::to_string(py::len(columns)) + " columns");
  const std::size_t width = names.size();
  // Every column read and checked first, then the cases one after another.
  std::vector<ColumnValues> values;
  std::vector<std::optional<Dimension>> dimension_of(width);
  std::vector<bool> bare_refused(width);
  std::size_t n = 0;
  for (std::size_t v = 0; v < width; ++v) {
    const std::string& name = names[v];
    const std::string& unit = units[v];
    table.variables.push_back({name, unit});
    values.push_back(column_values(columns[v], "cases: column '" + excerpt(name) + "'"));
    const ColumnValues& column = values.back();
    if (v == 0) {
      n = column.size();
      if (n > max_sweep_cases)
        throw SceneError("more than " + std::string(max_sweep_cases_text) + " cases in one sweep; split it into several sweeps");
      if (n * width > max_case_cells)
        throw SceneError("more than " + std::to_string(max_case_cells) + " values in one sweep; split it into several sweeps");
    } else if (column.size() != n) {
      throw SceneError("cases: column '" + excerpt(name) + "' has " + std::to_string(column.size()) + " values, the first " +
                       std::to_string(n));
    }
    dimension_of[v] = unit.empty() ? session.dimension_of(name) : std::nullopt;
    bare_refused[v] = unit.empty() && !si[v] && dimension_of[v] && !dimension_of[v]->dimensionless();
  }
  CaseTable::Numbers::Written& written = table.numbers.written;
  table.numbers.count = n;
  table.numbers.dimensions.assign(width, Dimension{});  // each value keeps its own
  written.column_units = units;
  reserve_large(table.numbers.si, n * width);
  reserve_large(written.ends, n * width);
  reserve_large(written.in_column_unit, n * width);
  std::vector<std::optional<UnitScale>> scales(width);
  for (std::size_t v = 0; v < width; ++v)
    if (!units[v].empty()) scales[v] = parse_unit_cached(units[v]);
  // The texts' pool at its largest, so that it is not copied as it grows: a number in a column
  // without a unit takes its 17 digits (at most 24 characters, "-1.2345678901234567e-308") and
  // its SI unit after a space (si_text); a text cell about its own size with the column's unit.
  // A number in a column with a unit is kept as given (CaseTable::keep_given), without text: 10^6
  // rows of six such columns wrote 110 MB of digits, which the frame's input columns read back.
  std::size_t text_bytes = 0;
  bool given = false;
  for (std::size_t v = 0; v < width; ++v) {
    if (!values[v].text) {
      if (scales[v]) given = true;
      else text_bytes += n * (24 + (units[v].empty() ? 1 + dimension_of[v].value_or(Dimension{}).si_unit().size() : 0));
      continue;
    }
    for (const std::string& cell : values[v].cells) text_bytes += cell.size() + 1 + units[v].size();
  }
  reserve_large(written.text, text_bytes);
  if (given) reserve_large(written.given, n * width);
  const auto refuse_bare = [&](std::size_t v) {
    const std::string& name = names[v];
    throw SceneErrorAt(subject_of(name), bare_number_refusal("cases: column '" + excerpt(name) + "'", excerpt(name), "", *dimension_of[v],
                                         session.scene_unit_of(name, *dimension_of[v]), BareKind::column));
  };
  for (std::size_t v = 0; v < width; ++v)
    if (!values[v].text && bare_refused[v] && n > 0) refuse_bare(v);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t v = 0; v < width; ++v) {
      const std::string& name = names[v];
      const std::string& unit = units[v];
      const auto context = [&] { return "cases: column '" + excerpt(name) + "', row " + std::to_string(i); };
      const ColumnValues& column = values[v];
      if (!column.text) {
        const double x = column.numbers[i];
        if (!std::isfinite(x)) throw SceneError(context() + ": not a finite number");
        if (unit.empty()) {  // value_from_si's value: its text si_text's
          const Dimension d = dimension_of[v].value_or(Dimension{});
          table.keep_written(si_text(x, d), false, x, d);
          continue;
        }
        // The cell "DIGITS UNIT", DIGITS the number's 17 significant digits (which read back to x
        // itself): its value is that of x, kept as given, unread and unwritten.
        if (scales[v])
          if (const std::optional<double> number = bare_number_in(x, *scales[v])) {
            table.keep_given(x, *number, scales[v]->dimension);
            continue;
          }
        CaseTable::Numbers::Written::Digits buffer;
        const std::string_view digits = CaseTable::Numbers::Written::given_text(x, buffer);
        table.keep_written(value_from_text(std::string(digits) + " " + unit, context()), digits, v);
        continue;
      }
      const std::string& cell = column.cells[i];
      CaseValue value = value_from_text(cell, context());
      const bool bare = value.si && value.dimension.dimensionless() && cell.find_first_not_of("0123456789.eE+- ") == std::string::npos;
      if (bare && !unit.empty()) value = value_from_text(cell + " " + unit, context());
      else if (bare && bare_refused[v]) refuse_bare(v);
      else if (bare && si[v] && dimension_of[v]) value = value_from_si(*value.si, *dimension_of[v], context());
      table.adopt_unit(v, value, cell);
      table.keep_written(value, cell, v);
    }
  if (!shown_units.empty()) {
    if (shown_units.size() != width) throw SceneError("cases: " + std::to_string(shown_units.size()) + " column units for " + std::to_string(width) + " columns");
    for (std::size_t v = 0; v < width; ++v)
      if (units[v].empty()) table.variables[v].unit = shown_units[v];
  }
  return table;
}

// ---- results ------------------------------------------------------------------------------------

struct RunOutcome {
  std::shared_ptr<SceneSession> session;
  std::shared_ptr<const SessionRun> run;
  std::vector<std::string> outputs;

  const OutputValue& find(const std::string& label) const {
    for (const OutputValue& o : run->result.outputs)
      if (o.label == label) return o;
    std::vector<std::string> valid;
    for (const OutputValue& o : run->result.outputs) valid.push_back(o.label);
    throw py::key_error(unknown_name_message("output", label, valid));
  }

  // The declaration behind output `label` ("node.port"): its node type's description and the
  // port, or nullptrs (a label the scene's nodes do not declare).
  std::pair<const NodeInfo*, const PortSpec*> declared(const std::string& label) const {
    const auto dot = label.find('.');
    if (dot == std::string::npos) return {nullptr, nullptr};
    for (const NodeSpec& n : session->scene().nodes)
      if (n.name == label.substr(0, dot)) {
        const RegisteredType* t = session->registry().find(n.type);
        if (!t) break;
        const NodeInfo& info = t->type->info();
        return {&info, info.find_output(label.substr(dot + 1))};
      }
    return {nullptr, nullptr};
  }
};

// What output `label` declares for its presentation (presentation.hpp), per column as
// shown_units lists them (a scalar: its value; a series: its values, then its axis; a table: its
// axis, then its channels): `frames`, the angle each counts ("crank"; "" none: angle_reference.hpp,
// the rule of the terminal, the report and the sweep's header), and `codes`, a column's named
// values as [(value, name, doc)] (empty for one without), as the CLI's tables and CSV name them.
py::dict output_declarations(const RunOutcome& r, const std::string& label) {
  const OutputValue& o = r.find(label);
  const auto [info, port] = r.declared(label);
  py::list frames, codes;
  const auto column = [&](const std::string& name, const Dimension& d) {
    frames.append(info && port ? host::column_angle_reference(*info, *port, name, d) : std::string());
    py::list named;
    if (const ChannelDecl* decl = port ? port->presentation.find(name) : nullptr)
      for (const Code& c : decl->codes) named.append(py::make_tuple(c.value, python_text(c.name), python_text(c.doc)));
    codes.append(named);
  };
  switch (o.value.kind()) {
    case ValueKind::table: {
      const Table& t = o.value.as_table();
      column(t.axis.name, t.axis.dimension);
      for (const Table::Column& c : t.channels) column(c.name, c.dimension);
      break;
    }
    case ValueKind::series:
      frames.append(info && port ? host::angle_reference(*info, *port) : std::string());
      frames.append(info && port ? host::angle_reference(*info, port->angle_frame, o.value.as_series().axis_dimension) : std::string());
      codes.append(py::list());
      codes.append(py::list());
      break;
    default:
      frames.append(info && port ? host::angle_reference(*info, *port) : std::string());
      codes.append(py::list());
  }
  py::dict out;
  out["frames"] = frames;
  out["codes"] = codes;
  return out;
}

py::dict provenance(const RunOutcome& r) {
  // The run's own values given again to a graph built as the run's was: what was really used.
  const Graph graph = r.session->graph_for(*r.run->sets, r.outputs);
  const SceneSpec& scene = r.session->scene();
  py::dict out;
  out["program"] = py::dict(py::arg("name") = "mechgraph (Python)", py::arg("version") = MECHGRAPH_VERSION);
  out["scene"] = py::dict(py::arg("file") = scene.file, py::arg("title") = graph.title);
  out["overrides"] = r.run->overrides;
  py::dict nodes;
  for (std::size_t index : graph.order) {
    const GraphNode& n = graph.nodes[index];
    py::dict node;
    node["type"] = n.info().type;
    node["type_version"] = n.info().version;
    node["plugin"] = n.type->plugin_id;
    for (const PluginInfo& p : r.session->registry().plugins())
      if (p.id == n.type->plugin_id) node["plugin_version"] = p.version;
    py::dict used;
    for (const auto& [name, value] : n.params.all()) {
      switch (value.kind) {
        case ParamKind::number: used[name.c_str()] = value.number; break;
        case ParamKind::integer: used[name.c_str()] = static_cast<long>(value.number); break;
        case ParamKind::choice:
        case ParamKind::text: used[name.c_str()] = value.text; break;
        case ParamKind::number_list: used[name.c_str()] = to_array(value.numbers); break;
        case ParamKind::record_list: used[name.c_str()] = py::str("<" + std::to_string(value.records.size()) + " records>"); break;
      }
    }
    node["used_si"] = used;
    nodes[n.name.c_str()] = node;
  }
  out["nodes"] = nodes;
  out["plugins"] = plugin_list(r.session->registry());
  return out;
}

// A sweep's rows as numpy columns by header: `case` and `exit` int64, the outputs float64 (NaN
// where a case failed), an input float64 when every cell is a number (else objects: None, float
// or the text as written), `error` objects (None for a success). The same values as the rows of
// `mechgraph sweep --format jsonl`, without text in between.
py::tuple sweep_columns(const SessionSweep& s) {
  const std::size_t n = s.cases.size();
  const std::size_t inputs = s.inputs;
  const std::size_t outputs = s.header.size() - 3 - inputs;
  const py::module_ numpy = py::module_::import("numpy");
  py::dict columns;
  py::array_t<std::int64_t> cases(static_cast<py::ssize_t>(n)), exits(static_cast<py::ssize_t>(n));
  for (std::size_t i = 0; i < n; ++i) {
    cases.mutable_at(i) = static_cast<std::int64_t>(s.cases[i]);
    exits.mutable_at(i) = s.exits[i];
  }
  columns[py::str(s.header.front())] = cases;
  for (std::size_t v = 0; v < inputs; ++v) {
    const SessionInputColumn& input = s.input_columns[v];
    if (input.cells.empty()) {
      columns[python_text(s.header[1 + v])] = numpy_column(input.numbers);
      continue;
    }
    py::list column;
    for (const auto& cell : input.cells) {
      if (const auto* x = std::get_if<double>(&cell)) column.append(*x);
      else if (const auto* text = std::get_if<std::string>(&cell)) column.append(python_text(*text));
      else column.append(py::none());
    }
    columns[python_text(s.header[1 + v])] = numpy.attr("array")(column, py::arg("dtype") = "object");
  }
  for (std::size_t o = 0; o < outputs; ++o) {
    py::array_t<double> column(static_cast<py::ssize_t>(n));
    double* out = column.mutable_data();
    for (std::size_t i = 0; i < n; ++i) out[i] = s.outputs[i * outputs + o];
    columns[python_text(s.header[1 + inputs + o])] = column;
  }
  columns[py::str(s.header[s.header.size() - 2])] = exits;
  py::array errors = numpy.attr("full")(n, py::none(), py::arg("dtype") = "object");
  for (const auto& [row, message] : s.errors) errors[py::int_(row)] = python_text(message);
  columns[py::str(s.header.back())] = errors;
  py::list header;
  for (const std::string& h : s.header) header.append(python_text(h));
  return py::make_tuple(header, columns);
}

// ---- errors -------------------------------------------------------------------------------------

// Raises mechgraph's Python class `class_name` with `message` (which may quote a plugin's bytes)
// and, when the C++ error carried one, its subject as attributes: location (file, line, column),
// node, parameter. Read from the error's fields, never from its message.
void raise_as(const char* class_name, const std::string& message, const ErrorSubject* subject = nullptr) {
  const py::object cls = py::module_::import("mechgraph._errors").attr(class_name);
  py::object error = cls(python_text(message));
  if (subject) {
    if (subject->where.line > 0)
      error.attr("location") = py::make_tuple(python_text(subject->where.file), subject->where.line, subject->where.column);
    if (!subject->node.empty()) error.attr("node") = python_text(subject->node);
    if (!subject->parameter.empty()) error.attr("parameter") = python_text(subject->parameter);
  }
  PyErr_SetObject(cls.ptr(), error.ptr());
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "mechgraph's C++ core (libmechgraph and its plugins); use the package `mechgraph`.";
  m.attr("__version__") = MECHGRAPH_VERSION;
  // Log messages quote scene and plugin text: through terminal_text, as the command line's are.
  host::use_terminal_safe_logger("mechgraph");
  spdlog::set_level(spdlog::level::warn);  // a notebook wants results, not progress; set_log_level() changes it

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneErrorAt& e) {
      raise_as("SceneError", e.what(), &e.subject());
    } catch (const NodeEvaluationError& e) {
      raise_as("EvaluationError", e.what(), &e.subject());
    } catch (const UnitError& e) {
      raise_as("UnitError", e.what());
    } catch (const SceneError& e) {
      raise_as("SceneError", e.what());
    } catch (const host::UsageError& e) {
      raise_as("SceneError", e.what());
    } catch (const EvaluationError& e) {
      raise_as("EvaluationError", e.what());
    } catch (const PluginError& e) {
      raise_as("PluginError", e.what());
    } catch (const IoError& e) {
      raise_as("MechgraphError", e.what());
    }
  });

  m.def("load_plugins", [](const std::vector<std::string>& dirs, bool only) { return plugin_list(*load_registry(dirs, only)); },
        py::arg("plugin_dirs") = std::vector<std::string>{}, py::arg("only") = false);
  m.def("plugins", [] { return plugin_list(*registry()); });
  m.def("node_types", [] { return registry()->type_names(); });
  m.def("describe", [](const std::string& type) {
    const auto r = registry();
    const RegisteredType* t = r->find(type);
    if (!t) throw host::UsageError(unknown_name_message("node type", type, r->type_names()));
    std::ostringstream json_text, text;
    JsonWriter json(json_text);
    host::write_node_info_json(json, t->type->info());
    host::write_node_info_text(text, t->type->info());
    return py::make_tuple(json_text.str(), text.str());
  });
  m.def("set_log_level", [](const std::string& level) {
    const auto l = spdlog::level::from_str(level);
    if (l == spdlog::level::off && level != "off")
      throw SceneError("log level '" + level + "': valid levels are trace, debug, info, warn, error, critical, off");
    spdlog::set_level(l);
  });
  m.def("unit_scale", [](const std::string& unit) {
    // shown = si / scale - offset, and the SI unit of the unit's dimension ("" dimensionless); a
    // column label's angle reference ("deg (crank)") names the angle, not a scale
    const UnitScale u = parse_unit(host::unit_without_reference(unit));
    return py::make_tuple(u.scale, u.offset, si_unit_label(u.dimension));
  });
  m.def("shown_number", [](double shown, double si, const std::string& si_unit, double largest_si) {
    // `shown` as a person reads it: 6 significant digits, rounding noise as 0 (shown_number.hpp)
    const UnitScale u = parse_unit(si_unit.empty() ? std::string("1") : si_unit);
    return shown_number(shown, si, noise_floor(u.dimension, largest_si));
  }, py::arg("shown"), py::arg("si"), py::arg("si_unit"), py::arg("largest_si") = 0.0);
  m.def("unit_with_reference", &host::unit_with_reference);  // "deg" + "crank" -> "deg (crank)"
  m.def("unit_without_reference", &host::unit_without_reference);  // and back: "deg (crank)" -> "deg"
  m.def("to_unit", [](double si, const std::string& unit) {
    // the SI value of a quantity expressed in `unit` (its dimension taken from the unit)
    const UnitScale u = parse_unit(unit);
    return si / u.scale - u.offset;
  });

  py::class_<RunOutcome>(m, "RunOutcome")
      .def("labels", [](const RunOutcome& r) {
        std::vector<std::string> labels;
        for (std::size_t i = 0; i < r.run->result.outputs.size(); ++i) labels.push_back(r.run->result.outputs[i].label);
        return py::make_tuple(labels, r.run->scene_output_count);
      })
      .def("value", [](const RunOutcome& r, const std::string& label) { return output_value(r.find(label)); })
      .def("kind", [](const RunOutcome& r, const std::string& label) { return std::string(to_string(r.find(label).value.kind())); })
      .def("unit", [](const RunOutcome& r, const std::string& label) { return si_unit_label(r.find(label).dimension); })
      .def("display_unit", [](const RunOutcome& r, const std::string& label) { return python_text(r.find(label).display_unit); })
      .def("in_unit", [](const RunOutcome& r, const std::string& label, const std::string& unit) {
        const OutputValue& o = r.find(label);
        if (o.value.kind() != ValueKind::scalar) throw SceneError("output '" + label + "' is not a scalar");
        return to_unit(o.value.as_scalar(), o.dimension, unit);
      })
      .def("series_axis", [](const RunOutcome& r, const std::string& label) {
        const OutputValue& o = r.find(label);
        if (o.value.kind() != ValueKind::series) throw SceneError("output '" + label + "' is not a series");
        const Series& s = o.value.as_series();
        py::list labels;
        for (const std::string& l : s.labels) labels.append(python_text(l));
        return py::make_tuple(to_array(s.axis), si_unit_label(s.axis_dimension), labels);
      })
      .def("notes", [](const RunOutcome& r) {
        py::list notes;
        for (const NodeRun& n : r.run->result.runs)
          for (const std::string& note : n.notes) notes.append(py::make_tuple(n.node, python_text(note)));
        return notes;
      })
      .def("work", [](const RunOutcome& r) {
        py::dict work;
        for (const NodeRun& n : r.run->result.runs) {
          py::dict node;
          node["type"] = n.type;
          node["reused"] = n.reused;
          node["seconds"] = n.seconds;
          node["work"] = n.work;
          work[n.node.c_str()] = node;
        }
        return work;
      })
      .def("shown_units", [](const RunOutcome& r, const std::string& label) {
        // The units the scene shows this output in ("" keeps SI): a scalar's; a series' values and
        // axis; a table's axis and channels.
        const OutputValue& o = r.find(label);
        const DisplayUnits units = DisplayUnits::from_scene(r.session->scene().units);
        py::list out;
        switch (o.value.kind()) {
          case ValueKind::series:
            out.append(python_text(o.display_unit));
            out.append(python_text(units.unit_for(o.value.as_series().axis_dimension)));
            break;
          case ValueKind::table: {
            const Table& t = o.value.as_table();
            out.append(python_text(units.unit_for(t.axis.dimension, t.axis.display_unit)));
            for (const Table::Column& c : t.channels) out.append(python_text(units.unit_for(c.dimension, c.display_unit)));
            break;
          }
          default: out.append(python_text(o.display_unit));
        }
        return out;
      })
      .def("declarations", &output_declarations)
      .def("report_tables", [](const RunOutcome& r) {
        const Graph graph = r.session->graph_for(*r.run->sets, r.outputs);
        py::list tables;
        for (const ReportTableValues& t : report_table_values(graph, r.run->result)) {
          py::list columns, rows;
          for (const std::string& c : t.columns) columns.append(python_text(c));
          for (const auto& row : t.rows) {
            py::list values;
            for (const auto& v : row.values) values.append(v ? py::object(py::float_(*v)) : py::object(py::none()));
            rows.append(py::make_tuple(python_text(row.label), python_text(row.unit), values));
          }
          tables.append(py::make_tuple(python_text(t.title), columns, rows));
        }
        return tables;
      })
      .def_property_readonly("seconds", [](const RunOutcome& r) { return r.run->seconds; })
      .def("provenance", &provenance);

  py::class_<SceneSession, std::shared_ptr<SceneSession>>(m, "Session")
      .def_static("load", [](const std::string& path) {
        return std::make_shared<SceneSession>(registry(), load_scene(path));
      })
      .def_static("from_text", [](const std::string& yaml, const std::string& label) {
        return std::make_shared<SceneSession>(registry(), parse_scene(yaml, label));
      })
      .def("validate", [](SceneSession& s, double max_work, double max_memory) {
        const WorkBudget budget = python_budget(max_work, max_memory, false);
        py::gil_scoped_release released;
        s.validate(budget);
      }, py::arg("max_work") = 0.0, py::arg("max_memory") = 0.0)
      .def_property_readonly("title", [](const SceneSession& s) { return s.scene().title; })
      .def_property_readonly("file", [](const SceneSession& s) { return s.scene().file; })
      .def_property_readonly("params", [](const SceneSession& s) {
        std::vector<std::string> names;
        for (const auto& [name, value] : s.scene().params) names.push_back(name);
        return names;
      })
      .def_property_readonly("outputs", [](const SceneSession& s) {
        std::vector<std::string> labels;
        for (const PortRef& o : s.scene().outputs) labels.push_back(o.str());
        return labels;
      })
      .def("cache_counters", [](const SceneSession& s) { return py::make_tuple(s.cache_hits(), s.cache_misses()); })
      .def("clear_cache", &SceneSession::clear_cache)
      .def("run", [](const std::shared_ptr<SceneSession>& session, const py::list& sets, const std::vector<std::string>& outputs,
                     unsigned threads, bool interruptible, double max_work, double max_memory) {
        auto values = std::make_shared<std::vector<SetValue>>(set_values(sets));
        auto run = std::make_shared<SessionRun>();
        const WorkBudget budget = python_budget(max_work, max_memory, false);
        if (interruptible) {
          // The work owns what it touches: on Ctrl-C it may finish after this call has raised.
          run_interruptibly([session, values, outputs, threads, run, budget] { *run = session->run(values, outputs, threads, budget); },
                            [] {}, OnInterrupt::detach);
        } else {
          py::gil_scoped_release released;
          *run = session->run(values, outputs, threads, budget);
        }
        return RunOutcome{session, run, outputs};
      }, py::arg("sets"), py::arg("outputs"), py::arg("threads") = 1, py::arg("interruptible") = true, py::arg("max_work") = 0.0,
         py::arg("max_memory") = 0.0)
      .def("sweep", [](const std::shared_ptr<SceneSession>& session, const std::vector<std::string>& names,
                       const std::vector<std::string>& units, const std::vector<bool>& si, const py::list& columns,
                       const py::list& set, const std::vector<std::string>& outputs, unsigned threads,
                       const py::object& progress, double max_work, double max_memory, const std::vector<std::string>& shown_units) {
        const CaseTable table = case_table(*session, names, units, si, columns, shown_units);
        const std::vector<SetValue> sets = set_values(set);
        auto stop = std::make_shared<std::atomic<bool>>(false);
        std::atomic<std::size_t> done{0};
        SessionSweep result;
        // progress(done, total), every 20 ms while the cases run (a tqdm bar, _progress.py)
        std::function<void()> tick;
        if (!progress.is_none()) tick = [&] { progress(done.load(std::memory_order_relaxed), table.size()); };
        const WorkBudget budget = python_budget(max_work, max_memory, true);
        run_interruptibly([&] { result = session->sweep(table, sets, outputs, threads, stop.get(), budget, &done); }, [&] { *stop = true; },
                          OnInterrupt::wait, tick);
        if (result.summary.stopped) {  // only Ctrl-C stops it, and that raised above: never a frame of part of the rows
          PyErr_SetNone(PyExc_KeyboardInterrupt);
          throw py::error_already_set();
        }
        py::dict summary;
        summary["cases"] = result.summary.run;
        summary["failed"] = result.failed;
        summary["seconds"] = result.summary.seconds;
        return py::make_tuple(sweep_columns(result), summary);
      }, py::arg("names"), py::arg("units"), py::arg("si"), py::arg("columns"), py::arg("set"), py::arg("outputs"), py::arg("threads"),
         py::arg("progress"), py::arg("max_work"), py::arg("max_memory"), py::arg("shown_units") = std::vector<std::string>{})
      // What sweep() checks before its first case, for rows that run elsewhere (mechgraph.dask.sweep).
      // Returns each column's unit as the whole sweep shows it (a chunk's sweep takes them).
      .def("check_sweep", [](const std::shared_ptr<SceneSession>& session, const std::vector<std::string>& names,
                             const std::vector<std::string>& units, const std::vector<bool>& si, const py::list& columns,
                             const py::list& set, const std::vector<std::string>& outputs, unsigned threads, double max_work,
                             double max_memory) {
        const CaseTable table = case_table(*session, names, units, si, columns);
        const std::vector<SetValue> sets = set_values(set);
        const WorkBudget budget = python_budget(max_work, max_memory, true);
        {
          py::gil_scoped_release released;
          session->check_sweep(table, sets, outputs, threads, budget);
        }
        std::vector<std::string> shown_units;
        for (const SweepVariable& variable : table.variables) shown_units.push_back(variable.unit);
        return shown_units;
      })
      .def("study", [](const std::shared_ptr<SceneSession>& session, const std::string& block, const py::list& set,
                       const std::string& samples, const std::string& method, const std::string& seed,
                       const std::vector<std::string>& outputs, unsigned threads, double max_work, double max_memory) {
        // `block`: the settings from Python as JSON text ("" for none), read as the scene's block is.
        std::optional<RawValue> settings;
        if (!block.empty()) settings = parse_raw_value(block, SourceLocation{"Scene.study()", 0, 0});
        const std::vector<SetValue> sets = set_values(set);
        auto stop = std::make_shared<std::atomic<bool>>(false);
        std::unique_ptr<host::StudyOutcome> outcome;
        run_interruptibly([&] { outcome = session->study(sets, settings, samples, method, seed, outputs, threads, stop.get(),
                                                                  python_budget(max_work, max_memory, true)); },
                          [&] { *stop = true; }, OnInterrupt::wait);
        // The design's cases as the sweep's rows show them: parameters and outputs in their
        // columns' units, the failure class.
        py::dict cases;
        const host::StudyOutcome& o = *outcome;
        add_study_parameters(cases, o.graph, o.table, threads ? threads : std::thread::hardware_concurrency());
        for (std::size_t c = 0; c < o.data.outputs.size(); ++c)
          cases[py::str(study_sample_column(o.graph, o.data.outputs[c]))] = numpy_column(o.data.values[c]);
        std::vector<std::int64_t> exits;
        exits.reserve(o.data.failures.size());
        for (CaseFailure f : o.data.failures) exits.push_back(host::exit_code_of(f));
        cases["exit"] = numpy_column(exits);
        return py::make_tuple(o.json, cases);
      })
      .def("study_design", [](const std::shared_ptr<SceneSession>& session, const std::string& block, const py::list& set,
                              const std::string& samples, const std::string& method, const std::string& seed,
                              const std::vector<std::string>& outputs, double max_work, double max_memory) {
        // The study's cases: the parameters in SI by name (what the sweep is given), and as
        // Study.samples shows them (the sweep's input columns).
        std::optional<RawValue> settings;
        if (!block.empty()) settings = parse_raw_value(block, SourceLocation{"Scene.study()", 0, 0});
        const std::vector<SetValue> sets = set_values(set);
        // The design goes out as a sweep's cases (mechgraph.dask.study), whose table from Python
        // keeps a CaseValue a value: refused in the study's words before it is drawn, not later
        // as a sweep.
        const auto within_a_sweep = [](const StudySpec& spec) {
          if (const std::string excess = design_size_excess(spec, max_case_cells, "a sweep sent out from Python holds"); !excess.empty())
            throw SceneError("mechgraph.dask.study: " + excess + ", or run the study in one process (Scene.study, mechgraph study), "
                             "whose design holds up to " + std::to_string(max_design_values) + " values");
        };
        const auto o = session->prepare_study(sets, settings, samples, method, seed, outputs, python_budget(max_work, max_memory, true),
                                              within_a_sweep);
        py::dict cases, shown;
        for (std::size_t v = 0; v < o->table.variables.size(); ++v) {
          std::vector<double> column(o->table.size());
          CaseValue made;
          for (std::size_t i = 0; i < column.size(); ++i) column[i] = *o->table.cell(i, v, made).si;
          cases[py::str(o->table.variables[v].name)] = numpy_column(column);
        }
        add_study_parameters(shown, o->graph, o->table, std::thread::hardware_concurrency());
        return py::make_tuple(cases, shown);
      })
      .def("study_rows", [](const std::shared_ptr<SceneSession>& session, const std::string& block, const py::list& set,
                            const std::string& samples, const std::string& method, const std::string& seed,
                            const std::vector<std::string>& outputs, const py::dict& columns, const std::vector<int>& exits,
                            double max_work, double max_memory) {
        // The answers from rows a sweep of the study's cases gave (`name [unit]` columns in the
        // units the rows show, NaN where a case failed; exit per case), as Scene.study's.
        std::optional<RawValue> settings;
        if (!block.empty()) settings = parse_raw_value(block, SourceLocation{"Scene.study()", 0, 0});
        const std::vector<SetValue> sets = set_values(set);
        auto o = session->prepare_study(sets, settings, samples, method, seed, outputs, python_budget(max_work, max_memory, true));
        const std::size_t n = o->table.size();
        if (exits.size() != n) throw SceneError("study rows: " + std::to_string(exits.size()) + " rows for the design's " + std::to_string(n) + " cases");
        o->data.outputs = o->columns;
        o->data.failures.resize(n);
        for (std::size_t i = 0; i < n; ++i)
          o->data.failures[i] = exits[i] == 0 ? CaseFailure::none : exits[i] == 2 ? CaseFailure::scene : CaseFailure::evaluation;
        for (const StudyColumn& c : o->columns) {
          const std::string name = study_sample_column(o->graph, c);
          if (!columns.contains(name)) throw SceneError("study rows: no column '" + name + "'");
          std::vector<double> values = columns[py::str(name)].cast<std::vector<double>>();
          if (values.size() != n) throw SceneError("study rows: column '" + name + "' has " + std::to_string(values.size()) + " values");
          for (std::size_t i = 0; i < n; ++i)
            if (o->data.failures[i] != CaseFailure::none) values[i] = std::numeric_limits<double>::quiet_NaN();
          o->data.values.push_back(std::move(values));
        }
        host::finish_study(*o);
        return o->json;
      });
}
