#pragma once
// Stacking of toleranced sizes and of free play (docs/methods/backlash.md, "Stacking:
// worst case, RSS, Monte Carlo"). Pure mathematics, SI throughout; the nodes read parameters and call these.
//
// A link i is a size X_i spread over [m_i - h_i, m_i + h_i] (h_i = T_i/2, the source's limit
// deviation dA) with sensitivity s_i. For the linear stack Y = sum_i s_i X_i:
//   mean         E[Y] = sum s_i m_i
//   worst case   Y in [E[Y] - W, E[Y] + W],  W = sum |s_i| h_i            (arithmetic stack)
//   RSS          sigma_Y = sqrt(sum s_i^2 sigma_i^2), sigma_i = h_i/3 (normal, T = 6 sigma),
//                h_i/sqrt(3) (uniform), h_i/sqrt(6) (symmetric triangular)
//   Pareto       worst case |s_i| h_i / W;  RSS s_i^2 sigma_i^2 / sigma_Y^2
//
// Free play is not linear: a play term is max(0, sum_j s_j X_j) (a fit's clearance, clipped at
// zero for interference) and a chain sums w_k * play_k. Monte Carlo draws every X_j independently
// and is the reference the linear formulas approximate.
#include <mechgraph/domain/tolerance.hpp>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace mechgraph::backlash {

/// Worst case and RSS of a linear stack, with each link's share.
struct LinearStack {
  double mean = 0.0;             // sum s_i m_i
  double worst_case_half = 0.0;  // W = sum |s_i| h_i
  double rss_sigma = 0.0;        // sqrt(sum s_i^2 sigma_i^2)
  std::vector<double> contribution_worst_case;  // |s_i| h_i / W (all 0 when W = 0)
  std::vector<double> contribution_rss;         // s_i^2 sigma_i^2 / sigma_Y^2 (all 0 when sigma_Y = 0)
};

LinearStack stack_linear(const std::vector<ToleranceLink>& links);

/// Standard deviation of the untruncated sum of a play term, sqrt(sum s_j^2 sigma_j^2).
double term_sigma(const PlayTerm& term);

/// Phi(-3) and Phi(3): the probabilities of the +-3 sigma equivalents (0.135 % and 99.865 %).
inline constexpr double probability_minus_3_sigma = 0.0013498980316300946;
inline constexpr double probability_plus_3_sigma = 1.0 - probability_minus_3_sigma;

/// Counts of samples in equal bins [low + k width, low + (k + 1) width), k < counts.size(); the
/// samples outside them counted apart.
struct Histogram {
  double low = 0.0;
  double width = 0.0;
  std::vector<std::size_t> counts;
  double top = 0.0;       // the last bin holds samples up to here (its upper edge, or the largest sample)
  std::size_t under = 0;  // below low
  std::size_t over = 0;   // above top
  bool empty() const { return counts.empty(); }
  /// Adds one sample, and n samples.
  void add(double x) {
    const double u = (x - low) / width;  // bin k holds k <= u < k + 1
    if (u < 0.0) ++under;
    else if (u < static_cast<double>(counts.size())) ++counts[static_cast<std::size_t>(u)];
    else if (x <= top) ++counts.back();  // the top edge itself, when it belongs to the last bin
    else ++over;
  }
  void add(const double* x, std::size_t n);
  /// Drops the empty bins at both ends (keeps at least one bin).
  void trim();
};

/// Bins spanning [low, high]: `bins` of width (high - low)/bins; when high == low, one bin around
/// that value (width 1e-9 |low|, or 1e-30 at zero). A sample at `high` counts in the last bin.
Histogram histogram_over(double low, double high, std::size_t bins);

/// What Monte Carlo reports about its N samples.
struct SampleSummary {
  std::size_t count = 0;
  double mean = 0.0;
  double sigma = 0.0;        // sample standard deviation (divisor N - 1)
  double min = 0.0;
  double max = 0.0;
  double q_low = 0.0;        // quantile at Phi(-3)
  double q_high = 0.0;       // quantile at Phi(+3)
  double mean_error = 0.0;   // standard error of the mean, sigma / sqrt(N)
  double sigma_error = 0.0;  // standard error of sigma, sigma / sqrt(2 (N - 1)) (exact for normal samples)
  std::size_t below = 0;     // samples below SampleLimits::lower
  std::size_t above = 0;     // samples above SampleLimits::upper
  Histogram histogram;       // when bins were asked for
};

/// Limits to count samples outside of (a specification); infinite by default (none counted).
struct SampleLimits {
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
};

/// Summarises N >= 2 samples (moments in two passes, the 3-sigma quantiles by selection in the tails);
/// with bins > 0 also a histogram of that many bins from the smallest sample to the largest.
SampleSummary summarize(std::vector<double> samples, const SampleLimits& limits = {}, std::size_t bins = 0);

/// The type-7 p-quantile of `v` (as of sorted samples), by selection in O(n); the order of `v`
/// is changed.
double quantile_by_selection(std::vector<double>& v, double p);

/// Quantile p of sorted samples, linear between order statistics (Hyndman-Fan type 7):
/// h = (N - 1) p, x_(floor h) + (h - floor h)(x_(floor h + 1) - x_(floor h)).
double quantile_of_sorted(const std::vector<double>& sorted, double p);

/// N draws of the linear stack sum s_i X_i, each X_i drawn independently from its distribution
/// (normal N(m, h/3), unbounded; uniform U(m - h, m + h); triangular Tri(m - h, m, m + h)).
/// Reproducible on every platform for a given seed: the engine and distributions of variates.hpp,
/// whose algorithms are fixed (the standard library's are implementation-defined), drawn by the
/// sampler of monte_carlo_sampler.hpp. The normal links of a sum are drawn as one normal of their
/// combined variance (exact in distribution).
std::vector<double> sample_linear_stack(const std::vector<ToleranceLink>& links, std::size_t count, std::uint64_t seed);

/// A play term with the weight (transfer ratio) that carries it to the result.
struct WeightedTerm {
  double weight = 1.0;
  PlayTerm term;
};

/// Free play of a chain: an own play (an actuator's backlash, normal with mean and sigma,
/// clipped at zero) plus weighted play terms.
struct PlayStack {
  double own_mean = 0.0;
  double own_sigma = 0.0;
  std::vector<WeightedTerm> terms;
};

/// N draws of max(0, N(own_mean, own_sigma)) + sum_k w_k max(0, sum_j s_j X_j); the same engine
/// and distributions as sample_linear_stack.
std::vector<double> sample_play_stack(const PlayStack& stack, std::size_t count, std::uint64_t seed);

/// summarize(sample_linear_stack(...)) and summarize(sample_play_stack(...)) without keeping the
/// samples beyond the first 131072 (monte_carlo() of monte_carlo_sampler.hpp): the same order
/// statistics, extremes and counts, the moments summed about a pilot's mean (equal to the
/// two-pass ones to rounding); memory for about 1 % of them. A streamed histogram (bins > 0)
/// cannot wait for the extremes: its bins are laid over the range of a pilot of the first 65536
/// samples, `bins` across it and a quarter of it more on each side, the empty end bins then
/// dropped; samples beyond are counted in under and over. `threads` workers share the samples'
/// chunks; the result is the same bit for bit for any number of them.
SampleSummary monte_carlo_linear_stack(const std::vector<ToleranceLink>& links, std::size_t count, std::uint64_t seed,
                                       const SampleLimits& limits = {}, std::size_t bins = 0, unsigned threads = 1);
SampleSummary monte_carlo_play_stack(const PlayStack& stack, std::size_t count, std::uint64_t seed,
                                     const SampleLimits& limits = {}, std::size_t bins = 0, unsigned threads = 1);

}  // namespace mechgraph::backlash
