#include <mechgraph/sweep/case_estimate.hpp>

#include <mechgraph/errors.hpp>

#include <algorithm>
#include <string>

namespace mechgraph {

SweepEstimate estimate_cases(const Graph& graph, const CaseBinder& binder, const CaseTable& table,
                             const std::vector<std::size_t>& cases) {
  SweepEstimate result;
  const std::vector<char> writing = writing_nodes(graph);
  // The nodes no value reaches are estimated once, in order; their sizes feed the varied ones.
  Graph copy = graph;
  binder.mark_unmemoised(copy);  // memoised == false: a target of a variable or downstream of one
  std::vector<std::size_t> varied;
  std::vector<double> sizes(graph.nodes.size(), 1.0);
  double fixed_work = 0, fixed_memory = 0;
  for (std::size_t i : graph.order) {
    if (!copy.nodes[i].memoised) {
      varied.push_back(i);
      continue;
    }
    const NodeEstimate e = estimate_node(graph, i, sizes, writing[i] != 0, false);
    sizes[i] = e.output_size;
    fixed_work += e.work;
    fixed_memory += e.memory;
  }
  // A binder that rebuilds each case's graph (a value inside a list or record) still binds the
  // plain parameters in place; the values inside lists do not change how long the lists are, so
  // the estimate of the bound copy holds for the rebuilt graph.
  const CaseBinder::Slots slots = binder.bind(copy);
  // Whether some case changes a parameter of node i other than a real number (the conventions
  // read integers; anything else counts as changing them).
  std::vector<char> integers_vary(graph.nodes.size(), 0);
  for (const std::vector<CaseBinder::Target>& targets : binder.targets())
    for (const CaseBinder::Target& t : targets)
      if (t.node < integers_vary.size() && (!t.spec || t.spec->kind != ParamKind::number)) integers_vary[t.node] = 1;
  std::vector<RepeatedNodeEstimate> repeated;
  repeated.reserve(varied.size());
  for (std::size_t i : varied) repeated.emplace_back(copy, i, writing[i] != 0, integers_vary[i] != 0);
  double largest = -1;
  for (std::size_t c : cases) {
    if (c >= table.cases.size()) continue;
    try {
      binder.apply(slots, copy, table.cases[c]);
    } catch (const SceneError&) {
      continue;  // this case is refused before it runs: no work
    }
    double work = fixed_work, memory = fixed_memory;
    for (std::size_t k = 0; k < varied.size(); ++k) {
      const NodeEstimate e = repeated[k](copy, sizes);
      sizes[varied[k]] = e.output_size;
      work += e.work;
      memory += e.memory;
    }
    result.total.work += work;
    result.largest_memory = std::max(result.largest_memory, memory);
    if (work > largest) {
      largest = work;
      result.largest_case = c;
    }
  }
  // The terms (for the message) are the largest case's, estimated once more with their words.
  if (largest >= 0) {
    binder.apply(slots, copy, table.cases[result.largest_case]);
    WorkEstimate e = estimate_work(copy);
    for (WorkEstimate::Term& t : e.terms) t.what += " in case " + std::to_string(result.largest_case);
    result.total.terms = std::move(e.terms);
    result.total.bytes = e.bytes;
  }
  result.total.memory = result.largest_memory;
  return result;
}

void check_sweep_budget(const Graph& graph, const CaseBinder& binder, const CaseTable& table,
                        const std::vector<std::size_t>& cases, const WorkBudget& budget, unsigned threads) {
  const SweepEstimate e = estimate_cases(graph, binder, table, cases);
  const double n = static_cast<double>(cases.size());
  const std::string where = "over " + std::to_string(cases.size()) + " case" + (cases.size() == 1 ? "" : "s");
  check_work_budget(graph, e.total, budget, 1, false, std::min(n, static_cast<double>(std::max(threads, 1u))), where);
}

}  // namespace mechgraph
