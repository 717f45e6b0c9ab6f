#pragma once
// Demand-driven evaluation: each needed node runs once, producers first, and its outputs are
// memoised under a hash of its type, version, parameters, the effects it reads and the hashes of
// its inputs. A MemoCache kept across runs (a sweep) re-evaluates only what changed.
#include <mechgraph/graph.hpp>
#include <mechgraph/memo_cache.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace mechgraph {

struct OutputValue {
  std::string label;  // "node.port"
  Value value;
  Dimension dimension;
  std::string display_unit;
};

struct NodeRun {
  std::string node;
  std::string type;
  std::uint64_t hash = 0;
  bool reused = false;    // taken from the memo cache, not evaluated
  double seconds = 0.0;
  std::map<std::string, double> work;
  std::vector<std::string> notes;  // how the node made its results (OutputSet::note)
};

struct RunResult {
  std::vector<OutputValue> outputs;  // in the order of Graph::outputs
  std::vector<NodeRun> runs;         // in evaluation order
};

/// The memo key of every node of the graph that is needed (0 for culled nodes).
std::vector<std::uint64_t> node_hashes(const Graph& graph);

/// Evaluates the needed nodes. Throws EvaluationError naming the node (and parameter) on failure,
/// including a node that would emit NaN or Inf. `cache` may be shared across runs and threads.
/// With `threads` > 1, independent nodes run at once (a node starts when its producers are done);
/// the results are the same, `runs` stays in dependency order, but two identical nodes of one
/// graph may then both be evaluated instead of one being reused.
RunResult evaluate(const Graph& graph, MemoCache& cache, unsigned threads = 1);

/// What a sweep keeps of a run: the requested outputs' values in the order of Graph::outputs
/// (their labels, dimensions and display units are the graph's), and how many nodes ran.
struct RunValues {
  std::vector<Value> values;
  std::size_t evaluated = 0, reused = 0;  // nodes run, nodes taken from the memo cache
};

/// evaluate() without the per-node records a sweep does not print (names, times, work counters,
/// notes): the same values, refused the same way (a NaN output or work counter, an undisplayable
/// value), for less work per case.
RunValues evaluate_values(const Graph& graph, MemoCache& cache, unsigned threads = 1);

/// The number in a report table's cell of row `row` (SI): the cell's scalar output, or the element
/// of its series output. Throws EvaluationError naming the row when the series is too short.
double report_cell_value(const RunResult& result, const ResolvedReport::Row& row, const ResolvedReport::Cell& cell);

}  // namespace mechgraph
