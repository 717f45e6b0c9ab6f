// mechgraph._core: the pybind11 extension behind the Python package `mechgraph` (python/mechgraph).
// It holds the plugin registry (loaded by the command line's rules: --plugin-dir folders given to
// load_plugins(), MECHGRAPH_PLUGIN_PATH, the built-in folder beside libmechgraph), the scene
// sessions, and the conversions; the Pythonic surface (Result, DataFrames, errors) is Python code.
#include "case_values.hpp"
#include "interruptible.hpp"
#include "python_values.hpp"
#include "scene_session.hpp"
#include "value_arrays.hpp"

#include <study_run.hpp>
#include <sweep_rows.hpp>

#include <cli.hpp>
#include <node_info_format.hpp>
#include <terminal_output.hpp>

#include <mechgraph/did_you_mean.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/json_writer.hpp>
#include <mechgraph/units.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <spdlog/spdlog.h>

#include <atomic>
#include <charconv>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>

namespace py = pybind11;
using namespace mechgraph;
using namespace mechgraph::python;

namespace {

// ---- plugins ------------------------------------------------------------------------------------

std::mutex registry_mutex;
std::shared_ptr<const PluginRegistry> current_registry;

std::shared_ptr<const PluginRegistry> load_registry(const std::vector<std::string>& dirs, bool only) {
  cli::GlobalOptions options;
  options.plugin_dirs = dirs;
  options.only_plugin_dirs = only;
  auto registry = std::make_shared<const PluginRegistry>(cli::load_plugins(options));
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

// A `set=` entry through the one conversion of Python values (python_values.hpp): text, a number
// in SI, or a 1-D array of numbers in SI for a list parameter.
SetValue set_value(const std::string& name, const py::handle& value) {
  const std::string context = "set " + name;
  if (is_sequence(value)) {
    ColumnValues column = column_values(value, context);
    if (column.text) throw SceneError(context + ": an array goes to a list parameter as numbers in SI, not as text");
    return {name, std::move(column.numbers)};
  }
  ScalarValue scalar = scalar_value(value, context);
  if (auto* text = std::get_if<std::string>(&scalar)) return {name, std::move(*text)};
  return {name, std::get<double>(scalar)};
}

// A sweep's cases from columns, each through the one conversion of Python values: numbers in the
// column's unit, or in SI without one; or text cells read as a cases file's are (a bare number
// takes the column's unit).
CaseTable case_table(SceneSession& session, const std::vector<std::string>& names, const std::vector<std::string>& units,
                     const py::list& columns) {
  CaseTable table;
  table.origin = "python";
  if (py::len(columns) != names.size()) throw SceneError("cases: " + std::to_string(names.size()) + " names for " +
                                                         std::to_string(py::len(columns)) + " columns");
  std::size_t n = 0;
  for (std::size_t v = 0; v < names.size(); ++v) {
    const std::string& name = names[v];
    const std::string& unit = units[v];
    table.variables.push_back({name, unit});
    const ColumnValues column = column_values(columns[v], "cases: column '" + excerpt(name) + "'");
    if (v == 0) {
      n = column.size();
      if (n > max_sweep_cases) throw SceneError("more than 10^7 cases in one sweep; split it into several sweeps");
      if (n * names.size() > max_case_cells)
        throw SceneError("more than " + std::to_string(max_case_cells) + " values in one sweep; split it into several sweeps");
      table.cases.assign(n, std::vector<CaseValue>(names.size()));
    } else if (column.size() != n) {
      throw SceneError("cases: column '" + excerpt(name) + "' has " + std::to_string(column.size()) + " values, the first " +
                       std::to_string(n));
    }
    const auto context = [&](std::size_t i) { return "cases: column '" + excerpt(name) + "', row " + std::to_string(i); };
    if (!column.text) {
      const std::optional<Dimension> d = unit.empty() ? session.dimension_of(name) : std::nullopt;
      for (std::size_t i = 0; i < n; ++i) {
        const double x = column.numbers[i];
        if (!std::isfinite(x)) throw SceneError(context(i) + ": not a finite number");
        table.cases[i][v] = unit.empty() ? value_from_si(x, d.value_or(Dimension{}), context(i))
                                         : value_from_text(si_text(x, Dimension{}) + " " + unit, context(i));
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        const std::string& cell = column.cells[i];
        CaseValue value = value_from_text(cell, context(i));
        if (!unit.empty() && value.si && value.dimension.dimensionless() && cell.find_first_not_of("0123456789.eE+- ") == std::string::npos)
          value = value_from_text(cell + " " + unit, context(i));
        table.cases[i][v] = std::move(value);
      }
    }
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
};

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

// ---- errors -------------------------------------------------------------------------------------

void raise_as(const char* class_name, const std::string& message) {
  const py::object cls = py::module_::import("mechgraph._errors").attr(class_name);
  PyErr_SetObject(cls.ptr(), python_text(message).ptr());  // a message may quote a plugin's bytes
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "mechgraph's C++ core (libmechgraph and its plugins); use the package `mechgraph`.";
  m.attr("__version__") = MECHGRAPH_VERSION;
  // Log messages quote scene and plugin text: through terminal_text, as the command line's are.
  cli::use_terminal_safe_logger("mechgraph");
  spdlog::set_level(spdlog::level::warn);  // a notebook wants results, not progress; set_log_level() changes it

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneError& e) {
      raise_as("SceneError", e.what());
    } catch (const cli::UsageError& e) {
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
    if (!t) throw cli::UsageError(unknown_name_message("node type", type, r->type_names()));
    std::ostringstream json_text, text;
    JsonWriter json(json_text);
    cli::write_node_info_json(json, t->type->info());
    cli::write_node_info_text(text, t->type->info());
    return py::make_tuple(json_text.str(), text.str());
  });
  m.def("set_log_level", [](const std::string& level) {
    const auto l = spdlog::level::from_str(level);
    if (l == spdlog::level::off && level != "off")
      throw SceneError("log level '" + level + "': valid levels are trace, debug, info, warn, error, critical, off");
    spdlog::set_level(l);
  });
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
      .def_property_readonly("seconds", [](const RunOutcome& r) { return r.run->seconds; })
      .def("provenance", &provenance);

  py::class_<SceneSession, std::shared_ptr<SceneSession>>(m, "Session")
      .def_static("load", [](const std::string& path) {
        return std::make_shared<SceneSession>(registry(), load_scene(path));
      })
      .def_static("from_text", [](const std::string& yaml, const std::string& label) {
        return std::make_shared<SceneSession>(registry(), parse_scene(yaml, label));
      })
      .def("validate", [](SceneSession& s) {
        py::gil_scoped_release released;
        s.validate();
      })
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
      .def("run", [](const std::shared_ptr<SceneSession>& session, const py::dict& sets, const std::vector<std::string>& outputs,
                     unsigned threads, bool interruptible) {
        auto values = std::make_shared<std::vector<SetValue>>();
        for (const auto& [key, value] : sets) values->push_back(set_value(py::str(key), value));
        auto run = std::make_shared<SessionRun>();
        if (interruptible) {
          // The work owns what it touches: on Ctrl-C it may finish after this call has raised.
          run_interruptibly([session, values, outputs, threads, run] { *run = session->run(values, outputs, threads); }, [] {},
                            OnInterrupt::detach);
        } else {
          py::gil_scoped_release released;
          *run = session->run(values, outputs, threads);
        }
        return RunOutcome{session, run, outputs};
      }, py::arg("sets"), py::arg("outputs"), py::arg("threads") = 1, py::arg("interruptible") = true)
      .def("sweep", [](const std::shared_ptr<SceneSession>& session, const std::vector<std::string>& names,
                       const std::vector<std::string>& units, const py::list& columns, const py::dict& set,
                       const std::vector<std::string>& outputs, unsigned threads) {
        const CaseTable table = case_table(*session, names, units, columns);
        std::vector<SetValue> sets;
        for (const auto& [key, value] : set) sets.push_back(set_value(py::str(key), value));
        auto stop = std::make_shared<std::atomic<bool>>(false);
        SessionSweep result;
        run_interruptibly([&] { result = session->sweep(table, sets, outputs, threads, stop.get()); }, [&] { *stop = true; },
                          OnInterrupt::wait);
        py::dict summary;
        summary["cases"] = result.summary.run;
        summary["failed"] = result.failed;
        summary["seconds"] = result.summary.seconds;
        return py::make_tuple(result.header, result.lines, summary);
      })
      .def("study", [](const std::shared_ptr<SceneSession>& session, const std::string& block, const py::dict& set,
                       const std::string& samples, const std::string& method, const std::string& seed,
                       const std::vector<std::string>& outputs, unsigned threads) {
        // `block`: the settings from Python as JSON text ("" for none), read as the scene's block is.
        std::optional<RawValue> settings;
        if (!block.empty()) settings = parse_raw_value(block, SourceLocation{"Scene.study()", 0, 0});
        std::vector<SetValue> sets;
        for (const auto& [key, value] : set) sets.push_back(set_value(py::str(key), value));
        auto stop = std::make_shared<std::atomic<bool>>(false);
        std::unique_ptr<cli::StudyOutcome> outcome;
        run_interruptibly([&] { outcome = session->study(sets, settings, samples, method, seed, outputs, threads, stop.get()); },
                          [&] { *stop = true; }, OnInterrupt::wait);
        // The design's cases: the parameters in SI, the outputs in their shown units, the failure class.
        py::dict cases;
        const cli::StudyOutcome& o = *outcome;
        for (std::size_t v = 0; v < o.table.variables.size(); ++v) {
          std::vector<double> column(o.table.cases.size());
          for (std::size_t i = 0; i < column.size(); ++i) column[i] = *o.table.cases[i][v].si;
          cases[py::str(o.table.variables[v].name)] = column;
        }
        py::list units;
        for (std::size_t c = 0; c < o.data.outputs.size(); ++c) {
          const StudyColumn& col = o.data.outputs[c];
          const std::string unit = col.unit.empty() ? col.dimension.si_unit() : col.unit;
          const std::string name = unit.empty() || unit == "1" ? col.label : col.label + " [" + unit + "]";
          cases[py::str(name)] = o.data.values[c];
        }
        std::vector<int> exits;
        for (CaseFailure f : o.data.failures) exits.push_back(cli::exit_code_of(f));
        cases["exit"] = exits;
        return py::make_tuple(o.json, cases);
      })
      .def("study_design", [](const std::shared_ptr<SceneSession>& session, const std::string& block, const py::dict& set,
                              const std::string& samples, const std::string& method, const std::string& seed,
                              const std::vector<std::string>& outputs) {
        // The study's cases (parameters in SI) and the output columns its rows will carry.
        std::optional<RawValue> settings;
        if (!block.empty()) settings = parse_raw_value(block, SourceLocation{"Scene.study()", 0, 0});
        std::vector<SetValue> sets;
        for (const auto& [key, value] : set) sets.push_back(set_value(py::str(key), value));
        const auto o = session->prepare_study(sets, settings, samples, method, seed, outputs);
        py::dict cases;
        for (std::size_t v = 0; v < o->table.variables.size(); ++v) {
          std::vector<double> column(o->table.cases.size());
          for (std::size_t i = 0; i < column.size(); ++i) column[i] = *o->table.cases[i][v].si;
          cases[py::str(o->table.variables[v].name)] = column;
        }
        return cases;
      })
      .def("study_rows", [](const std::shared_ptr<SceneSession>& session, const std::string& block, const py::dict& set,
                            const std::string& samples, const std::string& method, const std::string& seed,
                            const std::vector<std::string>& outputs, const py::dict& columns, const std::vector<int>& exits) {
        // The answers from rows a sweep of the study's cases gave (`name [unit]` columns in the
        // units the rows show, NaN where a case failed; exit per case), as Scene.study's.
        std::optional<RawValue> settings;
        if (!block.empty()) settings = parse_raw_value(block, SourceLocation{"Scene.study()", 0, 0});
        std::vector<SetValue> sets;
        for (const auto& [key, value] : set) sets.push_back(set_value(py::str(key), value));
        auto o = session->prepare_study(sets, settings, samples, method, seed, outputs);
        const std::size_t n = o->table.cases.size();
        if (exits.size() != n) throw SceneError("study rows: " + std::to_string(exits.size()) + " rows for the design's " + std::to_string(n) + " cases");
        o->data.outputs = o->columns;
        o->data.failures.resize(n);
        for (std::size_t i = 0; i < n; ++i)
          o->data.failures[i] = exits[i] == 0 ? CaseFailure::none : exits[i] == 2 ? CaseFailure::scene : CaseFailure::evaluation;
        for (const StudyColumn& c : o->columns) {
          const std::string unit = c.unit.empty() ? c.dimension.si_unit() : c.unit;
          const std::string name = unit.empty() || unit == "1" ? c.label : c.label + " [" + unit + "]";
          if (!columns.contains(name)) throw SceneError("study rows: no column '" + name + "'");
          std::vector<double> values = columns[py::str(name)].cast<std::vector<double>>();
          if (values.size() != n) throw SceneError("study rows: column '" + name + "' has " + std::to_string(values.size()) + " values");
          for (std::size_t i = 0; i < n; ++i)
            if (o->data.failures[i] != CaseFailure::none) values[i] = std::numeric_limits<double>::quiet_NaN();
          o->data.values.push_back(std::move(values));
        }
        cli::finish_study(*o);
        return o->json;
      });
}
