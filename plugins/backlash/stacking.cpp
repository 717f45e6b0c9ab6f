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

void Histogram::add(const double* x, std::size_t n) {
  const double inv = 1.0 / width, bins = static_cast<double>(counts.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double u = (x[i] - low) * inv;  // bin k holds k <= u < k + 1
    if (u < 0.0) ++under;
    else if (u < bins) ++counts[static_cast<std::size_t>(u)];
    else if (x[i] <= top) ++counts.back();  // the top edge itself, when it belongs to the last bin
    else ++over;
  }
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

namespace {

// A stack's samples in sequence, a block at a time: each block draws every variate kind for the
// whole block, then the arithmetic runs over arrays. The same seed gives the same sequence.
class LinearStackSampler {
 public:
  LinearStackSampler(const std::vector<ToleranceLink>& links, std::uint64_t seed) : variates_(seed), sum_(links) {}
  void fill(double* out, std::size_t n) {  // n <= block
    std::fill_n(deviation_.begin(), n, 0.0);
    sum_.add_deviations(variates_, deviation_.data(), scratch_.data(), n);
    for (std::size_t i = 0; i < n; ++i) out[i] = sum_.mean + deviation_[i];
  }

 private:
  Variates variates_;
  CompiledSum sum_;
  std::vector<double> deviation_ = std::vector<double>(block), scratch_ = std::vector<double>(block);
};

class PlayStackSampler {
 public:
  PlayStackSampler(const PlayStack& stack, std::uint64_t seed)
      : variates_(seed), own_mean_(stack.own_mean), own_sigma_(stack.own_sigma) {
    for (const WeightedTerm& t : stack.terms) {
      terms_.emplace_back(t.term.links);
      weights_.push_back(t.weight);
    }
  }
  void fill(double* y, std::size_t n) {  // n <= block
    if (own_sigma_ > 0.0) {
      variates_.normals(scratch_.data(), n);
      for (std::size_t i = 0; i < n; ++i) y[i] = std::max(0.0, own_mean_ + own_sigma_ * scratch_[i]);
    } else {
      std::fill_n(y, n, std::max(0.0, own_mean_));
    }
    for (std::size_t k = 0; k < terms_.size(); ++k) {
      std::fill_n(deviation_.begin(), n, 0.0);
      terms_[k].add_deviations(variates_, deviation_.data(), scratch_.data(), n);
      const double m = terms_[k].mean, w = weights_[k];
      for (std::size_t i = 0; i < n; ++i) y[i] += w * std::max(0.0, m + deviation_[i]);
    }
  }

 private:
  Variates variates_;
  double own_mean_, own_sigma_;
  std::vector<CompiledSum> terms_;
  std::vector<double> weights_;
  std::vector<double> deviation_ = std::vector<double>(block), scratch_ = std::vector<double>(block);
};

template <class Sampler>
std::vector<double> all_samples(Sampler sampler, std::size_t count) {
  std::vector<double> out(count);
  for (std::size_t start = 0; start < count; start += block) sampler.fill(out.data() + start, std::min(block, count - start));
  return out;
}

// The summary of `count` samples without keeping them: one pass sums about a shift and keeps the
// extremes and the samples beyond two thresholds; the 3-sigma quantiles are then selected among
// those tails (the order statistics of the whole are the tails' when the tails hold their ranks).
// The thresholds come from a pilot of the stream's first samples (mean -+ 2 sigma); should a tail
// be too thin to hold its rank (a heavy tail), the stream is run again from its seed with the
// thresholds twice as far in. Memory: the tails, a few percent of the samples.
template <class MakeSampler>
SampleSummary summarize_stream(const MakeSampler& make, std::size_t count, const SampleLimits& limits, std::size_t bins) {
  constexpr std::size_t pilot_count = 1u << 16;
  if (count <= 2 * pilot_count) return summarize(all_samples(make(), count), limits, bins);
  const SampleSummary pilot = summarize(all_samples(make(), pilot_count));
  // The histogram's bins: `bins` across the pilot's range, as many again as a quarter of them each side.
  Histogram bins_laid;
  if (bins > 0) {
    const Histogram across = histogram_over(pilot.min, pilot.max, bins);
    const std::size_t margin = (bins + 3) / 4;
    bins_laid.width = across.width;
    bins_laid.low = across.low - static_cast<double>(margin) * across.width;
    bins_laid.counts.assign(across.counts.size() + 2 * margin, 0);
    bins_laid.top = bins_laid.low + static_cast<double>(bins_laid.counts.size()) * across.width;
  }
  const double n = static_cast<double>(count);
  for (double reach = 2.0; reach >= 0.25; reach /= 2.0) {
    const double t_low = pilot.mean - reach * pilot.sigma, t_high = pilot.mean + reach * pilot.sigma;
    auto sampler = make();
    std::vector<double> buffer(block), low_tail, high_tail;
    Histogram histogram = bins_laid;
    double shift = 0.0, sum = 0.0, squares = 0.0, low = 0.0, high = 0.0;
    std::size_t below = 0, above = 0;
    for (std::size_t start = 0; start < count; start += block) {
      const std::size_t m = std::min(block, count - start);
      sampler.fill(buffer.data(), m);
      if (start == 0) shift = low = high = buffer[0];
      double block_sum = 0.0, block_squares = 0.0;  // per block, then added: the sums keep their digits
      for (std::size_t i = 0; i < m; ++i) {
        const double x = buffer[i], d = x - shift;
        block_sum += d;
        block_squares += d * d;
        low = std::min(low, x);
        high = std::max(high, x);
        if (x < t_low) low_tail.push_back(x);
        if (x > t_high) high_tail.push_back(x);
        below += x < limits.lower;
        above += x > limits.upper;
      }
      sum += block_sum;
      squares += block_squares;
      if (!histogram.empty()) histogram.add(buffer.data(), m);
    }
    // The ranks a quantile interpolates between, and whether the tails hold them.
    auto ranks = [&](double p) {
      const double h = (n - 1.0) * p;
      const auto lo = static_cast<std::size_t>(std::floor(h));
      return std::pair{lo, h - static_cast<double>(lo)};
    };
    const auto [low_rank, low_frac] = ranks(probability_minus_3_sigma);
    const auto [high_rank, high_frac] = ranks(probability_plus_3_sigma);
    const std::size_t high_first = count - high_tail.size();
    if (low_rank + 1 >= low_tail.size() || high_rank < high_first || high_rank + 1 >= count) continue;
    SampleSummary s;
    s.count = count;
    s.min = low;
    s.max = high;
    s.mean = shift + sum / n;
    s.sigma = std::sqrt(std::max(0.0, (squares - sum * sum / n) / (n - 1.0)));
    s.mean_error = s.sigma / std::sqrt(n);
    s.sigma_error = s.sigma / std::sqrt(2.0 * (n - 1.0));
    s.below = below;
    s.above = above;
    if (!histogram.empty()) {
      histogram.trim();
      s.histogram = std::move(histogram);
    }
    auto select = [](std::vector<double>& tail, std::size_t k, double frac) {
      std::nth_element(tail.begin(), tail.begin() + static_cast<std::ptrdiff_t>(k), tail.end());
      const double a = tail[k];
      const double b = *std::min_element(tail.begin() + static_cast<std::ptrdiff_t>(k) + 1, tail.end());
      return a + frac * (b - a);
    };
    s.q_low = select(low_tail, low_rank, low_frac);
    s.q_high = select(high_tail, high_rank - high_first, high_frac);
    return s;
  }
  return summarize(all_samples(make(), count), limits, bins);  // tails never thin enough to hold the ranks
}

}  // namespace

std::vector<double> sample_linear_stack(const std::vector<ToleranceLink>& links, std::size_t count, std::uint64_t seed) {
  return all_samples(LinearStackSampler(links, seed), count);
}

std::vector<double> sample_play_stack(const PlayStack& stack, std::size_t count, std::uint64_t seed) {
  return all_samples(PlayStackSampler(stack, seed), count);
}

SampleSummary monte_carlo_linear_stack(const std::vector<ToleranceLink>& links, std::size_t count, std::uint64_t seed,
                                       const SampleLimits& limits, std::size_t bins) {
  return summarize_stream([&] { return LinearStackSampler(links, seed); }, count, limits, bins);
}

SampleSummary monte_carlo_play_stack(const PlayStack& stack, std::size_t count, std::uint64_t seed,
                                     const SampleLimits& limits, std::size_t bins) {
  return summarize_stream([&] { return PlayStackSampler(stack, seed); }, count, limits, bins);
}

}  // namespace mechgraph::backlash
