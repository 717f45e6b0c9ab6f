#include <mechgraph/uncertainty/study_statistics.hpp>

#include <mechgraph/uncertainty/distribution.hpp>
#include <mechgraph/uncertainty/sample_design.hpp>

#include <boost/math/distributions/beta.hpp>
#include <boost/math/distributions/binomial.hpp>

#include <mechgraph/worker_threads.hpp>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <cmath>

namespace mechgraph {
namespace {

double two_sided_z(double confidence) { return standard_normal_quantile(0.5 + 0.5 * confidence); }

constexpr std::uint64_t stream_bootstrap = 11;

}  // namespace

Moments moments(const std::vector<double>& values, double confidence) {
  Moments m;
  m.n = values.size();
  if (values.empty()) return m;
  double sum = 0.0;
  m.min = m.max = values.front();
  for (double x : values) {
    sum += x;
    m.min = std::min(m.min, x);
    m.max = std::max(m.max, x);
  }
  m.mean = sum / static_cast<double>(m.n);
  double squares = 0.0;
  for (double x : values) squares += (x - m.mean) * (x - m.mean);
  m.standard_deviation = m.n > 1 ? std::sqrt(squares / static_cast<double>(m.n - 1)) : 0.0;
  const double half = two_sided_z(confidence) * m.standard_deviation / std::sqrt(static_cast<double>(m.n));
  if (m.n > 1) m.mean_interval = {m.mean - half, m.mean + half};
  return m;
}

QuantileEstimate quantile(const std::vector<double>& sorted, double level, double confidence) {
  QuantileEstimate q;
  q.level = level;
  const std::size_t n = sorted.size();
  if (n == 0) return q;
  // Type 7: h = (n - 1) p, between x_(floor h) and x_(floor h + 1) (0-based).
  const double h = (static_cast<double>(n) - 1.0) * level;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, n - 1);
  q.value = sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
  // Distribution-free interval: K, the number of values below the quantile, is Binomial(n, p),
  // and [x_(l), x_(u)] (1-based ranks) covers it when l <= K < u. With k_lo the largest k with
  // P(K <= k) <= alpha/2 and k_hi the smallest with P(K > k) <= alpha/2, l = k_lo + 1 and
  // u = k_hi + 1 cover it with probability >= 1 - alpha. An end outside the sample is absent.
  const double alpha = 1.0 - confidence;
  using namespace boost::math::policies;
  using down = boost::math::binomial_distribution<double, policy<discrete_quantile<integer_round_down>>>;
  using up = boost::math::binomial_distribution<double, policy<discrete_quantile<integer_round_up>>>;
  const double nn = static_cast<double>(n);
  const double k_lo = boost::math::quantile(down(nn, level), alpha / 2);
  const double k_hi = boost::math::quantile(boost::math::complement(up(nn, level), alpha / 2));
  if (boost::math::cdf(down(nn, level), k_lo) <= alpha / 2) q.interval.lower = sorted[static_cast<std::size_t>(k_lo)];
  if (k_hi < nn && boost::math::cdf(boost::math::complement(up(nn, level), k_hi)) <= alpha / 2)
    q.interval.upper = sorted[static_cast<std::size_t>(k_hi)];
  return q;
}

Histogram histogram(const std::vector<double>& values, std::size_t bins, double low, double high) {
  Histogram h;
  bins = std::max<std::size_t>(bins, 1);
  if (!(high > low)) {
    h.low = low - 0.5;
    h.width = 1.0;
    h.counts.assign(1, values.size());
    return h;
  }
  h.low = low;
  h.width = (high - low) / static_cast<double>(bins);
  h.counts.assign(bins, 0);
  for (double x : values) {
    if (x < low || x > high) continue;
    const auto k = std::min(static_cast<std::size_t>((x - low) / h.width), bins - 1);
    ++h.counts[k];
  }
  return h;
}

Proportion proportion(std::size_t events, std::size_t trials, double confidence) {
  Proportion p;
  p.events = events;
  p.trials = trials;
  if (trials == 0) return p;
  const double n = static_cast<double>(trials), k = static_cast<double>(events);
  p.estimate = k / n;
  // Wilson score interval: (p + z^2/2n -+ z sqrt(p(1-p)/n + z^2/4n^2)) / (1 + z^2/n).
  const double z = two_sided_z(confidence), z2 = z * z;
  const double centre = (p.estimate + z2 / (2 * n)) / (1 + z2 / n);
  const double half = z * std::sqrt(p.estimate * (1 - p.estimate) / n + z2 / (4 * n * n)) / (1 + z2 / n);
  p.wilson = {std::max(0.0, centre - half), std::min(1.0, centre + half)};
  // Clopper-Pearson: beta quantiles B(a/2; k, n-k+1) and B(1-a/2; k+1, n-k).
  const double alpha = 1 - confidence;
  p.clopper_pearson.lower = events == 0 ? 0.0 : boost::math::ibeta_inv(k, n - k + 1, alpha / 2);
  p.clopper_pearson.upper = events == trials ? 1.0 : boost::math::ibeta_inv(k + 1, n - k, 1 - alpha / 2);
  return p;
}

Capability capability(const std::vector<double>& values, const Moments& m, std::optional<double> lower,
                      std::optional<double> upper, double confidence) {
  Capability c;
  for (double x : values) {
    if (lower && x < *lower) ++c.below;
    if (upper && x > *upper) ++c.above;
  }
  c.out_of_spec = proportion(c.below + c.above, values.size(), confidence);
  const double s = m.standard_deviation;
  if (!(s > 0)) return c;
  // Cp = (USL - LSL) / 6 sigma; Cpk = min(USL - mean, mean - LSL) / 3 sigma (one side when one limit).
  if (lower && upper) c.cp = (*upper - *lower) / (6 * s);
  std::optional<double> cpl, cpu;
  if (lower) cpl = (m.mean - *lower) / (3 * s);
  if (upper) cpu = (*upper - m.mean) / (3 * s);
  c.cpk = cpl && cpu ? std::min(*cpl, *cpu) : (cpl ? *cpl : *cpu);
  c.ppm_normal = 1e6 * ((cpl ? standard_normal_cdf(-3 * *cpl) : 0.0) + (cpu ? standard_normal_cdf(-3 * *cpu) : 0.0));
  return c;
}

namespace {

struct SobolEstimate {
  double variance;
  std::vector<double> first, total;
};

// The estimators over the base samples `pick` (indices into the arrays), outputs centred by `centre`.
SobolEstimate estimate(const std::vector<double>& f_a, const std::vector<double>& f_b, const std::vector<std::vector<double>>& f_ab,
                       const std::vector<std::size_t>& pick, double centre) {
  const double n = static_cast<double>(pick.size());
  double sum = 0.0;
  for (std::size_t i : pick) sum += (f_a[i] - centre) + (f_b[i] - centre);
  const double mean = sum / (2 * n);
  double squares = 0.0;
  for (std::size_t i : pick) squares += (f_a[i] - centre - mean) * (f_a[i] - centre - mean) + (f_b[i] - centre - mean) * (f_b[i] - centre - mean);
  SobolEstimate e{squares / (2 * n - 1), {}, {}};
  for (const std::vector<double>& f_j : f_ab) {
    double first = 0.0, total = 0.0;
    for (std::size_t i : pick) {
      const double a = f_a[i] - centre, b = f_b[i] - centre, ab = f_j[i] - centre;
      first += b * (ab - a);
      total += (a - ab) * (a - ab);
    }
    e.first.push_back(e.variance > 0 ? first / n / e.variance : 0.0);
    e.total.push_back(e.variance > 0 ? total / (2 * n) / e.variance : 0.0);
  }
  return e;
}

// The percentile interval of `draws` at `confidence` (type 7 quantiles of the sorted draws).
Interval percentile(std::vector<double> draws, double confidence) {
  if (draws.empty()) return {};
  std::sort(draws.begin(), draws.end());
  const double alpha = 1 - confidence;
  return {quantile(draws, alpha / 2, 0.5).value, quantile(draws, 1 - alpha / 2, 0.5).value};
}

}  // namespace

SobolIndices sobol_indices(const std::vector<double>& f_a, const std::vector<double>& f_b,
                           const std::vector<std::vector<double>>& f_ab, std::size_t bootstrap, double confidence,
                           std::uint64_t seed, unsigned threads) {
  SobolIndices out;
  const std::size_t n = f_a.size();
  out.samples = n;
  if (n < 2) return out;
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += f_a[i] + f_b[i];
    for (const auto& f_j : f_ab) sum += f_j[i];
  }
  const double centre = sum / static_cast<double>(n * (2 + f_ab.size()));
  std::vector<std::size_t> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = i;
  const SobolEstimate point = estimate(f_a, f_b, f_ab, all, centre);
  out.variance = point.variance;
  const std::size_t d = f_ab.size();
  // Each resample's draws come from the counter generator by (replicate, draw), so replicates run
  // on any number of threads and land in their own slots: the same bits whatever `threads` is.
  std::vector<std::vector<double>> first_draws(d, std::vector<double>(bootstrap)), total_draws(d, std::vector<double>(bootstrap));
  std::atomic<std::size_t> next{0};
  std::mutex failure_mutex;
  std::exception_ptr failure;
  run_on_workers(static_cast<unsigned>(std::max<std::size_t>(1, std::min<std::size_t>(threads, bootstrap))), [&](unsigned) {
    try {
      std::vector<std::size_t> pick(n);
      for (std::size_t r; (r = next.fetch_add(1)) < bootstrap;) {
        for (std::size_t i = 0; i < n; ++i)
          pick[i] = std::min(static_cast<std::size_t>(counter_uniform(seed, stream_bootstrap, r, i) * static_cast<double>(n)), n - 1);
        const SobolEstimate e = estimate(f_a, f_b, f_ab, pick, centre);
        for (std::size_t j = 0; j < d; ++j) {
          first_draws[j][r] = e.first[j];
          total_draws[j][r] = e.total[j];
        }
      }
    } catch (...) {
      std::lock_guard lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      next = bootstrap;
    }
  });
  if (failure) std::rethrow_exception(failure);
  for (std::size_t j = 0; j < d; ++j) {
    SobolIndex s;
    s.first = point.first[j];
    s.total = point.total[j];
    if (bootstrap > 1) {
      s.first_interval = percentile(first_draws[j], confidence);
      s.total_interval = percentile(total_draws[j], confidence);
    }
    out.indices.push_back(s);
  }
  return out;
}

}  // namespace mechgraph
