#pragma once
// The work of a sweep, case by case, before the first case runs: each case's values are written
// into a copy of the graph (as the sweep will write them) and the nodes they reach, and everything
// downstream of them, are estimated again (work_estimate.hpp); the rest is estimated once. So a
// value from a cases file, a grid or a sample counts as it would from --set: a cases file cannot
// admit 10^7 rows of a million curve points each because the scene's own value is small.
#include <mechgraph/sweep/case_binder.hpp>
#include <mechgraph/work_estimate.hpp>

#include <cstddef>
#include <vector>

namespace mechgraph {

struct SweepEstimate {
  WorkEstimate total;        // work: all the cases added up; terms: those of the largest case
  double largest_memory = 0;  // the most memory one case holds
  std::size_t largest_case = 0;
};

/// Estimates each case of `cases` (indices into `table`). A case whose values the binder refuses
/// costs nothing (it fails before any work). Linear in the cases times the nodes they reach; on
/// `threads` workers, chunks of cases added up in order: the same figures on any number.
SweepEstimate estimate_cases(const Graph& graph, const CaseBinder& binder, const CaseTable& table,
                             const std::vector<std::size_t>& cases, unsigned threads = 1);

/// estimate_cases checked against `budget`: work over all cases, memory of the largest case times
/// `threads` (at most the number of cases) running at once. Throws SceneError naming the case.
void check_sweep_budget(const Graph& graph, const CaseBinder& binder, const CaseTable& table,
                        const std::vector<std::size_t>& cases, const WorkBudget& budget, unsigned threads);

/// The bytes a sweep holds beside its cases' own memory: its table (a double a value kept as
/// numbers; a CaseValue, its text and its row's share else) and the order of `cases` (an index a
/// case).
double sweep_holdings(const CaseTable& table, std::size_t cases);
/// `budget` with sweep_holdings taken off its memory (memory_beside says so in a refusal): what a
/// sweep's threads may hold at once beside its table. (A study counts its design in its own.)
/// check_sweep_budget's refusal names the table where it is the larger part.
WorkBudget beside_the_table(WorkBudget budget, const CaseTable& table, std::size_t cases);

}  // namespace mechgraph
