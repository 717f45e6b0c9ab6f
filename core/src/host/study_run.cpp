#include <mechgraph/host/study_run.hpp>
#include <mechgraph/host/angle_reference.hpp>
#include <mechgraph/host/scene_loading.hpp>

#include <mechgraph/host/exit_codes.hpp>
#include <mechgraph/host/usage_error.hpp>
#include <mechgraph/shown_number.hpp>

#include <mechgraph/error_subject.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/evaluator.hpp>
#include <mechgraph/large_arrays.hpp>
#include <mechgraph/memo_cache.hpp>
#include <mechgraph/sweep/case_estimate.hpp>
#include <mechgraph/units.hpp>

#include <spdlog/spdlog.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>
#include <algorithm>
#include <bit>
#include <memory>
#include <set>
#include <sstream>
#include <thread>

namespace mechgraph::host {

Iso286Limits iso286_limits(const PluginRegistry& registry) {
  if (!registry.find(iso286_node_type)) return {};
  return [&registry](double size, const std::string& tolerance_class) {
    // One fit.iso286 node, its parameters given as values (never as YAML text): the class on its
    // side, a common class on the other.
    const bool hole = !tolerance_class.empty() && tolerance_class.front() >= 'A' && tolerance_class.front() <= 'Z';
    SceneSpec scene;
    scene.file = "ISO 286";
    NodeSpec node;
    node.name = "fit";
    node.type = iso286_node_type;
    char buffer[40];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, size, std::chars_format::general, 17);
    const auto text = [](std::string t) {
      RawValue v;
      v.text = std::move(t);
      return v;
    };
    node.params.emplace_back("size", text(std::string(buffer, end) + " m"));
    node.params.emplace_back("hole", text(hole ? tolerance_class : "H7"));
    node.params.emplace_back("shaft", text(hole ? "h7" : tolerance_class));
    scene.nodes.push_back(std::move(node));
    const std::string side = hole ? "hole" : "shaft";
    scene.outputs = {{"fit", side + "_lower", {}}, {"fit", side + "_upper", {}}};
    const Graph graph = build_graph(scene, registry);
    MemoCache cache(4);
    const RunValues run = evaluate_values(graph, cache);
    return std::pair<double, double>{run.values.at(0).as_scalar(), run.values.at(1).as_scalar()};
  };
}

StudySpec study_spec_of(const SceneSpec& scene, const PluginRegistry& registry) {
  if (!scene.uncertainty)
    throw SceneError(scene.file + ": the scene has no 'uncertainty' block (parameters with their distributions; docs/scenes.md, "
                     "\"Uncertainty\")");
  return parse_study(*scene.uncertainty, iso286_limits(registry));
}

void check_study_parameters(const StudySpec& spec, const Graph& graph, const SceneSpec& scene, const PluginRegistry& registry,
                            const std::vector<Override>& overrides) {
  for (const UncertainParameter& p : spec.parameters) {
    // A value set on an uncertain parameter would be overwritten by every sample (and the record
    // of the run would name a value no case used): one or the other.
    for (const Override& o : overrides)
      if (o.target == p.name)
        throw SceneErrorAt({p.where, {}, p.name}, p.where.str() + "'" + p.name + "' is set (" + o.text + ") and uncertain in this study: every sample " +
                         "draws its own value, so the set one would be ignored; drop the one or the other");
    try {
      const CaseBinder single(graph, scene, registry, overrides, {{p.name, p.unit}}, BinderUse::study);
      if (!single.reaches_needed_node(0))
        spdlog::warn("{}'{}' only reaches nodes the studied outputs do not need: its distribution changes nothing", p.where.str(), p.name);
    } catch (const SceneError& e) {
      throw SceneErrorAt({p.where, {}, p.name}, p.where.str() + e.what());
    }
    // The dimension of what the name reaches: a node's parameter, or every use of a scene parameter.
    std::vector<const ParamSpec*> targets;
    if (const auto dot = p.name.find('.'); dot != std::string::npos) {
      if (const auto node = graph.find(p.name.substr(0, dot)))
        if (const ParamSpec* s = graph.nodes[*node].info().find_param(p.name.substr(dot + 1))) targets.push_back(s);
    } else if (const auto uses = graph.scene_param_uses.find(p.name); uses != graph.scene_param_uses.end()) {
      for (const SceneParamUse& use : uses->second)
        if (const ParamSpec* s = graph.nodes[use.node].info().find_param(use.param)) targets.push_back(s);
    }
    for (const ParamSpec* s : targets) {
      if (s->kind == ParamKind::record_list) {
        // A scene parameter inside a record (`links: [{ nominal: $a, ... }]`): the field it fills is
        // checked when each case's graph is built from the scene; here, that some number field of
        // the record has the distribution's dimension.
        const auto fits = [&](const ParamSpec& f) {
          return (f.kind == ParamKind::number || f.kind == ParamKind::number_list) && f.dimension == p.marginal.dimension;
        };
        if (std::none_of(s->fields.begin(), s->fields.end(), fits))
          throw SceneErrorAt({p.where, {}, p.name}, p.where.str() + "'" + p.name + "' is used inside the records of parameter '" + s->name +
                           "', none of whose number fields is " + p.marginal.dimension.describe());
        continue;
      }
      // A draw is a real number: a whole-number parameter (a count of samples, of points) would
      // refuse every case after the whole design had run.
      if (s->kind == ParamKind::integer)
        throw SceneErrorAt({p.where, {}, p.name}, p.where.str() + "'" + p.name + "' reaches parameter '" + s->name +
                                                      "', a whole number: a distribution draws real numbers (vary a whole number in a sweep)");
      if (s->kind != ParamKind::number && s->kind != ParamKind::number_list)
        throw SceneErrorAt({p.where, {}, p.name}, p.where.str() + "'" + p.name + "' reaches parameter '" + s->name + "', which is not a number");
      if (!(s->dimension == p.marginal.dimension))
        throw SceneErrorAt({p.where, {}, p.name}, p.where.str() + "'" + p.name + "' is " + s->dimension.describe() + " (parameter '" + s->name +
                         "'), its distribution is " + p.marginal.dimension.describe());
    }
  }
  // A scene parameter and a node parameter it feeds that has a distribution of its own: the node
  // parameter's draws replace the scene parameter's value there (as `run --set node.param` does).
  // Where that leaves an uncertain scene parameter acting nowhere, its distribution would change
  // nothing and its Sobol' indices read "does not matter"; where it leaves a --set one acting
  // nowhere, the record of the run would name a value no case used: both refused. Where it still
  // acts elsewhere, said once. (A node parameter --set is no use of the scene parameter it was
  // written with: the graph records the set value's uses, `--set 'A.x=$c'` one of c.)
  const auto uncertain = [&](const std::string& name) {
    return std::any_of(spec.parameters.begin(), spec.parameters.end(), [&](const UncertainParameter& q) { return q.name == name; });
  };
  // The uses of scene parameter `name` whose node parameter has a distribution, listed, with
  // whether that is every use (false where it has none).
  const auto replaced_uses = [&](const std::string& name) {
    std::pair<std::string, bool> out{{}, false};
    const auto uses = graph.scene_param_uses.find(name);
    if (uses == graph.scene_param_uses.end()) return out;
    std::size_t count = 0;
    for (const SceneParamUse& use : uses->second) {
      const std::string target = graph.nodes[use.node].name + "." + use.param;
      if (uncertain(target)) out.first += (count++ ? ", " : "") + target;
    }
    out.second = count > 0 && count == uses->second.size();
    return out;
  };
  for (const UncertainParameter& p : spec.parameters) {
    if (p.name.find('.') != std::string::npos) continue;
    const auto [replaced, everywhere] = replaced_uses(p.name);
    if (replaced.empty()) continue;
    if (everywhere)
      throw SceneErrorAt({p.where, {}, p.name}, p.where.str() + "'" + p.name + "' has a distribution, and so has every parameter it feeds (" +
                                                    replaced + "): their own draws replace its draws, so its distribution changes nothing; "
                                                    "drop the one or the others");
    spdlog::warn("{}'{}' also feeds {}, which has a distribution of its own: there its draws replace '{}''s", p.where.str(), p.name,
                 replaced, p.name);
  }
  for (const Override& o : overrides) {
    if (o.target.find('.') != std::string::npos || uncertain(o.target)) continue;  // the latter refused above
    const auto [replaced, everywhere] = replaced_uses(o.target);
    if (replaced.empty()) continue;
    if (everywhere) {
      // Said at the distribution of the first parameter it feeds.
      const std::string first = replaced.substr(0, replaced.find(','));
      const UncertainParameter& q =
          *std::find_if(spec.parameters.begin(), spec.parameters.end(), [&](const UncertainParameter& u) { return u.name == first; });
      throw SceneErrorAt({q.where, {}, q.name}, q.where.str() + "'" + o.target + "' is set (" + o.text + "), and every parameter it feeds (" +
                                                    replaced + ") has a distribution in this study: every sample draws its own value " +
                                                    "there, so the set one would be ignored; drop the one or the other");
    }
    spdlog::warn("--set {}: {} has a distribution in this study: there each sample draws its own value, not '{}''s", o.text, replaced,
                 o.target);
  }
}

void leave_out_unstudied(StudySpec& spec, const std::vector<StudyColumn>& columns, const std::set<std::string>& scene_outputs) {
  const auto left_out = [&](const std::string& output) {
    if (std::any_of(columns.begin(), columns.end(), [&](const StudyColumn& c) { return c.label == output; })) return false;
    return scene_outputs.count(output) > 0;  // a name that is no output of the scene stays, to be refused
  };
  std::erase_if(spec.limits, [&](const SpecLimits& l) {
    if (!left_out(l.output)) return false;
    spdlog::info("study: the limits of '{}' are left out: it is not among the outputs chosen", l.output);
    return true;
  });
  std::erase_if(spec.events, [&](const StudyEvent& e) {
    if (e.kind == StudyEvent::Kind::failure || !left_out(e.output)) return false;
    spdlog::info("study: event '{}' is left out: '{}' is not among the outputs chosen", e.name, e.output);
    return true;
  });
}

std::vector<StudyColumn> study_columns(const Graph& graph) {
  std::vector<StudyColumn> columns;
  std::set<std::string> seen;
  for (const RequestedOutput& o : graph.outputs) {
    if (o.spec->kind != ValueKind::scalar || !seen.insert(o.label).second) continue;
    StudyColumn c;
    c.label = o.label;
    c.dimension = o.spec->dimension;
    c.unit = o.spec->display_unit;
    const std::string unit = c.unit.empty() ? c.dimension.si_unit() : c.unit;
    c.shown = o.node < graph.nodes.size() ? unit_with_reference(unit, angle_reference(graph.nodes[o.node].info(), *o.spec)) : unit;
    if (!c.unit.empty()) {
      const UnitScale u = parse_unit(c.unit);
      c.scale = u.scale;
      c.offset = u.offset;
    }
    columns.push_back(std::move(c));
  }
  return columns;
}

StudyData evaluate_study(const Graph& graph, const CaseBinder& binder, const CaseTable& table, const std::vector<StudyColumn>& columns,
                         unsigned threads, const std::atomic<bool>* stop, SweepSummary* summary) {
  StudyData data;
  data.outputs = columns;
  const std::size_t n = table.size();
  data.values.resize(columns.size());
  for (std::vector<double>& column : data.values) {
    reserve_large(column, n);
    column.assign(n, std::numeric_limits<double>::quiet_NaN());
  }
  data.failures.assign(n, CaseFailure::none);
  std::vector<std::size_t> where(columns.size());
  for (std::size_t c = 0; c < columns.size(); ++c)
    for (std::size_t o = 0; o < graph.outputs.size(); ++o)
      if (graph.outputs[o].label == columns[c].label) {
        where[c] = o;
        break;
      }
  SweepOptions options;
  options.threads = threads;
  options.stop = stop;
  options.cases.resize(n);
  for (std::size_t i = 0; i < n; ++i) options.cases[i] = i;
  MemoCache cache;
  const SweepSummary s = run_sweep(graph, binder, table, cache, options, [&](CaseResult&& r) {
    if (r.failure != CaseFailure::none) return data.record_failure(r.index, r.failure, r.error);
    for (std::size_t c = 0; c < columns.size(); ++c) data.values[c][r.index] = shown_value(r.outputs[where[c]].as_scalar(), columns[c]);
  });
  if (summary) *summary = s;
  return data;
}

}  // namespace mechgraph::host

namespace mechgraph::host {

void apply_study_options(StudySpec& spec, const std::string& samples, const std::string& method, const std::string& seed,
                         const OptionNames& names) {
  const auto whole = [](const std::string& text, const char* option, std::size_t low, std::size_t high) {
    std::size_t n = 0;
    const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
    if (ec != std::errc() || p != text.data() + text.size() || n < low || n > high)
      throw UsageError(std::string(option) + " '" + excerpt(text, 40) + "' is not a whole number from " + std::to_string(low) + " to " +
                       std::to_string(high));
    return n;
  };
  if (!samples.empty()) spec.samples = whole(samples, names.samples, 2, max_sweep_cases);
  if (!seed.empty()) spec.seed = whole(seed, names.seed, 0, std::size_t{1} << 62);
  if (method == "monte_carlo") spec.method = SamplingMethod::monte_carlo;
  else if (method == "latin_hypercube") spec.method = SamplingMethod::latin_hypercube;
  else if (method == "sobol") spec.method = SamplingMethod::sobol;
  else if (!method.empty())
    throw UsageError(std::string(names.method) + " " + excerpt(method, 40) + ": valid methods are monte_carlo, latin_hypercube, sobol");
  if (spec.evaluations() > max_sweep_cases)
    throw UsageError(std::string(names.samples) + " " + std::to_string(spec.samples) + ": the design would need " + std::to_string(spec.evaluations()) +
                     " evaluations, more than " + std::string(max_sweep_cases_text));
  // Sobol' points stratify (one in each 1/N of every coordinate) only for N a power of 2; other N
  // are valid, the estimate unbiased over seeds, its variance that of a part of a net.
  if (spec.method == SamplingMethod::sobol && !std::has_single_bit(spec.samples))
    spdlog::warn("study: {} Sobol' samples, not a power of 2: the points stratify only for a power of 2 ({} or {})", spec.samples,
                 std::bit_floor(spec.samples), std::bit_ceil(spec.samples));
}

}  // namespace mechgraph::host

namespace mechgraph::host {

// What a study holds and does beyond its cases (check_sweep_budget counts those): the design's
// table (a value a parameter a case), every output's value of every case, the Sobol' rows (the
// base samples' outputs, and a copy laid out for the resamples) and the bootstrap's draws; the
// bootstrap's work (each resample passes over every output's rows: N (d + 2) values). Refused
// before the design is made, naming the term and the flag that raises the budget.
double check_study_budget(const StudySpec& spec, std::size_t outputs, const WorkBudget& budget, const std::string& file,
                          unsigned threads) {
  check_design_size(spec);  // the design's own cap first: no budget flag removes it
  const double n = static_cast<double>(spec.samples), d = static_cast<double>(spec.parameters.size());
  const double cases = static_cast<double>(spec.evaluations()), out = static_cast<double>(outputs);
  const double statistical = spec.sensitivity ? 2.0 * n : n;  // the A and B rows, or every case
  const unsigned answer_threads = std::max({threads, std::thread::hardware_concurrency(), 1u});
  struct Term {
    const char* what;
    double amount;
  };
  const Term memory[] = {
      {"the design's table (a value a parameter a case)", cases * d * sizeof(double)},  // CaseTable::Numbers
      {"the outputs' values (one a case an output)", cases * (out * sizeof(double) + sizeof(CaseFailure))},
      {"the cases' order (an index a case)", cases * sizeof(std::size_t)},  // SweepOptions::cases
      // study_answers.cpp: the statistical rows' indices, and each output answered at once its
      // values, sorted in place for the quantiles: up to one a core of this machine, whatever
      // `threads` the answers get (a study and the same study from Dask rows count the same).
      {"the answers' scratch (the statistical rows' indices and values)",
       statistical * sizeof(std::size_t) + statistical * sizeof(double) * std::min(out, static_cast<double>(answer_threads))},
      {"the Sobol' rows (every case of every output, twice)", spec.sensitivity ? 2.0 * out * n * (d + 2.0) * sizeof(double) : 0.0},
      {"the bootstrap's draws", spec.sensitivity ? 2.0 * out * d * static_cast<double>(spec.bootstrap) * sizeof(double) : 0.0}};
  double held = 0.0;
  const Term* biggest = &memory[0];
  for (const Term& t : memory) {
    held += t.amount;
    if (t.amount > biggest->amount) biggest = &t;
  }
  if (!(held <= budget.max_memory))
    throw SceneError(file + ": the study would hold about " + budget_amount(held / (1 << 20)) + " MiB beside its cases (" +
                     std::to_string(spec.evaluations()) + " cases, " + std::to_string(outputs) + " outputs), more than the budget of " +
                     budget_amount(budget.max_memory / (1 << 20)) + " MiB; the biggest term is " + biggest->what +
                     ". Fewer samples or outputs, or raise the budget with " + budget.names.memory + budget_amount(held * 1.01));
  const double bootstrap = spec.sensitivity ? static_cast<double>(spec.bootstrap) * n * (1.0 + out * (d + 2.0)) : 0.0;
  if (!(bootstrap <= budget.max_work))
    throw SceneError(file + ": the study's bootstrap asks for about " + budget_amount(bootstrap) + " work items (" + std::to_string(spec.bootstrap) +
                     " resamples of " + std::to_string(spec.samples) + " base samples, " + std::to_string(outputs) +
                     " outputs), more than the budget of " + budget_amount(budget.max_work) +
                     ". Fewer resamples (bootstrap:), or raise the budget with " + budget.names.work + budget_amount(bootstrap * 1.01));
  return held;
}

RawValue merged_uncertainty(const SceneSpec& scene, const std::optional<RawValue>& block) {
  RawValue merged;
  merged.kind = RawValue::Kind::map;
  if (scene.uncertainty) merged = *scene.uncertainty;
  if (!block) return merged;
  if (block->kind != RawValue::Kind::map) throw SceneError(block->where.str() + "expected the uncertainty settings as a map");
  merged.where = block->where;
  for (const RawField& f : block->fields) {
    auto same = std::find_if(merged.fields.begin(), merged.fields.end(), [&](const RawField& m) { return m.first == f.first; });
    if (same == merged.fields.end()) {
      merged.fields.push_back(f);
    } else if (f.first == "parameters" && f.second.kind == RawValue::Kind::map && same->second.kind == RawValue::Kind::map) {
      for (const RawField& p : f.second.fields) {
        auto old = std::find_if(same->second.fields.begin(), same->second.fields.end(), [&](const RawField& m) { return m.first == p.first; });
        if (old == same->second.fields.end()) same->second.fields.push_back(p);
        else old->second = p.second;
      }
    } else {
      same->second = f.second;
    }
  }
  return merged;
}

std::unique_ptr<StudyOutcome> prepare_scene_study(SceneSpec scene, const PluginRegistry& registry, const std::vector<Override>& overrides,
                                                  const std::optional<RawValue>& block, const std::string& samples, const std::string& method,
                                                  const std::string& seed, const std::optional<std::string>& outputs,
                                                  unsigned threads, const WorkBudget* budget, double* held,
                                                  const OptionNames& option_names, const std::function<void(const StudySpec&)>& check_spec) {
  auto outcome = std::make_unique<StudyOutcome>();
  if (block) scene.uncertainty = merged_uncertainty(scene, block);
  outcome->spec = study_spec_of(scene, registry);
  apply_study_options(outcome->spec, samples, method, seed, option_names);
  if (check_spec) check_spec(outcome->spec);
  outcome->scene = std::make_unique<SceneSpec>(std::move(scene));
  std::set<std::string> scene_outputs;  // before a choice of outputs replaces them
  for (const PortRef& o : outcome->scene->outputs) scene_outputs.insert(o.str());
  outcome->graph = build_sweep_graph(*outcome->scene, registry, overrides, outputs, option_names);
  check_study_parameters(outcome->spec, outcome->graph, *outcome->scene, registry, overrides);
  outcome->columns = study_columns(outcome->graph);
  if (outputs) leave_out_unstudied(outcome->spec, outcome->columns, scene_outputs);
  check_study_outputs(outcome->spec, outcome->columns);
  if (budget) {
    const double own = check_study_budget(outcome->spec, outcome->columns.size(), *budget, outcome->graph.file, threads);
    if (held) *held = own;
  }
  outcome->table = make_study_cases(outcome->spec, threads);
  return outcome;
}

void finish_study(StudyOutcome& outcome, const std::atomic<bool>* stop) {
  outcome.answers = analyse_study(outcome.spec, outcome.data, outcome.threads, stop);
  if (stop && stop->load(std::memory_order_relaxed)) {
    outcome.summary.stopped = true;  // asked to stop while the answers were made: none are given
    return;
  }
  std::ostringstream json;
  JsonWriter w(json);
  write_study_json(w, outcome.spec, outcome.answers);
  outcome.json = json.str();
}

std::unique_ptr<StudyOutcome> run_scene_study(SceneSpec scene, const PluginRegistry& registry, const std::vector<Override>& overrides,
                                              const std::optional<RawValue>& block, const std::string& samples, const std::string& method,
                                              const std::string& seed, const std::optional<std::string>& outputs, const WorkBudget& budget,
                                              unsigned threads, const std::atomic<bool>* stop, const OptionNames& option_names) {
  threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  // Each phase's wall time in the debug log (-v), so a slow study shows where its time went.
  auto phase_start = std::chrono::steady_clock::now();
  auto phase_done = [&phase_start](const char* what) {
    const auto now = std::chrono::steady_clock::now();
    spdlog::debug("study: {} in {:.3f} s", what, std::chrono::duration<double>(now - phase_start).count());
    phase_start = now;
  };
  double held = 0.0;  // what the study holds beside its cases: the cases get the rest of the memory budget
  auto outcome = prepare_scene_study(std::move(scene), registry, overrides, block, samples, method, seed, outputs, threads, &budget, &held,
                                     option_names);
  phase_done("graph built and cases drawn");
  const CaseBinder binder(outcome->graph, *outcome->scene, registry, overrides, outcome->table.variables, BinderUse::study);
  outcome->threads = threads;
  {
    std::vector<std::size_t> all(outcome->table.size());  // freed before the cases run (they hold their own order)
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    WorkBudget for_cases = budget;
    for_cases.max_memory = budget.max_memory - held;  // positive: check_study_budget kept held within it
    for_cases.memory_beside = held;
    check_sweep_budget(outcome->graph, binder, outcome->table, all, for_cases, threads);
  }
  phase_done("work budget checked");
  outcome->data = evaluate_study(outcome->graph, binder, outcome->table, outcome->columns, threads, stop, &outcome->summary);
  phase_done("cases evaluated");
  if (!outcome->summary.stopped) {
    finish_study(*outcome, stop);
    phase_done("answers computed");
  }
  return outcome;
}

}  // namespace mechgraph::host
