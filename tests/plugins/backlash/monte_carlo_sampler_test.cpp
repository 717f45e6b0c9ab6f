// The fused Monte Carlo sampler (plugins/backlash/monte_carlo_sampler.hpp, lane_variates.hpp):
// the engine's jumps against the GF(2) matrix power of its update (second method); the ziggurat's
// table against the closed form of its strip area; the lanes' variates equal to the scalar
// algorithm's on each lane's engine, and distributed as they should (Kolmogorov-Smirnov, the
// tails' probabilities); results the same bit for bit on 1, 2 and 3 threads; the streamed summary
// equal to the kept samples' where the tails are a point mass; the chain's mean and sigma against
// the closed form of clipped normals.
#include "backlash/lane_variates.hpp"
#include "backlash/node_types.hpp"
#include "backlash/monte_carlo_sampler.hpp"
#include "backlash/stacking.hpp"
#include "backlash/variates.hpp"
#include "test_support.hpp"

#include <mechgraph/errors.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

using namespace mechgraph;
using namespace mechgraph::backlash;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

// The lanes are 64-byte vectors returned from inlined functions only (see lane_variates.hpp).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace {

// ---- GF(2) linear algebra of the engine's state update -------------------------------------------

using Bits256 = std::array<std::uint64_t, 4>;
using Matrix256 = std::array<Bits256, 256>;  // column i: the image of unit vector i

Bits256 step_state(const Bits256& s) {  // the state update alone (the output is not linear)
  Xoshiro256 e = Xoshiro256::from_state(s);
  e();
  return e.state();
}

Bits256 apply(const Matrix256& m, const Bits256& v) {
  Bits256 r{};
  for (int i = 0; i < 256; ++i)
    if ((v[i / 64] >> (i % 64)) & 1u)
      for (int w = 0; w < 4; ++w) r[w] ^= m[i][w];
  return r;
}

Matrix256 multiply(const Matrix256& a, const Matrix256& b) {  // a b: b first
  Matrix256 r{};
  for (int j = 0; j < 256; ++j) r[j] = apply(a, b[j]);
  return r;
}

Matrix256 update_matrix() {
  Matrix256 t{};
  for (int i = 0; i < 256; ++i) {
    Bits256 unit{};
    unit[i / 64] = std::uint64_t{1} << (i % 64);
    t[i] = step_state(unit);
  }
  return t;
}

Matrix256 power_of_two(Matrix256 t, int k) {  // t^(2^k) by k squarings
  for (int i = 0; i < k; ++i) t = multiply(t, t);
  return t;
}

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

// sqrt(n) times the Kolmogorov-Smirnov distance of the sample from cdf.
template <class Cdf>
double ks_statistic(std::vector<double> x, Cdf cdf) {
  std::sort(x.begin(), x.end());
  const double n = static_cast<double>(x.size());
  double d = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double f = cdf(x[i]);
    d = std::max({d, std::abs(f - static_cast<double>(i) / n), std::abs(f - static_cast<double>(i + 1) / n)});
  }
  return d * std::sqrt(n);
}

// The steering chain of scenes/backlash_chain.yaml: 20 H11/h11 (IT11 = 130 um), bearing internal
// clearances 40-82 and 50-100 um, 16 H11/h11 (110 um), 25 H11/h11 (130 um); actuator 25 +- 25 um.
PlayTerm h11_fit(double it) {
  return {"fit", {{"hole", 0.5 * it, 0.5 * it, 1.0, Distribution::normal}, {"shaft", -0.5 * it, 0.5 * it, -1.0, Distribution::normal}}};
}
PlayTerm clearance(double low, double high) {
  return {"internal", {{"clearance", 0.5 * (low + high), 0.5 * (high - low), 1.0, Distribution::normal}}};
}
PlayStack steering_chain() {
  constexpr double um = 1e-6;
  PlayStack s;
  s.own_mean = 25 * um;
  s.own_sigma = 25 * um / 3;
  for (const PlayTerm& t : {h11_fit(130 * um), clearance(40 * um, 82 * um), h11_fit(130 * um), h11_fit(110 * um),
                            h11_fit(110 * um), clearance(50 * um, 100 * um), h11_fit(130 * um)})
    s.terms.push_back({1.0, t});
  return s;
}

}  // namespace

TEST_CASE("xoshiro256++ jump and long_jump are the update raised to 2^128 and 2^192", "[backlash][sampler]") {
  // Second method: the update is linear over GF(2); its 256 x 256 matrix squared 128 (192) times.
  const Matrix256 t = update_matrix();
  const Matrix256 t128 = power_of_two(t, 128);
  const Matrix256 t192 = power_of_two(t128, 64);
  for (const std::uint64_t seed : {1ull, 2026ull, 0xFFFFFFFFFFFFull}) {
    Xoshiro256 e(seed), f(seed);
    const Bits256 start = e.state();
    e.jump();
    f.long_jump();
    CHECK(e.state() == apply(t128, start));
    CHECK(f.state() == apply(t192, start));
  }
  // And the matrix itself is the update: one step by both.
  Xoshiro256 g(5);
  const Bits256 s0 = g.state();
  g();
  CHECK(g.state() == apply(t, s0));
}

TEST_CASE("the ziggurat's table closes: equal strip areas, the top strip ending at zero", "[backlash][sampler]") {
  // v = r f(r) + integral_r^inf exp(-x^2/2) dx = r f(r) + sqrt(pi/2) erfc(r/sqrt(2)) (closed form).
  const double r = ZigguratTable::r;
  const double v = r * std::exp(-0.5 * r * r) + std::sqrt(std::numbers::pi / 2) * std::erfc(r / std::numbers::sqrt2);
  CHECK_THAT(ZigguratTable::v, WithinRel(v, 1e-14) || WithinAbs(v, 1e-300));
  const auto& z = ziggurat_table;
  // The top strip [0, x[N-1]] x [f(x[N-1]), 1] has the area v too.
  const double top = z.x[ZigguratTable::strips - 1] * (1.0 - z.f[ZigguratTable::strips - 1]);
  CHECK_THAT(top, WithinRel(v, 1e-11) || WithinAbs(v, 1e-300));
  for (int i = 1; i + 1 < ZigguratTable::strips; ++i) {  // every strip: x[i] (f(x[i+1]) - f(x[i])) = v
    INFO("strip " << i);
    REQUIRE_THAT(z.x[i] * (z.f[i + 1] - z.f[i]), WithinRel(v, 1e-11) || WithinAbs(v, 1e-300));
  }
}

TEST_CASE("each lane draws the scalar ziggurat's normals from its own engine", "[backlash][sampler]") {
  // Second method: the scalar algorithm (variates.hpp) on lane j's engine, the seed's engine
  // advanced by j long jumps. Bit for bit, through the strips' cores, wedges and tail.
  const Xoshiro256 start(77);
  LaneVariates lanes_of(start);
  std::array<Xoshiro256, lanes> scalar{start, start, start, start, start, start, start, start};
  for (int j = 0; j < lanes; ++j)
    for (int k = 0; k < j; ++k) scalar[j].long_jump();
  std::size_t mismatches = 0, beyond_r = 0;
  for (int step = 0; step < 200000; ++step) {
    const LaneDoubles z = lanes_of.normals();
    for (int j = 0; j < lanes; ++j) {
      const double expected = ziggurat_normal(scalar[j]);
      mismatches += z[j] != expected;
      beyond_r += std::abs(expected) > ZigguratTable::r;
    }
  }
  CHECK(mismatches == 0);
  CHECK(beyond_r > 0);  // the tail was visited
  for (int j = 0; j < lanes; ++j) CHECK(lanes_of.lane(j).state() == scalar[j].state());
}

TEST_CASE("the lanes' normal, uniform and triangular variates pass Kolmogorov-Smirnov and the tails' test", "[backlash][sampler]") {
  // D sqrt(n) > 1.95 has probability ~0.1 % for a correct generator.
  LaneVariates v(Xoshiro256(2026));
  const std::size_t groups = 40000;  // 320000 of each
  std::vector<double> normal, uniform, triangular;
  for (std::size_t g = 0; g < groups; ++g) {
    const LaneDoubles a = v.normals(), b = v.uniforms(), c = v.triangulars();
    for (int j = 0; j < lanes; ++j) {
      normal.push_back(a[j]);
      uniform.push_back(b[j]);
      triangular.push_back(c[j]);
    }
  }
  CHECK(ks_statistic(normal, normal_cdf) < 1.95);
  CHECK(ks_statistic(uniform, [](double x) { return std::clamp(0.5 * (x + 1.0), 0.0, 1.0); }) < 1.95);
  CHECK(ks_statistic(triangular, [](double x) { return x < 0 ? 0.5 * (1 + x) * (1 + x) : 1 - 0.5 * (1 - x) * (1 - x); }) < 1.95);
  CHECK(*std::min_element(uniform.begin(), uniform.end()) >= -1.0);
  CHECK(*std::max_element(uniform.begin(), uniform.end()) < 1.0);

  // Moments of the normals: mean 0 and variance 1 within 4 standard errors (1/sqrt(n), sqrt(2/n)).
  const double n = static_cast<double>(normal.size());
  double sum = 0.0, squares = 0.0;
  for (const double x : normal) {
    sum += x;
    squares += x * x;
  }
  CHECK(std::abs(sum / n) < 4.0 / std::sqrt(n));
  CHECK(std::abs(squares / n - 1.0) < 4.0 * std::sqrt(2.0 / n));

  // The tail beyond r = 4.04 and the wedges near it: the share beyond 3, 4 and 4.5 sigma among 8e6.
  std::size_t beyond3 = 0, beyond4 = 0, beyond45 = 0;
  const std::size_t tail_groups = 1000000;
  for (std::size_t g = 0; g < tail_groups; ++g) {
    const LaneDoubles z = v.normals();
    for (int j = 0; j < lanes; ++j) {
      const double a = std::abs(z[j]);
      beyond3 += a > 3.0;
      beyond4 += a > 4.0;
      beyond45 += a > 4.5;
    }
  }
  const double m = static_cast<double>(tail_groups * lanes);
  for (const auto& [count, z] : {std::pair{beyond3, 3.0}, std::pair{beyond4, 4.0}, std::pair{beyond45, 4.5}}) {
    const double p = std::erfc(z / std::numbers::sqrt2);
    INFO("beyond " << z << " sigma: " << count << " of " << m << ", expected " << p * m);
    CHECK(std::abs(static_cast<double>(count) / m - p) < 4.0 * std::sqrt(p / m));
  }
}

TEST_CASE("Monte Carlo is the same bit for bit on 1, 2 and 3 threads", "[backlash][sampler]") {
  const PlayStack chain = steering_chain();
  const SampledStack stack = sampled_stack(chain);
  SampleLimits limits;
  limits.upper = 900e-6;
  const std::size_t n = 5 * chunk_samples + 1234;  // streamed, a short last chunk
  const SampleSummary one = monte_carlo(stack, n, 11, limits, 30, 1);
  for (const unsigned threads : {2u, 3u}) {
    INFO(threads << " threads");
    SamplerWork work;
    const SampleSummary s = monte_carlo(stack, n, 11, limits, 30, threads, &work);
    CHECK(work.threads == threads);
    CHECK(work.chunks == 6);
    CHECK(s.mean == one.mean);
    CHECK(s.sigma == one.sigma);
    CHECK(s.min == one.min);
    CHECK(s.max == one.max);
    CHECK(s.q_low == one.q_low);
    CHECK(s.q_high == one.q_high);
    CHECK(s.above == one.above);
    CHECK(s.histogram.counts == one.histogram.counts);
    CHECK(s.histogram.low == one.histogram.low);
    CHECK(draw_samples(stack, n, 4, threads) == draw_samples(stack, n, 4, 1));
  }
  CHECK(one.above > 0);
  // A seed's sequence does not depend on how many samples are asked for: a prefix stays a prefix.
  const std::vector<double> longer = draw_samples(stack, n, 4), shorter = draw_samples(stack, chunk_samples + 9, 4);
  CHECK(std::equal(shorter.begin(), shorter.end(), longer.begin()));
}

TEST_CASE("the streamed summary holds its quantiles where a tail is a point mass", "[backlash][sampler]") {
  // max(0, X), X ~ N(-5 um, 10 um): 69 % of the samples are exactly 0, so the lower threshold is 0
  // itself and the lower quantile is among the ties; second method: every sample kept.
  PlayStack clipped;
  clipped.terms.push_back({1.0, clearance(-35e-6, 25e-6)});
  const std::size_t n = 3 * chunk_samples + 17;
  const SampledStack stack = sampled_stack(clipped);
  const SampleSummary stream = monte_carlo(stack, n, 8, {}, 0, 2);
  const SampleSummary kept = summarize(draw_samples(stack, n, 8));
  CHECK(stream.q_low == 0.0);
  CHECK(stream.q_low == kept.q_low);
  CHECK(stream.q_high == kept.q_high);
  CHECK(stream.min == kept.min);
  CHECK(stream.max == kept.max);
  CHECK_THAT(stream.mean, WithinRel(kept.mean, 1e-12));
  CHECK_THAT(stream.sigma, WithinRel(kept.sigma, 1e-10));
}

TEST_CASE("Monte Carlo of the steering chain: mean and sigma against the clipped normals' closed form", "[backlash][sampler]") {
  // For X ~ N(mu, s) and a = mu/s: E[max(0, X)] = mu Phi(a) + s phi(a),
  // E[max(0, X)^2] = (mu^2 + s^2) Phi(a) + mu s phi(a); the terms are independent, so means and
  // variances add. Within 4 standard errors of the mean (sigma/sqrt(N)) and of sigma.
  const PlayStack chain = steering_chain();
  auto phi = [](double x) { return std::exp(-0.5 * x * x) / std::sqrt(2 * std::numbers::pi); };
  double mean = 0.0, variance = 0.0;
  auto add = [&](double mu, double s) {
    const double a = mu / s;
    const double m1 = mu * normal_cdf(a) + s * phi(a), m2 = (mu * mu + s * s) * normal_cdf(a) + mu * s * phi(a);
    mean += m1;
    variance += m2 - m1 * m1;
  };
  add(chain.own_mean, chain.own_sigma);
  for (const WeightedTerm& t : chain.terms) add(t.term.mean(), term_sigma(t.term));
  const std::size_t n = 2000000;
  SamplerWork work;
  const SampleSummary s = monte_carlo(sampled_stack(chain), n, 1, {}, 0, 2, &work);
  CHECK(work.passes == 1);
  CHECK(work.samples == n + chunk_samples);  // the pilot, then one pass
  CHECK_THAT(s.mean, WithinAbs(mean, 4.0 * s.mean_error));
  // sigma's standard error for these near-normal sums (kurtosis within a few % of 3): about
  // sigma/sqrt(2(N-1)); 5 of them.
  CHECK_THAT(s.sigma, WithinAbs(std::sqrt(variance), 5.0 * s.sigma_error));
  CHECK(mean == Approx(771.0035257e-6).epsilon(1e-9).margin(0));  // as the numpy peer's closed form gives
}

TEST_CASE("stack.linear and backlash.chain: the threads parameter changes no output, a bad value names it", "[backlash][sampler]") {
  auto type = make_stack_linear_type();
  ParamValue links;
  links.kind = ParamKind::record_list;
  for (const char* distribution : {"normal", "uniform", "triangular"})
    links.records.push_back({{"nominal", ParamValue::of_number(0.010)},
                             {"upper", ParamValue::of_number(3e-5)},
                             {"lower", ParamValue::of_number(-2e-5)},
                             {"distribution", ParamValue::of_choice(distribution)}});
  auto run = [&](double threads) {
    OutputSet out;
    testing::RecordingContext ctx(std::vector<std::string>{"monte_carlo"});
    type->evaluate(testing::defaults_of(type->info(), {{"links", links},
                                                       {"samples", ParamValue::of_integer(400000)},
                                                       {"threads", ParamValue::of_integer(threads)}}),
                   InputSet{}, out, ctx);
    CHECK(ctx.work.at("samples") == 400000.0);
    CHECK(ctx.work.at("chunks") == 7.0);  // ceil(400000 / 65536)
    return out;
  };
  const OutputSet one = run(1);
  for (const double threads : {0.0, 2.0, 3.0}) {
    INFO("threads " << threads);
    const OutputSet other = run(threads);
    for (const char* port : {"mc_mean", "mc_sigma", "mc_min", "mc_max", "mc_q001", "mc_q999"})
      CHECK(other.all().at(port).as_scalar() == one.all().at(port).as_scalar());
  }
  CHECK_THROWS_MATCHES(run(300), NodeError,
                       Catch::Matchers::Predicate<NodeError>([](const NodeError& e) { return e.parameter() == "threads"; }));
  CHECK(make_backlash_chain_type()->info().find_param("threads") != nullptr);
}
