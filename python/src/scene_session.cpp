#include "scene_session.hpp"

#include "case_values.hpp"

#include <cli.hpp>
#include <sweep_rows.hpp>

#include <mechgraph/errors.hpp>
#include <mechgraph/work_estimate.hpp>

#include <algorithm>
#include <chrono>
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

SceneSession::SceneSession(std::shared_ptr<const PluginRegistry> registry, SceneSpec scene)
    : registry_(std::move(registry)), scene_(std::move(scene)) {}

SceneSpec SceneSession::with_outputs(const std::vector<std::string>& outputs) const {
  SceneSpec scene = scene_;
  if (!outputs.empty()) {
    scene.outputs.clear();
    scene.report.clear();
    for (const std::string& o : outputs) scene.outputs.push_back(parse_port_ref(o, {"outputs=" + o, 0, 0}));
  }
  return scene;
}

void SceneSession::validate() {
  std::lock_guard lock(mutex_);
  prepared({}, {}, {});
}

std::optional<Dimension> SceneSession::dimension_of(const std::string& name) {
  std::lock_guard lock(plain_mutex_);
  if (!plain_) plain_ = build_graph(scene_, *registry_);
  return target_dimension(*plain_, name);
}

void SceneSession::clear_cache() {
  std::lock_guard lock(mutex_);
  cache_ = std::make_unique<MemoCache>();
}

SceneSession::Prepared& SceneSession::prepared(const std::vector<std::string>& outputs, const std::vector<std::string>& names,
                                               const std::vector<Override>& list_overrides) {
  std::string key = joined(outputs, ',') + '\n' + joined(names, ',');
  for (const Override& o : list_overrides) key += '\n' + o.text;
  if (auto it = prepared_.find(key); it != prepared_.end()) return it->second;
  if (prepared_.size() >= max_prepared) prepared_.clear();
  Prepared p;
  p.scene = std::make_unique<SceneSpec>(with_outputs(outputs));
  p.graph = build_graph(*p.scene, *registry_, list_overrides);
  check_work_budget(p.graph, estimate_work(p.graph), WorkBudget{}, 1, false);
  std::vector<SweepVariable> variables;
  for (const std::string& n : names) variables.push_back({n, ""});
  p.binder = std::make_unique<CaseBinder>(p.graph, *p.scene, *registry_, list_overrides, variables);
  return prepared_.emplace(std::move(key), std::move(p)).first->second;
}

SessionRun SceneSession::run(const std::vector<SetValue>& sets, const std::vector<std::string>& outputs, unsigned threads) {
  std::lock_guard lock(mutex_);
  SessionRun run;
  std::vector<std::string> names;
  std::vector<CaseValue> values;
  std::vector<Override> list_overrides;
  for (const SetValue& s : sets) {
    const std::string context = "set " + s.name;
    if (const auto* text = std::get_if<std::string>(&s.value)) {
      names.push_back(s.name);
      values.push_back(value_from_text(*text, context));
      run.overrides.push_back(s.name + "=" + *text);
    } else if (const auto* number = std::get_if<double>(&s.value)) {
      names.push_back(s.name);
      values.push_back(value_from_si(*number, dimension_of(s.name).value_or(Dimension{}), context));
      run.overrides.push_back(s.name + "=" + values.back().text);
    } else {
      // A list (a lift table's angles) is written into the scene as --set would: the graph is built
      // again for it (and kept while the same list comes back).
      const auto& list = std::get<std::vector<double>>(s.value);
      const std::string text = s.name + "=" + si_list_text(list, dimension_of(s.name).value_or(Dimension{}), context);
      list_overrides.push_back(parse_override(text));
      run.overrides.push_back(text);
    }
  }
  Prepared& p = prepared(outputs, names, list_overrides);
  p.binder->apply(p.graph, values);
  const auto start = std::chrono::steady_clock::now();
  run.result = evaluate(p.graph, *cache_, threads);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.scene_output_count = p.graph.scene_output_count;
  return run;
}

SessionSweep SceneSession::sweep(const CaseTable& table, const std::vector<std::string>& sets_text,
                                 const std::vector<std::string>& outputs, unsigned threads, const std::atomic<bool>* stop) {
  SceneSpec scene = scene_;
  std::vector<Override> overrides;
  for (const std::string& s : sets_text) overrides.push_back(parse_override(s));
  const Graph graph = cli::build_sweep_graph(scene, *registry_, overrides,
                                             outputs.empty() ? std::nullopt : std::optional<std::string>(joined(outputs, ',')));
  const CaseBinder binder(graph, scene, *registry_, overrides, table.variables);
  WorkBudget budget;
  budget.max_work = sweep_default_max_work;
  check_work_budget(graph, estimate_work(graph), budget, static_cast<double>(std::max<std::size_t>(table.cases.size(), 1)), false);

  SweepOptions options;
  for (std::size_t i = 0; i < table.cases.size(); ++i) options.cases.push_back(i);
  options.threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  options.stop = stop;

  // As `mechgraph sweep` does: rows wait until the first success fixes the columns of a series.
  SessionSweep out;
  cli::SweepRows rows(graph, table, cli::RowFormat::jsonl);
  std::vector<CaseResult> waiting;
  auto put = [&](const CaseResult& r) {
    out.lines.push_back(rows.line(r, cli::exit_code_of(r.failure)));
    if (r.failure != CaseFailure::none) ++out.failed;
  };
  auto settle = [&](const CaseResult* success) {
    rows.settle(success);
    for (const CaseResult& r : waiting) put(r);
    waiting.clear();
  };
  MemoCache cache;
  out.summary = run_sweep(graph, binder, table, cache, options, [&](CaseResult&& r) {
    if (!rows.settled()) {
      if (r.failure != CaseFailure::none) {
        waiting.push_back(std::move(r));
        return;
      }
      settle(&r);
    }
    put(r);
  });
  if (!rows.settled()) settle(nullptr);
  out.header = rows.header();
  return out;
}

Graph SceneSession::graph_for(const std::vector<std::string>& overrides, const std::vector<std::string>& outputs) const {
  const SceneSpec scene = with_outputs(outputs);
  std::vector<Override> parsed;
  for (const std::string& o : overrides) parsed.push_back(parse_override(o));
  return build_graph(scene, *registry_, parsed);
}

}  // namespace mechgraph::python
