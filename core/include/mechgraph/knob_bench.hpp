#pragma once
// Work-precision of the accuracy knobs (docs/bench.md): for each knob of a node, evaluate the node
// over a ladder of settings and report the time it took, the work it counted and its error.
// Upstream nodes are evaluated once and served from the memo cache, so the time is the node's own.
//
// Which way is "tighter": an integer knob (samples, points, iterations) is tighter when larger; a
// real knob (step, tolerance) when smaller; a choice knob (method) is tried at each of its choices,
// listed most accurate first.
//
// The error of a setting is measured against that knob's own converged reference: the knob alone
// tightened (integer x2, real /4 a step), the other knobs at the scene's settings, until three
// successive values agree to 1e-3 x the tolerance (two agreeing differences in a row: a result
// that moves in steps can repeat once by chance), the knob's range ends, the step limit or the
// work or time budget is reached, or an evaluation fails. The last difference (of two agreeing,
// the larger) is the reference's own uncertainty, the floor: an error below it is reported as
// "< floor", not as its value. A
// choice knob's reference is its first choice; its floor is how far that moves when each other
// knob acting in the scene is tightened one step.
//
// A node with a `seed` parameter is random (Monte Carlo): there the error of a setting is the
// relative spread (standard deviation) of its outputs over `seeds` independent seeds, with the
// standard error of that standard deviation, s / sqrt(2 (K - 1)).
//
// A knob that cannot act in the scene is not measured: one that an effect that is off for the node
// brings, or one whose every setting gives bit-identical outputs and work counters.
#include <mechgraph/graph.hpp>
#include <mechgraph/work_estimate.hpp>

#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph {

struct KnobTrial {
  std::string node;
  std::string type;
  std::string knob;
  std::string setting;        // the knob's value as text (in its display unit, or the choice)
  bool is_default = false;
  double seconds = 0.0;       // fastest of the repeats (Monte Carlo: of the seeds)
  std::map<std::string, double> work;
  /// Deterministic: the largest relative difference from the knob's reference over the node's
  /// outputs. Monte Carlo: the largest relative standard deviation over the seeds.
  double max_relative_error = 0.0;
  double error_uncertainty = 0.0;   // Monte Carlo: the standard error of that standard deviation
  double reference_floor = 0.0;     // the reference's own uncertainty (infinite: not known)
  bool below_floor = false;         // the error is below the floor: "< floor", not a value
  std::string worst_output;         // where the error is ("node.port", "node.port:channel")
  std::map<std::string, double> errors;  // per output
  std::string failure;              // the evaluation error, if the setting failed
  bool on_front = false;            // on the Pareto front of its knob (advise_knobs sets it)
};

/// One knob of one node: how it was measured, or why it was not.
struct KnobStudy {
  std::string node, type, knob;
  std::string not_measured;         // one line saying why the knob was not measured; empty if it was
  bool monte_carlo = false;
  int seeds = 0;                    // Monte Carlo: seeds per setting
  std::string reference;            // the reference's setting (deterministic)
  int reference_steps = 0;          // tightening steps from the scene's setting to the reference
  double floor = 0.0;               // the reference's own uncertainty (infinite: not known)
  std::string floor_output;         // where the last step changed the outputs most
  bool converged = false;           // three successive values agreed to 1e-3 x the tolerance
  std::string stopped;              // how the reference was found, in words
  std::size_t first_trial = 0;      // its trials: [first_trial, first_trial + trial_count)
  std::size_t trial_count = 0;
};

struct KnobBench {
  std::vector<KnobTrial> trials;
  std::vector<KnobStudy> knobs;     // in the nodes' order, each node's knobs in its parameters' order
};

struct KnobBenchOptions {
  std::optional<std::string> node;  // only this node (default: every needed node with knobs)
  int steps = 3;                    // ladder: default x 2^-steps .. x 2^steps
  int repeats = 3;                  // time = the fastest of this many evaluations
  double tolerance = 1e-9;          // a reference is converged when successive values agree to 1e-3 x this
  int reference_steps = 8;          // at most this many tightening steps for a reference
  double max_work = 1e9;            // no reference step whose work (estimated or extrapolated) exceeds this
  double reference_seconds = 30.0;  // no reference step that would take a knob's search beyond this
  int seeds = 8;                    // Monte Carlo: independent seeds per setting
  /// Called before each node is measured (done nodes, all nodes, the node's name): long runs show progress.
  std::function<void(std::size_t, std::size_t, const std::string&)> progress;
};

/// Whether a node draws random numbers: it has an integer parameter `seed` (set or defaulted).
bool is_monte_carlo(const GraphNode& node);

/// The work of the bench's ladders before anything runs, for check_work_budget: each needed node
/// with knobs, its own work estimate x knobs x (2^(steps+1) + steps) (the ladder, a rung x 2^k
/// costing at most 2^k times the scene's setting) x repeats (Monte Carlo: x max(repeats, seeds)).
/// The references are checked step by step against `options.max_work` as they are tightened.
WorkEstimate estimate_bench_work(const Graph& graph, const KnobBenchOptions& options);

/// Throws SceneError if `options.node` names no node (or one without knobs).
KnobBench bench_knobs(const Graph& graph, const KnobBenchOptions& options = {});

/// What the ladder of one knob says: which settings are on the Pareto front of error against
/// time, the cheapest setting whose error bound is within `tolerance` (the recommendation), and
/// whether the scene's setting is far off the front (a front setting at least as accurate, or
/// within the tolerance, costs at most half its time). The error bound of a setting is its error
/// + its uncertainty (Monte Carlo) + the reference's floor (deterministic).
struct KnobAdvice {
  std::string node, knob;
  std::optional<std::size_t> recommended;  // index into the trials
  std::optional<std::size_t> current;      // the scene's setting
  bool current_off_front = false;
  std::string text;                        // the advice as one line ("not measured: ..." for a knob that was not)
};

/// The error a setting certainly has no more than: error + uncertainty + floor.
double error_bound(const KnobTrial& trial);

/// Marks `on_front` in the trials and returns one advice per knob study, in the studies' order.
std::vector<KnobAdvice> advise_knobs(KnobBench& bench, double tolerance);

}  // namespace mechgraph
