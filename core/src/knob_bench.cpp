#include <mechgraph/knob_bench.hpp>

#include <mechgraph/did_you_mean.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/evaluator.hpp>
#include <mechgraph/graph_cut.hpp>
#include <mechgraph/knob_bench_outputs.hpp>
#include <mechgraph/units.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

namespace mechgraph {
namespace {

constexpr double unknown = std::numeric_limits<double>::infinity();

// The graph cut down to what `node` needs, requesting every numeric output of it that exists
// (an output brought by an effect that is off for the node is not there).
Graph focus_on(const Graph& graph, std::size_t node) {
  Graph g = graph;
  cut_to_producers(g, node);
  mark_wanted_outputs(g);
  // The node is asked for every output it has; what it produces (some need an effect or a
  // parameter) is what the bench compares.
  GraphNode& n = g.nodes[node];
  n.wanted.clear();
  for (const PortSpec& p : n.info().outputs) n.wanted.push_back(p.name);
  std::sort(n.wanted.begin(), n.wanted.end());
  refresh_wanted_mask(n);
  return g;
}

// The setting as the user writes it: in the knob's display unit when it has one.
std::string text_of(const ParamSpec& spec, const ParamValue& v) {
  if (spec.kind == ParamKind::choice || spec.kind == ParamKind::text) return v.text;
  char buffer[48];
  double shown = v.number;
  std::string unit = spec.dimension.si_unit();
  if (!spec.display_unit.empty()) {
    shown = to_unit(v.number, spec.dimension, spec.display_unit);
    unit = spec.display_unit;
  }
  std::snprintf(buffer, sizeof buffer, spec.kind == ParamKind::integer ? "%.0f" : "%.6g", shown);
  return unit == "1" || unit.empty() ? std::string(buffer) : std::string(buffer) + " " + unit;
}

std::string number_text(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2g", x);
  return buffer;
}

bool is_numeric(const ParamSpec& spec) { return spec.kind == ParamKind::integer || spec.kind == ParamKind::number; }

// The ladder's rung `k` (k < 0: looser): an integer knob x 2^k, a real knob / 2^k.
std::optional<ParamValue> ladder_rung(const ParamSpec& spec, const ParamValue& base, int k) {
  ParamValue v = base;
  if (spec.kind == ParamKind::integer) v.number = std::round(base.number * std::ldexp(1.0, k));
  else if (spec.kind == ParamKind::number) v.number = base.number * std::ldexp(1.0, -k);
  else return std::nullopt;
  if (!spec.admits(v.number)) return std::nullopt;
  return v;
}

// Step `j` of the reference search: an integer knob x 2^j, a real knob / 4^j. A step past the
// knob's range lands on the range's tight end once (when that is tighter than `previous`).
std::optional<ParamValue> reference_rung(const ParamSpec& spec, const ParamValue& base, int j, const ParamValue& previous) {
  ParamValue v = base;
  const bool integer = spec.kind == ParamKind::integer;
  v.number = integer ? std::round(base.number * std::ldexp(1.0, j)) : base.number * std::ldexp(1.0, -2 * j);
  if (spec.admits(v.number)) return v;
  const double end = integer ? std::floor(spec.max) : spec.min;
  const bool tighter = integer ? end > previous.number : end < previous.number;
  if (std::isfinite(end) && spec.admits(end) && tighter) {
    v.number = end;
    return v;
  }
  return std::nullopt;
}

// The K seeds of a Monte Carlo setting: the first is the scene's, the others follow from it by
// SplitMix64 (independent streams however close the scene's seed is to another), kept to 2^53.
std::vector<double> seeds_from(double scene_seed, int count) {
  std::vector<double> seeds{scene_seed};
  std::uint64_t state = static_cast<std::uint64_t>(scene_seed);
  while (static_cast<int>(seeds.size()) < count) {
    state += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    const double seed = static_cast<double>(z >> 11);  // 53 bits
    if (std::find(seeds.begin(), seeds.end(), seed) == seeds.end()) seeds.push_back(seed);
  }
  return seeds;
}

double total_work(const NodeRun& run) {
  double sum = 0.0;
  for (const auto& [counter, amount] : run.work) sum += amount;
  return sum;
}

// The work estimate of one node alone (estimate_work's conventions: points, samples, bins).
double node_work_estimate(const Graph& graph, std::size_t node) {
  Graph alone = graph;
  alone.order = {node};
  alone.outputs.clear();
  return estimate_work(alone).work;
}

struct Measured {
  std::vector<OutputValue> outputs;
  NodeRun run;
  std::string failure;
  int repeats = 0;
};

using Changes = std::vector<std::pair<std::string, ParamValue>>;

// Evaluates one node of a focused graph with some of its parameters changed. The ladders' settings
// are remembered (by the values that differ from the scene's), so the reference search, the floors
// and the other knobs' ladders share them; the reference search's own steps are not (a curve at
// 2^10 times the points is dropped as soon as the next step has replaced it). The node runs every
// time; its producers come from the memo cache.
class NodeBench {
 public:
  using Result = std::shared_ptr<const Measured>;
  enum class Keep { remember, forget };

  NodeBench(const Graph& focused, std::size_t node) : graph_(focused), node_(node) {}

  const GraphNode& node() const { return graph_.nodes[node_]; }
  std::size_t index() const { return node_; }
  const Graph& graph() const { return graph_; }

  Result measure(const Changes& changes, int repeats, Keep keep = Keep::remember) {
    std::string key;
    Graph g = graph_;
    for (const auto& [name, value] : changes) {
      const ParamValue& scene = node().params.get(name);
      if (value.kind == scene.kind && value.number == scene.number && value.text == scene.text) continue;
      char number[40];
      std::snprintf(number, sizeof number, "%a", value.number);
      key += name + "=" + (value.kind == ParamKind::choice ? value.text : std::string(number)) + ";";
      g.nodes[node_].params.set(name, value);
    }
    repeats = std::max(1, repeats);
    const auto found = done_.find(key);
    if (found != done_.end() && (found->second->repeats >= repeats || !found->second->failure.empty())) return found->second;
    auto m = std::make_shared<Measured>(found != done_.end() ? *found->second : Measured{});
    run(g, *m, repeats);
    if (keep == Keep::remember || found != done_.end()) done_[key] = m;
    return m;
  }

 private:
  void run(const Graph& g, Measured& m, int repeats) {
    const std::uint64_t key = node_hashes(g)[node_];
    if (m.repeats == 0) m.run.seconds = std::numeric_limits<double>::infinity();
    for (int r = m.repeats; r < repeats; ++r) {
      cache_.erase(key);  // the node itself runs every time
      try {
        RunResult result = evaluate(g, cache_);
        for (const NodeRun& run : result.runs)
          if (run.node == node().name && run.seconds < m.run.seconds) m.run = run;
        m.outputs.clear();
        if (const auto produced = cache_.find(key)) {
          for (const PortSpec& p : node().info().outputs) {
            if (p.kind == ValueKind::handle) continue;
            auto it = produced->all().find(p.name);
            if (it != produced->all().end()) m.outputs.push_back({node().name + "." + p.name, it->second, p.dimension, p.display_unit});
          }
        }
      } catch (const EvaluationError& e) {
        m.failure = e.what();
        break;
      }
    }
    m.repeats = repeats;
    cache_.erase(key);  // the cache keeps the producers only
  }

  const Graph& graph_;
  std::size_t node_;
  MemoCache cache_;
  std::map<std::string, Result> done_;
};

using Result = NodeBench::Result;

bool same_work(const Measured& a, const Measured& b) { return a.run.work == b.run.work; }

// Why a knob cannot act, from the node's description: it belongs to an effect that is off.
std::string effect_off(const GraphNode& n, const ParamSpec& knob) {
  const EffectSpec* effect = n.info().effect_of_param(knob.name);
  if (!effect) return {};
  if (std::find(n.effects_read.begin(), n.effects_read.end(), effect->name) != n.effects_read.end()) return {};
  return "not measured: " + knob.name + " belongs to the effect " + effect->name + ", which is off for this node";
}

std::string inert_reason(const ParamSpec& knob) {
  return "not measured: " + knob.name + " does not change any output or the work in this scene";
}

KnobTrial trial_of(const GraphNode& n, const ParamSpec& knob, const ParamValue& setting, const Measured& m) {
  KnobTrial t;
  t.node = n.name;
  t.type = n.info().type;
  t.knob = knob.name;
  t.setting = text_of(knob, setting);
  t.is_default = t.setting == text_of(knob, n.params.get(knob.name));
  t.failure = m.failure;
  if (m.failure.empty()) {
    t.seconds = m.run.seconds;
    t.work = m.run.work;
  }
  return t;
}

// The error of each trial against the reference, with the reference's floor.
void compare_with_reference(std::vector<KnobTrial>& trials, const std::vector<Result>& measured,
                            const Measured& reference, double floor, const std::vector<std::string>& work_counters) {
  for (std::size_t i = 0; i < trials.size(); ++i) {
    KnobTrial& t = trials[i];
    t.reference_floor = floor;
    if (!t.failure.empty()) continue;
    const OutputDeviation d = relative_difference(measured[i]->outputs, reference.outputs, work_counters);
    if (d.compared == 0) {
      t.failure = "no output of the same shape as the reference's to compare";
      continue;
    }
    t.max_relative_error = d.max_relative;
    t.worst_output = d.worst;
    t.errors = d.per_output;
    t.below_floor = std::isfinite(floor) && t.max_relative_error < floor;
  }
}

struct Studied {
  KnobStudy study;
  std::vector<KnobTrial> trials;
};

// An integer or real knob of a deterministic node: the ladder, then the reference search.
Studied study_numeric(NodeBench& bench, const ParamSpec& knob, const KnobBenchOptions& o) {
  const GraphNode& n = bench.node();
  Studied s;
  const ParamValue base = n.params.get(knob.name);
  std::vector<ParamValue> settings;
  for (int k = -o.steps; k <= o.steps; ++k)
    if (auto v = ladder_rung(knob, base, k)) settings.push_back(*v);
  std::vector<Result> ladder;
  for (const ParamValue& v : settings) ladder.push_back(bench.measure({{knob.name, v}}, o.repeats));
  const Result scene = bench.measure({}, 1);
  // A knob every setting of which gives the same bits and the same work cannot act here.
  auto unchanged = [&](const Measured& m) {
    return m.failure.empty() && bit_identical(m.outputs, scene->outputs) && same_work(m, *scene);
  };
  bool inert = std::all_of(ladder.begin(), ladder.end(), [&](const Result& m) { return unchanged(*m); });

  // The reference: this knob alone tightened until successive values agree.
  const double agreement = std::max(1e-3 * o.tolerance, 1e-15);
  Result previous = scene;
  Result reference = scene;
  ParamValue previous_value = base;
  std::vector<double> work_history{total_work(scene->run)}, time_history{scene->run.seconds};
  double search_seconds = 0.0;
  s.study.reference = text_of(knob, base);
  s.study.floor = unknown;
  std::string stop;
  auto growth = [](const std::vector<double>& history, double first) {
    if (history.size() < 2 || !(history[history.size() - 2] > 0.0)) return first;
    return std::max(1.0, history.back() / history[history.size() - 2]);
  };
  int agreeing = 0;  // successive differences in a row within the agreement
  int j = 1;
  for (; j <= o.reference_steps; ++j) {
    const auto v = reference_rung(knob, base, j, previous_value);
    if (!v) {
      stop = "the knob's range ends at " + text_of(knob, previous_value);
      break;
    }
    Graph probe = bench.graph();
    probe.nodes[bench.index()].params.set(knob.name, *v);
    const double work = std::max(node_work_estimate(probe, bench.index()), work_history.back() * growth(work_history, 4.0));
    if (work > o.max_work) {
      stop = "the next step (" + text_of(knob, *v) + ") would need about " + number_text(work) +
             " work items, over the budget of " + number_text(o.max_work) + " (--max-work)";
      break;
    }
    const double seconds = time_history.back() * growth(time_history, 4.0);
    if (search_seconds + seconds > o.reference_seconds) {
      stop = "the next step (" + text_of(knob, *v) + ") would take the search beyond " + number_text(o.reference_seconds) +
             " s (--reference-time)";
      break;
    }
    const Result m = bench.measure({{knob.name, *v}}, 1, NodeBench::Keep::forget);
    inert = inert && unchanged(*m);
    if (!m->failure.empty()) {
      stop = "the next step (" + text_of(knob, *v) + ") failed: " + m->failure;
      break;
    }
    search_seconds += m->run.seconds;
    const OutputDeviation d = relative_difference(m->outputs, previous->outputs, n.info().work_counters);
    if (d.compared == 0) {
      stop = "successive settings have no output of the same shape to compare";
      s.study.floor = unknown;
      break;
    }
    reference = m;
    s.study.reference = text_of(knob, *v);
    s.study.reference_steps = j;
    // The floor: the last difference, or the larger of the last two once they agree (a result
    // that moves in steps, a bisection's, can repeat itself once by chance and move again).
    const double last = d.max_relative;
    if (agreeing > 0 && s.study.floor >= last) {
      // the previous difference stays the floor, with its output
    } else {
      s.study.floor = last;
      s.study.floor_output = d.worst;
    }
    agreeing = last <= agreement ? agreeing + 1 : 0;
    if (agreeing == 2) {
      s.study.converged = true;
      break;
    }
    previous = m;
    previous_value = *v;
    work_history.push_back(total_work(m->run));
    time_history.push_back(m->run.seconds);
  }
  if (j > o.reference_steps) stop = "the step limit of " + std::to_string(o.reference_steps) + " steps";

  if (inert) {
    s.study.not_measured = inert_reason(knob);
    return s;
  }
  if (s.study.converged)
    s.study.stopped = "converged: three successive values agree to " + number_text(s.study.floor) + " (at most 1e-3 x --tol)";
  else if (std::isfinite(s.study.floor))
    s.study.stopped = "not converged (" + stop + "): the last step moved the outputs by " + number_text(s.study.floor);
  else
    s.study.stopped = "not known how far it is converged: " + stop;

  for (std::size_t i = 0; i < settings.size(); ++i) s.trials.push_back(trial_of(n, knob, settings[i], *ladder[i]));
  compare_with_reference(s.trials, ladder, *reference, s.study.floor, n.info().work_counters);
  return s;
}

// A choice knob of a deterministic node: each choice against the first, whose floor is how far it
// moves when each of the node's numeric knobs that can act (`others`: none of an effect that is
// off; one inert under the scene's choice may act under the first) is tightened one reference step.
Studied study_choice(NodeBench& bench, const ParamSpec& knob, const std::vector<const ParamSpec*>& others,
                     const KnobBenchOptions& o) {
  const GraphNode& n = bench.node();
  Studied s;
  std::vector<ParamValue> settings;
  for (const std::string& c : knob.choices) settings.push_back(ParamValue::of_choice(c));
  std::vector<Result> measured;
  for (const ParamValue& v : settings) measured.push_back(bench.measure({{knob.name, v}}, o.repeats));
  const Result scene = bench.measure({}, 1);
  const bool inert = std::all_of(measured.begin(), measured.end(), [&](const Result& m) {
    return m->failure.empty() && bit_identical(m->outputs, scene->outputs) && same_work(*m, *scene);
  });
  if (inert) {
    s.study.not_measured = inert_reason(knob);
    return s;
  }
  for (std::size_t i = 0; i < settings.size(); ++i) s.trials.push_back(trial_of(n, knob, settings[i], *measured[i]));
  const Measured& reference = *measured.front();
  s.study.reference = knob.choices.front();
  if (!reference.failure.empty()) {
    s.study.floor = unknown;
    s.study.stopped = "its first choice failed: no reference";
    for (KnobTrial& t : s.trials)
      if (t.failure.empty()) t.failure = "no reference to compare with (the first choice, " + knob.choices.front() + ", failed)";
    return s;
  }
  double floor = 0.0, largest = 0.0;
  std::vector<std::string> moved;
  for (const ParamSpec* other : others) {
    const ParamValue& base = n.params.get(other->name);
    const auto v = reference_rung(*other, base, 1, base);
    if (!v) continue;
    const Result m = bench.measure({{knob.name, settings.front()}, {other->name, *v}}, 1, NodeBench::Keep::forget);
    if (!m->failure.empty()) continue;
    const OutputDeviation d = relative_difference(m->outputs, reference.outputs, n.info().work_counters);
    if (d.compared == 0) continue;
    floor += d.max_relative;
    moved.push_back(other->name);
    if (d.max_relative >= largest) {
      largest = d.max_relative;
      s.study.floor_output = d.worst;
    }
  }
  s.study.floor = floor;
  if (moved.empty()) {
    s.study.stopped = "the first choice; no other knob acts in this scene, so nothing moves it";
  } else {
    std::string names;
    for (const std::string& name : moved) names += (names.empty() ? "" : ", ") + name;
    s.study.stopped = "the first choice, the other knobs at the scene's settings; tightening each of them one step (" +
                      names + (floor > 0.0 ? ") moves it by " + number_text(floor) + " in all" : ") leaves it the same to the bit");
  }
  compare_with_reference(s.trials, measured, reference, floor, n.info().work_counters);
  return s;
}

// Any knob of a Monte Carlo node: each setting run with K seeds, its error their spread.
Studied study_monte_carlo(NodeBench& bench, const ParamSpec& knob, const KnobBenchOptions& o) {
  const GraphNode& n = bench.node();
  Studied s;
  s.study.monte_carlo = true;
  s.study.seeds = o.seeds;
  const ParamValue base = n.params.get(knob.name);
  std::vector<ParamValue> settings;
  if (knob.kind == ParamKind::choice) {
    for (const std::string& c : knob.choices) settings.push_back(ParamValue::of_choice(c));
  } else {
    for (int k = -o.steps; k <= o.steps; ++k)
      if (auto v = ladder_rung(knob, base, k)) settings.push_back(*v);
  }
  const ParamValue scene_seed = n.params.get("seed");
  const std::vector<double> seeds = seeds_from(scene_seed.number, o.seeds);
  const Result scene = bench.measure({}, 1);
  bool inert = true;
  for (const ParamValue& v : settings) {
    std::vector<std::vector<OutputValue>> runs;
    KnobTrial t;
    for (std::size_t j = 0; j < seeds.size(); ++j) {
      ParamValue seed = scene_seed;
      seed.number = seeds[j];
      const Result m = bench.measure({{knob.name, v}, {"seed", seed}}, j == 0 ? o.repeats : 1, NodeBench::Keep::forget);
      if (j == 0) {
        t = trial_of(n, knob, v, *m);
        inert = inert && m->failure.empty() && bit_identical(m->outputs, scene->outputs) && same_work(*m, *scene);
      }
      if (!m->failure.empty()) {
        t.failure = m->failure;
        break;
      }
      t.seconds = std::min(t.seconds, m->run.seconds);
      runs.push_back(m->outputs);
    }
    if (t.failure.empty()) {
      const OutputDeviation d = relative_spread(runs, n.info().work_counters);
      if (d.compared == 0) {
        t.failure = "no output of the same shape in every seed to compare";
      } else {
        // The standard error of a standard deviation from K samples: s / sqrt(2 (K - 1)).
        t.max_relative_error = d.max_relative;
        t.error_uncertainty = d.max_relative / std::sqrt(2.0 * (static_cast<double>(seeds.size()) - 1.0));
        t.worst_output = d.worst;
        t.errors = d.per_output;
      }
    }
    s.trials.push_back(std::move(t));
  }
  if (inert) {
    s.trials.clear();
    s.study.not_measured = inert_reason(knob);
    return s;
  }
  s.study.stopped = "Monte Carlo: the spread over " + std::to_string(seeds.size()) + " seeds";
  return s;
}

}  // namespace

bool is_monte_carlo(const GraphNode& node) {
  const ParamSpec* seed = node.info().find_param("seed");
  if (!seed || seed->kind != ParamKind::integer || seed->knob || !node.params.has("seed")) return false;
  const EffectSpec* effect = node.info().effect_of_param("seed");
  return !effect || std::find(node.effects_read.begin(), node.effects_read.end(), effect->name) != node.effects_read.end();
}

WorkEstimate estimate_bench_work(const Graph& graph, const KnobBenchOptions& options) {
  WorkEstimate total;
  std::vector<std::size_t> nodes = graph.order;
  if (options.node) {
    const auto i = graph.find(*options.node);  // also a node the scene culled
    nodes.assign(i ? 1 : 0, i.value_or(0));
  }
  for (std::size_t i : nodes) {
    const GraphNode& n = graph.nodes[i];
    double knobs = 0;
    for (const ParamSpec& p : n.info().params) knobs += p.knob && n.params.has(p.name) ? 1 : 0;
    if (knobs == 0) continue;
    Graph alone = graph;
    alone.order = {i};
    alone.outputs.clear();
    const double runs = is_monte_carlo(n) ? std::max(options.repeats, options.seeds) : options.repeats;
    const double evaluations = knobs * (std::ldexp(1.0, options.steps + 1) + options.steps) * runs;
    for (WorkEstimate::Term t : estimate_work(alone).terms) {
      t.what += " x " + number_text(evaluations) + " evaluations of the bench";
      t.work *= evaluations;
      t.bytes = 0;
      total.work += t.work;
      total.terms.push_back(t);
    }
  }
  return total;
}

KnobBench bench_knobs(const Graph& graph, const KnobBenchOptions& options) {
  std::vector<std::size_t> nodes;
  if (options.node) {
    const auto i = graph.find(*options.node);
    if (!i) {
      std::vector<std::string> names;
      for (const GraphNode& n : graph.nodes) names.push_back(n.name);
      throw SceneError("bench: " + unknown_name_message("node", *options.node, names));
    }
    nodes.push_back(*i);
  } else {
    nodes = graph.order;
  }
  KnobBench result;
  std::size_t done = 0;
  for (std::size_t node : nodes) {
    const GraphNode& n = graph.nodes[node];
    if (options.progress) options.progress(done++, nodes.size(), n.name);
    std::vector<const ParamSpec*> knobs;
    for (const ParamSpec& p : n.info().params)
      if (p.knob && n.params.has(p.name)) knobs.push_back(&p);
    if (knobs.empty()) {
      if (options.node) throw SceneError("bench: node '" + n.name + "' (" + n.info().type + ") has no accuracy knobs");
      continue;
    }
    const Graph focused = focus_on(graph, node);
    NodeBench bench(focused, node);
    const Result scene = bench.measure({}, 1);
    if (!scene->failure.empty())
      throw EvaluationError("bench: node '" + n.name + "' fails at the scene's settings: " + scene->failure);
    const bool random = is_monte_carlo(n);
    // Integer and real knobs first, then the choices (whose floors tighten the numeric knobs).
    std::map<const ParamSpec*, Studied> studied;
    std::vector<const ParamSpec*> numeric;
    for (const ParamSpec* k : knobs) {
      if (k->kind == ParamKind::choice || !is_numeric(*k)) continue;
      Studied s;
      if (std::string off = effect_off(n, *k); !off.empty()) s.study.not_measured = off;
      else if (random) s = study_monte_carlo(bench, *k, options);
      else s = study_numeric(bench, *k, options);
      if (effect_off(n, *k).empty()) numeric.push_back(k);
      studied[k] = std::move(s);
    }
    for (const ParamSpec* k : knobs) {
      if (studied.count(k)) continue;
      Studied s;
      if (std::string off = effect_off(n, *k); !off.empty()) s.study.not_measured = off;
      else if (k->kind != ParamKind::choice) s.study.not_measured = "not measured: " + k->name + " is no number and no choice";
      else if (random) s = study_monte_carlo(bench, *k, options);
      else s = study_choice(bench, *k, numeric, options);
      studied[k] = std::move(s);
    }
    for (const ParamSpec* k : knobs) {
      Studied& s = studied[k];
      s.study.node = n.name;
      s.study.type = n.info().type;
      s.study.knob = k->name;
      s.study.first_trial = result.trials.size();
      s.study.trial_count = s.trials.size();
      for (KnobTrial& t : s.trials) result.trials.push_back(std::move(t));
      result.knobs.push_back(std::move(s.study));
    }
  }
  return result;
}

double error_bound(const KnobTrial& trial) {
  return trial.max_relative_error + trial.error_uncertainty + trial.reference_floor;
}

std::vector<KnobAdvice> advise_knobs(KnobBench& bench, double tolerance) {
  std::vector<KnobAdvice> advice;
  std::vector<KnobTrial>& trials = bench.trials;
  // What is known of a setting's error: its value, or the floor when it is below that.
  auto known_error = [](const KnobTrial& t) { return std::max(t.max_relative_error, t.reference_floor); };
  for (const KnobStudy& study : bench.knobs) {
    KnobAdvice a{study.node, study.knob, std::nullopt, std::nullopt, false, {}};
    if (!study.not_measured.empty()) {
      a.text = study.not_measured;
      advice.push_back(std::move(a));
      continue;
    }
    const std::size_t begin = study.first_trial, end = study.first_trial + study.trial_count;
    // On the front: no other setting is both faster and more accurate.
    for (std::size_t i = begin; i < end; ++i) {
      KnobTrial& t = trials[i];
      if (t.is_default) a.current = i;
      if (!t.failure.empty()) continue;
      t.on_front = true;
      for (std::size_t j = begin; j < end; ++j) {
        const KnobTrial& o = trials[j];
        if (j == i || !o.failure.empty()) continue;
        const bool no_worse = o.seconds <= t.seconds && known_error(o) <= known_error(t);
        const bool better = o.seconds < t.seconds || known_error(o) < known_error(t);
        if (no_worse && better) t.on_front = false;
      }
      if (error_bound(t) <= tolerance && (!a.recommended || t.seconds < trials[*a.recommended].seconds)) a.recommended = i;
    }
    auto describe = [&](std::size_t i) {
      const KnobTrial& t = trials[i];
      std::string error;
      if (t.below_floor) error = "< " + number_text(t.reference_floor);
      else error = number_text(t.max_relative_error);
      if (study.monte_carlo) error += " +- " + number_text(t.error_uncertainty);
      else if (!t.below_floor && t.reference_floor > 0.0) error += " + floor " + number_text(t.reference_floor);
      char seconds[32];
      std::snprintf(seconds, sizeof seconds, "%.3g s", t.seconds);
      return t.knob + " = " + t.setting + " (error " + error + (t.worst_output.empty() ? "" : " in " + t.worst_output) + ", " +
             seconds + ")";
    };
    if (a.recommended) {
      a.text = "within " + number_text(tolerance) + ": " + describe(*a.recommended);
    } else {
      std::optional<std::size_t> best;
      for (std::size_t i = begin; i < end; ++i)
        if (trials[i].failure.empty() && (!best || error_bound(trials[i]) < error_bound(trials[*best]))) best = i;
      a.text = "no setting on the ladder reaches " + number_text(tolerance);
      if (best) a.text += "; the most accurate is " + describe(*best);
      if (!(study.floor < tolerance)) {
        a.text += std::isfinite(study.floor) ? "; the reference itself is converged only to " + number_text(study.floor)
                                              : "; how far the reference is converged is not known";
      }
    }
    if (a.current && trials[*a.current].failure.empty()) {
      const KnobTrial& d = trials[*a.current];
      for (std::size_t i = begin; i < end; ++i) {
        const KnobTrial& t = trials[i];
        if (i == *a.current || !t.on_front) continue;
        const bool good_enough = known_error(t) <= std::max(known_error(d), tolerance);
        if (good_enough && t.seconds <= 0.5 * d.seconds) a.current_off_front = true;
      }
      if (a.current_off_front) a.text += "; the scene's setting (" + d.setting + ") is far off the front";
      else if (a.recommended && *a.recommended == *a.current) a.text += " (the scene's setting)";
    }
    advice.push_back(std::move(a));
  }
  return advice;
}

}  // namespace mechgraph
