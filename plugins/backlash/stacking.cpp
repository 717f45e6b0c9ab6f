#include "stacking.hpp"

#include "variates.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mechgraph::backlash {
namespace {

// A sum s_j X_j prepared for sampling, as deviations from its mean (the digits of the variation
// are kept). Its normal links are drawn as one: a sum of independent normals is normal, with
// sigma = sqrt(sum (s_j h_j / 3)^2), so a term of a hole and a shaft costs one normal draw. Each
// uniform or triangular link keeps its own draw, scaled to its half-range.
struct CompiledSum {
  double mean = 0.0;
  double normal_sigma = 0.0;
  std::vector<double> uniform, triangular;  // s_j h_j of those links

  explicit CompiledSum(const std::vector<ToleranceLink>& links) {
    double variance = 0.0, scale = 0.0;
    for (const ToleranceLink& l : links) scale = std::max(scale, std::abs(l.sensitivity * l.half_range));
    for (const ToleranceLink& l : links) {
      mean += l.sensitivity * l.mean;
      const double c = l.sensitivity * l.half_range;
      switch (l.distribution) {
        case Distribution::normal: {
          const double r = scale > 0.0 ? c / (3.0 * scale) : 0.0;  // scaled: no overflow when squared
          variance += r * r;
          break;
        }
        case Distribution::uniform: uniform.push_back(c); break;
        case Distribution::triangular: triangular.push_back(c); break;
      }
    }
    normal_sigma = scale * std::sqrt(variance);
  }

  // Adds the deviations of n samples to `out`, a block at a time (scratch: n doubles).
  void add_deviations(Variates& v, double* out, double* scratch, std::size_t n) const {
    if (normal_sigma > 0.0) {
      v.normals(scratch, n);
      for (std::size_t i = 0; i < n; ++i) out[i] += normal_sigma * scratch[i];
    }
    for (double c : uniform) {
      v.uniforms(scratch, n);
      for (std::size_t i = 0; i < n; ++i) out[i] += c * scratch[i];
    }
    for (double c : triangular) {
      v.triangulars(scratch, n);
      for (std::size_t i = 0; i < n; ++i) out[i] += c * scratch[i];
    }
  }
};

// Samples are made a block at a time: each variate kind is drawn for the whole block, then the
// arithmetic runs over arrays (no branch on a link's distribution per sample).
constexpr std::size_t block = 2048;

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

SampleSummary summarize(std::vector<double> samples) {
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
  }
  s.min = low;
  s.max = high;
  s.mean = shift + mean_offset;
  s.sigma = std::sqrt(squares / (n - 1.0));
  s.mean_error = s.sigma / std::sqrt(n);
  s.sigma_error = s.sigma / std::sqrt(2.0 * (n - 1.0));
  s.q_low = tail_quantile(samples, probability_minus_3_sigma, s.mean - 2.0 * s.sigma);
  s.q_high = tail_quantile(samples, probability_plus_3_sigma, s.mean + 2.0 * s.sigma);
  return s;
}

std::vector<double> sample_linear_stack(const std::vector<ToleranceLink>& links, std::size_t count, std::uint64_t seed) {
  Variates variates(seed);
  const CompiledSum sum(links);
  std::vector<double> out(count), deviation(block), scratch(block);
  for (std::size_t start = 0; start < count; start += block) {
    const std::size_t n = std::min(block, count - start);
    std::fill_n(deviation.begin(), n, 0.0);
    sum.add_deviations(variates, deviation.data(), scratch.data(), n);
    for (std::size_t i = 0; i < n; ++i) out[start + i] = sum.mean + deviation[i];
  }
  return out;
}

std::vector<double> sample_play_stack(const PlayStack& stack, std::size_t count, std::uint64_t seed) {
  Variates variates(seed);
  std::vector<CompiledSum> terms;
  std::vector<double> weights;
  for (const WeightedTerm& t : stack.terms) {
    terms.emplace_back(t.term.links);
    weights.push_back(t.weight);
  }
  std::vector<double> out(count), deviation(block), scratch(block);
  for (std::size_t start = 0; start < count; start += block) {
    const std::size_t n = std::min(block, count - start);
    double* y = out.data() + start;
    if (stack.own_sigma > 0.0) {
      variates.normals(scratch.data(), n);
      for (std::size_t i = 0; i < n; ++i) y[i] = std::max(0.0, stack.own_mean + stack.own_sigma * scratch[i]);
    } else {
      std::fill_n(y, n, std::max(0.0, stack.own_mean));
    }
    for (std::size_t k = 0; k < terms.size(); ++k) {
      std::fill_n(deviation.begin(), n, 0.0);
      terms[k].add_deviations(variates, deviation.data(), scratch.data(), n);
      const double m = terms[k].mean, w = weights[k];
      for (std::size_t i = 0; i < n; ++i) y[i] += w * std::max(0.0, m + deviation[i]);
    }
  }
  return out;
}

}  // namespace mechgraph::backlash
