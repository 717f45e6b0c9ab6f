#pragma once
// Runs the cases of a sweep on one pool of worker threads, started once for the whole sweep.
// Each worker keeps its own copy of the built graph and writes each case's values into it
// (CaseBinder); every case shares one memo cache, so what cases have in common (a part evaluated
// for many speeds) is computed once. Results reach the caller in case order, whatever
// the thread count, and are the same bit for bit: nodes are pure and a cached value is the value.
// A failed case is a result with its error; the sweep goes on.
#include <mechgraph/evaluator.hpp>
#include <mechgraph/sweep/case_binder.hpp>

#include <atomic>
#include <functional>
#include <string>
#include <vector>

namespace mechgraph {

enum class CaseFailure { none, scene, evaluation };

struct CaseResult {
  std::size_t index = 0;             // the case's number in its CaseTable
  std::vector<Value> outputs;  // in the order of Graph::outputs (their labels and units), when it succeeded
  CaseFailure failure = CaseFailure::none;
  std::string error;
  std::size_t evaluated = 0, reused = 0;  // nodes run, nodes taken from the memo cache
};

struct SweepOptions {
  unsigned threads = 1;
  std::vector<std::size_t> cases;             // the cases to run, in the order they are emitted
  const std::atomic<bool>* stop = nullptr;    // when set, no new case starts; started ones finish
  std::size_t window = 0;                     // cases run ahead of the oldest unfinished (0: 64 per thread)
  /// Cases per block on the block path (sweep/block_plan.hpp), taken when every node the sweep
  /// needs offers it; 0 runs every case alone. The rows are the same either way.
  std::size_t block_size = default_block_size;
  static constexpr std::size_t default_block_size = 256;
};

struct SweepSummary {
  std::size_t run = 0, failed = 0;
  std::size_t in_blocks = 0;  // cases whose results came from the block path
  bool stopped = false;  // `stop` was set before every case had started
  double seconds = 0.0;
};

/// Runs `options.cases` of `table` and hands each result to `emit`, in order, one call at a time.
/// An exception from `emit` stops the sweep (started cases finish) and is rethrown.
SweepSummary run_sweep(const Graph& base, const CaseBinder& binder, const CaseTable& table, MemoCache& cache,
                       const SweepOptions& options, const std::function<void(CaseResult&&)>& emit);

}  // namespace mechgraph
