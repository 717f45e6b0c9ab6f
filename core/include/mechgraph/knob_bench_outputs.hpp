#pragma once
// How `mechgraph bench` compares what one node produced in different evaluations
// (docs/bench.md): the largest relative difference from a reference, the relative spread over
// independent Monte Carlo runs, and whether two evaluations are the same to the bit.
//
// A node's numeric outputs are cut into comparable pieces: a scalar, a series, a table's channel.
// Each element is measured relative to its own magnitude with a floor for values near zero:
//   scalar      e = |x - r| / max(|r|, 1e-3 * max |r'|),  r' over the node's scalars of the same
//               dimension (a margin that is zero by construction sits beside forces of kN);
//   series      e = |x_i - r_i| / max_j |r_j|,  the largest element of the same series;
//   table       the same, channel by channel (a curve crossing zero has no relative error of its own).
// Two pieces are compared only when they have the same shape: as many elements and the same axis
// (a knob that sets the number of curve points, a histogram whose bins follow the samples' range:
// not comparable, so not compared). Outputs that are not results are left out: those named like a
// work counter of the node and uncertainties (a name ending in "_error").
#include <mechgraph/evaluator.hpp>

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph {

/// The largest relative difference (or spread) over a node's numeric outputs, and where.
struct OutputDeviation {
  double max_relative = 0.0;
  std::string worst;                        // "node.port" or "node.port:channel"
  std::map<std::string, double> per_output;  // the largest per output (table: per channel)
  std::size_t compared = 0;                 // elements compared; 0: nothing was comparable
};

/// Whether output `port` is a result the bench compares (not a work counter, not an uncertainty).
bool is_compared_output(std::string_view port, const std::vector<std::string>& work_counters);

/// Each comparable element of `trial` against the same element of `reference`.
OutputDeviation relative_difference(const std::vector<OutputValue>& trial, const std::vector<OutputValue>& reference,
                                    const std::vector<std::string>& work_counters);

/// The spread of each element over `runs` (the same node with independent seeds): its sample
/// standard deviation s = sqrt(sum (x_k - mean)^2 / (K - 1)) relative to |mean|, with the floors
/// above taken from the means. Elements missing or of another shape in any run are left out.
/// Fewer than two runs compare nothing.
OutputDeviation relative_spread(const std::vector<std::vector<OutputValue>>& runs,
                                const std::vector<std::string>& work_counters);

/// Whether every numeric output (results, counters and uncertainties alike) is the same to the
/// bit in both, with the same outputs present. Handles (domain objects) are not compared.
bool bit_identical(const std::vector<OutputValue>& a, const std::vector<OutputValue>& b);

}  // namespace mechgraph
