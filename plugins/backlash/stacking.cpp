#include "stacking.hpp"

#include "monte_carlo_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mechgraph::backlash {
namespace {

double link_sigma(const ToleranceLink& l) { return standard_deviation(l.distribution, l.half_range); }

}  // namespace

LinearStack stack_linear(const std::vector<ToleranceLink>& links) {
  LinearStack s;
  // The variances are summed scaled by the largest |s_i sigma_i| (a hypot over many terms), so
  // sizes far from 1 m neither overflow nor underflow when squared.
  double scale = 0.0;
  for (const ToleranceLink& l : links) scale = std::max(scale, std::abs(l.sensitivity * link_sigma(l)));
  double variance = 0.0;  // in units of scale^2
  std::vector<double> worst(links.size()), var(links.size());
  for (std::size_t i = 0; i < links.size(); ++i) {
    const ToleranceLink& l = links[i];
    s.mean += l.sensitivity * l.mean;
    worst[i] = std::abs(l.sensitivity) * l.half_range;
    const double si = scale > 0.0 ? l.sensitivity * link_sigma(l) / scale : 0.0;
    var[i] = si * si;
    s.worst_case_half += worst[i];
    variance += var[i];
  }
  s.rss_sigma = scale * std::sqrt(variance);
  s.contribution_worst_case.assign(links.size(), 0.0);
  s.contribution_rss.assign(links.size(), 0.0);
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (s.worst_case_half > 0.0) s.contribution_worst_case[i] = worst[i] / s.worst_case_half;
    if (variance > 0.0) s.contribution_rss[i] = var[i] / variance;
  }
  return s;
}

double term_sigma(const PlayTerm& term) {
  double variance = 0.0;
  for (const ToleranceLink& l : term.links) {
    const double si = l.sensitivity * link_sigma(l);
    variance += si * si;
  }
  return std::sqrt(variance);
}

double quantile_of_sorted(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) throw std::invalid_argument("quantile of no samples");
  const double h = static_cast<double>(sorted.size() - 1) * std::clamp(p, 0.0, 1.0);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  if (lo + 1 >= sorted.size()) return sorted.back();
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[lo + 1] - sorted[lo]);
}

namespace {


// The same quantile by selection among the samples beyond `threshold` only: one pass copies the
// tail (the samples above it for p > 1/2, below it otherwise) and, when the tail holds both order
// statistics the interpolation needs, nth_element runs on the tail alone. Otherwise (a tail
// thinner than assumed) the whole vector is selected in.
double tail_quantile(std::vector<double>& v, double p, double threshold) {
  const double h = static_cast<double>(v.size() - 1) * std::clamp(p, 0.0, 1.0);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const bool upper = p > 0.5;
  std::vector<double> tail;
  for (double x : v)
    if (upper ? x > threshold : x < threshold) tail.push_back(x);
  // Ranks (ascending) the tail holds: the top tail.size() for the upper tail, the bottom ones else.
  const std::size_t first = upper ? v.size() - tail.size() : 0;
  const std::size_t last = upper ? v.size() - 1 : tail.size() - (tail.empty() ? 0 : 1);
  const std::size_t need_high = std::min(lo + 1, v.size() - 1);
  if (tail.empty() || lo < first || need_high > last) return quantile_by_selection(v, p);
  const std::size_t k = lo - first;
  std::nth_element(tail.begin(), tail.begin() + static_cast<std::ptrdiff_t>(k), tail.end());
  const double a = tail[k];
  if (lo + 1 >= v.size()) return a;
  const double b = *std::min_element(tail.begin() + static_cast<std::ptrdiff_t>(k) + 1, tail.end());
  return a + (h - static_cast<double>(lo)) * (b - a);
}

}  // namespace

void Histogram::add(const double* x, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) add(x[i]);
}

void Histogram::trim() {
  std::size_t first = 0, last = counts.size();
  while (first + 1 < last && counts[first] == 0) ++first;
  while (last > first + 1 && counts[last - 1] == 0) --last;
  if (last < counts.size()) top = low + static_cast<double>(last) * width;
  low += static_cast<double>(first) * width;
  counts = std::vector<std::size_t>(counts.begin() + static_cast<std::ptrdiff_t>(first), counts.begin() + static_cast<std::ptrdiff_t>(last));
}

Histogram histogram_over(double low, double high, std::size_t bins) {
  Histogram h;
  if (!(high > low)) {  // equal samples: one bin about them, wide enough to be a number apart
    const double w = std::max(1e-9 * std::abs(low), 1e-30);
    h.low = low - 0.5 * w;
    h.width = w;
    h.top = h.low + w;
    h.counts.assign(1, 0);
    return h;
  }
  h.low = low;
  h.width = (high - low) / static_cast<double>(bins);
  h.top = high;
  h.counts.assign(bins, 0);
  return h;
}

SampleSummary summarize(std::vector<double> samples, const SampleLimits& limits, std::size_t bins) {
  if (samples.size() < 2) throw std::invalid_argument("Monte Carlo needs at least two samples");
  SampleSummary s;
  s.count = samples.size();
  const double n = static_cast<double>(s.count);
  // Two passes about a shift (the first sample, inside the spread) so that a large common value
  // costs no digits.
  const double shift = samples.front();
  double sum = 0.0;
  for (double x : samples) sum += x - shift;
  const double mean_offset = sum / n;
  double squares = 0.0, low = samples.front(), high = samples.front();
  for (double x : samples) {
    const double d = x - shift - mean_offset;
    squares += d * d;
    low = std::min(low, x);
    high = std::max(high, x);
    s.below += x < limits.lower;
    s.above += x > limits.upper;
  }
  s.min = low;
  s.max = high;
  s.mean = shift + mean_offset;
  s.sigma = std::sqrt(squares / (n - 1.0));
  s.mean_error = s.sigma / std::sqrt(n);
  s.sigma_error = s.sigma / std::sqrt(2.0 * (n - 1.0));
  if (bins > 0) {
    s.histogram = histogram_over(low, high, bins);
    s.histogram.add(samples.data(), samples.size());
  }
  s.q_low = tail_quantile(samples, probability_minus_3_sigma, s.mean - 2.0 * s.sigma);
  s.q_high = tail_quantile(samples, probability_plus_3_sigma, s.mean + 2.0 * s.sigma);
  return s;
}

std::vector<double> sample_linear_stack(const std::vector<ToleranceLink>& links, std::size_t count, std::uint64_t seed) {
  return draw_samples(sampled_stack(links), count, seed);
}

std::vector<double> sample_play_stack(const PlayStack& stack, std::size_t count, std::uint64_t seed) {
  return draw_samples(sampled_stack(stack), count, seed);
}

SampleSummary monte_carlo_linear_stack(const std::vector<ToleranceLink>& links, std::size_t count, std::uint64_t seed,
                                       const SampleLimits& limits, std::size_t bins, unsigned threads) {
  return monte_carlo(sampled_stack(links), count, seed, limits, bins, threads);
}

SampleSummary monte_carlo_play_stack(const PlayStack& stack, std::size_t count, std::uint64_t seed,
                                     const SampleLimits& limits, std::size_t bins, unsigned threads) {
  return monte_carlo(sampled_stack(stack), count, seed, limits, bins, threads);
}

// The quantile quantile_of_sorted would give, by selection instead of a full sort (O(n), the
// order of `v` is changed): nth_element places rank lo, the next rank is the least above it.
double quantile_by_selection(std::vector<double>& v, double p) {
  const double h = static_cast<double>(v.size() - 1) * std::clamp(p, 0.0, 1.0);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(lo), v.end());
  const double a = v[lo];
  if (lo + 1 >= v.size()) return a;
  const double b = *std::min_element(v.begin() + static_cast<std::ptrdiff_t>(lo) + 1, v.end());
  return a + (h - static_cast<double>(lo)) * (b - a);
}

}  // namespace mechgraph::backlash
