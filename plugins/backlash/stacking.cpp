#include "stacking.hpp"

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <boost/random/triangle_distribution.hpp>
#include <boost/random/uniform_real_distribution.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mechgraph::backlash {
namespace {

// Draws of standardized variates: a link's value is m + h z, z from the link's distribution
// scaled to the half-range 1 (normal: N(0, 1/3); uniform: U(-1, 1); triangular: Tri(-1, 0, 1)).
// Drawing standardized variates keeps the distributions' parameters valid for h = 0 too.
class VariateSource {
 public:
  explicit VariateSource(std::uint64_t seed) : engine_(seed) {}

  double unit(Distribution d) {
    switch (d) {
      case Distribution::normal: return normal_(engine_) / 3.0;
      case Distribution::uniform: return uniform_(engine_);
      case Distribution::triangular: return triangle_(engine_);
    }
    return 0.0;
  }
  double standard_normal() { return normal_(engine_); }

 private:
  boost::random::mt19937_64 engine_;
  boost::random::normal_distribution<double> normal_{0.0, 1.0};
  boost::random::uniform_real_distribution<double> uniform_{-1.0, 1.0};
  boost::random::triangle_distribution<double> triangle_{-1.0, 0.0, 1.0};
};

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

}  // namespace

SampleSummary summarize(std::vector<double> samples) {
  if (samples.size() < 2) throw std::invalid_argument("Monte Carlo needs at least two samples");
  SampleSummary s;
  s.count = samples.size();
  const double n = static_cast<double>(s.count);
  // Two passes about a shift (the median) so that a large common value costs no digits.
  const auto [low, high] = std::minmax_element(samples.begin(), samples.end());
  s.min = *low;
  s.max = *high;
  s.q_low = quantile_by_selection(samples, probability_minus_3_sigma);
  s.q_high = quantile_by_selection(samples, probability_plus_3_sigma);
  std::nth_element(samples.begin(), samples.begin() + static_cast<std::ptrdiff_t>(s.count / 2), samples.end());
  const double shift = samples[s.count / 2];
  double sum = 0.0;
  for (double x : samples) sum += x - shift;
  const double mean_offset = sum / n;
  double squares = 0.0;
  for (double x : samples) {
    const double d = x - shift - mean_offset;
    squares += d * d;
  }
  s.mean = shift + mean_offset;
  s.sigma = std::sqrt(squares / (n - 1.0));
  s.mean_error = s.sigma / std::sqrt(n);
  s.sigma_error = s.sigma / std::sqrt(2.0 * (n - 1.0));
  return s;
}

std::vector<double> sample_linear_stack(const std::vector<ToleranceLink>& links, std::size_t count, std::uint64_t seed) {
  VariateSource source(seed);
  double mean = 0.0;
  for (const ToleranceLink& l : links) mean += l.sensitivity * l.mean;
  std::vector<double> out(count);
  for (double& y : out) {
    // Sum the deviations from the means first: the digits of the variation are kept.
    double deviation = 0.0;
    for (const ToleranceLink& l : links) deviation += l.sensitivity * l.half_range * source.unit(l.distribution);
    y = mean + deviation;
  }
  return out;
}

std::vector<double> sample_play_stack(const PlayStack& stack, std::size_t count, std::uint64_t seed) {
  VariateSource source(seed);
  std::vector<double> term_means;
  for (const WeightedTerm& t : stack.terms) term_means.push_back(t.term.mean());
  std::vector<double> out(count);
  for (double& y : out) {
    double play = std::max(0.0, stack.own_mean + stack.own_sigma * source.standard_normal());
    for (std::size_t k = 0; k < stack.terms.size(); ++k) {
      double deviation = 0.0;
      for (const ToleranceLink& l : stack.terms[k].term.links)
        deviation += l.sensitivity * l.half_range * source.unit(l.distribution);
      play += stack.terms[k].weight * std::max(0.0, term_means[k] + deviation);
    }
    y = play;
  }
  return out;
}

}  // namespace mechgraph::backlash
