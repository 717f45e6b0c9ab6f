#pragma once
// The node types of the backlash plugin, and the few things their descriptions share.
#include <mechgraph/node.hpp>
#include <mechgraph/printf_number.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <thread>

namespace mechgraph::backlash {

std::shared_ptr<const NodeType> make_stack_linear_type();
std::shared_ptr<const NodeType> make_backlash_chain_type();
std::shared_ptr<const NodeType> make_two_axis_type();

/// Effect names this plugin implements.
inline constexpr const char* monte_carlo_effect = "monte_carlo";
inline constexpr const char* compliance_effect = "compliance";

inline constexpr double max_samples = 1e7;  // 80 MB of doubles: the samples are kept for the quantiles

/// The Monte Carlo knobs every stacking node offers.
inline ParamSpec samples_param() {
  return ParamSpec::integer("samples", "Monte Carlo sample count N (with monte_carlo); the standard error of the mean "
                                       "falls as 1/sqrt(N)")
      .with_default(100000.0)
      .at_least(100)
      .at_most(max_samples)
      .because("100 to 1e7: fewer give no tail quantile; the samples are kept for the quantiles (1e7 is 80 MB)")
      .as_knob();
}
inline ParamSpec seed_param() {
  return ParamSpec::integer("seed", "Monte Carlo seed of the xoshiro256++ engine (with monte_carlo): the same seed gives "
                                    "the same numbers on every platform and for any number of threads")
      .with_default(1.0)
      .non_negative()
      .at_most(9007199254740992.0)
      .because("0 to 2^53: a whole number a double holds exactly");
}

/// Threads the Monte Carlo samples may be drawn on. The node contract gives a node no share of
/// the host's threads, so the scene decides; 1 by default (a sweep already runs a case per core).
inline constexpr double max_threads = 256;
inline ParamSpec threads_param() {
  return ParamSpec::integer("threads", "threads that draw the Monte Carlo samples (with monte_carlo), 0: one per core; "
                                       "the results are the same bit for bit for any number")
      .with_default(1.0)
      .non_negative()
      .at_most(max_threads)
      .because("0 (all cores) to 256 worker threads");
}

/// A number as text for messages, with up to six significant digits.
inline std::string number_text(double x) { return printf_g(x, 6); }

/// A length as text for messages, in mm with four significant digits.
inline std::string mm_text(double metres) { return printf_g(metres * 1e3, 4) + " mm"; }

/// Reads and re-checks the Monte Carlo knobs (a node may be called without the scene's checks).
inline std::size_t read_samples(const ParamSet& p) {
  const double n = p.number("samples");
  if (!(n >= 100.0 && n <= max_samples) || n != std::floor(n))
    throw NodeError("samples", "samples must be a whole number from 100 to 10000000, got " + number_text(n));
  return static_cast<std::size_t>(n);
}
inline std::uint64_t read_seed(const ParamSet& p) {
  const double s = p.number("seed");
  if (!(s >= 0.0 && s <= 9007199254740992.0) || s != std::floor(s))
    throw NodeError("seed", "seed must be a whole number from 0 to 2^53, got " + number_text(s));
  return static_cast<std::uint64_t>(s);
}

inline unsigned read_threads(const ParamSet& p) {
  const double t = p.number("threads");
  if (!(t >= 0.0 && t <= max_threads) || t != std::floor(t))
    throw NodeError("threads", "threads must be a whole number from 0 to 256, got " + number_text(t));
  if (t == 0.0) return std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(t);
}

/// How a Monte Carlo result was made, for the results' notes: "Monte Carlo: 1000000 samples,
/// seed 1, standard error of the mean 0.00011 mm".
inline std::string monte_carlo_note(std::size_t samples, std::uint64_t seed, double mean_error) {
  return "Monte Carlo: " + std::to_string(samples) + " samples, seed " + std::to_string(seed) +
         ", standard error of the mean " + printf_g(mean_error * 1e3, 3) + " mm";
}

}  // namespace mechgraph::backlash
