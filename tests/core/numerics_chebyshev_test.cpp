#include <mechgraph/numerics/chebyshev.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

using namespace mechgraph::numerics;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

std::vector<double> interpolate(double (*f)(double), int n) {
  std::vector<double> values(static_cast<std::size_t>(n) + 1), c;
  for (int j = 0; j <= n; ++j) values[static_cast<std::size_t>(j)] = f(chebyshev_point(j, n));
  chebyshev_coefficients(values, c);
  return c;
}

}  // namespace

TEST_CASE("Chebyshev coefficients of a polynomial are exact, of exp(x) fall to rounding by 15 terms", "[numerics]") {
  // T_3(x) = 4x^3 - 3x: one coefficient.
  const auto t3 = interpolate([](double x) { return 4 * x * x * x - 3 * x; }, 16);
  for (std::size_t k = 0; k < t3.size(); ++k) CHECK_THAT(t3[k], WithinAbs(k == 3 ? 1.0 : 0.0, 1e-15));
  // exp(x) = I_0(1) + 2 sum I_k(1) T_k(x): c_0 = I_0(1) = 1.2660658777520082, c_1 = 2 I_1(1).
  const auto e = interpolate([](double x) { return std::exp(x); }, 32);
  CHECK_THAT(e[0], WithinRel(1.2660658777520082, 1e-15));
  CHECK_THAT(e[1], WithinRel(2 * 0.5651591039924851, 1e-15));
  const std::size_t length = chebyshev_resolved_length(e, std::numeric_limits<double>::epsilon());
  CHECK(length >= 13);
  CHECK(length <= 17);
  CHECK_THAT(chebyshev_value(e, 0.3), WithinRel(std::exp(0.3), 1e-15));
  // A kink is never resolved at 257 points: |x| has coefficients falling like k^-2.
  CHECK(chebyshev_resolved_length(interpolate([](double x) { return std::abs(x); }, 256), std::numeric_limits<double>::epsilon()) == 0);
  // Derivative: d/dx T_3 = 12 x^2 - 3 = 3 T_0 + 6 T_2... checked by value.
  const auto d = chebyshev_derivative(t3);
  CHECK_THAT(chebyshev_value(d, 0.7), WithinAbs(12 * 0.49 - 3, 1e-13));
}

TEST_CASE("Chebyshev zeros: all roots of T_9, a double root is a zone, a flat zero stretch one zone", "[numerics]") {
  std::vector<double> t9(10, 0.0);
  t9[9] = 1.0;
  long cells = 0;
  const auto zeros = chebyshev_zeros(t9, 1e-14, cells);
  REQUIRE(zeros.size() == 9);
  for (std::size_t i = 0; i < zeros.size(); ++i) {
    const double expected = std::cos((2.0 * (8 - static_cast<double>(i)) + 1.0) * std::numbers::pi / 18.0);
    CHECK(zeros[i].crosses);
    CHECK_THAT(zeros[i].x, WithinAbs(expected, 1e-14));
  }
  CHECK(cells < 200);
  // (x - 0.3)^2 touches zero: a zone, not a crossing.
  const auto touch = interpolate([](double x) { return (x - 0.3) * (x - 0.3); }, 16);
  const auto z = chebyshev_zeros(touch, 1e-14, cells);
  REQUIRE(z.size() == 1);
  CHECK_FALSE(z[0].crosses);
  CHECK_THAT(z[0].x, WithinAbs(0.3, 1e-6));
  // (x - 0.3)^3 crosses, though flat there: a zone that crosses, rising.
  const auto flat_cross = interpolate([](double x) { return (x - 0.3) * (x - 0.3) * (x - 0.3); }, 16);
  const auto fc = chebyshev_zeros(flat_cross, 1e-14, cells);
  REQUIRE(fc.size() == 1);
  CHECK(fc[0].crosses);
  CHECK(fc[0].rising);
  CHECK_THAT(fc[0].x, WithinAbs(0.3, 1e-4));
}

TEST_CASE("Chebyshev maximum candidates: two near-equal peaks with a valley between are both seen", "[numerics]") {
  // The shape that fooled the sampled search: two maxima at +-0.5 with a minimum between, the right
  // one higher by 1e-9; the best sample sits elsewhere.
  auto f = [](double x) { return -std::pow(x * x - 0.25, 2) + 1e-9 * x; };
  std::vector<double> values(17), c;
  for (int j = 0; j <= 16; ++j) values[static_cast<std::size_t>(j)] = f(chebyshev_point(j, 16));
  chebyshev_coefficients(values, c);
  double best = -1.0;
  long cells = 0;
  const auto candidates = chebyshev_maximum_candidates(c, best, 1e-15, cells);
  double top_t = 0.0, top_v = -1.0;
  for (const auto& p : candidates)
    if (p.value > top_v) top_v = p.value, top_t = p.t;
  CHECK_THAT(top_t, WithinAbs(0.5, 1e-6));
  CHECK_THAT(top_v, WithinAbs(f(0.5000000005), 1e-15));
}

TEST_CASE("Chebyshev resolved length does not depend on the function's size (1e-300 to 1e300)", "[numerics]") {
  // The chop is relative to the largest coefficient. It once divided by envelope[0] inside the
  // loop that overwrote it: every entry but the first stayed absolute, so a function of size 1e-15
  // was "resolved" by one coefficient (the maximum of 1e-15 sin(pi x) came out 0.4 % low) and one of
  // size 1e9 never resolved.
  std::vector<double> values(65), c;
  std::size_t reference = 0;
  for (const double size : {1.0, 1e-300, 1e-15, 1e-13, 1e9, 1e300}) {
    INFO("size " << size);
    for (int j = 0; j <= 64; ++j) values[static_cast<std::size_t>(j)] = -size * std::sin(std::numbers::pi * chebyshev_point(j, 64));
    chebyshev_coefficients(values, c);
    const std::size_t length = chebyshev_resolved_length(c, std::numeric_limits<double>::epsilon());
    if (size == 1.0) reference = length;
    CHECK(length >= 18);
    CHECK(length == reference);
  }
}
