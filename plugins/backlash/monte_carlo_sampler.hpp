#pragma once
// The fused Monte Carlo sampler of the stacks (docs/methods/backlash.md, "Monte Carlo sampler").
//
// A stack, linear or of free play, is compiled to one form:
//   y = constant + sum_k w_k c_k(m_k + sigma_k Z_k + sum_u a_u U_u + sum_t b_t T_t),
// Z standard normal (a term's normal links drawn as one normal of their combined variance, exact
// in distribution), U uniform on [-1, 1), T triangular Tri(-1, 0, 1), c_k = max(0, .) for a play
// term (clipped at zero: interference gives no play) and the identity for a linear stack.
//
// Samples are drawn eight at a time (lane_variates.hpp): for each group of eight, every term's
// variates, the clip, the weight and the sum stay in registers, and the summaries (shifted sums,
// extremes, counts beyond limits, the tails beyond two thresholds, the histogram) take the eight
// results at once; no array of intermediate values is made.
//
// The samples are cut into chunks of `chunk_samples`. Chunk c draws from the seed's engine
// advanced by c jumps (c 2^128 steps), its lane j that advanced by j long jumps more, so a chunk's
// samples depend on the seed and c only. Chunks may run on several threads in any order: the
// floating-point sums are kept per chunk and added in chunk order, everything else is exact
// (counts, extremes, the set of tail values), so the result is the same bit for bit for any thread
// count.
#include "stacking.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mechgraph::backlash {

/// One term of the compiled form: w c(m + sigma Z + sum a U + sum b T).
struct SampledTerm {
  double mean = 0.0;
  double normal_sigma = 0.0;      // 0: no normal link
  std::vector<double> uniform;    // a = s h of each uniform link
  std::vector<double> triangular; // b = s h of each triangular link
  double weight = 1.0;
  bool clipped = false;
};

/// A stack in the compiled form; terms without any spread are folded into `constant`.
struct SampledStack {
  double constant = 0.0;
  std::vector<SampledTerm> terms;
};

SampledStack sampled_stack(const std::vector<ToleranceLink>& links);
SampledStack sampled_stack(const PlayStack& stack);

/// Samples per chunk (a multiple of the eight lanes); also the pilot that sets a streamed run's
/// thresholds and histogram bins.
inline constexpr std::size_t chunk_samples = 65536;

/// What a run did, for the work counters and notes.
struct SamplerWork {
  std::size_t samples = 0;  // drawn, the pilot and any repeated pass included
  std::size_t chunks = 0;   // chunks of the final pass
  unsigned threads = 1;     // threads that drew them
  std::size_t passes = 0;   // passes over the samples (1, or more when a tail was too thin)
};

/// The first `count` samples of the seed's sequence, in order; threads share the chunks.
std::vector<double> draw_samples(const SampledStack& stack, std::size_t count, std::uint64_t seed, unsigned threads = 1,
                                 SamplerWork* work = nullptr);

/// The summary of the first `count` samples: summarize() of draw_samples() for up to two chunks;
/// beyond, streamed (moments by sums about the pilot's mean, the 3-sigma quantiles selected among
/// the samples beyond the pilot's quantiles at 4 Phi(-3) and 1 - 4 Phi(-3), the histogram over
/// the pilot's range widened by a quarter each side), equal to summarize() of the kept samples in
/// the quantiles, extremes and counts, and to rounding in the moments. `threads` >= 1.
SampleSummary monte_carlo(const SampledStack& stack, std::size_t count, std::uint64_t seed, const SampleLimits& limits,
                          std::size_t bins, unsigned threads = 1, SamplerWork* work = nullptr);

}  // namespace mechgraph::backlash
