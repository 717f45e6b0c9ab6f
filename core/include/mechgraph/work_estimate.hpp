#pragma once
// What a scene asks of the machine, estimated from its parameters before anything runs, and the
// budget it must keep: a scene from a stranger cannot start an hour of work or a gigabyte of files
// unless the user says so (--max-work, --max-output).
//
// The estimate reads the conventions of the SDK (docs/writing-plugins.md, "Counts of work"): an
// integer parameter whose name ends in `points`, `samples` or `bins` counts work items of its node
// (points of a curve, samples of a search or a Monte Carlo run, bins of a histogram) and
// `revolutions` multiplies them; every record of a record list and every number of a number list
// counts as work items too. A node's curves are written with a row per point. It is an order of
// magnitude, not a prediction of seconds: its use is to refuse what is absurd, naming the term
// that makes it so.
#include <mechgraph/graph.hpp>

#include <string>
#include <vector>

namespace mechgraph {

struct WorkEstimate {
  struct Term {
    std::string what;    // "k.curve_points = 1000000"
    double work = 0;     // work items it brings to one evaluation of the scene
    double bytes = 0;    // bytes of result files it brings when curves are written
  };
  double work = 0;       // work items of one evaluation of every needed node
  double bytes = 0;      // bytes of the requested curves as CSV
  std::vector<Term> terms;
};

/// A sweep's default work budget, for all its cases together.
inline constexpr double sweep_default_max_work = 1e12;

struct WorkBudget {
  double max_work = 1e9;            // work items of one evaluation of the scene (a sweep: sweep_default_max_work)
  double max_bytes = 256.0 * (1 << 20);  // bytes of result files
};

WorkEstimate estimate_work(const Graph& graph);

/// Throws SceneError when `cases` evaluations of the scene exceed the budget's work, or the files
/// written (when `writes_curves`) exceed its bytes: the message gives the estimate, the budget,
/// the biggest term and the option that raises the budget.
void check_work_budget(const Graph& graph, const WorkEstimate& estimate, const WorkBudget& budget, double cases,
                       bool writes_curves);

}  // namespace mechgraph
