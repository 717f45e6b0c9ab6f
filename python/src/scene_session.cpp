#include "scene_session.hpp"

#include "case_values.hpp"
#include "input_columns.hpp"
#include "unit_rule.hpp"

#include <mechgraph/host/plugin_search.hpp>
#include <mechgraph/host/scene_loading.hpp>
#include <mechgraph/host/usage_error.hpp>
#include <mechgraph/host/sweep_rows.hpp>

#include <mechgraph/did_you_mean.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/sweep/case_estimate.hpp>
#include <mechgraph/work_estimate.hpp>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <limits>
#include <thread>

namespace mechgraph::python {
namespace {

// Built graphs kept per choice of outputs and varied names; more than this and they are dropped.
constexpr std::size_t max_prepared = 64;

std::string joined(const std::vector<std::string>& items, char separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? std::string(1, separator) : std::string()) + items[i];
  return out;
}

}  // namespace

WorkBudget python_budget(double max_work, double max_memory, bool sweep) {
  WorkBudget budget;
  budget.names = python_budget_names;
  if (sweep) budget.max_work = sweep_default_max_work;
  if (max_work > 0.0) budget.max_work = max_work;
  if (max_memory > 0.0) budget.max_memory = max_memory;
  return budget;
}

SceneSession::SceneSession(std::shared_ptr<const PluginRegistry> registry, SceneSpec scene)
    : registry_(std::move(registry)), scene_(std::move(scene)) {}

SceneSpec SceneSession::with_outputs(const std::vector<std::string>& outputs) const {
  SceneSpec scene = scene_;
  if (!outputs.empty()) {
    scene.outputs.clear();
    scene.report.clear();
    for (const std::string& o : outputs) {
      PortRef ref = parse_port_ref(o, {"outputs=" + o, 0, 0});
      if (listed_before(scene.outputs, ref))
        throw SceneError("outputs: '" + ref.str() + "' is listed twice; each output is one value (one column): list it once");
      scene.outputs.push_back(std::move(ref));
    }
  }
  return scene;
}

void SceneSession::validate(const WorkBudget& budget) {
  std::lock_guard lock(mutex_);
  const Graph& graph = prepared({}, {}, {}).graph;
  check_work_budget(graph, estimate_work(graph), budget, 1, false);
}

std::optional<Dimension> SceneSession::dimension_of(const std::string& name) {
  std::lock_guard lock(plain_mutex_);
  if (!plain_) plain_ = build_graph(scene_, *registry_);
  return target_dimension(*plain_, name);
}

std::string SceneSession::scene_unit_of(std::string_view name, Dimension d) const { return scene_unit(scene_, name, d); }

void SceneSession::require_unit_or_si(const std::string& context, const std::string& name, double given) {
  const std::optional<Dimension> d = dimension_of(name);
  if (d && !d->dimensionless())
    throw SceneErrorAt(subject_of(name), bare_number_refusal(context, name, number_text(given), *d, scene_unit_of(name, *d), BareKind::number));
}

void SceneSession::clear_cache() {
  std::lock_guard lock(mutex_);
  cache_ = std::make_unique<MemoCache>();
}

SceneSession::Prepared& SceneSession::prepared(const std::vector<std::string>& outputs, const std::vector<std::string>& names,
                                               const std::vector<std::string>& list_names) {
  const std::string key = joined(outputs, ',') + '\n' + joined(names, ',') + '\n' + joined(list_names, ',');
  if (auto it = prepared_.find(key); it != prepared_.end()) return it->second;
  if (prepared_.size() >= max_prepared) prepared_.clear();
  return prepared_.emplace(std::move(key), prepare(outputs, names)).first->second;
}

SceneSession::Prepared SceneSession::prepare(const std::vector<std::string>& outputs, const std::vector<std::string>& names) const {
  Prepared p;
  p.scene = std::make_unique<SceneSpec>(with_outputs(outputs));
  p.graph = build_graph(*p.scene, *registry_);
  std::vector<SweepVariable> variables;
  for (const std::string& n : names) variables.push_back({n, ""});
  p.binder = std::make_unique<CaseBinder>(p.graph, *p.scene, *registry_, std::vector<Override>{}, variables, BinderUse::set);
  return p;
}

namespace {

// Writes a list parameter (`table.angles`) straight into the built graph, each element checked as
// the scene loader checks a list's numbers: finite, within the parameter's range. No YAML: a table
// of a million rows costs its copy.
void write_list(Graph& graph, const SceneSpec& scene, const SetValue& given) {
  const std::string& name = given.name;
  const auto dot = name.find('.');
  const std::string context = "set " + name;
  if (dot == std::string::npos)
    throw SceneError(context + ": an array goes to a node's list parameter (node.param), not to a scene parameter");
  const std::string node_name = name.substr(0, dot), param = name.substr(dot + 1);
  const auto node = graph.find(node_name);
  if (!node) {
    std::vector<std::string> valid;
    for (const GraphNode& n : graph.nodes) valid.push_back(n.name);
    throw SceneError(context + ": " + unknown_name_message("node", node_name, valid));
  }
  GraphNode& target = graph.nodes[*node];
  const ParamSpec* spec = target.info().find_param(param);
  if (!spec || spec->kind != ParamKind::number_list) {
    std::vector<std::string> lists;
    for (const ParamSpec& p : target.info().params)
      if (p.kind == ParamKind::number_list) lists.push_back(p.name);
    const std::string type = " (" + target.info().type + ")";
    if (!spec) throw SceneError(context + type + ": " + unknown_name_message("list parameter", param, lists));
    std::string valid;
    for (const std::string& l : lists) valid += (valid.empty() ? "" : " ") + l;
    throw SceneError(context + type + ": '" + param + "' takes one value, not an array (its list parameters: " +
                     (valid.empty() ? "none" : valid) + ")");
  }
  // In SI: converted from the unit given with them, or marked SI; bare numbers only when dimensionless.
  std::vector<double> values = std::get<std::vector<double>>(given.value);
  if (!given.unit.empty()) {
    values = values_in_si(values, given.unit, spec->dimension, context);
  } else if (!given.si && !spec->dimension.dimensionless()) {
    throw SceneErrorAt(subject_of(name), bare_number_refusal(context, name, "", spec->dimension, scene_unit(scene, name, spec->dimension),
                                         BareKind::array));
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i]))
      throw SceneError(context + ": element " + std::to_string(i) + " is " + (std::isnan(values[i]) ? "NaN" : "infinite"));
    if (const std::string problem = spec->value_problem(values[i]); !problem.empty())
      throw SceneError(context + ": element " + std::to_string(i) + " = " + si_text(values[i], spec->dimension) + " " + problem);
  }
  target.params.set(param, ParamValue::of_list(std::move(values)));
}

}  // namespace

SceneSession::BoundSets SceneSession::bound_sets(const std::vector<SetValue>& sets) {
  BoundSets b;
  for (const SetValue& s : sets) {
    const std::string context = "set " + s.name;
    if (const auto* text = std::get_if<std::string>(&s.value)) {
      b.names.push_back(s.name);
      b.values.push_back(value_from_text(*text, context));
      b.overrides.push_back(s.name + "=" + *text);
    } else if (const auto* number = std::get_if<double>(&s.value)) {
      if (!s.si) require_unit_or_si(context, s.name, *number);
      b.names.push_back(s.name);
      b.values.push_back(value_from_si(*number, dimension_of(s.name).value_or(Dimension{}), context));
      b.overrides.push_back(s.name + "=" + b.values.back().text);
    } else {
      b.list_names.push_back(s.name);
      b.lists.push_back(&s);
      b.overrides.push_back(s.name + "=<" + std::to_string(std::get<std::vector<double>>(s.value).size()) + " values, " +
                            (s.unit.empty() ? std::string("SI") : s.unit) + ">");
    }
  }
  return b;
}

void SceneSession::give(const CaseBinder& binder, Graph& graph, const BoundSets& sets) const {
  binder.apply(graph, sets.values);
  for (const SetValue* l : sets.lists) write_list(graph, scene_, *l);
}

SessionRun SceneSession::run(std::shared_ptr<const std::vector<SetValue>> sets, const std::vector<std::string>& outputs,
                             unsigned threads, const WorkBudget& budget) {
  std::lock_guard lock(mutex_);
  SessionRun run;
  BoundSets bound = bound_sets(*sets);
  // The graph for this choice of outputs and names: every run with it writes all of its names, so
  // nothing of an earlier run's values stays behind.
  Prepared& p = prepared(outputs, bound.names, bound.list_names);
  give(*p.binder, p.graph, bound);
  // With this run's values: a set= value (curve points, revolutions, samples) can ask for far more
  // than the scene as written, which is all a check at preparation would see.
  check_work_budget(p.graph, estimate_work(p.graph), budget, 1, false);
  const auto start = std::chrono::steady_clock::now();
  run.result = evaluate(p.graph, *cache_, threads);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.scene_output_count = p.graph.scene_output_count;
  run.overrides = std::move(bound.overrides);
  run.sets = std::move(sets);
  return run;
}

std::vector<Override> SceneSession::fixed_overrides(const std::vector<SetValue>& sets) {
  std::vector<Override> overrides;
  for (const SetValue& s : sets) {
    // An override is read as YAML (as --set's are); a value from Python goes in as one quoted
    // scalar, so its text is the value whatever it holds ("*x", "[1, 2]", "~").
    std::string text;
    if (const auto* t = std::get_if<std::string>(&s.value)) text = *t;
    else if (const auto* number = std::get_if<double>(&s.value)) {
      if (!s.si) require_unit_or_si("set " + s.name, s.name, *number);
      text = value_from_si(*number, dimension_of(s.name).value_or(Dimension{}), "set " + s.name).text;
    } else throw SceneError("set " + s.name + ": an array is not a sweep's fixed value (give it to Scene.run, or vary it)");
    overrides.push_back({s.name, yaml_quoted(text), s.name + "=" + text});
  }
  return overrides;
}

std::unique_ptr<host::StudyOutcome> SceneSession::study(const std::vector<SetValue>& sets, const std::optional<RawValue>& block,
                                                       const std::string& samples, const std::string& method, const std::string& seed,
                                                       const std::vector<std::string>& outputs, unsigned threads,
                                                       const std::atomic<bool>* stop, const WorkBudget& budget) {
  const std::vector<Override> overrides = fixed_overrides(sets);
  return host::run_scene_study(scene_, *registry_, overrides, block, samples, method, seed,
                              outputs.empty() ? std::nullopt : std::optional<std::string>(joined(outputs, ',')), budget, threads, stop,
                              host::python_option_names);
}

std::unique_ptr<host::StudyOutcome> SceneSession::prepare_study(const std::vector<SetValue>& sets, const std::optional<RawValue>& block,
                                                               const std::string& samples, const std::string& method,
                                                               const std::string& seed, const std::vector<std::string>& outputs,
                                                               const WorkBudget& budget,
                                                               const std::function<void(const StudySpec&)>& check_spec) {
  // Within the budget Scene.study keeps (what the study holds beside its cases, its bootstrap's
  // work): the design a Dask study sends out and analyses is refused as the in-process one is.
  return host::prepare_scene_study(scene_, *registry_, fixed_overrides(sets), block, samples, method, seed,
                                  outputs.empty() ? std::nullopt : std::optional<std::string>(joined(outputs, ',')), 1, &budget, nullptr,
                                  host::python_option_names, check_spec);
}

void SceneSession::with_sweep_graph(const CaseTable& table, const std::vector<SetValue>& sets,
                                    const std::vector<std::string>& outputs,
                                    const std::function<void(const Graph&, const CaseBinder&)>& use) {
  SceneSpec scene = scene_;
  const std::vector<Override> overrides = fixed_overrides(sets);
  const Graph graph = host::build_sweep_graph(scene, *registry_, overrides,
                                             outputs.empty() ? std::nullopt : std::optional<std::string>(joined(outputs, ',')),
                                             host::python_option_names);
  const CaseBinder binder(graph, scene, *registry_, overrides, table.variables);
  use(graph, binder);
}

namespace {
SweepOptions sweep_options(const CaseTable& table, unsigned threads) {
  SweepOptions options;
  for (std::size_t i = 0; i < table.size(); ++i) options.cases.push_back(i);
  options.threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  return options;
}

// Input v of the rows as SessionInputColumn keeps it: numbers, or the cells where a row holds text
// or nothing (such a row's number is NaN: input_number).
SessionInputColumn input_column(const host::SweepRows& rows, const std::vector<std::size_t>& cases, std::size_t v,
                                std::vector<double>&& numbers) {
  SessionInputColumn column;
  if (std::none_of(numbers.begin(), numbers.end(), [](double x) { return std::isnan(x); })) {
    column.numbers = std::move(numbers);
    return column;
  }
  std::string cell;
  column.cells.reserve(cases.size());
  for (const std::size_t i : cases) column.cells.push_back(rows.input_value(i, v, cell));
  return column;
}

// The rows of a sweep: the cases of `options` run, each row into `out` in case order.
void run_rows(const Graph& graph, const CaseBinder& binder, const CaseTable& table, const SweepOptions& options,
              std::atomic<std::size_t>* done, SessionSweep& out) {
  // As `mechgraph sweep` does: rows wait until the first success fixes the columns of a series.
  host::SweepRows rows(graph, table, host::RowFormat::jsonl);
  out.cases.reserve(options.cases.size());
  out.exits.reserve(options.cases.size());
  std::string error;
  host::RowSequencer sequence(
      rows, [] {},
      [&](const CaseResult& r) {
        const std::size_t row = out.cases.size();
        if (row == 0) out.outputs.reserve(options.cases.size() * rows.output_columns());
        out.cases.push_back(r.index);
        const std::size_t filled = out.outputs.size();
        out.exits.push_back(rows.outcome(r, host::exit_code_of(r.failure), out.outputs, error));
        if (out.exits.back() == 0) return;
        ++out.failed;
        out.outputs.resize(filled + rows.output_columns(), std::numeric_limits<double>::quiet_NaN());
        if (!error.empty()) out.errors.emplace_back(row, error);
      });
  MemoCache cache;
  out.summary = run_sweep(graph, binder, table, cache, options, [&](CaseResult&& r) {
    sequence(std::move(r));
    if (done) done->fetch_add(1, std::memory_order_relaxed);
  });
  sequence.finish();
  // Stopped by Ctrl-C: the caller raises and reads none of it, so the rows done are not made into
  // input columns (0.2 s at 10^6 rows, before the interrupt reached Python).
  if (out.summary.stopped) return;
  out.header = rows.header();
  out.inputs = table.variables.size();
  // The inputs column by column, as the rows show them, on the sweep's threads.
  std::vector<std::vector<double>> numbers = input_number_columns(rows, out.cases.size(), out.cases.data(), options.threads);
  for (std::size_t v = 0; v < numbers.size(); ++v) out.input_columns.push_back(input_column(rows, out.cases, v, std::move(numbers[v])));
}
}  // namespace

void SceneSession::check_sweep(const CaseTable& table, const std::vector<SetValue>& sets, const std::vector<std::string>& outputs,
                               unsigned threads, const WorkBudget& budget) {
  with_sweep_graph(table, sets, outputs, [&](const Graph& graph, const CaseBinder& binder) {
    // The whole sweep's work and largest case, before its chunks go out (mechgraph.dask.sweep):
    // its memory budget is a chunk's, and each worker counts its own chunk's table (sweep below).
    const SweepOptions options = sweep_options(table, threads);
    check_sweep_budget(graph, binder, table, options.cases, budget, options.threads);
  });
}

SessionSweep SceneSession::sweep(const CaseTable& table, const std::vector<SetValue>& sets,
                                 const std::vector<std::string>& outputs, unsigned threads, const std::atomic<bool>* stop,
                                 const WorkBudget& budget, std::atomic<std::size_t>* done) {
  SessionSweep out;
  with_sweep_graph(table, sets, outputs, [&](const Graph& graph, const CaseBinder& binder) {
    SweepOptions options = sweep_options(table, threads);
    // Every case with its own values, as `mechgraph sweep` estimates them (sweep/case_estimate.hpp).
    check_sweep_budget(graph, binder, table, options.cases, beside_the_table(budget, table, options.cases.size()), options.threads);
    options.stop = stop;
    run_rows(graph, binder, table, options, done, out);
  });
  return out;
}

Graph SceneSession::graph_for(const std::vector<SetValue>& sets, const std::vector<std::string>& outputs) {
  const BoundSets bound = bound_sets(sets);
  std::lock_guard lock(mutex_);
  const Prepared& p = prepared(outputs, bound.names, bound.list_names);
  Graph graph = p.graph;  // a copy: the prepared graph belongs to the runs
  give(*p.binder, graph, bound);
  return graph;
}

}  // namespace mechgraph::python
