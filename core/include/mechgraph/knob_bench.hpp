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

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mechgraph {

struct KnobTrial {
  std::string node;
  std::string type;
  std::string knob;
  std::string setting;        // the knob's value as text (SI, or the choice)
  bool is_default = false;
  double seconds = 0.0;       // fastest of the repeats
  std::map<std::string, double> work;
  double max_relative_error = 0.0;  // over the node's numeric outputs, against the reference
  std::string worst_output;         // where that error is
  std::string failure;              // the evaluation error, if the setting failed
};

struct KnobBenchOptions {
  std::optional<std::string> node;  // only this node (default: every needed node with knobs)
  int steps = 3;                    // ladder: default x 2^-steps .. x 2^steps
  int repeats = 3;                  // time = the fastest of this many evaluations
};

/// Throws SceneError if `options.node` names no node (or one without knobs).
std::vector<KnobTrial> bench_knobs(const Graph& graph, const KnobBenchOptions& options = {});

}  // namespace mechgraph
