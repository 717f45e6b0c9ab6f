#include <mechgraph/numerics/piecewise.hpp>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

namespace mechgraph::numerics {
namespace {

// Sample points of one piece: uniform, the two ends pulled inside by a relative 1e-13 so that at a
// knot where f jumps we see the one-sided limit belonging to this piece.
double sample_point(double a, double b, int i, int n) {
  const double inset = 1e-13 * (b - a);
  if (i == 0) return a + inset;
  if (i == n - 1) return b - inset;
  return a + (b - a) * static_cast<double>(i) / (n - 1);
}

void check_knots(std::span<const double> knots, int samples) {
  if (knots.size() < 2) throw std::invalid_argument("piecewise numerics need at least two knots");
  if (samples < 3) throw std::invalid_argument("piecewise numerics need at least 3 samples per piece");
}

Extremum maximize(const Function1D& f, std::span<const double> knots, int n, long& evaluations) {
  check_knots(knots, n);
  Extremum best{knots.front(), -std::numeric_limits<double>::infinity()};
  for (std::size_t p = 0; p + 1 < knots.size(); ++p) {
    const double a = knots[p], b = knots[p + 1];
    if (!(b > a)) continue;
    int best_i = 0;
    double best_v = -std::numeric_limits<double>::infinity();
    std::vector<double> v(n);
    for (int i = 0; i < n; ++i) {
      v[i] = f(sample_point(a, b, i, n));
      if (v[i] > best_v) { best_v = v[i]; best_i = i; }
    }
    evaluations += n;
    Extremum piece{sample_point(a, b, best_i, n), best_v};
    // Refine inside the bracket of the neighbouring samples (Brent, full precision).
    const double lo = sample_point(a, b, std::max(best_i - 1, 0), n);
    const double hi = sample_point(a, b, std::min(best_i + 1, n - 1), n);
    std::uintmax_t iterations = 100;
    auto r = boost::math::tools::brent_find_minima([&](double x) { return -f(x); }, lo, hi,
                                                   std::numeric_limits<double>::digits / 2, iterations);
    evaluations += static_cast<long>(iterations);
    if (-r.second > piece.value) piece = {r.first, -r.second};
    if (piece.value > best.value) best = piece;
  }
  return best;
}

}  // namespace

void maximize_piecewise_together(const Sampler& sample, std::size_t count, std::span<const double> knots, int n,
                                 long& evaluations, Extremum* maxima) {
  check_knots(knots, n);
  struct Candidate {
    std::size_t piece;
    int index;        // best sample in the piece
    double value;     // its value
    double drop;      // how far the neighbouring samples fall below it (0 at a piece's end)
  };
  std::vector<std::vector<Candidate>> candidates(count);
  std::vector<double> values(count * static_cast<std::size_t>(n)), slopes(count * static_cast<std::size_t>(n));
  std::vector<double> overall(count, -std::numeric_limits<double>::infinity());
  for (std::size_t p = 0; p + 1 < knots.size(); ++p) {
    const double a = knots[p], b = knots[p + 1];
    if (!(b > a)) continue;
    for (int i = 0; i < n; ++i)
      sample(sample_point(a, b, i, n), &values[static_cast<std::size_t>(i) * count], &slopes[static_cast<std::size_t>(i) * count]);
    evaluations += n;
    for (std::size_t j = 0; j < count; ++j) {
      int best = 0;
      for (int i = 1; i < n; ++i)
        if (values[static_cast<std::size_t>(i) * count + j] > values[static_cast<std::size_t>(best) * count + j]) best = i;
      const double v = values[static_cast<std::size_t>(best) * count + j];
      double drop = 0.0;
      for (int i : {best - 1, best + 1})
        if (i >= 0 && i < n) drop = std::max(drop, v - values[static_cast<std::size_t>(i) * count + j]);
      candidates[j].push_back({p, best, v, drop});
      overall[j] = std::max(overall[j], v);
    }
  }
  std::vector<double> one(count), one_slope(count);
  const double x_tolerance = 0x1.0p-26 * (knots.back() - knots.front());
  for (std::size_t j = 0; j < count; ++j) {
    Extremum best{knots.front(), -std::numeric_limits<double>::infinity()};
    for (const Candidate& c : candidates[j]) {
      const double a = knots[c.piece], b = knots[c.piece + 1];
      if (c.value > best.value) best = {sample_point(a, b, c.index, n), c.value};
      // Between samples a smooth function rises at most about its drop to a neighbour above the
      // best sample; twice that is the margin.
      if (c.value + 2.0 * c.drop < overall[j] && c.value < overall[j]) continue;
      const int i_lo = std::max(c.index - 1, 0), i_hi = std::min(c.index + 1, n - 1);
      const double lo = sample_point(a, b, i_lo, n), hi = sample_point(a, b, i_hi, n);
      auto at = [&](double x) {
        sample(x, one.data(), one_slope.data());
        ++evaluations;
        return one[j];
      };
      at(lo);
      const double slope_lo = one_slope[j];
      at(hi);
      const double slope_hi = one_slope[j];
      if (slope_lo > 0.0 && slope_hi < 0.0) {
        // Rising into the bracket and falling out of it: the maximum is where the slope is zero.
        std::uintmax_t iterations = 100;
        const auto root = boost::math::tools::toms748_solve(
            [&](double x) {
              at(x);
              return one_slope[j];
            },
            // Half the digits in x are all the value needs: near a maximum it moves as dx^2. The
            // tolerance is absolute, on the scale of the whole interval, so a maximum at x = 0
            // (a cam's nose) converges too.
            lo, hi, slope_lo, slope_hi, [&](double x0, double x1) { return std::abs(x1 - x0) <= x_tolerance; }, iterations);
        const double x = 0.5 * (root.first + root.second);
        const double v = at(x);
        if (v > best.value) best = {x, v};
        continue;
      }
      if (slope_lo >= 0.0 && slope_hi >= 0.0 && c.index == n - 1) continue;  // rising to the piece's end
      if (slope_lo <= 0.0 && slope_hi <= 0.0 && c.index == 0) continue;      // falling from its start
      std::uintmax_t iterations = 100;
      auto r = boost::math::tools::brent_find_minima([&](double x) { return -at(x); }, lo, hi,
                                                     std::numeric_limits<double>::digits / 2, iterations);
      if (-r.second > best.value) best = {r.first, -r.second};
    }
    maxima[j] = best;
  }
}

Extremum maximize_piecewise(const Function1D& f, std::span<const double> knots, int samples, long& evaluations) {
  return maximize(f, knots, samples, evaluations);
}

Extremum minimize_piecewise(const Function1D& f, std::span<const double> knots, int samples, long& evaluations) {
  Extremum e = maximize([&](double x) { return -f(x); }, knots, samples, evaluations);
  return {e.x, -e.value};
}

namespace {

// Walks the samples of every piece and reports each change of sign (refined with TOMS 748) to
// `on_root`, which returns false to stop. Samples where f is exactly zero are stepped over, so a
// function that only touches zero does not count. A jump across zero at a knot is a root there.
void scan_sign_changes(const Function1D& f, std::span<const double> knots, int n, long& evaluations,
                       const std::function<bool(double)>& on_root) {
  check_knots(knots, n);
  for (std::size_t p = 0; p + 1 < knots.size(); ++p) {
    const double a = knots[p], b = knots[p + 1];
    if (!(b > a)) continue;
    double x_prev = sample_point(a, b, 0, n);
    double f_prev = f(x_prev);
    ++evaluations;
    if (p > 0) {
      const double left = f(knots[p] - 1e-13 * (knots[p] - knots[p - 1]));
      ++evaluations;
      if (((left > 0 && f_prev < 0) || (left < 0 && f_prev > 0)) && !on_root(knots[p])) return;
    }
    for (int i = 1; i < n; ++i) {
      const double x = sample_point(a, b, i, n);
      const double fx = f(x);
      ++evaluations;
      if ((f_prev > 0 && fx < 0) || (f_prev < 0 && fx > 0)) {
        std::uintmax_t iterations = 200;
        boost::math::tools::eps_tolerance<double> tol(std::numeric_limits<double>::digits - 3);
        auto r = boost::math::tools::toms748_solve(f, x_prev, x, f_prev, fx, tol, iterations);
        evaluations += static_cast<long>(iterations);
        if (!on_root(0.5 * (r.first + r.second))) return;
      }
      if (fx != 0.0) {
        x_prev = x;
        f_prev = fx;
      }
    }
  }
}

}  // namespace

std::optional<double> first_sign_change(const Function1D& f, std::span<const double> knots, int n,
                                        long& evaluations) {
  std::optional<double> first;
  scan_sign_changes(f, knots, n, evaluations, [&](double x) {
    first = x;
    return false;
  });
  return first;
}

std::vector<double> all_sign_changes(const Function1D& f, std::span<const double> knots, int n, long& evaluations) {
  std::vector<double> roots;
  scan_sign_changes(f, knots, n, evaluations, [&](double x) {
    roots.push_back(x);
    return true;
  });
  return roots;
}

double integrate_piecewise(const Function1D& f, std::span<const double> knots, double tolerance, long& evaluations,
                           double* error_estimate) {
  if (knots.size() < 2) throw std::invalid_argument("integrate_piecewise needs at least two knots");
  double total = 0.0, error = 0.0;
  for (std::size_t p = 0; p + 1 < knots.size(); ++p) {
    const double a = knots[p], b = knots[p + 1];
    if (!(b > a)) continue;
    double piece_error = 0.0;
    long count = 0;
    auto counted = [&](double x) { ++count; return f(x); };
    total += boost::math::quadrature::gauss_kronrod<double, 15>::integrate(counted, a, b, 15, tolerance, &piece_error);
    evaluations += count;
    error += piece_error;
  }
  if (error_estimate) *error_estimate = error;
  return total;
}

}  // namespace mechgraph::numerics
