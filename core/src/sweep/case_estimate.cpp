#include <mechgraph/sweep/case_estimate.hpp>

#include <mechgraph/errors.hpp>
#include <mechgraph/chunked_work.hpp>

#include <algorithm>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

namespace mechgraph {
namespace {

// What one run of consecutive cases adds up to: its work (in case order), its largest memory, and
// its case of the most work (the first of equals).
struct ChunkEstimate {
  double work = 0, largest_memory = 0, largest_work = -1;
  std::size_t largest_case = 0;
};

// The cases are estimated in chunks of this many, each chunk on whichever worker takes it and
// added up in chunk order: the same figures whatever the number of threads.
constexpr std::size_t cases_per_chunk = 4096;

// Case c's values as apply() needs them: a value it writes as a number without its text (a table
// that keeps its cells' texts then makes none: a cases file's million rows), any other with it (a
// word, a value refused: its message shows the text).
const std::vector<CaseValue>& binding_row(const CaseTable& table, const CaseBinder& binder, std::size_t c,
                                          std::vector<CaseValue>& row) {
  if (!table.cases.empty()) return table.cases[c];
  row.resize(table.numbers.dimensions.size());
  for (std::size_t v = 0; v < row.size(); ++v)
    if (!binder.writes_number(v, table.number_cell(c, v, row[v]))) table.cell(c, v, row[v]);
  return row;
}

}  // namespace

SweepEstimate estimate_cases(const Graph& graph, const CaseBinder& binder, const CaseTable& table,
                             const std::vector<std::size_t>& cases, unsigned threads) {
  SweepEstimate result;
  const std::vector<char> writing = writing_nodes(graph);
  // The nodes no value reaches are estimated once, in order; their sizes feed the varied ones.
  Graph marked = graph;
  binder.mark_unmemoised(marked);  // memoised == false: a target of a variable or downstream of one
  std::vector<std::size_t> varied;
  std::vector<double> fixed_sizes(graph.nodes.size(), 1.0);
  double fixed_work = 0, fixed_memory = 0;
  for (std::size_t i : graph.order) {
    if (!marked.nodes[i].memoised) {
      varied.push_back(i);
      continue;
    }
    const NodeEstimate e = estimate_node(graph, i, fixed_sizes, writing[i] != 0, false);
    fixed_sizes[i] = e.output_size;
    fixed_work += e.work;
    fixed_memory += e.memory;
  }
  // Whether some case changes a parameter of node i other than a real number (the conventions
  // read integers; anything else counts as changing them).
  std::vector<char> integers_vary(graph.nodes.size(), 0);
  std::vector<std::vector<std::string>> varied_names(graph.nodes.size());  // the parameters some case changes
  for (const std::vector<CaseBinder::Target>& targets : binder.targets())
    for (const CaseBinder::Target& t : targets) {
      if (t.node >= integers_vary.size()) continue;
      if (t.spec->kind != ParamKind::number) integers_vary[t.node] = 1;
      varied_names[t.node].push_back(t.spec->name);
    }
  // Whether a node's forecast reads none of them (SDK 1.3): asked once a worker, not once a case.
  // Decided here, once, not by each worker.
  std::vector<char> forecast_fixed(graph.nodes.size(), 0);
  for (std::size_t i : varied) forecast_fixed[i] = forecast_reads_none_of(*graph.nodes[i].type->type, varied_names[i]) ? 1 : 0;
  // Whether every case that binds has the figures of the first: no varied node's figures read what
  // the cases change (a forecast that reads none of it, or none at all and the conventions, which
  // read integers, list lengths and input sizes), and no case changes an integer. The sizes between
  // the nodes then stay too. Each case is still bound (a refused one has no work), and estimated
  // once a worker.
  const bool cases_alike = std::all_of(varied.begin(), varied.end(), [&](std::size_t i) {
    return !integers_vary[i] && (forecast_fixed[i] || !graph.nodes[i].type->offers_forecast);
  });

  // A binder that rebuilds each case's graph (a value inside a list or record) still binds the
  // plain parameters in place; the values inside lists do not change how long the lists are, so
  // the estimate of the bound copy holds for the rebuilt graph.
  const std::size_t chunks = (cases.size() + cases_per_chunk - 1) / cases_per_chunk;
  std::vector<ChunkEstimate> chunk_estimates(chunks);
  struct Worker {  // each worker's own graph and estimators
    Graph copy;
    CaseBinder::Slots slots;
    std::vector<RepeatedNodeEstimate> repeated;
    std::vector<double> sizes;
    std::optional<std::pair<double, double>> alike;  // a case's work and memory, when cases_alike
    std::vector<CaseValue> row;                      // a case's values, where the table keeps numbers only
  };
  const auto make_worker = [&] {
    Worker w{marked, {}, {}, fixed_sizes, std::nullopt, {}};
    w.slots = binder.bind(w.copy);
    w.repeated.reserve(varied.size());
    for (std::size_t i : varied)
      w.repeated.emplace_back(w.copy, i, writing[i] != 0, integers_vary[i] != 0, forecast_fixed[i] != 0);
    return w;
  };
  run_chunks(chunks, threads, make_worker, [&](Worker& w, std::size_t chunk) {
    ChunkEstimate& out = chunk_estimates[chunk];
    const std::size_t end = std::min(cases.size(), (chunk + 1) * cases_per_chunk);
    for (std::size_t k = chunk * cases_per_chunk; k < end; ++k) {
      const std::size_t c = cases[k];
      if (c >= table.size()) continue;
      try {
        binder.apply(w.slots, w.copy, binding_row(table, binder, c, w.row));
      } catch (const SceneError&) {
        continue;  // this case is refused before it runs: no work
      }
      double work = fixed_work, memory = fixed_memory;
      if (w.alike) {
        std::tie(work, memory) = *w.alike;
      } else {
        for (std::size_t v = 0; v < varied.size(); ++v) {
          const NodeEstimate e = w.repeated[v](w.copy, w.sizes);
          w.sizes[varied[v]] = e.output_size;
          work += e.work;
          memory += e.memory;
        }
        if (cases_alike) w.alike.emplace(work, memory);
      }
      out.work += work;
      out.largest_memory = std::max(out.largest_memory, memory);
      if (work > out.largest_work) {
        out.largest_work = work;
        out.largest_case = c;
      }
    }
  });
  double largest = -1;
  for (const ChunkEstimate& e : chunk_estimates) {
    result.total.work += e.work;
    result.largest_memory = std::max(result.largest_memory, e.largest_memory);
    if (e.largest_work > largest) {
      largest = e.largest_work;
      result.largest_case = e.largest_case;
    }
  }
  // The terms (for the message) are the largest case's, estimated once more with their words.
  if (largest >= 0) {
    Graph copy = marked;
    std::vector<CaseValue> row;
    binder.apply(binder.bind(copy), copy, table.row(result.largest_case, row));
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
  const SweepEstimate e = estimate_cases(graph, binder, table, cases, threads);
  const double n = static_cast<double>(cases.size());
  const std::string where = "over " + std::to_string(cases.size()) + " case" + (cases.size() == 1 ? "" : "s");
  check_work_budget(graph, e.total, budget, 1, false, std::min(n, static_cast<double>(std::max(threads, 1u))), where);
}

double sweep_holdings(const CaseTable& table, std::size_t cases) {
  double bytes = static_cast<double>(cases) * sizeof(std::size_t) + static_cast<double>(table.numbers.si.capacity()) * sizeof(double);
  const CaseTable::Numbers::Written& written = table.numbers.written;
  // The texts as held: their pool may be reserved beyond them (Python's tables reserve the most a
  // number's 17 digits can take), address space whose pages are never touched.
  bytes += static_cast<double>(written.text.size() + written.ends.capacity() * sizeof(std::uint32_t) +
                               written.in_column_unit.capacity() + written.dimensions.bytes_held() +
                               written.given.capacity() * sizeof(double));
  for (const std::vector<CaseValue>& row : table.cases) {
    bytes += sizeof(row) + static_cast<double>(row.capacity()) * sizeof(CaseValue);
    for (const CaseValue& v : row)
      if (v.text.capacity() > std::string().capacity()) bytes += static_cast<double>(v.text.capacity()) + 1;  // beyond the string's own buffer
  }
  return bytes;
}

WorkBudget beside_the_table(WorkBudget budget, const CaseTable& table, std::size_t cases) {
  const double held = sweep_holdings(table, cases);
  budget.max_memory -= held;  // below zero where the table alone fills it: every case is then refused, naming the table
  budget.memory_beside += held;
  budget.beside_holder = "the sweep's table of cases and order";
  return budget;
}

}  // namespace mechgraph
