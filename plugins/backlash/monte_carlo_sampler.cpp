#include "monte_carlo_sampler.hpp"

#include "lane_variates.hpp"

#include <mechgraph/worker_threads.hpp>

#include <algorithm>
#include <bit>
#include <atomic>
#include <cmath>
#include <cstring>
#include <exception>
#include <optional>
#include <stdexcept>
#include <thread>

// The two kernels are compiled for AVX-512 besides the baseline, and the AVX-512 one is chosen
// when the plugin loads on a processor that has it (GCC's function multiversioning). The sources
// are the same and this file is built with -ffp-contract=off, so both round alike and give the
// same bits. The eight lanes fill one AVX-512 register. Without AVX-512, GCC 12 keeps an
// eight-lane vector in memory and works on it piecewise: with SSE2 in pieces of its own size (the
// baseline: 0.28 s of CPU for the steering chain's 10^7 samples against 0.15 s), with AVX2 by
// reassembling 128-bit pieces through the stack (0.60 s), so there is no AVX2 version. A kernel
// written on packs of the target's own width would lift both; not done yet.
// Not under ThreadSanitizer: the dispatching resolver runs while the dynamic loader relocates the
// program, before TSan's runtime is set up, and its instrumented code crashes there.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_THREAD__)
#define MECHGRAPH_LANE_KERNEL __attribute__((target_clones("avx512f", "default")))
#else
#define MECHGRAPH_LANE_KERNEL
#endif

#pragma GCC diagnostic ignored "-Wpsabi"  // 64-byte vectors stay inside inlined code (lane_variates.hpp)

namespace mechgraph::backlash {
namespace {

// A sum s_j X_j as one term: its mean, its normal links as one normal of the combined variance,
// sigma = sqrt(sum (s_j h_j / 3)^2) (summed scaled by the largest |s_j h_j|: no overflow when
// squared), each uniform or triangular link its own a = s_j h_j.
SampledTerm term_of(const std::vector<ToleranceLink>& links, double weight, bool clipped) {
  SampledTerm t;
  t.weight = weight;
  t.clipped = clipped;
  double variance = 0.0, scale = 0.0;
  for (const ToleranceLink& l : links) scale = std::max(scale, std::abs(l.sensitivity * l.half_range));
  for (const ToleranceLink& l : links) {
    t.mean += l.sensitivity * l.mean;
    const double c = l.sensitivity * l.half_range;
    if (c == 0.0) continue;  // no spread
    switch (l.distribution) {
      case Distribution::normal: {
        const double r = c / (3.0 * scale);
        variance += r * r;
        break;
      }
      case Distribution::uniform: t.uniform.push_back(c); break;
      case Distribution::triangular: t.triangular.push_back(c); break;
    }
  }
  t.normal_sigma = scale * std::sqrt(variance);
  return t;
}

bool has_spread(const SampledTerm& t) { return t.normal_sigma > 0.0 || !t.uniform.empty() || !t.triangular.empty(); }

void add_term(SampledStack& s, SampledTerm t) {
  if (has_spread(t)) {
    s.terms.push_back(std::move(t));
  } else {
    s.constant += t.weight * (t.clipped ? std::max(0.0, t.mean) : t.mean);
  }
}

// ---- The kernel: a chunk's samples, eight at a time, into a sink. -------------------------------

// max(0, x) by the bits: a negative x (sign bit set) masked to +0. Vector comparisons and selects
// are avoided here and below: without AVX-512 they are taken lane by lane; shifts, ands and
// subtractions of 64-bit lanes are not.
[[gnu::always_inline]] inline LaneDoubles clip_at_zero(const LaneDoubles& x) {
  const LaneBits b = std::bit_cast<LaneBits>(x);
  return std::bit_cast<LaneDoubles>(b & ((b >> 63) - 1u));
}
// 1 in the lanes where a - b < 0 (a < b), 0 elsewhere: the sign of the difference, which is exact.
[[gnu::always_inline]] inline LaneBits less(const LaneDoubles& a, const LaneDoubles& b) {
  return std::bit_cast<LaneBits>(a - b) >> 63;
}

// Draws n samples of chunk `start` (n <= chunk_samples) and gives them to sink.take(y, m), eight
// at a time (m < 8 for the last group only: its other lanes are drawn and dropped). For each group
// the normal terms' candidates come first, then the slow path for the lanes that missed a core
// (one test for all of them: about one group in four here), then the terms are summed.
template <class Sink>
[[gnu::always_inline]] inline void draw_chunk(const SampledStack& s, const Xoshiro256& start, std::size_t n, Sink& sink) {
  LaneVariates v(start);
  std::size_t normal_terms = 0;
  for (const SampledTerm& t : s.terms) normal_terms += t.normal_sigma > 0.0 ? 1 : 0;
  // The candidates, their draws and whether they missed, one vector per normal term, 64-byte
  // aligned in plain storage (a std::vector of vector types would not honour their alignment).
  std::vector<std::uint64_t> storage(3 * lanes * normal_terms + lanes);
  auto* base = reinterpret_cast<std::uint64_t*>((reinterpret_cast<std::uintptr_t>(storage.data()) + 63) & ~std::uintptr_t{63});
  auto* z = reinterpret_cast<LaneDoubles*>(base);
  auto* bits = reinterpret_cast<LaneBits*>(base + lanes * normal_terms);
  auto* missed = reinterpret_cast<LaneMask*>(base + 2 * lanes * normal_terms);
  const LaneDoubles constant = splat(s.constant);
  for (std::size_t done = 0; done < n; done += lanes) {
    LaneMask missed_any{};
    for (std::size_t k = 0; k < normal_terms; ++k) {
      z[k] = v.normal_candidates(bits[k], missed[k]);
      missed_any |= missed[k];
    }
    if (any(missed_any)) [[unlikely]] v.fix_normals(z, bits, missed, missed_any, normal_terms);
    LaneDoubles y = constant;
    std::size_t k = 0;
    for (const SampledTerm& t : s.terms) {
      LaneDoubles d{};
      if (t.normal_sigma > 0.0) d = t.normal_sigma * z[k++];
      for (const double a : t.uniform) d += a * v.uniforms();
      for (const double b : t.triangular) d += b * v.triangulars();
      LaneDoubles x = t.mean + d;
      if (t.clipped) x = clip_at_zero(x);
      y += t.weight * x;
    }
    sink.take(y, std::min<std::size_t>(lanes, n - done));
  }
}

struct StoreSink {
  double* out;
  [[gnu::always_inline]] void take(const LaneDoubles& y, std::size_t m) {
    std::memcpy(out, &y, m * sizeof(double));
    out += m;
  }
};

// The summary of a streamed run as far as one worker got: exact quantities only (counts, tail
// values, histogram counts), so that the workers' tallies combine in any order. The extremes are
// the tails' (a tail that holds its quantile's ranks holds rank 0, or N - 1).
struct Tally {
  std::size_t below = 0, above = 0;          // beyond the limits
  std::vector<double> low_tail, high_tail;   // the samples strictly beyond the thresholds
  std::size_t low_ties = 0, high_ties = 0;   // the samples equal to them
  Histogram histogram;                       // empty when none is wanted
};

// What every chunk of a pass shares: the shift of the sums, the tail thresholds, the limits.
struct PassSettings {
  double shift = 0.0;
  double t_low = 0.0, t_high = 0.0;
  SampleLimits limits;
};

// A chunk's floating-point sums about the shift, added in chunk order afterwards.
struct ChunkSums {
  double sum = 0.0;
  double squares = 0.0;
};

class TallySink {
 public:
  TallySink(const PassSettings& p, Tally& t)
      : p_(p), t_(t), shift_(splat(p.shift)), t_low_(splat(p.t_low)), t_high_(splat(p.t_high)),
        lower_(splat(p.limits.lower)), upper_(splat(p.limits.upper)) {}

  [[gnu::always_inline]] void take(const LaneDoubles& y, std::size_t m) {
    if (m < static_cast<std::size_t>(lanes)) [[unlikely]] {
      take_some(y, m);
      return;
    }
    const LaneDoubles d = y - shift_;
    sum_ += d;
    squares_ += d * d;
    below_ += less(y, lower_);  // y < lower (an infinite limit: never)
    above_ += less(upper_, y);
    // y <= t_low or y >= t_high in some lane: not both t_low - y and y - t_high negative.
    const LaneBits inside = std::bit_cast<LaneBits>(t_low_ - y) & std::bit_cast<LaneBits>(y - t_high_);
    if (any(std::bit_cast<LaneMask>(~inside >> 63))) [[unlikely]]
      for (int j = 0; j < lanes; ++j) keep_tail(y[j]);
    if (!t_.histogram.empty())
      for (int j = 0; j < lanes; ++j) t_.histogram.add(y[j]);
  }

  // The chunk's sums (its lanes added in lane order), the counts into the tally.
  ChunkSums finish() {
    ChunkSums c;
    for (int j = 0; j < lanes; ++j) {
      c.sum += sum_[j];
      c.squares += squares_[j];
      t_.below += below_[j];
      t_.above += above_[j];
    }
    return c;
  }

 private:
  void take_some(const LaneDoubles& y, std::size_t m) {
    for (std::size_t j = 0; j < m; ++j) {
      const double x = y[j], d = x - p_.shift;
      sum_[j] += d;
      squares_[j] += d * d;
      below_[j] += x < p_.limits.lower;
      above_[j] += x > p_.limits.upper;
      keep_tail(x);
      if (!t_.histogram.empty()) t_.histogram.add(x);
    }
  }
  void keep_tail(double x) {
    if (x < p_.t_low) t_.low_tail.push_back(x);
    else if (x == p_.t_low) ++t_.low_ties;
    if (x > p_.t_high) t_.high_tail.push_back(x);
    else if (x == p_.t_high) ++t_.high_ties;
  }

  const PassSettings& p_;
  Tally& t_;
  const LaneDoubles shift_, t_low_, t_high_, lower_, upper_;
  LaneDoubles sum_{}, squares_{};
  LaneBits below_{}, above_{};
};

MECHGRAPH_LANE_KERNEL
void fill_chunk(const SampledStack& s, const Xoshiro256& start, std::size_t n, double* out) {
  StoreSink sink{out};
  draw_chunk(s, start, n, sink);
}

MECHGRAPH_LANE_KERNEL
ChunkSums tally_chunk(const SampledStack& s, const Xoshiro256& start, std::size_t n, const PassSettings& p, Tally& t) {
  TallySink sink(p, t);
  draw_chunk(s, start, n, sink);
  return sink.finish();
}

// ---- Chunks and threads. ------------------------------------------------------------------------

std::size_t chunks_of(std::size_t count) { return (count + chunk_samples - 1) / chunk_samples; }
std::size_t samples_in(std::size_t chunk, std::size_t count) {
  return std::min(chunk_samples, count - chunk * chunk_samples);
}

// Where each chunk's stream starts: the seed's engine advanced by c jumps.
std::vector<Xoshiro256> chunk_starts(std::uint64_t seed, std::size_t chunks) {
  std::vector<Xoshiro256> starts;
  starts.reserve(chunks);
  Xoshiro256 engine(seed);
  for (std::size_t c = 0; c < chunks; ++c) {
    starts.push_back(engine);
    if (c + 1 < chunks) engine.jump();
  }
  return starts;
}

// Runs work(chunk, worker) for every chunk on `threads` workers (the calling thread one of them),
// each taking the next chunk not yet taken. The first exception thrown is rethrown here.
template <class Work>
void for_each_chunk(std::size_t chunks, unsigned threads, const Work& work) {
  threads = static_cast<unsigned>(std::clamp<std::size_t>(threads, 1, std::max<std::size_t>(chunks, 1)));
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::atomic<bool> failed{false};
  auto worker = [&](unsigned w) {
    try {
      for (std::size_t c = next++; c < chunks && !failed; c = next++) work(c, w);
    } catch (...) {
      if (!failed.exchange(true)) failure = std::current_exception();
    }
  };
  // Chunks are taken from a shared counter, so workers that cannot start (a process or memory
  // limit) leave theirs to the others; the samples do not depend on which worker drew them.
  run_on_workers(threads, worker);
  if (failure) std::rethrow_exception(failure);
}

unsigned workers_for(std::size_t chunks, unsigned threads) {
  return static_cast<unsigned>(std::clamp<std::size_t>(threads, 1, std::max<std::size_t>(chunks, 1)));
}

// ---- The streamed summary. ----------------------------------------------------------------------

// The samples beyond a threshold: those strictly beyond kept, those equal to it counted. For the
// lower tail they hold the ranks 0 .. beyond + ties - 1 (ascending); for the upper tail the top ones.
struct Tail {
  std::vector<double> beyond;
  std::size_t ties = 0;
  double threshold = 0.0;
  bool upper = false;

  // The order statistic of rank r (0-based, ascending) of all `count` samples, when the tail holds it.
  std::optional<double> at_rank(std::size_t r, std::size_t count) {
    const std::size_t held = beyond.size() + ties;
    if (!upper) {
      if (r < beyond.size()) return select(r);
      if (r < held) return threshold;
      return std::nullopt;
    }
    const std::size_t first_beyond = count - beyond.size();
    if (r >= first_beyond) return select(r - first_beyond);
    if (r + held >= count) return threshold;
    return std::nullopt;
  }
  double select(std::size_t k) {
    std::nth_element(beyond.begin(), beyond.begin() + static_cast<std::ptrdiff_t>(k), beyond.end());
    return beyond[k];
  }
};

// Quantile p as quantile_of_sorted gives it (type 7) from a tail, or nothing when the tail is too thin.
std::optional<double> tail_quantile(Tail& tail, std::size_t count, double p) {
  const double h = static_cast<double>(count - 1) * p;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::optional<double> a = tail.at_rank(lo, count);
  if (!a) return std::nullopt;
  if (lo + 1 >= count) return a;
  const std::optional<double> b = tail.at_rank(lo + 1, count);
  if (!b) return std::nullopt;
  return *a + (h - static_cast<double>(lo)) * (*b - *a);
}

// One pass over all the samples with the given thresholds; nothing when a tail missed its ranks.
std::optional<SampleSummary> stream_pass(const SampledStack& stack, const std::vector<Xoshiro256>& starts, std::size_t count,
                                         const PassSettings& settings, const Histogram& bins_laid, double tail_share,
                                         unsigned threads) {
  const std::size_t chunks = starts.size();
  const unsigned workers = workers_for(chunks, threads);
  std::vector<Tally> tallies(workers);
  // Each worker's tail buffers sized for its share of the expected tail, a fifth more.
  const auto expected = static_cast<std::size_t>(1.2 * tail_share * static_cast<double>(count) / workers) + 64;
  for (Tally& t : tallies) {
    t.low_tail.reserve(expected);
    t.high_tail.reserve(expected);
    t.histogram = bins_laid;
  }
  std::vector<ChunkSums> sums(chunks);
  for_each_chunk(chunks, workers, [&](std::size_t c, unsigned w) {
    sums[c] = tally_chunk(stack, starts[c], samples_in(c, count), settings, tallies[w]);
  });

  // Combine: the sums in chunk order, the exact parts in any order.
  double sum = 0.0, squares = 0.0;
  for (const ChunkSums& c : sums) {
    sum += c.sum;
    squares += c.squares;
  }
  Tally& all = tallies[0];
  for (std::size_t w = 1; w < tallies.size(); ++w) {
    const Tally& t = tallies[w];
    all.below += t.below;
    all.above += t.above;
    all.low_tail.insert(all.low_tail.end(), t.low_tail.begin(), t.low_tail.end());
    all.high_tail.insert(all.high_tail.end(), t.high_tail.begin(), t.high_tail.end());
    all.low_ties += t.low_ties;
    all.high_ties += t.high_ties;
    if (!all.histogram.empty()) {
      for (std::size_t k = 0; k < all.histogram.counts.size(); ++k) all.histogram.counts[k] += t.histogram.counts[k];
      all.histogram.under += t.histogram.under;
      all.histogram.over += t.histogram.over;
    }
  }
  Tail low{std::move(all.low_tail), all.low_ties, settings.t_low, false};
  Tail high{std::move(all.high_tail), all.high_ties, settings.t_high, true};
  const std::optional<double> q_low = tail_quantile(low, count, probability_minus_3_sigma);
  const std::optional<double> q_high = tail_quantile(high, count, probability_plus_3_sigma);
  if (!q_low || !q_high) return std::nullopt;

  const double n = static_cast<double>(count);
  SampleSummary s;
  s.count = count;
  // The extremes: rank 0 and N - 1, held by the tails (their values beyond, else the threshold).
  s.min = *low.at_rank(0, count);
  s.max = *high.at_rank(count - 1, count);
  s.mean = settings.shift + sum / n;
  s.sigma = std::sqrt(std::max(0.0, (squares - sum * sum / n) / (n - 1.0)));
  s.mean_error = s.sigma / std::sqrt(n);
  s.sigma_error = s.sigma / std::sqrt(2.0 * (n - 1.0));
  s.below = all.below;
  s.above = all.above;
  s.q_low = *q_low;
  s.q_high = *q_high;
  if (!all.histogram.empty()) {
    all.histogram.trim();
    s.histogram = std::move(all.histogram);
  }
  return s;
}

}  // namespace

SampledStack sampled_stack(const std::vector<ToleranceLink>& links) {
  SampledStack s;
  add_term(s, term_of(links, 1.0, false));
  return s;
}

SampledStack sampled_stack(const PlayStack& stack) {
  SampledStack s;
  SampledTerm own;
  own.mean = stack.own_mean;
  own.normal_sigma = stack.own_sigma;
  own.clipped = true;
  add_term(s, std::move(own));
  for (const WeightedTerm& t : stack.terms) add_term(s, term_of(t.term.links, t.weight, true));
  return s;
}

std::vector<double> draw_samples(const SampledStack& stack, std::size_t count, std::uint64_t seed, unsigned threads,
                                 SamplerWork* work) {
  std::vector<double> out(count);
  const std::vector<Xoshiro256> starts = chunk_starts(seed, chunks_of(count));
  const unsigned workers = workers_for(starts.size(), threads);
  for_each_chunk(starts.size(), workers, [&](std::size_t c, unsigned) {
    fill_chunk(stack, starts[c], samples_in(c, count), out.data() + c * chunk_samples);
  });
  if (work) {
    work->samples += count;
    work->chunks = starts.size();
    work->threads = workers;
    work->passes += 1;
  }
  return out;
}

SampleSummary monte_carlo(const SampledStack& stack, std::size_t count, std::uint64_t seed, const SampleLimits& limits,
                          std::size_t bins, unsigned threads, SamplerWork* work) {
  if (count < 2) throw std::invalid_argument("Monte Carlo needs at least two samples");
  if (count <= 2 * chunk_samples) return summarize(draw_samples(stack, count, seed, threads, work), limits, bins);

  // The pilot: the first chunk, kept. Its mean is the shift of the sums; its quantiles at
  // 4 Phi(-3) and 1 - 4 Phi(-3) the thresholds beyond which samples are kept for the 3-sigma
  // quantiles (a tail four times the rank it must hold: too thin only by a deviation of many
  // standard errors of the pilot; then the pass is run again with a tail 32 times the rank).
  std::vector<double> pilot(chunk_samples);
  const std::vector<Xoshiro256> starts = chunk_starts(seed, chunks_of(count));
  fill_chunk(stack, starts[0], chunk_samples, pilot.data());
  double pilot_sum = 0.0, pilot_low = pilot[0], pilot_high = pilot[0];
  for (const double x : pilot) {
    pilot_sum += x - pilot[0];
    pilot_low = std::min(pilot_low, x);
    pilot_high = std::max(pilot_high, x);
  }
  // The histogram's bins: `bins` across the pilot's range, as many again as a quarter of them each side.
  Histogram bins_laid;
  if (bins > 0) {
    const Histogram across = histogram_over(pilot_low, pilot_high, bins);
    const std::size_t margin = (bins + 3) / 4;
    bins_laid.width = across.width;
    bins_laid.low = across.low - static_cast<double>(margin) * across.width;
    bins_laid.counts.assign(across.counts.size() + 2 * margin, 0);
    bins_laid.top = bins_laid.low + static_cast<double>(bins_laid.counts.size()) * across.width;
  }
  PassSettings settings;
  settings.shift = pilot[0] + pilot_sum / static_cast<double>(chunk_samples);
  settings.limits = limits;
  const unsigned workers = workers_for(starts.size(), threads);
  if (work) {
    work->samples += chunk_samples;
    work->chunks = starts.size();
    work->threads = workers;
  }
  for (const double factor : {4.0, 32.0}) {
    const double share = factor * probability_minus_3_sigma;
    settings.t_low = quantile_by_selection(pilot, share);
    settings.t_high = quantile_by_selection(pilot, 1.0 - share);
    std::optional<SampleSummary> s = stream_pass(stack, starts, count, settings, bins_laid, share, workers);
    if (work) {
      work->samples += count;
      work->passes += 1;
    }
    if (s) return std::move(*s);
  }
  // Tails never thin enough to hold the ranks: every sample kept.
  return summarize(draw_samples(stack, count, seed, threads, work), limits, bins);
}

}  // namespace mechgraph::backlash
