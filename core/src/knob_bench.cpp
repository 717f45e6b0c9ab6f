#include <mechgraph/knob_bench.hpp>

#include <mechgraph/did_you_mean.hpp>
#include <mechgraph/errors.hpp>
#include <mechgraph/evaluator.hpp>
#include <mechgraph/units.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace mechgraph {
namespace {

// The graph cut down to what `node` needs, requesting every numeric output of it that exists
// (an output brought by an effect that is off for the node is not there).
Graph focus_on(const Graph& graph, std::size_t node) {
  Graph g = graph;
  g.reports.clear();
  g.outputs.clear();
  std::vector<bool> keep(g.nodes.size(), false);
  std::vector<std::size_t> stack{node};
  while (!stack.empty()) {
    const std::size_t i = stack.back();
    stack.pop_back();
    if (keep[i]) continue;
    keep[i] = true;
    for (std::size_t u : g.nodes[i].upstream) stack.push_back(u);
  }
  std::vector<std::size_t> order;
  for (std::size_t i : graph.order)
    if (keep[i]) order.push_back(i);
  // Keep the node even when the scene did not need it (bench --node on a culled node).
  if (std::find(order.begin(), order.end(), node) == order.end()) {
    for (std::size_t i = 0; i < g.nodes.size(); ++i)
      if (keep[i] && std::find(order.begin(), order.end(), i) == order.end()) order.push_back(i);
  }
  g.order = std::move(order);
  for (std::size_t i = 0; i < g.nodes.size(); ++i) g.nodes[i].needed = keep[i];
  mark_wanted_outputs(g);
  // The node is asked for every output it has; what it produces (some need an effect or a
  // parameter) is what the bench compares.
  GraphNode& n = g.nodes[node];
  n.wanted.clear();
  for (const PortSpec& p : n.info().outputs) n.wanted.push_back(p.name);
  std::sort(n.wanted.begin(), n.wanted.end());
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
  std::snprintf(buffer, sizeof buffer, "%.6g", shown);
  return unit == "1" || unit.empty() ? std::string(buffer) : std::string(buffer) + " " + unit;
}


// The knob's value `k` steps tighter than `base` (k < 0: looser).
std::optional<ParamValue> tighter(const ParamSpec& spec, const ParamValue& base, int k) {
  ParamValue v = base;
  if (spec.kind == ParamKind::integer) {
    v.number = std::round(base.number * std::ldexp(1.0, k));
  } else if (spec.kind == ParamKind::number) {
    v.number = base.number * std::ldexp(1.0, -k);
  } else {
    return std::nullopt;
  }
  if (!spec.admits(v.number)) return std::nullopt;
  return v;
}

struct Measured {
  std::vector<OutputValue> outputs;
  NodeRun run;
  std::string failure;
};

Measured measure(Graph g, std::size_t node, MemoCache& upstream, int repeats) {
  Measured m;
  m.run.seconds = std::numeric_limits<double>::infinity();
  const std::uint64_t key = node_hashes(g)[node];
  for (int r = 0; r < std::max(1, repeats); ++r) {
    upstream.erase(key);  // the node itself runs every time; its producers come from the cache
    try {
      RunResult result = evaluate(g, upstream);
      for (const NodeRun& run : result.runs)
        if (run.node == g.nodes[node].name && run.seconds < m.run.seconds) m.run = run;
      m.outputs.clear();
      if (const auto produced = upstream.find(key)) {
        for (const PortSpec& p : g.nodes[node].info().outputs) {
          if (p.kind == ValueKind::handle) continue;
          auto it = produced->all().find(p.name);
          if (it != produced->all().end()) m.outputs.push_back({g.nodes[node].name + "." + p.name, it->second, p.dimension, p.display_unit});
        }
      }
    } catch (const EvaluationError& e) {
      m.failure = e.what();
      return m;
    }
  }
  return m;
}

// Largest relative difference over all numeric outputs (series element by element). A value
// near zero is measured against a thousandth of the scale of its kind: the largest reference value among the
// node's scalars of the same dimension (a margin that is zero by construction against the forces
// beside it), or the largest element of its own series. Outputs that count the node's work
// (named like one of its work counters) are not results and are not compared.
void compare(const Measured& trial, const Measured& reference, const std::vector<std::string>& work_counters, KnobTrial& out) {
  auto scale_of = [&](const Dimension& d) {
    double scale = 0.0;
    for (const OutputValue& o : reference.outputs)
      if (o.value.kind() == ValueKind::scalar && o.dimension == d) scale = std::max(scale, std::abs(o.value.as_scalar()));
    return scale;
  };
  for (std::size_t i = 0; i < trial.outputs.size(); ++i) {
    const std::string& label = trial.outputs[i].label;
    const std::string port = label.substr(label.find('.') + 1);
    if (std::find(work_counters.begin(), work_counters.end(), port) != work_counters.end()) continue;
    if (port.size() > 6 && port.compare(port.size() - 6, 6, "_error") == 0) continue;  // an uncertainty, not a result
    const auto match = std::find_if(reference.outputs.begin(), reference.outputs.end(),
                                    [&](const OutputValue& o) { return o.label == label; });
    if (match == reference.outputs.end()) continue;
    const Value& a = trial.outputs[i].value;
    const Value& b = match->value;
    auto consider = [&](double x, double ref, double floor) {
      const double e = std::abs(x - ref) / std::max({std::abs(ref), floor, 1e-300});
      double& per_output = out.errors[label];
      per_output = std::max(per_output, e);
      if (e > out.max_relative_error) {
        out.max_relative_error = e;
        out.worst_output = label;
      }
    };
    if (a.kind() == ValueKind::scalar) {
      consider(a.as_scalar(), b.as_scalar(), 1e-3 * scale_of(trial.outputs[i].dimension));
    } else if (a.kind() == ValueKind::series) {
      const auto& va = a.as_series().values;
      const auto& vb = b.as_series().values;
      if (va.size() != vb.size()) continue;  // a knob that sets the number of points: not comparable
      double scale = 0.0;
      for (double v : vb) scale = std::max(scale, std::abs(v));
      for (std::size_t j = 0; j < va.size(); ++j) consider(va[j], vb[j], scale);
    } else if (a.kind() == ValueKind::table) {
      const Table& ta = a.as_table();
      const Table& tb = b.as_table();
      if (ta.axis.values.size() != tb.axis.values.size()) continue;
      for (const Table::Column& ca : ta.channels) {
        const Table::Column* cb = tb.find(ca.name);
        if (!cb) continue;
        // Channel by channel, relative to the channel's own scale: a curve crossing zero would
        // otherwise turn tiny absolute differences into huge relative ones.
        double scale = 0.0;
        for (double v : cb->values) scale = std::max(scale, std::abs(v));
        for (std::size_t j = 0; j < ca.values.size(); ++j) {
          const double e = std::abs(ca.values[j] - cb->values[j]) / std::max(scale, 1e-300);
          double& per_output = out.errors[trial.outputs[i].label + ":" + ca.name];
          per_output = std::max(per_output, e);
          if (e > out.max_relative_error) {
            out.max_relative_error = e;
            out.worst_output = trial.outputs[i].label + ":" + ca.name;
          }
        }
      }
    }
  }
}

}  // namespace

std::vector<KnobTrial> bench_knobs(const Graph& graph, const KnobBenchOptions& options) {
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
  std::vector<KnobTrial> trials;
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
    Graph focused = focus_on(graph, node);
    MemoCache cache;
    // Reference: every numeric knob well past the tightest rung of the ladder, every choice knob
    // at its first (most accurate) choice.
    Graph reference_graph = focused;
    for (const ParamSpec* k : knobs) {
      if (k->kind == ParamKind::choice && !k->choices.empty())
        reference_graph.nodes[node].params.set(k->name, ParamValue::of_choice(k->choices.front()));
      for (int extra = options.steps + 2; extra > 0; --extra)
        if (auto v = tighter(*k, n.params.get(k->name), extra)) {
          reference_graph.nodes[node].params.set(k->name, *v);
          break;
        }
    }
    const Measured reference = measure(reference_graph, node, cache, 1);
    if (!reference.failure.empty())
      throw EvaluationError("bench: the reference evaluation of node '" + n.name + "' failed: " + reference.failure);
    for (const ParamSpec* k : knobs) {
      std::vector<ParamValue> settings;
      const ParamValue& base = n.params.get(k->name);
      if (k->kind == ParamKind::choice) {
        for (const std::string& c : k->choices) settings.push_back(ParamValue::of_choice(c));
      } else {
        for (int step = -options.steps; step <= options.steps; ++step)
          if (auto v = tighter(*k, base, step)) settings.push_back(*v);
      }
      for (const ParamValue& setting : settings) {
        Graph trial_graph = focused;
        trial_graph.nodes[node].params.set(k->name, setting);
        const Measured m = measure(trial_graph, node, cache, options.repeats);
        KnobTrial t;
        t.node = n.name;
        t.type = n.info().type;
        t.knob = k->name;
        t.setting = text_of(*k, setting);
        t.is_default = t.setting == text_of(*k, base);
        t.failure = m.failure;
        if (m.failure.empty()) {
          t.seconds = m.run.seconds;
          t.work = m.run.work;
          compare(m, reference, n.info().work_counters, t);
        }
        trials.push_back(std::move(t));
      }
    }
  }
  return trials;
}

std::vector<KnobAdvice> advise_knobs(std::vector<KnobTrial>& trials, double tolerance) {
  std::vector<KnobAdvice> advice;
  for (std::size_t begin = 0; begin < trials.size();) {
    std::size_t end = begin;
    while (end < trials.size() && trials[end].node == trials[begin].node && trials[end].knob == trials[begin].knob) ++end;
    KnobAdvice a{trials[begin].node, trials[begin].knob, std::nullopt, std::nullopt, false, {}};
    // On the front: no other setting is both faster and more accurate.
    for (std::size_t i = begin; i < end; ++i) {
      KnobTrial& t = trials[i];
      if (t.is_default) a.current = i;
      if (!t.failure.empty()) continue;
      t.on_front = true;
      for (std::size_t j = begin; j < end; ++j) {
        const KnobTrial& o = trials[j];
        if (j == i || !o.failure.empty()) continue;
        const bool no_worse = o.seconds <= t.seconds && o.max_relative_error <= t.max_relative_error;
        const bool better = o.seconds < t.seconds || o.max_relative_error < t.max_relative_error;
        if (no_worse && better) t.on_front = false;
      }
      if (t.max_relative_error <= tolerance && (!a.recommended || t.seconds < trials[*a.recommended].seconds)) a.recommended = i;
    }
    char line[320];
    auto describe = [&](std::size_t i) {
      char b[160];
      std::snprintf(b, sizeof b, "%s = %s (error %.2g, %.3g s)", trials[i].knob.c_str(), trials[i].setting.c_str(),
                    trials[i].max_relative_error, trials[i].seconds);
      return std::string(b);
    };
    if (a.recommended) {
      std::snprintf(line, sizeof line, "within %.0e: %s", tolerance, describe(*a.recommended).c_str());
    } else {
      std::size_t best = begin;
      for (std::size_t i = begin; i < end; ++i)
        if (trials[i].failure.empty() && (!trials[best].failure.empty() || trials[i].max_relative_error < trials[best].max_relative_error)) best = i;
      std::snprintf(line, sizeof line, "no setting reaches %.0e; the most accurate is %s", tolerance, describe(best).c_str());
    }
    a.text = line;
    if (a.current && trials[*a.current].failure.empty()) {
      const KnobTrial& d = trials[*a.current];
      for (std::size_t i = begin; i < end; ++i) {
        const KnobTrial& t = trials[i];
        if (i == *a.current || !t.on_front) continue;
        const bool good_enough = t.max_relative_error <= std::max(d.max_relative_error, tolerance);
        if (good_enough && t.seconds <= 0.5 * d.seconds) a.current_off_front = true;
      }
      if (a.current_off_front) a.text += "; the scene's setting (" + d.setting + ") is far off the front";
      else if (a.recommended && *a.recommended == *a.current) a.text += " (the scene's setting)";
    }
    advice.push_back(std::move(a));
    begin = end;
  }
  return advice;
}

}  // namespace mechgraph
