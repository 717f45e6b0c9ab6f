#pragma once
// The estimators of an uncertainty study, on plain arrays of one output's values (no graph):
// moments, quantiles with distribution-free intervals, histograms, process capability against
// spec limits, the probability of an event with its interval, and Sobol' indices (Saltelli 2010
// first order, Jansen total) with bootstrap intervals. Every formula and what it promises:
// docs/methods/uncertainty.md. Deterministic: the same values in the same order give the same
// bits; the bootstrap draws from counter_hash (sample_design.hpp).
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace mechgraph {

/// A two-sided interval at a confidence level; an end the data cannot give is absent.
struct Interval {
  std::optional<double> lower, upper;
};

struct Moments {
  std::size_t n = 0;
  double mean = 0.0, standard_deviation = 0.0, min = 0.0, max = 0.0;
  Interval mean_interval;  // mean -+ t(n - 1) sd / sqrt(n)
};
/// Two-pass mean and sample standard deviation (n - 1), Student's interval of the mean; n >= 1.
Moments moments(const std::vector<double>& values, double confidence);

struct QuantileEstimate {
  double level = 0.0, value = 0.0;
  Interval interval;  // order statistics x_(l) .. x_(u) covering the quantile with >= confidence (exact binomial)
};
/// `sorted` ascending. Point estimate: linear interpolation between order statistics (Hyndman and
/// Fan's type 7, numpy's default).
QuantileEstimate quantile(const std::vector<double>& sorted, double level, double confidence);

struct Histogram {
  double low = 0.0, width = 0.0;
  std::vector<std::size_t> counts;  // bin k holds [low + k width, low + (k + 1) width), the last one closed
};
/// `bins` equal bins over [low, high] (high > low, else one bin of width 1 around low).
Histogram histogram(const std::vector<double>& values, std::size_t bins, double low, double high);

struct Proportion {
  std::size_t events = 0, trials = 0;
  double estimate = 0.0;
  Interval wilson, clopper_pearson;
};
/// k events in n trials (n >= 1): k / n, the Wilson score interval and the exact Clopper-Pearson one.
Proportion proportion(std::size_t events, std::size_t trials, double confidence);

struct Capability {
  std::optional<double> cp, cpk;     // cp needs both limits
  double ppm_normal = 0.0;           // out of spec under the normal model of mean and sigma
  Proportion out_of_spec;            // counted among the values
  std::size_t below = 0, above = 0;
  /// The samples that failed (no value) counted as out of spec too: (below + above + failed) /
  /// (values + failed). Failures often sit where the design is extreme, in a tail; this is the
  /// share the values alone cannot rule out. Equal to out_of_spec when nothing failed.
  std::size_t failed = 0;
  Proportion out_of_spec_or_failed;
};
/// Against the limits, from the values and the samples that failed (no value; counted in
/// out_of_spec_or_failed only).
Capability capability(const std::vector<double>& values, const Moments& m, std::optional<double> lower,
                      std::optional<double> upper, double confidence, std::size_t failed = 0);

struct SobolIndex {
  double first = 0.0, total = 0.0;
  Interval first_interval, total_interval;  // bootstrap percentile intervals
};
struct SobolIndices {
  std::size_t samples = 0;  // base samples used
  double variance = 0.0;    // of the pooled f(A), f(B)
  std::vector<SobolIndex> indices;
};
/// f(A), f(B) and f(AB^(j)) over the same base samples (each of length N >= 2). The outputs are
/// centred by the mean of all of them; V is the sample variance of f(A) and f(B) pooled;
///   S_j  = (1/N) sum f(B) (f(AB^j) - f(A)) / V           (Saltelli et al. 2010)
///   ST_j = (1/2N) sum (f(A) - f(AB^j))^2 / V             (Jansen 1999)
/// `bootstrap` resamples of the N base samples with replacement give percentile intervals; they
/// run on `threads` workers with the same result on any number.
SobolIndices sobol_indices(const std::vector<double>& f_a, const std::vector<double>& f_b,
                           const std::vector<std::vector<double>>& f_ab, std::size_t bootstrap, double confidence,
                           std::uint64_t seed, unsigned threads = 1);
/// f(A), f(B) and f(AB^(j)) of one output.
struct SobolSamples {
  std::vector<double> f_a, f_b;
  std::vector<std::vector<double>> f_ab;
};
/// sobol_indices of several outputs over the same N base samples, each result the same as
/// sobol_indices on that output alone: each resample is drawn once and serves every output.
/// Throws std::invalid_argument when the outputs differ in N or in the number of parameters.
/// `stop` (Ctrl-C, SIGTERM) ends the resampling early; the result is then not to be used.
std::vector<SobolIndices> sobol_indices(const std::vector<const SobolSamples*>& samples, std::size_t bootstrap,
                                        double confidence, std::uint64_t seed, unsigned threads = 1,
                                        const std::atomic<bool>* stop = nullptr);

}  // namespace mechgraph
