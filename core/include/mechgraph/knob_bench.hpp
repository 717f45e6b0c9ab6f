#pragma once
// Work-precision of the accuracy knobs: for each knob of a node, evaluate the node over a ladder
// of settings and report the time it took, the work it counted and its error against a reference
// evaluated with every numeric knob tightened well past the ladder. Upstream nodes are evaluated
// once and served from the memo cache, so the time is the node's own.
//
// Which way is "tighter": an integer knob (samples, points, iterations) is tighter when larger; a
// real knob (step, tolerance) when smaller; a choice knob (method) is tried at each of its choices,
// and the reference takes its first choice (a knob's choices are listed most accurate first).
#include <mechgraph/graph.hpp>

#include <functional>
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
  double seconds = 0.0;       // fastest of the repeats
  std::map<std::string, double> work;
  double max_relative_error = 0.0;  // over the node's numeric outputs, against the reference
  std::string worst_output;         // where that error is
  std::map<std::string, double> errors;  // per output ("node.port"), against the reference
  std::string failure;              // the evaluation error, if the setting failed
  bool on_front = false;            // on the Pareto front of its knob (advise_knobs sets it)
};

struct KnobBenchOptions {
  std::optional<std::string> node;  // only this node (default: every needed node with knobs)
  int steps = 3;                    // ladder: default x 2^-steps .. x 2^steps
  int repeats = 3;                  // time = the fastest of this many evaluations
  /// Called before each node is measured (done nodes, all nodes, the node's name): long runs show progress.
  std::function<void(std::size_t, std::size_t, const std::string&)> progress;
};

/// Throws SceneError if `options.node` names no node (or one without knobs).
///
/// The error of an output is relative to the reference, with a floor for values near zero: a
/// thousandth of the largest reference value among the node's scalars of the same dimension, or
/// the largest element of the same series. Outputs that report the run's own work or uncertainty
/// (named like a work counter, or ending in "_error": a Monte Carlo standard error) are not
/// compared; a Monte Carlo estimate is compared with the same estimate from 2^(steps+2) times the
/// samples, so its error column is the estimate's error, not a ratio of standard errors.
std::vector<KnobTrial> bench_knobs(const Graph& graph, const KnobBenchOptions& options = {});

/// What the ladder of one knob says: which settings are on the Pareto front of error against
/// time, the cheapest setting within `tolerance` (the recommendation), and whether the scene's
/// setting is far off the front (a front setting at least as accurate, or within the tolerance,
/// costs at most half its time).
struct KnobAdvice {
  std::string node, knob;
  std::optional<std::size_t> recommended;  // index into the trials
  std::optional<std::size_t> current;      // the scene's setting
  bool current_off_front = false;
  std::string text;                        // the advice as one line
};

/// Marks `on_front` in `trials` and returns one advice per node and knob, in the trials' order.
std::vector<KnobAdvice> advise_knobs(std::vector<KnobTrial>& trials, double tolerance);

}  // namespace mechgraph
