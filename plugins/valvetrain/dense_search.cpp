// Turning points and first crossings inside one step (dense_search.hpp).
#include "dense_search.hpp"

#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mechgraph::valvetrain {

namespace {
constexpr double eps = std::numeric_limits<double>::epsilon();
}

DenseSearch::DenseSearch(double rtol) : relative_width_(std::clamp(std::sqrt(rtol), 1e-7, 1e-2)) {}

Pieces DenseSearch::pieces(const Sample& a, const Sample& b, const Probe& q, SearchWork& work) const {
  const double h = b.t - a.t;
  if (!(h > 0.0) || a.rate * b.rate < 0.0) return Pieces{{a, b, b}, 2};
  const Pieces whole{{a, b, b}, 2};  // one turn at most (signs at the ends differ)
  // The cubic Hermite interpolant on s = (t - a) / h: p'(s) = A s^2 + B s + C.
  const double ma = h * a.rate, mb = h * b.rate, d = b.value - a.value;
  const double A = 3.0 * (ma + mb - 2.0 * d), B = 2.0 * (3.0 * d - 2.0 * ma - mb), C = ma;
  if (A == 0.0) return whole;
  const double vertex = -B / (2.0 * A);
  if (!(vertex > 0.0 && vertex < 1.0)) return whole;
  const double least_rate = C - B * B / (4.0 * A);  // p' at its vertex
  const bool turns_twice = (ma >= 0.0 && mb >= 0.0 && least_rate < 0.0) || (ma <= 0.0 && mb <= 0.0 && least_rate > 0.0);
  if (!turns_twice) return whole;
  const double t = a.t + vertex * h;
  if (!(t > a.t && t < b.t)) return whole;
  ++work.evaluations;
  return Pieces{{a, q(t), b}, 3};
}

double DenseSearch::tangent_bound(const Sample& a, const Sample& b) {
  // q_a + q'_a x = q_b + q'_b (x - h): x = (q_b - q_a - q'_b h) / (q'_a - q'_b).
  const double h = b.t - a.t, den = a.rate - b.rate;
  if (den == 0.0) return std::numeric_limits<double>::quiet_NaN();
  const double x = (b.value - a.value - b.rate * h) / den;
  if (!(x >= 0.0 && x <= h)) return std::numeric_limits<double>::quiet_NaN();  // q not concave/convex: no bound
  return a.value + a.rate * x;
}

Sample DenseSearch::refine_turn(const Sample& a, const Sample& b, bool maximum, const Probe& q, SearchWork& work) const {
  ++work.refinements;
  Sample best = maximum == (a.value >= b.value) ? a : b;
  auto rate = [&](double t) {
    ++work.evaluations;
    const Sample s = q(t);
    if (maximum ? s.value > best.value : s.value < best.value) best = s;
    return s.rate;
  };
  const double width = relative_width_ * (b.t - a.t);
  auto narrow = [width](double lo, double hi) { return hi - lo <= std::max(width, 4.0 * eps * std::abs(hi)); };
  boost::uintmax_t iterations = 60;
  try {
    boost::math::tools::toms748_solve(rate, a.t, b.t, a.rate, b.rate, narrow, iterations);
  } catch (const boost::math::evaluation_error&) {
    // The rate lost its sign change to rounding: the best value seen stands.
  }
  return best;
}

double DenseSearch::root(const Sample& above, const Sample& below, const Probe& q, SearchWork& work) const {
  if (below.value == 0.0) return below.t;
  ++work.refinements;
  auto value = [&](double t) {
    ++work.evaluations;
    return q(t).value;
  };
  boost::uintmax_t iterations = 100;
  const auto bracket = boost::math::tools::toms748_solve(value, above.t, below.t, above.value, below.value,
                                                         boost::math::tools::eps_tolerance<double>(50), iterations);
  return bracket.second;  // the side where q has fallen
}

std::optional<Sample> DenseSearch::interior_max(const Sample& a, const Sample& b, double beat, const Probe& q,
                                                SearchWork& work) const {
  if (!(a.rate > 0.0 && b.rate < 0.0)) return std::nullopt;
  // The tangent bound, with as much again for a q not quite concave across the step.
  const double bound = tangent_bound(a, b), top = std::max(a.value, b.value);
  if (std::isfinite(bound) && top + 2.0 * (bound - top) <= beat) return std::nullopt;
  return refine_turn(a, b, true, q, work);
}

std::optional<Sample> DenseSearch::interior_min(const Sample& a, const Sample& b, double beat, const Probe& q,
                                                SearchWork& work) const {
  if (!(a.rate < 0.0 && b.rate > 0.0)) return std::nullopt;
  const double bound = tangent_bound(a, b), bottom = std::min(a.value, b.value);
  if (std::isfinite(bound) && bottom + 2.0 * (bound - bottom) >= beat) return std::nullopt;
  return refine_turn(a, b, false, q, work);
}

std::optional<double> DenseSearch::first_fall(const Sample& a, const Sample& b, const Probe& q, SearchWork& work) const {
  const Pieces p = pieces(a, b, q, work);
  for (std::size_t i = 0; i + 1 < p.size; ++i)
    if (const auto t = fall_in_piece(p.at[i], p.at[i + 1], q, work)) return t;
  return std::nullopt;
}

std::optional<double> DenseSearch::fall_in_piece(Sample a, const Sample& b, const Probe& q, SearchWork& work) const {
  if (a.value == 0.0 && a.rate == 0.0) {
    // At rest on zero (e.g. a valve carried on at a landing): its side is the one it moves to.
    const double ahead = a.t + 1e-6 * (b.t - a.t);
    if (!(ahead > a.t && ahead < b.t)) return std::nullopt;
    ++work.evaluations;
    a = q(ahead);
    if (a.value == 0.0) return std::nullopt;
  }
  const bool above = a.value > 0.0 || (a.value == 0.0 && a.rate > 0.0);
  if (above) {
    if (b.value <= 0.0) {
      if (a.value > 0.0) return root(a, b, q, work);
      // Rising from zero and back at or below it: over a maximum first.
      if (a.rate > 0.0 && b.rate < 0.0) {
        const Sample top = refine_turn(a, b, true, q, work);
        if (top.value > 0.0 && top.t < b.t) return root(top, b, q, work);
      }
      return std::nullopt;
    }
    // Above at both ends: does it dip through zero between?
    if (a.value > 0.0)
      if (const auto low = interior_min(a, b, 0.0, q, work); low && low->value <= 0.0) return root(a, *low, q, work);
    return std::nullopt;
  }
  // Below (or leaving zero downward): a rise over zero and a fall back inside the step?
  if (b.value <= 0.0)
    if (const auto top = interior_max(a, b, 0.0, q, work); top && top->value > 0.0 && top->t < b.t) return root(*top, b, q, work);
  return std::nullopt;
}

}  // namespace mechgraph::valvetrain
