// DenseSearch (the turning points and first crossings inside one integration step) on functions
// whose extremes and roots are known in closed form: a maximum between samples, two turns inside
// one step, a dip through zero and back, a hop that leaves zero and returns, a start at rest on
// zero; and the tangent bound that spares refinements which cannot matter.
#include "dense_search.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace mechgraph::valvetrain;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

// q(t) = f(t) with its derivative, as a probe.
template <class F, class D>
struct Analytic {
  F f;
  D d;
  Sample operator()(double t) const { return {t, f(t), d(t)}; }
};
template <class F, class D>
Analytic<F, D> analytic(F f, D d) {
  return {f, d};
}

}  // namespace

TEST_CASE("dense search: the maximum between two samples, to about rtol of its curvature", "[valvetrain][dense_search]") {
  const auto q = analytic([](double t) { return std::sin(t); }, [](double t) { return std::cos(t); });
  for (double rtol : {1e-6, 1e-8, 1e-12}) {
    INFO("rtol " << rtol);
    const DenseSearch search(rtol);
    SearchWork work;
    const auto top = search.interior_max(q(1.0), q(2.2), -1.0, Probe(q), work);
    REQUIRE(top);
    CHECK_THAT(top->value, WithinAbs(1.0, 2 * rtol));  // 1 - cos(dt) ~ dt^2 / 2, dt ~ sqrt(rtol) of the step
    CHECK_THAT(top->t, WithinAbs(std::numbers::pi / 2, 2 * std::sqrt(rtol)));
    CHECK(work.refinements == 1);
    CHECK(work.evaluations < 20);
    // The minimum of -sin likewise; none where the rate does not turn.
    const auto flip = analytic([](double t) { return -std::sin(t); }, [](double t) { return -std::cos(t); });
    const auto low = search.interior_min(flip(1.0), flip(2.2), 1.0, Probe(flip), work);
    REQUIRE(low);
    CHECK_THAT(low->value, WithinAbs(-1.0, 2 * rtol));
    CHECK_FALSE(search.interior_max(q(0.1), q(1.2), -1.0, Probe(q), work));
  }
}

TEST_CASE("dense search: a maximum that cannot beat the best so far is not refined (tangent bound)", "[valvetrain][dense_search]") {
  // q = 1 - (t - 0.5)^2 on [0, 1]: the tangents at the ends meet at t = 0.5, q = 1.25 >= the true 1.
  const auto q = analytic([](double t) { return 1.0 - (t - 0.5) * (t - 0.5); }, [](double t) { return -2.0 * (t - 0.5); });
  CHECK_THAT(DenseSearch::tangent_bound(q(0.0), q(1.0)), WithinRel(1.25, 1e-15));
  const DenseSearch search(1e-10);
  SearchWork work;
  // Beaten by a best of 1.6 (the bound with its margin: 0.75 + 2 * 0.5 = 1.75 > 1.6 still refines; 1.8 does not).
  CHECK_FALSE(search.interior_max(q(0.0), q(1.0), 1.8, Probe(q), work));
  CHECK(work.refinements == 0);
  const auto top = search.interior_max(q(0.0), q(1.0), 1.6, Probe(q), work);
  REQUIRE(top);
  CHECK_THAT(top->value, WithinAbs(1.0, 1e-12));
}

TEST_CASE("dense search: two turns inside one step are split apart", "[valvetrain][dense_search]") {
  // q = t^3 - t on [-1.5, 1.5]: q' = 5.75 at both ends, a maximum at -1/sqrt(3) and a minimum at +1/sqrt(3).
  const auto q = analytic([](double t) { return t * t * t - t; }, [](double t) { return 3 * t * t - 1; });
  const DenseSearch search(1e-10);
  SearchWork work;
  const Pieces p = search.pieces(q(-1.5), q(1.5), Probe(q), work);
  REQUIRE(p.size == 3);
  const double turn = 1 / std::sqrt(3.0), extreme = 2 / (3 * std::sqrt(3.0));
  const auto top = search.interior_max(p.at[0], p.at[1], -10, Probe(q), work);
  const auto low = search.interior_min(p.at[1], p.at[2], 10, Probe(q), work);
  REQUIRE(top);
  REQUIRE(low);
  CHECK_THAT(top->value, WithinAbs(extreme, 1e-9));
  CHECK_THAT(top->t, WithinAbs(-turn, 1e-4));
  CHECK_THAT(low->value, WithinAbs(-extreme, 1e-9));
  // A monotone step is one piece.
  CHECK(search.pieces(q(1.0), q(1.5), Probe(q), work).size == 2);
}

TEST_CASE("dense search: first crossings a check at the step's ends misses", "[valvetrain][dense_search]") {
  const DenseSearch search(1e-8);
  SECTION("a dip through zero and back: positive at both ends") {
    // q = (t - 0.5)^2 - 1e-6: below zero on (0.499, 0.501) only.
    const auto q = analytic([](double t) { return (t - 0.5) * (t - 0.5) - 1e-6; }, [](double t) { return 2 * (t - 0.5); });
    SearchWork work;
    const auto t = search.first_fall(q(0.0), q(1.0), Probe(q), work);
    REQUIRE(t);
    CHECK_THAT(*t, WithinAbs(0.499, 1e-14));
    CHECK(q(*t).value <= 0.0);  // on the side that has fallen
    // A dip that stays above zero is no crossing.
    const auto above = analytic([](double t) { return (t - 0.5) * (t - 0.5) + 1e-6; }, [](double t) { return 2 * (t - 0.5); });
    CHECK_FALSE(search.first_fall(above(0.0), above(1.0), Probe(above), work));
  }
  SECTION("a hop: leaving zero upward and back inside the step") {
    const auto q = analytic([](double t) { return t * (0.3 - t); }, [](double t) { return 0.3 - 2 * t; });
    SearchWork work;
    const auto t = search.first_fall(q(0.0), q(1.0), Probe(q), work);
    REQUIRE(t);
    CHECK_THAT(*t, WithinAbs(0.3, 1e-14));
  }
  SECTION("a rise over zero and a fall back, below zero at both ends") {
    const auto q = analytic([](double t) { return 1e-6 - (t - 0.5) * (t - 0.5); }, [](double t) { return -2 * (t - 0.5); });
    SearchWork work;
    const auto t = search.first_fall(q(0.0), q(1.0), Probe(q), work);
    REQUIRE(t);
    CHECK_THAT(*t, WithinAbs(0.501, 1e-14));
  }
  SECTION("a start at rest on zero takes the side it moves to") {
    // q = t^2 (0.5 - t): q = q' = 0 at 0, positive after, falling through zero at 0.5.
    const auto q = analytic([](double t) { return t * t * (0.5 - t); }, [](double t) { return t - 3 * t * t; });
    SearchWork work;
    const auto t = search.first_fall(q(0.0), q(1.0), Probe(q), work);
    REQUIRE(t);
    CHECK_THAT(*t, WithinAbs(0.5, 1e-14));
    // ... and the same moving downward first is no crossing (it was never above).
    const auto down = analytic([](double t) { return -t * t * (0.5 - t); }, [](double t) { return -(t - 3 * t * t); });
    CHECK_FALSE(search.first_fall(down(0.0), down(0.4), Probe(down), work));
  }
  SECTION("an ordinary crossing") {
    const auto q = analytic([](double t) { return std::cos(t); }, [](double t) { return -std::sin(t); });
    SearchWork work;
    const auto t = search.first_fall(q(0.0), q(2.0), Probe(q), work);
    REQUIRE(t);
    CHECK_THAT(*t, WithinAbs(std::numbers::pi / 2, 1e-14));
  }
}
