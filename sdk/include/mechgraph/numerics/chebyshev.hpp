#pragma once
// Chebyshev series on [-1, 1]: the building block of the certified searches (piecewise.hpp).
//
// A smooth function sampled at the n + 1 Chebyshev points x_j = cos(pi j / n) (j = 0..n, from +1
// down to -1) has the interpolant p(x) = sum_k c_k T_k(x); once the coefficients c_k have fallen to
// a plateau of rounding noise, p equals the function to rounding level everywhere in the interval,
// not only at the samples (Trefethen, "Approximation Theory and Approximation Practice", ch. 8; the
// plateau test of Aurentz & Trefethen, "Chopping a Chebyshev series", 2017). What p does between
// the samples is then known: its roots are found by subdivision, where a cell is excluded by the
// bound |p(x) - a_0| <= sum_{k>=1} |a_k| on the cell's own series a_k, and a cell with
// |a_1| > sum_{k>=2} k^2 |a_k| is monotone (|T_k'| <= k^2), so it holds one root or none.
// See docs/methods/numerics.md.
#include <cstddef>
#include <functional>
#include <span>
#include <vector>

namespace mechgraph::numerics {

/// The largest number of intervals n of one interpolant (n + 1 points); a power of two.
inline constexpr int chebyshev_max_intervals = 256;

/// The Chebyshev point cos(pi j / n).
double chebyshev_point(int j, int n);

/// Coefficients c_0..c_n of the interpolant through values[j] = f(cos(pi j / n)), j = 0..n; n a
/// power of two from 1 to chebyshev_max_intervals. O(n^2) with a shared cosine table.
void chebyshev_coefficients(std::span<const double> values, std::vector<double>& coefficients);

/// How many leading coefficients carry the function: the plateau test ("standardChop") with
/// relative tolerance `tolerance`. Returns 0 when no plateau is reached (the series is not
/// resolved: more points are needed), else the length to keep (>= 1).
std::size_t chebyshev_resolved_length(std::span<const double> coefficients, double tolerance);

/// p(x) by Clenshaw's recurrence, x in [-1, 1].
double chebyshev_value(std::span<const double> c, double x);

/// Coefficients of p' (on [-1, 1]); one fewer than c (at least one).
std::vector<double> chebyshev_derivative(std::span<const double> c);

/// A place where p is zero: a simple root where p changes sign (`crosses`), or a cell [lo, hi]
/// where |p| stays within the rounding floor (a double root, a touch, or p flat at zero there);
/// x is the root, or the cell's middle.
struct SeriesZero {
  double x = 0.0;
  double lo = 0.0, hi = 0.0;
  bool crosses = true;  // p changes sign here (for a zone: read off p just outside it)
  bool rising = false;  // for a crossing: p goes from negative to positive
  bool zone = false;    // a cell (or run of cells) where |p| <= floor, rather than a simple root
};

/// Every zero of p on [-1, 1], ascending. `floor` is the absolute rounding level below which |p|
/// counts as zero (e.g. 64 eps sum |c_k|). `cells` counts the subdivision cells examined.
/// `skip(lo, hi, a)`, if given, may rule a cell out before it is searched (a is p's series on
/// the cell [lo, hi] in the cell's own variable): the extremum search skips cells where the
/// function it differentiates cannot beat the best value found.
std::vector<SeriesZero> chebyshev_zeros(std::span<const double> c, double floor, long& cells,
                                        const std::function<bool(double, double, std::span<const double>)>& skip = {});

/// Where p may take its maximum on [-1, 1], by branch and bound on cells: a cell is dropped when
/// the bound a_0 + sum_{k>=1} |a_k| of its own series a cannot beat `best` + `margin`; a cell on
/// which p varies by at most `margin` (sum_{k>=1} |a_k|) is represented by its middle; a cell
/// where p' has no zero (its series b has |b_0| > sum |b_k|) by its ends; a cell where p' is
/// monotone and changes sign by the root of p' (TOMS 748). Returns candidate points t with p(t);
/// `best` is raised as candidates come in. `cells` counts the cells examined.
struct SeriesPoint {
  double t = 0.0;
  double value = 0.0;
};
std::vector<SeriesPoint> chebyshev_maximum_candidates(std::span<const double> c, double& best, double margin,
                                                      long& cells);

}  // namespace mechgraph::numerics
