#include <mechgraph/work_estimate.hpp>

#include <mechgraph/errors.hpp>

#include <algorithm>
#include <cstdio>
#include <set>

namespace mechgraph {
namespace {

bool ends_with(std::string_view s, std::string_view tail) {
  return s.size() >= tail.size() && s.substr(s.size() - tail.size()) == tail;
}

// A CSV row of a curve: about ten channels of about 18 characters each.
constexpr double bytes_per_row = 180.0;
// A node whose curves have no points parameter writes a few hundred rows.
constexpr double default_rows = 361.0;

std::string amount(double v) {
  char text[32];
  std::snprintf(text, sizeof text, v < 1e6 ? "%.0f" : "%.3g", v);
  return text;
}

}  // namespace

WorkEstimate estimate_work(const Graph& graph) {
  WorkEstimate e;
  std::set<std::size_t> writing;  // nodes with a requested series or table
  for (const RequestedOutput& o : graph.outputs)
    if (o.spec && (o.spec->kind == ValueKind::series || o.spec->kind == ValueKind::table)) writing.insert(o.node);
  for (std::size_t index : graph.order) {
    const GraphNode& n = graph.nodes[index];
    double revolutions = 1, rows = 0;
    std::vector<WorkEstimate::Term> node_terms;
    // Parameters of an effect that is off are not read: they cost nothing.
    std::set<std::string> idle;
    for (const EffectSpec& effect : n.info().effects)
      if (std::find(n.effects_read.begin(), n.effects_read.end(), effect.name) == n.effects_read.end())
        idle.insert(effect.params.begin(), effect.params.end());
    for (const auto& [name, value] : n.params.all()) {
      if (idle.count(name)) continue;
      const std::string what = n.name + "." + name;
      if (value.kind == ParamKind::integer) {
        if (name == "revolutions") revolutions = std::max(1.0, value.number);
        if (ends_with(name, "points") || ends_with(name, "samples") || ends_with(name, "bins")) {
          node_terms.push_back({what + " = " + amount(value.number), value.number, 0});
          if (ends_with(name, "points")) rows = std::max(rows, value.number);
        }
      } else if (value.kind == ParamKind::record_list && !value.records.empty()) {
        node_terms.push_back({what + " (" + amount(static_cast<double>(value.records.size())) + " records)",
                              static_cast<double>(value.records.size()), 0});
      } else if (value.kind == ParamKind::number_list && !value.numbers.empty()) {
        node_terms.push_back({what + " (" + amount(static_cast<double>(value.numbers.size())) + " numbers)",
                              static_cast<double>(value.numbers.size()), 0});
      }
    }
    for (WorkEstimate::Term& t : node_terms) {
      t.work *= revolutions;
      if (revolutions > 1) t.what += " x " + amount(revolutions) + " revolutions";
    }
    if (writing.count(index)) {
      const double written = (rows > 0 ? rows : default_rows) * bytes_per_row;
      node_terms.push_back({n.name + "'s curves (" + amount(rows > 0 ? rows : default_rows) + " rows)", 0, written});
    }
    for (const WorkEstimate::Term& t : node_terms) {
      e.work += t.work;
      e.bytes += t.bytes;
      e.terms.push_back(t);
    }
  }
  return e;
}

void check_work_budget(const Graph& graph, const WorkEstimate& e, const WorkBudget& budget, double cases,
                       bool writes_curves) {
  const auto biggest = [&](auto key) {
    const auto it = std::max_element(e.terms.begin(), e.terms.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
    return it == e.terms.end() ? std::string("-") : it->what;
  };
  const std::string per_case = cases > 1 ? " over " + amount(cases) + " cases" : std::string();
  const double work = e.work * cases;
  if (!(work <= budget.max_work))
    throw SceneError(graph.file + ": the scene asks for about " + amount(work) + " work items" + per_case +
                     ", more than the budget of " + amount(budget.max_work) + "; the biggest term is " +
                     biggest([](const WorkEstimate::Term& t) { return t.work; }) +
                     ". Lower it, or raise the budget with --max-work " + amount(std::max(work * 1.01, 1.0)));
  if (writes_curves && !(e.bytes <= budget.max_bytes))
    throw SceneError(graph.file + ": the scene would write about " + amount(e.bytes / (1 << 20)) +
                     " MiB of curves, more than the budget of " + amount(budget.max_bytes / (1 << 20)) +
                     " MiB; the biggest term is " + biggest([](const WorkEstimate::Term& t) { return t.bytes; }) +
                     ". Lower it, or raise the budget with --max-output " + amount(std::max(e.bytes * 1.01, 1.0)));
}

}  // namespace mechgraph
