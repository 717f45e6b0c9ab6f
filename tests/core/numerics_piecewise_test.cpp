#include <mechgraph/numerics/piecewise.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

using namespace mechgraph::numerics;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

TEST_CASE("piecewise quadrature reaches machine precision on smooth pieces", "[numerics]") {
  long evaluations = 0;
  const std::vector<double> knots{0.0, std::numbers::pi};
  CHECK_THAT(integrate_piecewise([](double x) { return std::sin(x); }, knots, 1e-14, evaluations), WithinRel(2.0, 1e-14));
  CHECK(evaluations > 0);
  // |x - 1| has a kink at 1: with the kink as a knot the result is exact.
  const std::vector<double> kinked{0.0, 1.0, 3.0};
  CHECK_THAT(integrate_piecewise([](double x) { return std::abs(x - 1.0); }, kinked, 1e-14, evaluations),
             WithinRel(0.5 + 2.0, 1e-14));
}

TEST_CASE("extrema and sign changes on piecewise functions", "[numerics]") {
  long evaluations = 0;
  const std::vector<double> knots{-1.0, 2.0};
  const auto m = maximize_piecewise([](double x) { return 1.0 - (x - 0.3) * (x - 0.3); }, knots, 11, evaluations);
  CHECK_THAT(m.x, WithinAbs(0.3, 1e-7));
  CHECK_THAT(m.value, WithinAbs(1.0, 1e-14));
  // A step: the one-sided limit at the knot is seen.
  const std::vector<double> step_knots{0.0, 1.0, 2.0};
  auto step = [](double x) { return x < 1.0 ? x : x - 5.0; };
  CHECK_THAT(maximize_piecewise(step, step_knots, 5, evaluations).value, WithinAbs(1.0, 1e-12));
  CHECK_THAT(minimize_piecewise(step, step_knots, 5, evaluations).value, WithinAbs(-4.0, 1e-12));
  auto root = first_sign_change([](double x) { return std::cos(x); }, std::vector<double>{0.0, 3.0}, 10, evaluations);
  REQUIRE(root);
  CHECK_THAT(*root, WithinAbs(std::numbers::pi / 2.0, 1e-14));
  // A jump across zero at a knot is a sign change at that knot.
  auto jump = first_sign_change([](double x) { return x < 1.0 ? 1.0 : -1.0; }, step_knots, 5, evaluations);
  REQUIRE(jump);
  CHECK(*jump == 1.0);
  const auto roots = all_sign_changes([](double x) { return std::sin(x); }, std::vector<double>{0.5, 10.0}, 50, evaluations);
  REQUIRE(roots.size() == 3);
  CHECK_THAT(roots[2], WithinAbs(3 * std::numbers::pi, 1e-13));
  CHECK_FALSE(first_sign_change([](double) { return 1.0; }, knots, 5, evaluations));
}

TEST_CASE("the extremes of a function are found alike at any size of its values (1e-300 to 1e300)", "[numerics]") {
  // A contact's face position of 1e-15 m, a stress of 1e9 Pa: the searches are relative.
  for (const double size : {1.0, 1e-300, 1e-15, 1e-13, 1e9, 1e300}) {
    INFO("size " << size);
    const std::vector<double> knots{-std::numbers::pi, std::numbers::pi};
    SmoothPieces pieces([&](double x, double* v, double*) { v[0] = -size * std::sin(x); }, 1, knots, 16);
    CHECK_THAT(pieces.maximum(0).value, WithinRel(size, 1e-14));
    CHECK_THAT(pieces.maximum(0).x, WithinAbs(-0.5 * std::numbers::pi, 1e-7));
    CHECK_THAT(pieces.minimum(0).value, WithinRel(-size, 1e-14));
    CHECK(pieces.work().unresolved == 0);
  }
}

TEST_CASE("has_interior and one_sided_point step by ulps as std::nextafter does", "[numerics]") {
  // The searches step to the next double without the library call; the reference is nextafter.
  const double tiny = std::numeric_limits<double>::denorm_min(), big = std::numeric_limits<double>::max();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> values{0.0, -0.0, tiny, -tiny, 1e-310, -1e-310, 1e-300, 0.5, 1.0, -1.0, 3.0, -2.5, 1e300, big, -big, inf, -inf};
  for (double a : values)
    for (double b : values) {
      INFO(a << " -> " << b);
      CHECK(has_interior(a, b) == (std::nextafter(a, b) < b));
      if (!std::isfinite(a) || !std::isfinite(b) || a == b) continue;
      const double x = one_sided_point(a, b);
      CHECK(x != a);
      CHECK(std::abs(x - a) <= std::abs(b - a));  // never beyond the other end
      CHECK((b > a ? x > a : x < a));
    }
  // Two adjacent doubles: no interior; three: the middle one is each end's one-sided point.
  const double one_up = std::nextafter(1.0, 2.0), two_up = std::nextafter(one_up, 2.0);
  CHECK_FALSE(has_interior(1.0, one_up));
  CHECK(has_interior(1.0, two_up));
  CHECK(one_sided_point(1.0, two_up) == one_up);
  CHECK(one_sided_point(two_up, 1.0) == one_up);
  CHECK(one_sided_point(-tiny, tiny) == 0.0);
}
