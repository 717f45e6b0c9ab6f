#include <mechgraph/uncertainty/study_statistics.hpp>

#include <mechgraph/uncertainty/distribution.hpp>
#include <mechgraph/uncertainty/sample_design.hpp>

#include <boost/math/distributions/beta.hpp>
#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/students_t.hpp>

#include <mechgraph/chunked_work.hpp>
#include <mechgraph/large_arrays.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
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
  m.min = m.max = values.front();
  for (double x : values) {
    m.min = std::min(m.min, x);
    m.max = std::max(m.max, x);
  }
  // Values all equal: that value, no spread (the sums below would leave rounding noise, a mean a
  // few ulps outside [min, max] and a Cp of 1e13 for an output that never moves).
  if (m.min == m.max) {
    m.mean = m.min;
    if (m.n > 1) m.mean_interval = {m.mean, m.mean};
    return m;
  }
  // Two passes over the values divided by a power of two (exact: the same bits as without it) where
  // they are large enough for their sum or their squares to overflow.
  const double largest = std::max(std::abs(m.min), std::abs(m.max));
  const double scale = largest > 0x1p300 ? std::ldexp(1.0, std::ilogb(largest)) : 1.0;
  double sum = 0.0;
  for (double x : values) sum += x / scale;
  const double mean = sum / static_cast<double>(m.n);
  double squares = 0.0;
  for (double x : values) squares += (x / scale - mean) * (x / scale - mean);
  m.mean = std::clamp(mean * scale, m.min, m.max);
  m.standard_deviation = m.n > 1 ? scale * std::sqrt(squares / static_cast<double>(m.n - 1)) : 0.0;
  // The mean's interval: Student's t with n - 1 degrees of freedom (the normal's z would cover 70 %
  // at n = 2 and 81 % at n = 3 where 95 % is asked).
  if (m.n > 1) {
    const boost::math::students_t_distribution<double> t(static_cast<double>(m.n - 1));
    const double half = boost::math::quantile(t, 0.5 + 0.5 * confidence) * m.standard_deviation / std::sqrt(static_cast<double>(m.n));
    m.mean_interval = {m.mean - half, m.mean + half};
  }
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
  // At no event or all, the end is 0 or 1 exactly (centre - half leaves a rounding residue, 5.6e-17).
  if (events == 0) p.wilson.lower = 0.0;
  if (events == trials) p.wilson.upper = 1.0;
  // Clopper-Pearson: beta quantiles B(a/2; k, n-k+1) and B(1-a/2; k+1, n-k).
  const double alpha = 1 - confidence;
  p.clopper_pearson.lower = events == 0 ? 0.0 : boost::math::ibeta_inv(k, n - k + 1, alpha / 2);
  p.clopper_pearson.upper = events == trials ? 1.0 : boost::math::ibeta_inv(k + 1, n - k, 1 - alpha / 2);
  return p;
}

Capability capability(const std::vector<double>& values, const Moments& m, std::optional<double> lower,
                      std::optional<double> upper, double confidence, std::size_t failed) {
  Capability c;
  for (double x : values) {
    if (lower && x < *lower) ++c.below;
    if (upper && x > *upper) ++c.above;
  }
  c.out_of_spec = proportion(c.below + c.above, values.size(), confidence);
  c.failed = failed;
  c.out_of_spec_or_failed = proportion(c.below + c.above + failed, values.size() + failed, confidence);
  const double s = m.standard_deviation;
  if (!(s > 0)) {
    // No spread: the normal model is a point at the mean, all in spec or all out (Cp and Cpk, a
    // width over 0, stay absent).
    c.ppm_normal = (lower && m.mean < *lower) || (upper && m.mean > *upper) ? 1e6 : 0.0;
    return c;
  }
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

// A spread within rounding of none: the pooled f(A), f(B) all equal, their variance a residue of
// the sums rather than 0. There the indices are 0 / 0: undefined. The values are centred on the
// mean of all outputs, so a varying output's variance is of the order of its mean square; the
// residue is about n eps of it in the resamples' one-pass sums (sum w (a^2 + b^2) - 2N mean^2), far
// less in the point estimate's two passes: `tolerance` is the share of the mean square below which
// a variance is such a residue.
bool no_spread(double variance, double mean_square, double tolerance) { return !(variance > tolerance * mean_square); }
constexpr double two_pass_residue = 1e-24, one_pass_residue = 1e-10;

// The outputs of each base sample side by side, centred: f(A), f(B), f(AB^1) ... f(AB^d) in one
// row, so that a resample reads one short contiguous row per draw instead of d + 2 scattered values.
struct SobolRows {
  std::size_t width;  // d + 2
  std::vector<double> values;
  const double* row(std::size_t i) const { return values.data() + i * width; }
};

// The estimators over the base samples `pick` (indices into the rows): two passes over the picks,
// the mean first, then the variance and every index's sums (each sum in the order of the picks).
SobolEstimate estimate(const SobolRows& rows, const std::vector<std::size_t>& pick, std::vector<double>& first,
                       std::vector<double>& total) {
  const double n = static_cast<double>(pick.size());
  const std::size_t d = rows.width - 2;
  double sum = 0.0;
  for (std::size_t i : pick) {
    const double* r = rows.row(i);
    sum += r[0] + r[1];
  }
  const double mean = sum / (2 * n);
  double squares = 0.0, raw_squares = 0.0;
  std::fill(first.begin(), first.end(), 0.0);
  std::fill(total.begin(), total.end(), 0.0);
  for (std::size_t i : pick) {
    const double* r = rows.row(i);
    const double a = r[0], b = r[1];
    squares += (a - mean) * (a - mean) + (b - mean) * (b - mean);
    raw_squares += a * a + b * b;
    for (std::size_t j = 0; j < d; ++j) {
      const double ab = r[2 + j];
      first[j] += b * (ab - a);
      total[j] += (a - ab) * (a - ab);
    }
  }
  SobolEstimate e{squares / (2 * n - 1), std::vector<double>(d), std::vector<double>(d)};
  if (no_spread(e.variance, raw_squares / (2 * n), two_pass_residue)) e.variance = 0.0;
  for (std::size_t j = 0; j < d; ++j) {
    e.first[j] = e.variance > 0 ? first[j] / n / e.variance : 0.0;
    e.total[j] = e.variance > 0 ? total[j] / (2 * n) / e.variance : 0.0;
  }
  return e;
}

// The same estimators over resamples given as the number of times each base sample was drawn
// (`times`, `count` resamples side by side: times[i * resamples_at_once + k] for resample k, each summing to
// N): one pass in the order of the rows, each row weighted by each resample's count, with the
// variance from the weighted sums of squares, sum w (a^2 + b^2) - 2N mean^2 (the rows are centred
// on the mean of all outputs, so the two terms do not cancel). It streams the rows once for
// `count` resamples, where the draws in the order drawn would read a random row each time; each
// resample's sums are the same, term by term and in the same order, as it alone would give.
constexpr std::size_t resamples_at_once = 8;

[[gnu::always_inline]] inline void estimate_drawn_body(const SobolRows& rows, const std::uint32_t* times, std::size_t count,
                                                      SobolEstimate* out) {
  const std::size_t d = rows.width - 2, samples = rows.values.size() / rows.width;
  double n[resamples_at_once] = {}, sum[resamples_at_once] = {}, squares[resamples_at_once] = {};
  std::vector<double> first(d * resamples_at_once, 0.0), total(d * resamples_at_once, 0.0);
  double w[resamples_at_once] = {};
  // Every lane is summed, the unused ones of a last short group with weight 0 (their sums are
  // never read): a loop of a fixed length the compiler unrolls and vectorises, each lane's sums
  // still the same terms in the same order.
  constexpr std::size_t lanes = resamples_at_once;
  for (std::size_t i = 0; i < samples; ++i) {  // no branch on w = 0: its terms add +0, exactly nothing
    for (std::size_t k = 0; k < lanes; ++k) w[k] = static_cast<double>(times[i * lanes + k]);
    const double* r = rows.row(i);
    const double a = r[0], b = r[1], ab_sum = a + b, ab_squares = a * a + b * b;
    for (std::size_t k = 0; k < lanes; ++k) {
      n[k] += w[k];
      sum[k] += w[k] * ab_sum;
      squares[k] += w[k] * ab_squares;
    }
    for (std::size_t j = 0; j < d; ++j) {
      const double ab = r[2 + j], first_term = b * (ab - a), total_term = (a - ab) * (a - ab);
      double* f = first.data() + j * resamples_at_once;
      double* t = total.data() + j * resamples_at_once;
      for (std::size_t k = 0; k < lanes; ++k) {
        f[k] += w[k] * first_term;
        t[k] += w[k] * total_term;
      }
    }
  }
  for (std::size_t k = 0; k < count; ++k) {
    const double mean = sum[k] / (2 * n[k]);
    SobolEstimate& e = out[k];
    e.variance = std::max(0.0, squares[k] - 2 * n[k] * mean * mean) / (2 * n[k] - 1);
    // A resample whose drawn outputs do not vary has no indices (NaN, left out of the interval):
    // counted as 0, they pinned an interval's end at 0 wherever a few base samples carry the spread.
    const bool undefined = no_spread(e.variance, squares[k] / (2 * n[k]), one_pass_residue);
    e.first.assign(d, 0.0);
    e.total.assign(d, 0.0);
    for (std::size_t j = 0; j < d; ++j) {
      e.first[j] = undefined ? std::numeric_limits<double>::quiet_NaN() : first[j * resamples_at_once + k] / n[k] / e.variance;
      e.total[j] = undefined ? std::numeric_limits<double>::quiet_NaN() : total[j * resamples_at_once + k] / (2 * n[k]) / e.variance;
    }
  }
}

// On x86-64 a second version for processors with AVX (four doubles an operation, where SSE2 has
// two), chosen on the first call; AVX has no fused multiply-add, so both round every operation
// alike and give the same bits. Chosen by a test at run time, not by an ifunc (target_clones):
// an ifunc resolver runs while the library is relocated, before a sanitizer's runtime is ready.
#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target("avx"))) void estimate_drawn_avx(const SobolRows& rows, const std::uint32_t* times, std::size_t count,
                                                       SobolEstimate* out) {
  estimate_drawn_body(rows, times, count, out);
}
#endif

void estimate_drawn(const SobolRows& rows, const std::uint32_t* times, std::size_t count, SobolEstimate* out) {
#if defined(__x86_64__) && defined(__GNUC__)
  static const bool avx = __builtin_cpu_supports("avx");
  if (avx) return estimate_drawn_avx(rows, times, count, out);
#endif
  estimate_drawn_body(rows, times, count, out);
}

// The percentile interval of `draws` at `confidence` (type 7 quantiles of the sorted draws), the
// undefined ones (NaN: a resample without spread) left out; none defined, no interval.
Interval percentile(std::vector<double> draws, double confidence) {
  draws.erase(std::remove_if(draws.begin(), draws.end(), [](double x) { return std::isnan(x); }), draws.end());
  if (draws.empty()) return {};
  std::sort(draws.begin(), draws.end());
  const double alpha = 1 - confidence;
  return {quantile(draws, alpha / 2, 0.5).value, quantile(draws, 1 - alpha / 2, 0.5).value};
}

}  // namespace

namespace {

// One output's rows, centred on the mean of all its values, and its point estimate.
struct SobolOutput {
  SobolRows rows;
  SobolEstimate point;
};

SobolOutput prepare(const SobolSamples& f) {
  const std::size_t n = f.f_a.size(), d = f.f_ab.size();
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += f.f_a[i] + f.f_b[i];
    for (const auto& f_j : f.f_ab) sum += f_j[i];
  }
  const double centre = sum / static_cast<double>(n * (2 + d));
  SobolOutput out{{d + 2, {}}, {}};
  reserve_large(out.rows.values, n * (d + 2));
  out.rows.values.resize(n * (d + 2));
  for (std::size_t i = 0; i < n; ++i) {
    double* r = out.rows.values.data() + i * out.rows.width;
    r[0] = f.f_a[i] - centre;
    r[1] = f.f_b[i] - centre;
    for (std::size_t j = 0; j < d; ++j) r[2 + j] = f.f_ab[j][i] - centre;
  }
  std::vector<std::size_t> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = i;
  std::vector<double> first_sums(d), total_sums(d);
  out.point = estimate(out.rows, all, first_sums, total_sums);
  return out;
}

}  // namespace

std::vector<SobolIndices> sobol_indices(const std::vector<const SobolSamples*>& samples, std::size_t bootstrap,
                                        double confidence, std::uint64_t seed, unsigned threads, const std::atomic<bool>* stop) {
  const std::size_t outputs = samples.size();
  std::vector<SobolIndices> result(outputs);
  if (outputs == 0) return result;
  const std::size_t n = samples.front()->f_a.size();
  for (const SobolSamples* f : samples)
    if (f->f_a.size() != n || f->f_b.size() != n || f->f_ab.size() != samples.front()->f_ab.size())
      throw std::invalid_argument("sobol_indices: the outputs do not share their base samples");
  for (SobolIndices& r : result) r.samples = n;
  if (n < 2) return result;
  const std::size_t d = samples.front()->f_ab.size();
  std::vector<SobolOutput> prepared;
  prepared.reserve(outputs);
  for (const SobolSamples* f : samples) prepared.push_back(prepare(*f));
  // Each resample's draws come from the counter generator by (replicate, draw), so replicates run
  // on any number of threads and land in their own slots: the same bits whatever `threads` is.
  // A resample is drawn once and serves every output.
  std::vector<double> first_draws(outputs * d * bootstrap), total_draws(outputs * d * bootstrap);
  const auto slot = [&](std::size_t o, std::size_t j, std::size_t r) { return (o * d + j) * bootstrap + r; };
  // Resamples in groups drawn side by side: one pass over each output's rows serves a group.
  struct Worker {
    std::vector<std::uint32_t> times;
    SobolEstimate estimates[resamples_at_once];
  };
  const std::size_t groups = (bootstrap + resamples_at_once - 1) / resamples_at_once;
  run_chunks(groups, threads,
             [&] {
               Worker w{};  // its estimates zero, as they were made before
               reserve_large(w.times, n * resamples_at_once);
               w.times.resize(n * resamples_at_once);
               return w;
             },
             [&](Worker& w, std::size_t group) {
               if (stop && stop->load(std::memory_order_relaxed)) return;  // stopped: nothing more is drawn
               const std::size_t first_r = group * resamples_at_once, count = std::min(resamples_at_once, bootstrap - first_r);
               std::fill(w.times.begin(), w.times.end(), 0u);  // lanes past `count` stay 0
               for (std::size_t k = 0; k < count; ++k) {
                 // Draw i of resample r picks base sample floor(u(seed, r, i) N): counted, not listed.
                 const CounterRow draw(seed, stream_bootstrap, first_r + k);
                 for (std::size_t i = 0; i < n; ++i)
                   ++w.times[std::min(static_cast<std::size_t>(draw(i) * static_cast<double>(n)), n - 1) * resamples_at_once + k];
               }
               for (std::size_t o = 0; o < outputs; ++o) {
                 estimate_drawn(prepared[o].rows, w.times.data(), count, w.estimates);
                 for (std::size_t k = 0; k < count; ++k)
                   for (std::size_t j = 0; j < d; ++j) {
                     first_draws[slot(o, j, first_r + k)] = w.estimates[k].first[j];
                     total_draws[slot(o, j, first_r + k)] = w.estimates[k].total[j];
                   }
               }
             });
  if (stop && stop->load(std::memory_order_relaxed)) return result;
  for (std::size_t o = 0; o < outputs; ++o) {
    result[o].variance = prepared[o].point.variance;
    for (std::size_t j = 0; j < d; ++j) {
      SobolIndex s;
      s.first = prepared[o].point.first[j];
      s.total = prepared[o].point.total[j];
      if (bootstrap > 1) {
        const auto draws = [&](const std::vector<double>& all) {
          return std::vector<double>(all.begin() + static_cast<std::ptrdiff_t>(slot(o, j, 0)),
                                     all.begin() + static_cast<std::ptrdiff_t>(slot(o, j, 0) + bootstrap));
        };
        s.first_interval = percentile(draws(first_draws), confidence);
        s.total_interval = percentile(draws(total_draws), confidence);
      }
      result[o].indices.push_back(s);
    }
  }
  return result;
}

SobolIndices sobol_indices(const std::vector<double>& f_a, const std::vector<double>& f_b,
                           const std::vector<std::vector<double>>& f_ab, std::size_t bootstrap, double confidence,
                           std::uint64_t seed, unsigned threads) {
  const SobolSamples samples{f_a, f_b, f_ab};
  return sobol_indices(std::vector<const SobolSamples*>{&samples}, bootstrap, confidence, seed, threads).front();
}

}  // namespace mechgraph
