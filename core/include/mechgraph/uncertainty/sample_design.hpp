#pragma once
// The cases of an uncertainty study: points in the unit cube by the study's method, made into
// parameter values by the Gaussian copula of the correlations and each parameter's quantile
// function. Every number depends only on (seed, case index): a case's values are the same whoever
// makes them, on one thread or many, in one process or in a shard of a Slurm array
// (docs/methods/uncertainty.md, "Sampling").
//
// Without sensitivity, case i is sample i. With sensitivity (Saltelli's design), base sample i
// makes d + 2 consecutive cases: A_i, B_i, then A_i with parameter j taken from B_i, j = 1..d
// (AB_i^(j)); A and B are the first and last d coordinates of one 2d-dimensional point.
#include <mechgraph/sweep/case_table.hpp>
#include <mechgraph/uncertainty/study_spec.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace mechgraph {

/// A 64-bit value fixed by (seed, stream, i, j) alone (splitmix64's finaliser, chained): the
/// counter-based generator every random number of a study comes from.
std::uint64_t counter_hash(std::uint64_t seed, std::uint64_t stream, std::uint64_t i, std::uint64_t j);
/// counter_hash as a double strictly inside (0, 1): 53 bits and half a step.
double counter_uniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t i, std::uint64_t j);
/// counter_uniform for one (seed, stream, i) and many j: the chain's first three rounds made once.
/// row(j) == counter_uniform(seed, stream, i, j), bit for bit.
class CounterRow {
 public:
  CounterRow(std::uint64_t seed, std::uint64_t stream, std::uint64_t i);
  double operator()(std::uint64_t j) const;

 private:
  std::uint64_t prefix_;
};

/// Point i (0 <= i < n) of the method's design in `dims` dimensions, each coordinate in (0, 1).
/// Monte Carlo: counter_uniform. Latin hypercube: coordinate j of point i lies in stratum
/// pi_j(i) of n, pi_j a permutation fixed by the seed. Sobol': Joe-Kuo directions (Boost),
/// scrambled by a random digital shift (an XOR of each coordinate's 64 bits with a number drawn
/// from the seed), the point then moved half a step inside so no coordinate is 0.
class UnitDesign {
 public:
  UnitDesign(SamplingMethod method, std::size_t n, std::size_t dims, std::uint64_t seed);
  void point(std::size_t i, double* out) const;
  std::size_t dims() const { return dims_; }

 private:
  SamplingMethod method_;
  std::size_t n_, dims_;
  std::uint64_t seed_;
  std::vector<std::uint32_t> strata_;  // Latin hypercube: strata_[j * n + i]
  std::vector<std::uint64_t> shift_;   // Sobol': per dimension
};

/// Every case of the study as a sweep's cases (the parameter names --set uses, values in SI as
/// exact text), `origin` naming the design and seed. Throws SceneError when the correlations are
/// not a valid correlation matrix (naming the first of them).
CaseTable make_study_cases(const StudySpec& spec, unsigned threads = 1);

/// The most values (cases times parameters) a study's design may hold: a table of numbers'
/// (max_number_cells, 2.5 x 10^8, 2 GB at a double each). The memory budget (--max-memory) counts
/// the table with the rest of the study; this cap holds whatever the budget is raised to.
/// (mechgraph.dask.study sends the design out as a sweep's cases, within max_case_cells.)
inline constexpr std::size_t max_design_values = max_number_cells;

/// Where the design of `spec` would hold more than `max_values` values: "samples: N make M cases of
/// d values each, more than the MAX values HOLDER; at most K samples here" (with sensitivity, how
/// many cases a sample makes); empty where it fits.
std::string design_size_excess(const StudySpec& spec, std::size_t max_values, const std::string& holder);

/// The design's own cap: at most max_design_values values in its table. Throws SceneError naming
/// the samples and the largest number that fits.
void check_design_size(const StudySpec& spec);

}  // namespace mechgraph
